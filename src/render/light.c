/* Light sources: sampling of incident light, densities and emission. */
#include "subsurf/light.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int vec_finite(ss_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static ss_status unit_direction(ss_light *l, ss_error *err) {
  double len = ss_vec3_length(l->direction);
  if (!vec_finite(l->direction) || !(len > 0.0)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': direction must be non-zero",
                        l->name);
  }
  l->direction = ss_vec3_scale(l->direction, 1.0 / len);
  return SS_OK;
}

/* The mesh's bounding sphere (centre of its box, radius to its farthest
 * vertex, widened by 1e-6 so that every point of the float mesh is inside)
 * and whether the emitter is round: its area at least 2 pi R^2. */
static void bounding_sphere(ss_light *l) {
  ss_vec3 lo, hi;
  ss_mesh_bounds(l->mesh, &lo, &hi);
  ss_vec3 c = ss_vec3_scale(ss_vec3_add(lo, hi), 0.5);
  double r2 = 0.0;
  for (size_t i = 0; i < l->mesh->num_vertices; ++i) {
    const float *q = l->mesh->positions + 3 * i;
    r2 = fmax(r2, ss_vec3_length2(ss_vec3_sub(ss_vec3_make(q[0], q[1], q[2]), c)));
  }
  l->bound_centre = c;
  l->bound_radius = sqrt(r2) * (1.0 + 1e-6);
  l->round = l->area >= 2.0 * SS_PI * r2;
}

ss_status ss_light_init(ss_light *l, const ss_mesh *mesh, ss_error *err) {
  memset(&l->tris, 0, sizeof l->tris);
  l->mesh = NULL;
  if (!ss_rgb_is_finite(l->value) || !(ss_rgb_min(l->value) >= 0.0) ||
      !(ss_rgb_max(l->value) <= SS_LIGHT_MAX_VALUE)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': value must be in [0, %g]",
                        l->name, SS_LIGHT_MAX_VALUE);
  }
  if (!ss_in_world(l->position)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "light '%s': position must have coordinates in [-%g, %g]", l->name,
                        SS_WORLD_LIMIT, SS_WORLD_LIMIT);
  }
  switch (l->type) {
  case SS_LIGHT_POINT:
  case SS_LIGHT_ENVIRONMENT:
    return SS_OK;
  case SS_LIGHT_DIRECTIONAL:
    return unit_direction(l, err);
  case SS_LIGHT_SPOT:
    if (!(l->cone_angle > 0.0 && l->cone_angle <= 180.0) ||
        !(l->falloff_angle >= 0.0 && l->falloff_angle <= l->cone_angle)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "light '%s': need 0 < cone_angle <= 180 and 0 <= falloff_angle <= "
                          "cone_angle (degrees)",
                          l->name);
    }
    l->cos_outer = cos(l->cone_angle * SS_PI / 180.0);
    l->cos_inner = cos(l->falloff_angle * SS_PI / 180.0);
    return unit_direction(l, err);
  case SS_LIGHT_BEAM:
    if (!(isfinite(l->radius) && l->radius > 0.0)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': beam radius must be > 0",
                          l->name);
    }
    if (unit_direction(l, err) != SS_OK) {
      return SS_ERR_INVALID_ARGUMENT;
    }
    l->frame = ss_frame_from_normal(l->direction);
    return SS_OK;
  case SS_LIGHT_AREA:
    break;
  }
  if (!mesh || mesh->num_triangles == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': area light needs a mesh",
                        l->name);
  }
  double *areas = malloc(mesh->num_triangles * sizeof *areas);
  if (!areas) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "light '%s': out of memory", l->name);
  }
  for (size_t i = 0; i < mesh->num_triangles; ++i) {
    areas[i] = ss_mesh_triangle_area(mesh, i);
  }
  int rc = ss_distribution1d_init(&l->tris, areas, mesh->num_triangles);
  free(areas);
  if (rc != 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "light '%s': emissive mesh has zero area",
                        l->name);
  }
  l->area = l->tris.integral * (double)mesh->num_triangles;
  l->mesh = mesh;
  bounding_sphere(l);
  l->accel = NULL;
  return SS_OK;
}

void ss_light_bind(ss_light *l, const ss_accel *accel) {
  l->accel = l->type == SS_LIGHT_AREA && l->round ? accel : NULL;
}

void ss_light_free(ss_light *l) {
  if (l->type == SS_LIGHT_AREA && l->tris.cdf) {
    ss_distribution1d_free(&l->tris);
  }
  if (l->type == SS_LIGHT_ENVIRONMENT) {
    ss_envmap_destroy(l->map);
    l->map = NULL;
  }
}

int ss_light_is_delta(const ss_light *l) {
  return l->type != SS_LIGHT_AREA && l->type != SS_LIGHT_ENVIRONMENT;
}

/* The spot's falloff between its cones, of t, the place of cos(theta)
 * between the outer cone's cosine (t = 0) and the inner one's (t = 1):
 * pbrt-v3's t^4 (pbrt-v3 sec. 12.2.1) or pbrt-v4's smoothstep
 * t^2 (3 - 2 t), which is brighter everywhere inside (0.5 against 0.0625
 * halfway). */
