/* The OpenVDB reader and writer as a plugin, libsubsurf_vdb.so (built from
 * grid_vdb.cpp), opened on first use by grid_vdb.c instead of linked:
 * libopenvdb pulls in log4cplus, whose static initialiser starts three
 * threads, and every subsurf process paid ~0.07 s for it (five times the
 * rest of its start-up). Only plain arrays and an ss_error (a plain struct)
 * cross this boundary, so the plugin calls nothing of libsubsurf. */
#ifndef SUBSURF_IO_VDB_PLUGIN_H
#define SUBSURF_IO_VDB_PLUGIN_H

#include "subsurf/status.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SS_VDB_PLUGIN_FILE "libsubsurf_vdb.so"

/* One grid: n[0] x n[1] x n[2] voxels over the box [lo, hi]; density has one
 * value per voxel, axis (or NULL) three, x fastest. */
typedef struct {
  int n[3];
  double lo[3], hi[3];
  float *density;
  float *axis;
} ss_vdb_grid;

/* Reads the float grid (named "density" or the first one) over its active
 * bounding box and the Vec3SGrid "axis" if any, refusing more than
 * max_voxels voxels before allocating. On SS_OK the arrays are malloc'ed
 * and the caller frees them; messages do not name the file. */
typedef ss_status ss_vdb_read_fn(const char *path, int64_t max_voxels, ss_vdb_grid *out,
                                 ss_error *err);
/* Writes density (and axis) on cubic voxels of side (hi[0] - lo[0]) / n[0]. */
typedef ss_status ss_vdb_write_fn(const char *path, const ss_vdb_grid *g, ss_error *err);

ss_vdb_read_fn ss_vdb_plugin_read;
ss_vdb_write_fn ss_vdb_plugin_write;

#ifdef __cplusplus
}
#endif

#endif
