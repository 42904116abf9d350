/* The `fem` integrator's meshes and solutions cached on disk, so that a
 * render of the same translucent objects (another camera, resolution, spp)
 * skips gmsh and the Cholesky solves, and a render of the same objects
 * under other light skips gmsh (docs/fem.md, "The cache").
 *
 * One file holds, per translucent shape of the last render that wrote it,
 * two records, each under the 64-bit key of everything it depends on:
 *   - the tetrahedral mesh, keyed by the shape's world-space surface
 *     (vertex positions and triangles, as handed to gmsh), the mesh options
 *     (element sizes, refinement) and, with a medium size field, its whole
 *     lattice (origin, spacing, counts, every size);
 *   - the solution the render reads (the exitance M_o per vertex and colour
 *     channel, as floats), keyed by the mesh's key and, per channel, the
 *     coefficients (M, mu0) of every element at its centroid as the
 *     assembly evaluates them, the load (the boundary index eta, the spot,
 *     point and volume sources, every face's Gamma_s or every ray's origin,
 *     direction, extinction and power) and the solver's options.
 * Every key also hashes SS_FEM_CACHE_VERSION and ss_fem_libraries() (gmsh's
 * and CHOLMOD's versions and files), and the header carries that code key:
 * coefficients and loads are hashed by value, so a change to the medium's
 * or the irradiance's code is seen; a change to subsurf's meshing, assembly
 * or solve code must raise SS_FEM_CACHE_VERSION.
 *
 * Layout (cache_file.h's frame): "SSFEMCH\0", u32 version, u32 byte-order
 * mark, u64 code key, u64 record count; per record u32 kind (1 mesh, 2
 * solution), u32 0, u64 key, u64 vertices, u64 tetrahedra (0 for a
 * solution), then for a mesh 3 doubles per vertex and 4 u32 per
 * tetrahedron (its boundary faces are found again by ss_fem_mesh_create,
 * as after gmsh), for a solution 3 floats per vertex; then the CRC-32. */
#ifndef SUBSURF_FEM_CACHE_H
#define SUBSURF_FEM_CACHE_H

#include "subsurf/fem.h"

#define SS_FEM_CACHE_VERSION 1

/* The records of a cache file, read and checked. */
typedef struct ss_fem_cache ss_fem_cache;

/* The key of a mesh: the surface as ss_fem_mesh_surface takes it and its
 * options (with the size field's lattice when opt->medium_size is set). */
uint64_t ss_fem_cache_mesh_key(const float *positions, size_t num_vertices, const uint32_t *indices,
                               size_t num_triangles, const ss_fem_mesh_options *opt);

/* Adds one channel's solve to the running key *h (start it at the mesh's
 * key): the coefficients of every element at its centroid (the medium's
 * error, prefixed as the assembly prefixes it, is returned), the problem
 * and the solver's options. */
ss_status ss_fem_cache_hash_solve(uint64_t *h, const ss_fem_mesh *mesh, ss_fem_medium_fn medium,
                                  void *medium_ctx, const ss_fem_problem *problem,
                                  const ss_fem_solve_options *opt, ss_error *err);

/* Reads and checks the whole file: SS_ERR_IO when it cannot be opened (a
 * missing file: nothing cached yet), SS_ERR_PARSE with the reason, the
 * message naming the file ("fem cache 'F': checksum mismatch (damaged)",
 * "truncated", "not an fem cache", "made by another version of the fem
 * code, gmsh or CHOLMOD (stale)", a record's bad size, index or value). */
ss_status ss_fem_cache_read(const char *path, ss_fem_cache **out, ss_error *err);
void ss_fem_cache_destroy(ss_fem_cache *c);

/* The cached mesh of `key` (a new mesh in *out), or *out NULL when there is
 * none; a record whose tetrahedra ss_fem_mesh_create refuses is an error. */
ss_status ss_fem_cache_mesh(const ss_fem_cache *c, uint64_t key, ss_fem_mesh **out, ss_error *err);
/* Copies the cached solution of `key` (3 floats per vertex) into
 * `exitance` and returns 1 when there is one for `num_vertices` vertices;
 * else 0. */
int ss_fem_cache_solution(const ss_fem_cache *c, uint64_t key, size_t num_vertices,
                          float *exitance);

/* One shape's records for ss_fem_cache_write. */
typedef struct {
  uint64_t mesh_key, solution_key;
  const ss_fem_mesh *mesh;
  const float *exitance; /* 3 per vertex */
} ss_fem_cache_entry;

/* Writes the records of `n` shapes atomically (ss_atomic_file: a temporary
 * file renamed over `path`; an interrupted write leaves the old file). */
ss_status ss_fem_cache_write(const char *path, const ss_fem_cache_entry *e, size_t n,
                             ss_error *err);

#endif
