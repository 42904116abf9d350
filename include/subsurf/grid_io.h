/* Grid files (grid.h): subsurf's raw format and OpenVDB.
 *
 * Raw format (".ssgrid"), little-endian, an 80-byte header then the voxels:
 *   0  magic "SSGRID1\n" (8 bytes)
 *   8  uint32 version (1)
 *   12 uint32 channels: 1 (density) or 4 (density, axis x, y, z)
 *   16 uint32 nx, ny, nz (each >= 1, product <= 2^31)
 *   28 uint32 zero
 *   32 float64 lo x, y, z, hi x, y, z (the box, finite, lo < hi)
 *   80 float32 values, channels per voxel, x fastest, then y, then z
 * The file's size must be exactly 80 + 4 channels nx ny nz. Densities must
 * be finite and >= 0; an axis must be finite and non-zero where the density
 * is positive (its length does not matter).
 *
 * OpenVDB (".vdb", Museth 2013; read with Debian's libopenvdb): the first
 * FloatGrid (or the one named "density") is resampled at the centres of the
 * voxels of its active bounding box in index space, the box's world bounds
 * from the grid's (linear) transform; an optional Vec3SGrid named "axis"
 * gives the flake axes. */
#ifndef SUBSURF_GRID_IO_H
#define SUBSURF_GRID_IO_H

#include "subsurf/grid.h"

#include <stddef.h>

#define SS_GRID_RAW_MAGIC "SSGRID1\n"
#define SS_GRID_RAW_HEADER 80

/* Reads a raw grid file or an OpenVDB file (told apart by the magic);
 * errors name the file. */
ss_status ss_grid_read(const char *path, ss_grid **out, ss_error *err);

/* The raw format from memory (`name` for messages) and to a file (written
 * atomically). */
ss_status ss_grid_read_raw_memory(const unsigned char *data, size_t size, const char *name,
                                  ss_grid **out, ss_error *err);
ss_status ss_grid_write_raw(const char *path, const ss_grid *g, ss_error *err);

/* OpenVDB: a FloatGrid "density" (and a Vec3SGrid "axis" when the grid has
 * axes) with a uniform scale transform mapping the voxels onto the box
 * (the box's extents over the dimensions must agree per axis to 1e-9
 * relative, else SS_ERR_INVALID_ARGUMENT). */
ss_status ss_grid_read_vdb(const char *path, ss_grid **out, ss_error *err);
ss_status ss_grid_write_vdb(const char *path, const ss_grid *g, ss_error *err);

#endif
