/* The irradiance points of the `hierarchical` integrator cached on disk, so
 * that a render of the same scene and lighting (only the camera or the
 * render settings changed) skips pass 1. The file holds a key: a 64-bit
 * hash of everything pass 1 depends on, the points, and a CRC-32 of all
 * that. The key covers
 *   - the points as placed: every point's position, normal, area and shape
 *     (in any order), so that the placement algorithm, its version and its
 *     parameters (candidate pool, radius schedule, tiles, the point count
 *     or automatic density, the seed) are covered by what they produce:
 *     the placement runs again before a cache is read (it costs a small
 *     part of pass 1);
 *   - the irradiance estimate's inputs: the samples per point and seed, the
 *     scene's geometry (positions, indices, normals, texture coordinates of
 *     every shape), materials (every field, their BSSRDF models and
 *     options, textures by their values on a fixed grid of look-ups),
 *     media (coefficients, phase, flakes, density grids), lights,
 *     max_depth and rr_depth; not the camera, spp or epsilon;
 *   - the estimator's code, by a spot check: the irradiance of the first
 *     SS_IRRADIANCE_CACHE_SPOT_CHECK placed points is computed again (each
 *     point draws from its own stream) and must equal the cached values bit
 *     for bit, so that a cache written by another version of pass 1 is
 *     stale even when no version number was raised.
 * A file that is damaged (size, magic, version, byte order, checksum, a
 * non-finite value, a shape out of range) or made for another key, or that
 * fails the spot check, is refused with the reason, never trusted; the
 * integrator then rebuilds the points and rewrites the file.
 *
 * Layout (little-endian): "SSIRRCH\0", u32 version, u32 0x01020304, u64 key,
 * u64 count, then per point 10 doubles (p, n, area, E) and u32 shape, then
 * u32 CRC-32 of every byte before it. The octree is rebuilt from the points
 * (they are stored in octree order, so it is the same tree). */
#ifndef SUBSURF_IRRADIANCE_CACHE_H
#define SUBSURF_IRRADIANCE_CACHE_H

#include "subsurf/irradiance_points.h"

#define SS_IRRADIANCE_CACHE_VERSION 2
/* Points whose irradiance a read computes again (the spot check). */
#define SS_IRRADIANCE_CACHE_SPOT_CHECK 4

/* Pass 1 besides the scene: the points as placed (p, n, area and shape set,
 * in the order of placement, which gives each its random stream), the
 * relative index of each shape's boundary, and the estimator's settings
 * (ss_irradiance_points_compute). */
typedef struct {
  const ss_irradiance_point *placed;
  size_t count;
  const double *eta_of_shape;
  int samples;
  uint64_t seed;
} ss_irradiance_pass1;

/* The key of pass 1 for this scene. */
uint64_t ss_irradiance_cache_key(const ss_scene *scene, const ss_irradiance_pass1 *pass1);

/* Reads the points (malloc'd into *out, in the file's order) when `path` is
 * a valid cache for this scene and pass 1 (the key, then the spot check);
 * otherwise SS_ERR_IO (cannot open) or SS_ERR_PARSE with the reason ("made
 * for another scene, lighting or point set (stale)", "checksum mismatch",
 * ...), the message naming the file. */
ss_status ss_irradiance_cache_read(const char *path, const ss_scene *scene,
                                   const ss_irradiance_pass1 *pass1, ss_irradiance_point **out,
                                   size_t *count, ss_error *err);
/* Writes the points computed by pass 1 (any order) atomically
 * (ss_atomic_file), under the key of this scene and pass 1. */
ss_status ss_irradiance_cache_write(const char *path, const ss_scene *scene,
                                    const ss_irradiance_pass1 *pass1, const ss_irradiance_point *p,
                                    size_t count, ss_error *err);

/* Whether `path` is a valid cache for the `hierarchical` integrator's pass 1
 * of this scene (its options as set): SS_OK, else the reader's error. */
ss_status ss_hierarchical_cache_check(const ss_scene *scene, const char *path, ss_error *err);

#endif
