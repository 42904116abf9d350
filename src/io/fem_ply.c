/* A finite-element solution as a PLY file with per-vertex values, for
 * viewers (MeshLab, ParaView colour by "exitance") and for scripts. */
#include "subsurf/fem_io.h"

#include "core/atomic_file.h"

#include <stdarg.h>
#include <stdio.h>

/* Appends one formatted line. */
static ss_status put(ss_atomic_file *f, ss_error *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static ss_status put(ss_atomic_file *f, ss_error *err, const char *fmt, ...) {
  char line[1024];
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  if (n < 0 || (size_t)n >= sizeof line) {
    return ss_error_set(err, SS_ERR_IO, "%s: line too long", f->path);
  }
  return ss_atomic_file_write(f, line, (size_t)n, err);
}

ss_status ss_fem_write_ply(const char *path, const ss_fem_mesh *mesh, const ss_fem_solution *sol,
                           ss_error *err) {
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_PLY, err);
  if (st != SS_OK) {
    return st;
  }
  st = put(&f, err,
           "ply\nformat ascii 1.0\ncomment subsurf fem: fluence and exitance per vertex\n"
           "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
           "property float fluence\nproperty float exitance\n"
           "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
           mesh->num_vertices, mesh->num_faces);
  for (size_t i = 0; i < mesh->num_vertices && st == SS_OK; ++i) {
    const double *p = mesh->positions + 3 * i;
    st = put(&f, err, "%.9g %.9g %.9g %.9g %.9g\n", p[0], p[1], p[2], sol->fluence[i],
             sol->exitance[i]);
  }
  for (size_t t = 0; t < mesh->num_faces && st == SS_OK; ++t) {
    const uint32_t *v = mesh->faces + 3 * t;
    st = put(&f, err, "3 %u %u %u\n", v[0], v[1], v[2]);
  }
  if (st != SS_OK) {
    ss_atomic_file_abort(&f);
    return st;
  }
  return ss_atomic_file_commit(&f, err);
}