static double spot_falloff(const ss_light *l, double cos_theta) {
  if (cos_theta >= l->cos_inner) {
    return 1.0;
  }
  if (cos_theta <= l->cos_outer) {
    return 0.0;
  }
  double t = (cos_theta - l->cos_outer) / (l->cos_inner - l->cos_outer);
  return l->spot_smoothstep ? t * t * (3.0 - 2.0 * t) : (t * t) * (t * t);
}

int ss_light_sample_point(const ss_light *l, double u1, double u2, ss_vec3 *p_out, ss_vec3 *n) {
  double prob;
  size_t tri = ss_distribution1d_sample_discrete(&l->tris, u1, &prob);
  /* Reuse the remainder of u1 within the chosen cell for the triangle. */
  double lo = l->tris.cdf[tri], hi = l->tris.cdf[tri + 1];
  double v = hi > lo ? (u1 - lo) / (hi - lo) : 0.5;
  v = fmin(fmax(v, 0.0), 0x1.fffffffffffffp-1);
  ss_vec3 p[3];
  ss_mesh_triangle(l->mesh, tri, p);
  double b0, b1;
  ss_sample_uniform_triangle(v, u2, &b0, &b1);
  *p_out = ss_vec3_add(ss_vec3_add(ss_vec3_scale(p[0], b0), ss_vec3_scale(p[1], b1)),
                       ss_vec3_scale(p[2], 1.0 - b0 - b1));
  *n = ss_vec3_normalize(ss_mesh_triangle_normal(l->mesh, tri));
  return 1;
}

/* The cosine of the half-angle of the cone the bounding sphere subtends at
 * ref, when the light is sampled in it from there (bound, round, ref
 * outside the sphere); -1 when it is sampled by area. */
static double cone_cos(const ss_light *l, ss_vec3 ref) {
  if (!l->accel) {
    return -1.0;
  }
  double d2 = ss_vec3_length2(ss_vec3_sub(l->bound_centre, ref));
  double sin2 = l->bound_radius * l->bound_radius / d2;
  return sin2 < 1.0 - 1e-9 ? sqrt(1.0 - sin2) : -1.0;
}

/* Uniform density on the cone of half-angle cosine cos_max: 1 / (2 pi (1 - cos_max)),
 * with 1 - cos_max = sin^2 / (1 + cos_max) free of cancellation. */
static double cone_pdf(double cos_max) {
  return (1.0 + cos_max) / (2.0 * SS_PI * (1.0 - cos_max * cos_max));
}

/* A direction uniform in the cone (pbrt-v3 sec. 13.6.5, UniformSampleCone)
 * toward the bounding sphere's centre, and the emitter where it first meets
 * the mesh; 0 when it misses the mesh or meets it from behind. */
static int sample_cone(const ss_light *l, ss_vec3 ref, double cos_max, double u1, double u2,
                       ss_light_sample *s) {
  ss_vec3 axis = ss_vec3_sub(l->bound_centre, ref);
  double d = ss_vec3_length(axis);
  double cos_t = 1.0 - u1 * (1.0 - cos_max), sin_t = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
  double phi = 2.0 * SS_PI * u2;
  ss_frame f = ss_frame_from_normal(ss_vec3_scale(axis, 1.0 / d));
  s->wi = ss_frame_to_world(f, ss_vec3_make(sin_t * cos(phi), sin_t * sin(phi), cos_t));
  ss_ray ray = {ref, s->wi, 0.0, d + l->bound_radius};
  ss_hit hit;
  if (ss_accel_intersect_all(l->accel, &ray, (unsigned)l->shape, &hit, 1) == 0 ||
      !(ss_vec3_dot(s->wi, hit.ng) < 0.0)) {
    return 0;
  }
  s->p = hit.p;
  s->n = hit.ng;
  s->dist = ss_vec3_length(ss_vec3_sub(hit.p, ref));
  s->pdf = cone_pdf(cos_max);
  s->li = l->value;
  s->delta = 0;
  return s->dist > 0.0;
}

static int sample_area(const ss_light *l, ss_vec3 ref, double u1, double u2, ss_light_sample *s) {
  double cos_max = cone_cos(l, ref);
  if (cos_max >= 0.0) {
    return sample_cone(l, ref, cos_max, u1, u2, s);
  }
  ss_light_sample_point(l, u1, u2, &s->p, &s->n);
  ss_vec3 d = ss_vec3_sub(s->p, ref);
  double dist2 = ss_vec3_length2(d);
  if (!(dist2 > 0.0)) {
    return 0;
  }
  s->dist = sqrt(dist2);
  s->wi = ss_vec3_scale(d, 1.0 / s->dist);
  double cos_l = -ss_vec3_dot(s->wi, s->n);
  if (!(cos_l > 0.0)) {
    return 0; /* one-sided emitter seen from behind */
  }
  /* Uniform by area: p_A = 1 / A; to solid angle p = p_A dist^2 / cos_l. */
  s->pdf = dist2 / (cos_l * l->area);
  s->li = l->value;
  s->delta = 0;
  return 1;
}

