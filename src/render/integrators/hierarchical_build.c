/* Pass 1 of the `hierarchical` integrator and its octrees (hierarchical.h;
 * Jensen & Buhler 2002, sec. 3). */
#include "render/integrators/hierarchical.h"

#include "subsurf/irradiance_cache.h"
#include "subsurf/progress.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

static int has_option(const ss_scene *s, const char *name) {
  for (size_t i = 0; i < s->integrator.num_options; ++i) {
    if (!strcmp(s->integrator.options[i].name, name)) {
      return 1;
    }
  }
  return 0;
}

static ss_status whole(const ss_scene *s, const char *name, double lo, double hi, double def,
                       double *out, ss_error *err) {
  double v = ss_scene_integrator_option(s, name, def);
  if (!(v >= lo && v <= hi) || v != floor(v)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "hierarchical: option %s: expected a whole number in [%.0f, %.0f], got %g",
                        name, lo, hi, v);
  }
  *out = v;
  return SS_OK;
}

ss_status ss_hier_options_read(const ss_scene *scene, ss_hier_options *o, ss_error *err) {
  memset(o, 0, sizeof *o);
  o->seed = scene->render.seed;
  double v = 0.0;
  ss_status st;
  if (has_option(scene, "points")) {
    if ((st = whole(scene, "points", 1, SS_HIER_MAX_POINTS, 0, &v, err)) != SS_OK) {
      return st;
    }
    o->points = (size_t)v;
  }
  if ((st = whole(scene, "irradiance_samples", 1, 1 << 20, SS_HIER_DEFAULT_IRRADIANCE_SAMPLES, &v,
                  err)) != SS_OK) {
    return st;
  }
  o->irradiance_samples = (int)v;
  if ((st = whole(scene, "kernel_table", 0, 1, 1, &v, err)) != SS_OK) {
    return st;
  }
  o->kernel_table = (int)v;
  o->near_field = ss_scene_integrator_option(scene, "near_field", 0.0);
  if (!(o->near_field >= 0.0 && o->near_field <= SS_HIER_MAX_NEAR_FIELD)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "hierarchical: option near_field: expected a number in [0, %d] (point "
                        "spacings), got %g",
                        SS_HIER_MAX_NEAR_FIELD, o->near_field);
  }
  o->epsilon = ss_scene_integrator_option(scene, "epsilon", SS_HIER_DEFAULT_EPSILON);
  if (!(o->epsilon > 0.0) || !isfinite(o->epsilon)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "hierarchical: option epsilon: expected a finite number > 0, got %g",
                        o->epsilon);
  }
  return SS_OK;
}

int ss_hier_kernel_ok(const ss_bssrdf *b) {
  unsigned f = ss_bssrdf_flags(b);
  return (f & SS_BSSRDF_RADIAL) && !(f & (SS_BSSRDF_BRDF | SS_BSSRDF_SINGULAR));
}

static int is_translucent(const ss_material *m) {
  return m && m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
}

/* Shape i's tabulated kernel, dropped when the model does not factor as
 * the table assumes (hierarchical_table.c). */
static ss_status table(ss_hier_state *s, size_t i, ss_error *err) {
  ss_status st = ss_hier_table_build(s->kernel[i], s->eta[i], &s->table[i], err);
  if (st == SS_OK &&
      !(ss_hier_table_check(&s->table[i], s->kernel[i], s->eta[i]) <= SS_HIER_TABLE_TOLERANCE)) {
    ss_hier_table_destroy(&s->table[i]);
  }
  return st;
}

/* The kernel of every translucent shape; an error names a material whose
 * model cannot be one. */
static ss_status kernels(const ss_scene *scene, ss_hier_state *s, ss_error *err) {
  for (size_t i = 0; i < scene->num_shapes; ++i) {
    int mi = scene->shapes[i].material;
    if (mi < 0 || !is_translucent(&scene->materials[mi])) {
      continue;
    }
    const ss_bssrdf *b = ss_subsurface_bssrdf(scene->subsurface, mi);
    if (!b || !ss_hier_kernel_ok(b)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "hierarchical: material '%s': model '%s' is not a radially symmetric "
                          "kernel (use dipole, better-dipole, pbd, table-radial, multipole, ...)",
                          scene->materials[mi].name, b ? ss_bssrdf_name(b) : "none");
    }
    s->kernel[i] = b;
    s->eta[i] = ss_bssrdf_get_params(b)->eta;
    ss_status st = s->opt.kernel_table ? table(s, i, err) : SS_OK;
    if (st != SS_OK) {
      return st;
    }
  }
  return SS_OK;
}

