/* Per-element coefficients of the `fem` integrator (fem_medium.h). */
#include "render/integrators/fem_medium.h"

#include "subsurf/flake_diffusion.h"
#include "subsurf/grid.h"
#include "subsurf/volume.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_fem_scene_medium_init(ss_fem_scene_medium *c, const ss_medium *med, int channel,
                                   double min_density, ss_error *err) {
  memset(c, 0, sizeof *c);
  c->med = med;
  c->channel = channel;
  c->min_density = min_density;
  if (med->optics.flakes.type == SS_FLAKE_NONE) {
    return SS_OK;
  }
  double s = med->optics.sigma_s.c[channel], a = med->optics.sigma_a.c[channel];
  ss_medium_flakes about_z = med->optics.flakes;
  about_z.axis = ss_vec3_make(0.0, 0.0, 1.0);
  c->mf = malloc(sizeof *c->mf);
  if (!c->mf) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory");
  }
  ss_status st = ss_microflake_init_medium(c->mf, &about_z, s / (s + a), err);
  if (st != SS_OK) {
    ss_error_prefix(err, "fem: medium '%s': ", med->name);
    return st;
  }
  /* g(w) for the reduced first events of every lit face and ray */
  ss_microflake_tabulate_scattered_mean(c->mf);
  /* microflake.h: a rho = 2 (sigma_s + sigma_a) at unit density */
  double density = ss_flake_medium_density(s, a);
  c->M1 = ss_flake_diffusion_matrix(c->mf, density);
  c->mu0_1 = ss_flake_diffusion_mu0(c->mf, density);
  return SS_OK;
}

void ss_fem_scene_medium_release(ss_fem_scene_medium *c) {
  free(c->mf);
  c->mf = NULL;
}

static double max_density(const ss_fem_scene_medium *c) {
  return c->med->grid ? c->med->grid->max_density : 1.0;
}

ss_status ss_fem_scene_medium_at(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  (void)err;
  const ss_fem_scene_medium *c = ctx;
  ss_volume_point q = ss_volume_at(c->med, x);
  double d = fmax(q.density, c->min_density * max_density(c));
  if (!c->mf) {
    const ss_medium_optics *o = &c->med->optics;
    int k = c->channel;
    *out = ss_fem_coeffs_isotropic(d * (1.0 - o->g.c[k]) * o->sigma_s.c[k], d * o->sigma_a.c[k]);
    return SS_OK;
  }
  /* M about the local axis: F M1 F^T, F = [s t n] the axis frame */
  ss_vec3 e[3] = {q.axis.s, q.axis.t, q.axis.n};
  double M[9] = {0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double m = d * c->M1.m[i][j];
      const double a[3] = {e[i].x, e[i].y, e[i].z}, b[3] = {e[j].x, e[j].y, e[j].z};
      for (int r = 0; r < 3; ++r) {
        for (int s = 0; s < 3; ++s) {
          M[3 * r + s] += m * a[r] * b[s];
        }
      }
    }
  }
  memcpy(out->M, M, sizeof M);
  out->mu0 = d * c->mu0_1;
  return SS_OK;
}

double ss_fem_scene_medium_mfp(const ss_fem_scene_medium *c) {
  double trace;
  if (c->mf) {
    trace = c->M1.m[0][0] + c->M1.m[1][1] + c->M1.m[2][2];
  } else {
    const ss_medium_optics *o = &c->med->optics;
    int k = c->channel;
    trace = 9.0 * ((1.0 - o->g.c[k]) * o->sigma_s.c[k] + o->sigma_a.c[k]);
  }
  return 9.0 / (trace * max_density(c));
}

ss_flake_first_event ss_fem_scene_medium_first_event(const ss_fem_scene_medium *c, ss_vec3 x,
                                                     ss_vec3 w) {
  ss_volume_point q = ss_volume_at(c->med, x);
  double d = fmax(q.density, c->min_density * max_density(c));
  const ss_medium_optics *o = &c->med->optics;
  int k = c->channel;
  if (!c->mf) {
    double s = (1.0 - o->g.c[k]) * o->sigma_s.c[k], t = s + o->sigma_a.c[k];
    return (ss_flake_first_event){d * t, t > 0.0 ? s / t : 0.0};
  }
  /* microflake.h: a rho = 2 (sigma_s + sigma_a) at unit density */
  return ss_flake_reduced_first_event(c->mf,
                                      d * ss_flake_medium_density(o->sigma_s.c[k], o->sigma_a.c[k]),
                                      ss_frame_to_local(q.axis, w));
}

double ss_fem_scene_medium_sigma(const ss_fem_scene_medium *c, ss_vec3 x, ss_vec3 w) {
  return ss_fem_scene_medium_first_event(c, x, w).sigma;
}

double ss_fem_scene_sigma_fn(void *ctx, ss_vec3 w) {
  const ss_fem_scene_sigma_at *s = ctx;
  return ss_fem_scene_medium_sigma(s->medium, s->at, w);
}

double ss_fem_scene_medium_attenuation(const ss_fem_scene_medium *c) {
  const ss_medium_optics *o = &c->med->optics;
  int k = c->channel;
  double s = c->mf ? o->sigma_s.c[k] : (1.0 - o->g.c[k]) * o->sigma_s.c[k];
  return s > 0.0 ? exp(-o->sigma_a.c[k] / s) : 0.0;
}

ss_status ss_fem_scene_medium_size_field(ss_fem_scene_medium *c, ss_vec3 lo, ss_vec3 hi,
                                         double size_min, double size_max, ss_fem_size_field **out,
                                         ss_error *err) {
  *out = NULL;
  const ss_grid *g = c->med->grid;
  if (!g) {
    return SS_OK;
  }
  ss_vec3 d = ss_vec3_sub(g->hi, g->lo);
  double voxel = fmin(fmin(d.x / g->n[0], d.y / g->n[1]), d.z / g->n[2]);
  ss_fem_size_options o = {.lo = lo,
                           .hi = hi,
                           .spacing = voxel,
                           .tolerance = 0.1,
                           .size_min = size_min,
                           .size_max = size_max,
                           .grade = 0.5};
  return ss_fem_size_field_from_medium(ss_fem_scene_medium_at, c, &o, out, err);
}
