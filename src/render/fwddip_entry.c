/* Entry points for the forward scattering dipole: probe rays and the
 * ballistic ray, combined by one-sample MIS (see fwddip_entry.h). */
#include "subsurf/fwddip_entry.h"

#include "subsurf/fwddip.h"

#include <math.h>

/* The ray of the ballistic strategy from the exit point along d. */
static ss_ray ballistic_ray(const ss_probe *p, ss_vec3 d) {
  return ss_ray_spawn(p->x_o, p->frame.n, d);
}

double ss_fwddip_entry_ballistic_pdf(const ss_probe *p, const ss_hit *hit, size_t count,
                                     unsigned long long *queries) {
  ss_vec3 v = ss_vec3_sub(hit->p, p->x_o);
  double t2 = ss_vec3_length2(v);
  if (!(t2 > 0.0)) {
    return 0.0;
  }
  ss_vec3 d = ss_vec3_scale(v, 1.0 / sqrt(t2));
  double pd = ss_fwddip_pdf_ballistic(p->bssrdf, p->frame.n, p->w_o, d);
  if (!(pd > 0.0)) {
    return 0.0;
  }
  if (count == 0) {
    ss_ray ray = ballistic_ray(p, d);
    ++*queries;
    count = ss_accel_intersect_all(p->accel, &ray, p->geom_id, NULL, 0);
    if (count == 0) {
      return 0.0;
    }
  }
  /* Solid angle to area at x_i: |n_i . d| / t^2; one of `count` hits. */
  return pd * fabs(ss_vec3_dot(hit->ng, d)) / (t2 * (double)count);
}

double ss_fwddip_entry_pdf(const ss_probe *p, const ss_hit *hit, unsigned long long *queries) {
  double beta = ss_fwddip_ballistic_fraction(p->bssrdf);
  double pdf = (1.0 - beta) * ss_probe_pdf(p, hit, -1, 0, queries);
  if (beta > 0.0) {
    pdf += beta * ss_fwddip_entry_ballistic_pdf(p, hit, 0, queries);
  }
  return pdf;
}

static int sample_ballistic(const ss_probe *p, double beta, const double u[5], ss_probe_sample *out,
                            unsigned long long *queries) {
  ss_vec3 d;
  double pd;
  if (!ss_fwddip_sample_ballistic(p->bssrdf, p->frame.n, p->w_o, u[1], u[2], u[3], &d, &pd)) {
    return 0;
  }
  ss_ray ray = ballistic_ray(p, d);
  ++*queries;
  size_t count = ss_accel_intersect_sample(p->accel, &ray, p->geom_id, u[4], &out->hit);
  if (count == 0) {
    return 0;
  }
  out->axis = -1;
  out->channel = -1;
  out->hits = count;
  out->pdf = beta * ss_fwddip_entry_ballistic_pdf(p, &out->hit, count, queries) +
             (1.0 - beta) * ss_probe_pdf(p, &out->hit, -1, 0, queries);
  return out->pdf > 0.0 && isfinite(out->pdf);
}

int ss_fwddip_entry_sample(const ss_probe *p, const double u[5], ss_probe_sample *out,
                           unsigned long long *queries) {
  double beta = ss_fwddip_ballistic_fraction(p->bssrdf);
  if (u[0] < beta) {
    return sample_ballistic(p, beta, u, out, queries);
  }
  double v[5] = {(u[0] - beta) / (1.0 - beta), u[1], u[2], u[3], u[4]};
  if (!ss_probe_sample_entry(p, v, out, queries)) {
    return 0;
  }
  if (beta > 0.0) {
    out->pdf =
        (1.0 - beta) * out->pdf + beta * ss_fwddip_entry_ballistic_pdf(p, &out->hit, 0, queries);
  }
  return out->pdf > 0.0 && isfinite(out->pdf);
}
