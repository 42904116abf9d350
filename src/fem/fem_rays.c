/* The exponentially attenuated volume source of refracted rays: the
 * reduced-intensity source that Jakob2010 eq. 37 replaces by a flux on the
 * boundary ("approximated by a diffusive flux term equal to the net refracted
 * irradiance attenuated by the expected absorption before the first
 * scattering event", sec. 6.2.1). The first scattering events of a ray of
 * power P with extinction sigma are distributed as P sigma exp(-sigma s)
 * along it; their mean depth 1/sigma is where the dipole puts its single
 * source (Jakob2010 eq. 44; Jensen2001). Each ray is cut into depth
 * strata of equal probability, each stratum's power put at its median depth
 * and spread over the containing tetrahedron's vertices by the linear shape
 * functions (q_i = int Q0 beta_i, eq. 39). */
#include "fem/fem_internal.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>

/* depth strata per ray */
#define STRATA 16

ss_status ss_fem_spot_rays(ss_vec3 center, ss_vec3 normal, double radius, double power, int diffuse,
                           int rings, int n_dirs, ss_fem_sigma_fn sigma, void *ctx,
                           ss_fem_ray **out, size_t *num_rays, ss_error *err) {
  *out = NULL;
  *num_rays = 0;
  double len = ss_vec3_length(normal);
  if (!(len > 0.0) || !isfinite(len) || !(radius > 0.0) || !isfinite(radius) || !(power >= 0.0) ||
      !isfinite(power) || rings < 1 || rings > 256 || n_dirs < 1 || n_dirs > 256) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: spot rays need a normal, a radius > 0, a power >= 0 and 1-256 "
                        "rings and directions (radius %g, power %g, rings %d, directions %d)",
                        radius, power, rings, n_dirs);
  }
  ss_frame f = ss_frame_from_normal(ss_vec3_scale(normal, 1.0 / len));
  size_t sectors = 2 * (size_t)rings, nd = diffuse ? (size_t)n_dirs * 2 * (size_t)n_dirs : 1;
  size_t n = (size_t)rings * sectors * nd;
  ss_fem_ray *r = malloc(n * sizeof *r);
  if (!r) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for %zu spot rays", n);
  }
  size_t k = 0;
  for (int i = 0; i < rings; ++i) {
    /* equal-area rings: the disc's points are uniform */
    double rho = radius * sqrt((i + 0.5) / rings);
    for (size_t j = 0; j < sectors; ++j) {
      double a = 2.0 * SS_PI * (j + 0.5) / (double)sectors;
      ss_vec3 o = ss_vec3_add(
          center, ss_vec3_add(ss_vec3_scale(f.s, rho * cos(a)), ss_vec3_scale(f.t, rho * sin(a))));
      for (size_t d = 0; d < nd; ++d) {
        /* cosine-distributed about -n: sin^2 theta uniform, strata of it and
         * of the azimuth */
        double u = diffuse ? ((double)(d / (2 * (size_t)n_dirs)) + 0.5) / n_dirs : 0.0;
        double b = 2.0 * SS_PI * ((double)(d % (2 * (size_t)n_dirs)) + 0.5) / (2.0 * n_dirs);
        double st = sqrt(u), ct = sqrt(1.0 - u);
        ss_vec3 w =
            ss_vec3_add(ss_vec3_scale(f.n, -ct), ss_vec3_add(ss_vec3_scale(f.s, st * cos(b)),
                                                             ss_vec3_scale(f.t, st * sin(b))));
        double s = sigma(ctx, w);
        if (!(s > 0.0) || !isfinite(s)) {
          free(r);
          return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                              "fem: extinction %g along a spot ray must be > 0", s);
        }
        r[k++] = (ss_fem_ray){.origin = o, .dir = w, .sigma = s, .power = power / (double)n};
      }
    }
  }
  *out = r;
  *num_rays = n;
  return SS_OK;
}

ss_status ss_fem_deposit_rays(const ss_fem_mesh *m, const ss_fem_problem *pb, double *b,
                              double *injected, ss_error *err) {
  *injected = 0.0;
  if (!pb->rays || pb->num_rays == 0) {
    return SS_OK;
  }
  for (size_t i = 0; i < pb->num_rays; ++i) {
    const ss_fem_ray *r = &pb->rays[i];
    double len = ss_vec3_length(r->dir);
    if (!(r->sigma > 0.0) || !isfinite(r->sigma) || !(r->power >= 0.0) || !isfinite(r->power) ||
        !(fabs(len - 1.0) < 1e-6) || !isfinite(r->origin.x + r->origin.y + r->origin.z)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem: ray %zu needs a finite origin, a unit direction, sigma > 0 and a "
                          "power >= 0 (sigma %g, power %g, |dir| %g)",
                          i, r->sigma, r->power, len);
    }
  }
  double total = 0.0;
  for (size_t i = 0; i < pb->num_rays; ++i) {
    total += pb->rays[i].power;
  }
  ss_fem_grid g;
  ss_status st = ss_fem_grid_build(m, &g, err);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < pb->num_rays; ++i) {
    const ss_fem_ray *r = &pb->rays[i];
    for (int k = 0; k < STRATA; ++k) {
      /* the median of stratum k of the exponential's distribution function */
      double s = -log(1.0 - (k + 0.5) / STRATA) / r->sigma, w = r->power / STRATA, lambda[4];
      size_t t;
      if (ss_fem_grid_locate(&g, m, ss_vec3_add(r->origin, ss_vec3_scale(r->dir, s)), &t, lambda)) {
        for (int v = 0; v < 4; ++v) {
          b[m->tets[4 * t + (size_t)v]] += w * lambda[v];
        }
        *injected += w;
      }
    }
  }
  ss_fem_grid_free(&g);
  if (!(*injected > 0.0) && total > 0.0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: no first scattering event of the %zu rays lies inside the mesh "
                        "(a source off the surface?)",
                        pb->num_rays);
  }
  return SS_OK;
}