int ss_light_sample_li(const ss_light *l, ss_vec3 ref, double u1, double u2, ss_light_sample *s) {
  s->n = ss_vec3_make(0.0, 0.0, 0.0);
  s->pdf = 1.0;
  s->delta = 1;
  switch (l->type) {
  case SS_LIGHT_POINT:
  case SS_LIGHT_SPOT: {
    ss_vec3 d = ss_vec3_sub(l->position, ref);
    double dist2 = ss_vec3_length2(d);
    if (!(dist2 > 0.0)) {
      return 0;
    }
    s->dist = sqrt(dist2);
    s->wi = ss_vec3_scale(d, 1.0 / s->dist);
    s->p = l->position;
    double k = 1.0 / dist2;
    if (l->type == SS_LIGHT_SPOT) {
      k *= spot_falloff(l, -ss_vec3_dot(s->wi, l->direction));
    }
    s->li = ss_rgb_scale(l->value, k);
    return k > 0.0;
  }
  case SS_LIGHT_DIRECTIONAL:
    s->wi = ss_vec3_neg(l->direction);
    s->dist = INFINITY;
    s->p = ref;
    s->li = l->value;
    return 1;
  case SS_LIGHT_BEAM: {
    /* The beam lights points inside its half-infinite cylinder with the
     * irradiance power / (pi r^2) from the single direction -direction. */
    ss_vec3 d = ss_vec3_sub(ref, l->position);
    double along = ss_vec3_dot(d, l->direction);
    if (!(along > 0.0)) {
      return 0;
    }
    ss_vec3 radial = ss_vec3_madd(d, l->direction, -along);
    if (ss_vec3_length2(radial) >= l->radius * l->radius) {
      return 0;
    }
    s->wi = ss_vec3_neg(l->direction);
    s->dist = along;
    s->p = ss_vec3_madd(ref, s->wi, along);
    s->li = ss_rgb_scale(l->value, 1.0 / (SS_PI * l->radius * l->radius));
    return 1;
  }
  case SS_LIGHT_ENVIRONMENT:
    s->dist = INFINITY;
    s->p = ref;
    s->delta = 0;
    if (l->map) {
      if (!ss_envmap_sample(l->map, u1, u2, &s->wi, &s->pdf, &s->li)) {
        return 0;
      }
      s->li = ss_rgb_mul(s->li, l->value);
      return 1;
    }
    s->wi = ss_sample_uniform_sphere(u1, u2);
    s->pdf = ss_pdf_uniform_sphere();
    s->li = l->value;
    return 1;
  case SS_LIGHT_AREA:
    return sample_area(l, ref, u1, u2, s);
  }
  return 0;
}

double ss_light_pdf_li(const ss_light *l, ss_vec3 ref, ss_vec3 wi, const ss_hit *hit) {
  if (l->type == SS_LIGHT_ENVIRONMENT) {
    double pdf = ss_pdf_uniform_sphere();
    if (l->map) {
      ss_envmap_eval(l->map, wi, &pdf);
    }
    return pdf;
  }
  if (l->type != SS_LIGHT_AREA || !hit) {
    return 0.0;
  }
  double cos_l = -ss_vec3_dot(wi, hit->ng);
  if (!(cos_l > 0.0)) {
    return 0.0;
  }
  double cos_max = cone_cos(l, ref);
  if (cos_max >= 0.0) {
    return cone_pdf(cos_max);
  }
  double dist2 = ss_vec3_length2(ss_vec3_sub(hit->p, ref));
  return dist2 / (cos_l * l->area);
}

ss_rgb ss_light_le(const ss_light *l, ss_vec3 ng, ss_vec3 w) {
  if (l->type == SS_LIGHT_ENVIRONMENT) {
    return l->map ? ss_rgb_mul(l->value, ss_envmap_eval(l->map, ss_vec3_neg(w), NULL)) : l->value;
  }
  if (l->type == SS_LIGHT_AREA && ss_vec3_dot(ng, w) > 0.0) {
    return l->value;
  }
  return ss_rgb_gray(0.0);
}

ss_rgb ss_light_environment_li(const ss_light *l, ss_vec3 w, double *pdf) {
  if (!l->map) {
    *pdf = ss_pdf_uniform_sphere();
    return l->value;
  }
  return ss_rgb_mul(l->value, ss_envmap_eval(l->map, w, pdf));
}

static const char *const light_names[] = {"point", "spot",        "directional",
                                          "area",  "environment", "beam"};

int ss_light_type_from_name(const char *name, ss_light_type *type) {
  for (int i = 0; i < 6; ++i) {
    if (!strcmp(name, light_names[i])) {
      *type = (ss_light_type)i;
      return 1;
    }
  }
  return 0;
}

const char *ss_light_type_name(ss_light_type type) { return light_names[type]; }