/* Points per unit area at the automatic density: 1 / l^2, l = 1 / max_c
 * sigma_t' of the shape's medium. */
static double auto_density(const ss_scene *scene, size_t shape) {
  const ss_medium *med = &scene->media[scene->materials[scene->shapes[shape].material].medium];
  double st_max = 0.0;
  for (int c = 0; c < 3; ++c) {
    st_max = fmax(st_max,
                  med->optics.sigma_s.c[c] * (1.0 - med->optics.g.c[c]) + med->optics.sigma_a.c[c]);
  }
  return st_max * st_max;
}

/* Points per translucent shape: the requested total shared by area (each
 * at least 1), or one per l^2 (hierarchical.h). */
static ss_status counts(const ss_scene *scene, const ss_hier_state *s, size_t *n, ss_error *err) {
  double area_total = 0.0, auto_total = 0.0;
  for (size_t i = 0; i < scene->num_shapes; ++i) {
    if (!s->kernel[i]) {
      continue;
    }
    double a = ss_mesh_area(scene->shapes[i].mesh);
    area_total += a;
    auto_total += a * auto_density(scene, i);
  }
  double scale = 1.0;
  if (s->opt.points) {
    scale = (double)s->opt.points / area_total;
  } else if (auto_total > SS_HIER_AUTO_MAX_POINTS) {
    scale = SS_HIER_AUTO_MAX_POINTS / auto_total;
  }
  for (size_t i = 0; i < scene->num_shapes; ++i) {
    n[i] = 0;
    if (!s->kernel[i]) {
      continue;
    }
    double a = ss_mesh_area(scene->shapes[i].mesh);
    double want = a * scale * (s->opt.points ? 1.0 : auto_density(scene, i));
    if (!isfinite(want)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "hierarchical: shape '%s': cannot place points on it",
                          scene->shapes[i].name);
    }
    n[i] = want < 1.0 ? 1 : (size_t)llround(want);
  }
  return SS_OK;
}

static ss_status alloc_state(const ss_scene *scene, const ss_hier_options *o, ss_hier_state **out,
                             ss_error *err) {
  ss_hier_state *s = calloc(1, sizeof *s);
  if (!s) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "hierarchical: out of memory");
  }
  s->opt = *o;
  s->num_shapes = scene->num_shapes;
  s->trees = calloc(scene->num_shapes + 1, sizeof *s->trees);
  s->kernel = calloc(scene->num_shapes + 1, sizeof *s->kernel);
  s->eta = calloc(scene->num_shapes + 1, sizeof *s->eta);
  s->table = calloc(scene->num_shapes + 1, sizeof *s->table);
  s->near_radius = calloc(scene->num_shapes + 1, sizeof *s->near_radius);
  s->near_disk = calloc(scene->num_shapes + 1, sizeof *s->near_disk);
  *out = s;
  if (!s->trees || !s->kernel || !s->eta || !s->table || !s->near_radius || !s->near_disk) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "hierarchical: out of memory");
  }
  return SS_OK;
}

/* Blue-noise points on every translucent shape, grouped by shape. */
static ss_status place_points(const ss_scene *scene, ss_hier_state *s, ss_error *err) {
  size_t *n = calloc(scene->num_shapes + 1, sizeof *n);
  if (!n) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "hierarchical: out of memory");
  }
  ss_status st = counts(scene, s, n, err);
  size_t total = 0;
  for (size_t i = 0; st == SS_OK && i < scene->num_shapes; ++i) {
    total += n[i];
  }
  if (st == SS_OK && total > 0) {
    s->points = malloc(total * sizeof *s->points);
    if (!s->points) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "hierarchical: out of memory for %zu points", total);
    }
  }
  for (size_t i = 0; st == SS_OK && i < scene->num_shapes; ++i) {
    if (n[i]) {
      st = ss_poisson_disk_points(scene->shapes[i].mesh, (uint32_t)i, n[i], s->opt.seed,
                                  s->points + s->num_points, err);
      s->num_points += n[i];
    }
  }
  free(n);
  return st;
}

/* The near field of each shape with a tabulated kernel: radius near_field
 * point spacings sqrt(A_j) (A_j the area of its points, all equal), and the
 * table's integral over that disk. */
static void near_fields(ss_hier_state *s) {
  for (size_t i = 0; s->opt.near_field > 0.0 && i < s->num_points; ++i) {
    uint32_t shape = s->points[i].shape;
    if (shape < s->num_shapes && s->table[shape].n && s->near_radius[shape] == 0.0) {
      s->near_radius[shape] = s->opt.near_field * sqrt(s->points[i].area);
      ss_hier_table_disk(&s->table[shape], s->near_radius[shape], s->near_disk[shape]);
    }
  }
}

