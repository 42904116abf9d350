/* OpenVDB grids (grid_io.h) through the plugin of vdb_plugin.h, opened on
 * the first .vdb file (io/plugin.h) like gmsh (src/fem/gmsh_api.c). */
#include "io/vdb_plugin.h"

#include "io/grid_file_axis.h"
#include "io/plugin.h"
#include "subsurf/grid_io.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  ss_vdb_read_fn *read;
  ss_vdb_write_fn *write;
} vdb_plugin;

/* The plugin's functions; SS_OK, or the reason it cannot be used. */
static ss_status open_plugin(vdb_plugin *p, ss_error *err) {
  const ss_dynlib_symbol symbols[] = {{"ss_vdb_plugin_read", (void **)&p->read},
                                      {"ss_vdb_plugin_write", (void **)&p->write}};
  return ss_plugin_open(SS_VDB_PLUGIN_FILE, "OpenVDB files", "libopenvdb", symbols, 2, err);
}

/* The plugin, opened once per process; a failure is reported every time. */
static ss_status plugin_get(const vdb_plugin **out, ss_error *err) {
  static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
  static vdb_plugin plugin;
  static int loaded;
  ss_status st = SS_OK;
  pthread_mutex_lock(&lock);
  if (!loaded && (st = open_plugin(&plugin, err)) == SS_OK) {
    loaded = 1;
  }
  pthread_mutex_unlock(&lock);
  *out = &plugin;
  return st;
}

static ss_status grid_of(const char *path, const ss_vdb_grid *v, ss_grid **out, ss_error *err) {
  ss_grid *g = NULL;
  ss_status st =
      ss_grid_create(v->n, ss_vec3_make(v->lo[0], v->lo[1], v->lo[2]),
                     ss_vec3_make(v->hi[0], v->hi[1], v->hi[2]), v->axis != NULL, &g, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    return st == SS_ERR_INVALID_ARGUMENT ? SS_ERR_PARSE : st;
  }
  int64_t count = ss_grid_voxels(g);
  memcpy(g->density, v->density, (size_t)count * sizeof *g->density);
  for (int64_t i = 0; v->axis && i < count; ++i) {
    const float *a = v->axis + 3 * i;
    if ((st = ss_grid_set_file_axis(g, i, ss_vec3_make(a[0], a[1], a[2]), path, err)) != SS_OK) {
      ss_grid_destroy(g);
      return st;
    }
  }
  if ((st = ss_grid_finish(g, err)) != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    ss_grid_destroy(g);
    return SS_ERR_PARSE;
  }
  *out = g;
  return SS_OK;
}

ss_status ss_grid_read_vdb(const char *path, ss_grid **out, ss_error *err) {
  *out = NULL;
  const vdb_plugin *p;
  ss_status st = plugin_get(&p, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    return st;
  }
  ss_vdb_grid v;
  if ((st = p->read(path, SS_GRID_MAX_VOXELS, &v, err)) != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    return st;
  }
  st = grid_of(path, &v, out, err);
  free(v.density);
  free(v.axis);
  return st;
}

ss_status ss_grid_write_vdb(const char *path, const ss_grid *g, ss_error *err) {
  double h = (g->hi.x - g->lo.x) / g->n[0];
  for (int a = 1; a < 3; ++a) {
    double ha = (ss_vec3_component(g->hi, a) - ss_vec3_component(g->lo, a)) / g->n[a];
    if (fabs(ha - h) > 1e-9 * h) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: OpenVDB needs cubic voxels, the grid's "
                          "are %g along x and %g along %c",
                          path, h, ha, "xyz"[a]);
    }
  }
  const vdb_plugin *p;
  ss_status st = plugin_get(&p, err);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
    return st;
  }
  int64_t count = ss_grid_voxels(g);
  float *axis = g->axis ? malloc((size_t)count * 3 * sizeof *axis) : NULL;
  if (g->axis && !axis) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory for %lld axes", path,
                        (long long)count);
  }
  for (int64_t i = 0; axis && i < count; ++i) {
    ss_vec3 a = ss_grid_axis_of(g, i);
    axis[3 * i] = (float)a.x;
    axis[3 * i + 1] = (float)a.y;
    axis[3 * i + 2] = (float)a.z;
  }
  ss_vdb_grid v = {{g->n[0], g->n[1], g->n[2]},
                   {g->lo.x, g->lo.y, g->lo.z},
                   {g->hi.x, g->hi.y, g->hi.z},
                   g->density,
                   axis};
  /* Written beside the target and renamed, so that it appears complete or not at all. */
  size_t size = strlen(path) + sizeof ".tmp-vdb";
  char *tmp = malloc(size);
  if (!tmp) {
    free(axis);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", path);
  }
  snprintf(tmp, size, "%s.tmp-vdb", path);
  st = p->write(tmp, &v, err);
  free(axis);
  if (st != SS_OK) {
    ss_error_prefix(err, "%s: ", path);
  } else if (rename(tmp, path) != 0) {
    st = ss_error_set(err, SS_ERR_IO, "%s: cannot write", path);
  }
  if (st != SS_OK) {
    remove(tmp);
  }
  free(tmp);
  return st;
}
