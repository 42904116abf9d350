/* A voxel's axis as a grid file gives it (three floats), checked the same
 * way for every format (grid_io.h). */
#ifndef SUBSURF_IO_GRID_FILE_AXIS_H
#define SUBSURF_IO_GRID_FILE_AXIS_H

#include "subsurf/grid.h"

/* Sets voxel v's axis to a (whose density must already be set): SS_ERR_PARSE
 * naming `name` and the voxel unless a is finite, and non-zero where the
 * density is positive; a zero axis (of an empty voxel) becomes +z. */
ss_status ss_grid_set_file_axis(ss_grid *g, int64_t v, ss_vec3 a, const char *name, ss_error *err);

#endif
