/* Render checkpoints: a long render saves its film (every pixel's
 * accumulation state, bit for bit) and the options that decide the image,
 * and a later run continues it (ss_render_options.resume) to exactly the
 * image an uninterrupted render gives. The sampler needs nothing else: sample
 * s of a pixel draws from its own PCG32 stream position (render.h), and each
 * pixel's next sample is the number it has drawn.
 *
 * File layout, version 1 (native byte order, checked by a byte-order mark):
 *   0   "SSRENDCK"           8 bytes
 *   8   u32 version          1
 *   12  u32 byte-order mark  0x01020304
 *   16  u32 scene CRC-32     of the scene file's bytes
 *   20  u32 spp
 *   24  u64 seed
 *   32  i32 window[4]        x0, y0, x1, y1 in the image
 *   48  char integrator[64]  NUL-padded (SS_NAME_SIZE)
 *   112 pixels, row by row   u32 n, u32 rejected, f64 mean[3], f64 m2[3]
 *   end u32 CRC-32 (zlib) of every byte before it
 * The film's size is the window's. Meshes a scene file names are not part
 * of its CRC. */
#ifndef SUBSURF_CHECKPOINT_H
#define SUBSURF_CHECKPOINT_H

#include "subsurf/film.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

#include <stdint.h>

#define SS_CHECKPOINT_VERSION 1

/* What a checkpoint must match to be continued. */
typedef struct {
  uint32_t scene_crc;
  uint32_t spp;
  uint64_t seed;
  int32_t window[4];
  char integrator[SS_NAME_SIZE];
} ss_checkpoint_key;

/* The key of rendering `scene` (read from scene_path) with options `o`
 * (integrator from the scene, window = o->crop or the whole image); fails
 * when the scene file cannot be read. */
ss_status ss_checkpoint_key_init(ss_checkpoint_key *key, const char *scene_path,
                                 const ss_scene *scene, const ss_render_options *o, ss_error *err);

/* The size of the checkpoint of a width x height film. */
uint64_t ss_checkpoint_bytes(int width, int height);

/* Writes the film under `key` through core/atomic_file.h (a temporary file
 * renamed over `path`), so a crash never leaves a torn checkpoint; a
 * non-empty file that is not a checkpoint is not replaced. */
ss_status ss_checkpoint_write(const char *path, const ss_checkpoint_key *key, const ss_film *film,
                              ss_error *err);

/* Reads a checkpoint and checks its format, version, checksum and key
 * against `expect`; on success *film holds the saved film. Errors name the
 * file and what differs (SS_ERR_PARSE for a damaged or foreign file,
 * SS_ERR_INVALID_ARGUMENT for another scene or options, SS_ERR_IO). */
ss_status ss_checkpoint_read(const char *path, const ss_checkpoint_key *expect, ss_film **film,
                             ss_error *err);

#endif
