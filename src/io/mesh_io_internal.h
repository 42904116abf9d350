/* Shared pieces of the PLY and OBJ readers (private to src/io). */
#ifndef SUBSURF_IO_MESH_IO_INTERNAL_H
#define SUBSURF_IO_MESH_IO_INTERNAL_H

#include "subsurf/mesh_io.h"

#include <stddef.h>
#include <stdint.h>

/* A growing array of uint32 (triangle indices). */
typedef struct {
  uint32_t *data;
  size_t size, capacity;
} ss_index_buffer;

int ss_index_buffer_reserve(ss_index_buffer *b, size_t capacity);
int ss_index_buffer_push(ss_index_buffer *b, const uint32_t *v, size_t n);
void ss_index_buffer_free(ss_index_buffer *b);

/* Moves the arrays (malloc'ed; set to NULL on success) into a new mesh,
 * validates it and fills info. Messages are prefixed with the path. */
ss_status ss_mesh_io_finish(const char *path, size_t nv, float **pos, float **nrm, float **uv,
                            ss_index_buffer *tris, size_t npolys, ss_mesh **out,
                            ss_mesh_read_info *info, ss_error *err);

#endif
