/* The irradiance points of the `hierarchical` integrator cached on disk, so
 * that a render of the same scene and lighting (only the camera or the
 * render settings changed) skips pass 1. The file holds a key: a 64-bit
 * hash of everything pass 1 depends on (geometry, materials, media, their
 * BSSRDF models and options, lights, max_depth and rr_depth, the point
 * count, irradiance samples and seed; not the camera, spp or epsilon), the
 * points, and a CRC-32 of all that. A file that is damaged (size, magic,
 * version, byte order, checksum, a non-finite value, a shape out of range)
 * or made for another key is refused with the reason, never trusted; the
 * integrator then rebuilds the points and rewrites the file.
 *
 * Layout (little-endian): "SSIRRCH\0", u32 version, u32 0x01020304, u64 key,
 * u64 count, then per point 10 doubles (p, n, area, E) and u32 shape, then
 * u32 CRC-32 of every byte before it. The octree is rebuilt from the points
 * (they are stored in octree order, so it is the same tree). */
#ifndef SUBSURF_IRRADIANCE_CACHE_H
#define SUBSURF_IRRADIANCE_CACHE_H

#include "subsurf/irradiance_points.h"

#define SS_IRRADIANCE_CACHE_VERSION 1

/* The key of pass 1 for this scene and these pass-1 options. */
uint64_t ss_irradiance_cache_key(const ss_scene *scene, size_t points, int samples, uint64_t seed);

/* Reads the points (malloc'd into *out) when `path` is a valid cache for
 * `key` with shapes below `num_shapes`; otherwise SS_ERR_IO (cannot open)
 * or SS_ERR_PARSE with the reason ("made for another scene or lighting",
 * "checksum mismatch", ...), the message naming the file. */
ss_status ss_irradiance_cache_read(const char *path, uint64_t key, size_t num_shapes,
                                   ss_irradiance_point **out, size_t *count, ss_error *err);
/* Writes the cache atomically (ss_atomic_file). */
ss_status ss_irradiance_cache_write(const char *path, uint64_t key, const ss_irradiance_point *p,
                                    size_t count, ss_error *err);

/* Whether `path` is a valid cache for the `hierarchical` integrator's pass 1
 * of this scene (its options as set): SS_OK, else the reader's error. */
ss_status ss_hierarchical_cache_check(const ss_scene *scene, const char *path, ss_error *err);

#endif