static ss_status build_trees(ss_hier_state *s, ss_error *err) {
  size_t begin = 0;
  while (begin < s->num_points) {
    uint32_t shape = s->points[begin].shape;
    if (s->trees[shape].num_nodes) {
      return ss_error_set(err, SS_ERR_PARSE,
                          "hierarchical: the points of shape %u are not together", (unsigned)shape);
    }
    size_t end = begin;
    while (end < s->num_points && s->points[end].shape == shape) {
      ++end;
    }
    ss_status st =
        ss_irradiance_octree_build(s->points + begin, end - begin, &s->trees[shape], err);
    if (st != SS_OK) {
      return st;
    }
    begin = end;
  }
  return SS_OK;
}

/* Pass 1's description for the cache (irradiance_cache.h): the points as
 * placed (before the octrees reorder them) and the estimator's settings. */
static ss_irradiance_pass1 pass1_of(const ss_hier_state *s) {
  return (ss_irradiance_pass1){s->points, s->num_points, s->eta, s->opt.irradiance_samples,
                               s->opt.seed};
}

/* The points and their irradiance: placed, then read from the cache when it
 * is valid for them, else computed (pass 1). */
static ss_status points(const ss_scene *scene, ss_hier_state *s, int threads, const char *cache,
                        ss_error *err) {
  ss_status st = place_points(scene, s, err);
  if (st != SS_OK) {
    return st;
  }
  if (cache && *cache) {
    ss_error ignored;
    ss_irradiance_pass1 p1 = pass1_of(s);
    ss_irradiance_point *cached;
    size_t n;
    if (ss_irradiance_cache_read(cache, scene, &p1, &cached, &n, &ignored) == SS_OK) {
      free(s->points);
      s->points = cached;
      s->num_points = n;
      s->from_cache = 1;
      return SS_OK;
    }
  }
  double t0 = ss_seconds();
  ss_irradiance_points_compute(scene, s->points, s->num_points, s->eta, s->opt.irradiance_samples,
                               s->opt.seed, threads, NULL, &s->pass1);
  s->pass1_seconds = ss_seconds() - t0;
  return SS_OK;
}

ss_status ss_hier_build(const ss_scene *scene, const ss_hier_options *o, int threads,
                        const char *cache, ss_hier_state **out, ss_error *err) {
  ss_hier_state *s = NULL;
  ss_status st = alloc_state(scene, o, &s, err);
  if (st == SS_OK)
    st = kernels(scene, s, err);
  if (st == SS_OK)
    st = points(scene, s, threads, cache, err);
  if (st == SS_OK) {
    double t0 = ss_seconds();
    st = build_trees(s, err);
    s->octree_seconds = ss_seconds() - t0;
    near_fields(s);
  }
  if (st == SS_OK && cache && *cache && !s->from_cache && s->num_points) {
    ss_irradiance_pass1 p1 = pass1_of(s);
    st = ss_irradiance_cache_write(cache, scene, &p1, s->points, s->num_points, err);
  }
  if (st != SS_OK) {
    ss_hier_destroy(s);
    s = NULL;
  }
  *out = s;
  return st;
}

ss_status ss_hierarchical_cache_check(const ss_scene *scene, const char *path, ss_error *err) {
  ss_hier_options o;
  ss_hier_state *s = NULL;
  ss_status st = ss_hier_options_read(scene, &o, err);
  if (st == SS_OK)
    st = ss_subsurface_build(scene->subsurface, err);
  if (st == SS_OK)
    st = alloc_state(scene, &o, &s, err);
  if (st == SS_OK)
    st = kernels(scene, s, err);
  if (st == SS_OK)
    st = place_points(scene, s, err);
  if (st == SS_OK) {
    ss_irradiance_pass1 p1 = pass1_of(s);
    ss_irradiance_point *p = NULL;
    size_t n = 0;
    st = ss_irradiance_cache_read(path, scene, &p1, &p, &n, err);
    free(p);
  }
  ss_hier_destroy(s);
  return st;
}

void ss_hier_destroy(ss_hier_state *s) {
  if (!s) {
    return;
  }
  for (size_t i = 0; s->trees && i < s->num_shapes; ++i) {
    ss_irradiance_octree_destroy(&s->trees[i]);
  }
  for (size_t i = 0; s->table && i < s->num_shapes; ++i) {
    ss_hier_table_destroy(&s->table[i]);
  }
  free(s->table);
  free(s->near_radius);
  free(s->near_disk);
  free(s->trees);
  free(s->kernel);
  free(s->eta);
  free(s->points);
  free(s);
}
