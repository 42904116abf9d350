/* libFuzzer harness: any byte string given to the fem integrator's cache
 * reader (fem_cache.h) is accepted or refused with a message, never a
 * crash, an out-of-bounds read, a leak or an allocation the input's size
 * does not justify; a refusal names the file; an accepted file's first
 * record is then looked up as a mesh (ss_fem_mesh_create checks its
 * tetrahedra; an accepted mesh's indices must be in range and its positions
 * finite) and as a solution (whose values must be finite). The
 * trailing CRC-32 of a long enough input is set to match the rest, so that
 * mutations reach the checks behind it (the mismatch itself is tested in
 * tests/io/test_fem_cache.c). The seed (corpus/fem_cache) carries the code
 * key of a build against the same gmsh and CHOLMOD files. */
#include "input_file.h"
#include "subsurf/fem_cache.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = ss_fuzz_input_file_crc(data, size, 36, ".femcache");
  uint64_t key = 0, vertices = 0;
  if (size >= 64) {
    memcpy(&key, data + 40, 8);
    memcpy(&vertices, data + 48, 8);
  }
  ss_fem_cache *c = NULL;
  ss_error err;
  if (!path) {
    return 0;
  }
  ss_status st = ss_fem_cache_read(path, &c, &err);
  if (st != SS_OK) {
    if (st == SS_ERR_PARSE && !strstr(err.message, ".femcache'")) {
      abort(); /* a refusal that does not name the file */
    }
    return 0;
  }
  ss_fem_mesh *m = NULL;
  if (ss_fem_cache_mesh(c, key, &m, &err) == SS_OK && m) {
    for (size_t i = 0; i < 4 * m->num_tets; ++i) {
      if (m->tets[i] >= m->num_vertices) {
        abort();
      }
    }
    for (size_t i = 0; i < 3 * m->num_vertices; ++i) {
      if (!isfinite(m->positions[i])) {
        abort();
      }
    }
    ss_fem_mesh_destroy(m);
  }
  float *exitance =
      vertices <= size / 12 ? malloc(3 * (size_t)vertices * sizeof *exitance + 1) : NULL;
  if (exitance) {
    if (ss_fem_cache_solution(c, key, (size_t)vertices, exitance)) {
      for (size_t i = 0; i < 3 * (size_t)vertices; ++i) {
        if (!isfinite(exitance[i])) {
          abort();
        }
      }
    }
    free(exitance);
  }
  ss_fem_cache_destroy(c);
  return 0;
}
