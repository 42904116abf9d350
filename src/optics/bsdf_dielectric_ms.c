/* Energy compensation of rough dielectric interfaces for the light that the
 * single-scattering microfacet model loses between microfacets (Kulla &
 * Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH
 * course: the 1 - E(mu) lobe of sec. "Energy compensation", and its
 * dielectric form with a reciprocal split between reflection and
 * transmission).
 *
 * Side s (0: outside, wo.z > 0; 1: inside) has the directional albedo
 * E_s(mu_o) of the single-scattering BSDF, counted without the radiance
 * scaling of refraction (the albedo a path's weight sees: the 1/eta^2 of
 * entering and the eta^2 of leaving cancel), and its cosine average
 * E_avg,s = 2 int_0^1 E_s(mu) mu dmu. The compensation lobes are
 *   reflection on s:   (1 - x_s) (1 - E_s(mu_o)) (1 - E_s(mu_i)) / (pi (1 - E_avg,s))
 *   transmission s->t: x_s (1 - E_s(mu_o)) (1 - E_t(mu_i)) / (pi (1 - E_avg,t))
 * (transmission times the radiance scaling 1/eta'^2 in radiance mode). Each
 * integrates over mu_i to (1 - x_s) (1 - E_s(mu_o)) and x_s (1 - E_s(mu_o)),
 * so every direction's albedo becomes exactly 1 (the white furnace). Detailed
 * balance between the sides, which see radiances 1 and eta^2 in equilibrium,
 * asks x_0 (1 - E_avg,0) = eta^2 x_1 (1 - E_avg,1): the outside's share x_0
 * is the single-scattering model's transmitted share of its average albedo,
 * and x_1 follows (both clamped to [0, 1] keeping the ratio).
 *
 * E_s is tabulated at SS_DIELECTRIC_MS_NODES + 1 cosines when the BSDF is
 * built (jittered stratified visible-normal samples of the project's own
 * BSDF, fixed seeds) and
 * interpolated linearly; E_avg is the exact average of that interpolant, so
 * the albedo is 1 up to the table's error. Sampling: the single-scattering
 * BSDF with probability E_s(mu_o), else the compensation lobes (reflection
 * 1 - x_s, transmission x_s, cosine-distributed); pdf and f are the sums. */
#include "optics/dielectric_ms.h"
#include "subsurf/fresnel.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/table_index.h"

#include <math.h>

/* Jittered strata per side of the square for each table node. Midpoints
 * would miss the distributions' tails, where most of the loss happens (a
 * 48 x 48 midpoint rule overestimated GGX alpha 0.1's albedo by 0.7 %). */
#define MS_STRATA 64

/* The single-scattering albedo at cosine mu on the side of `sign`, split
 * into its transmitted part *trans: for each stratified visible normal, the
 * reflection and refraction weights f |cos| / pdf times the Fresnel lobe
 * probabilities (an exact sum over the lobe choice). */
static double albedo(const ss_bsdf *ss, double mu, double sign, ss_rng *rng, double *trans) {
  ss_vec3 wo = ss_vec3_make(sqrt(fmax(0.0, 1.0 - mu * mu)), 0.0, sign * mu);
  double sum = 0.0, sum_t = 0.0;
  for (int i = 0; i < MS_STRATA; ++i) {
    for (int j = 0; j < MS_STRATA; ++j) {
      double u1 = (i + ss_rng_uniform(rng)) / MS_STRATA, u2 = (j + ss_rng_uniform(rng)) / MS_STRATA;
      ss_vec3 wm = ss_microfacet_sample_visible(&ss->mf, wo, u1, u2);
      double r = ss_fresnel_dielectric(ss_vec3_dot(wo, wm), ss->eta);
      ss_bsdf_sample s;
      if (r > 0.0 && ss->ops->sample(ss, wo, 0.0, u1, u2, &s)) {
        sum += r * s.f.x * fabs(s.wi.z) / s.pdf;
      }
      if (r < 1.0 && ss->ops->sample(ss, wo, nextafter(1.0, 0.0), u1, u2, &s)) {
        double w = (1.0 - r) * s.f.x * fabs(s.wi.z) / s.pdf;
        sum += w;
        sum_t += w;
      }
    }
  }
  *trans = sum_t / (MS_STRATA * MS_STRATA);
  return sum / (MS_STRATA * MS_STRATA);
}

/* int_a^b (ea + (eb - ea) (mu - a) / (b - a)) mu dmu. */
static double segment_moment(double a, double b, double ea, double eb) {
  double m1 = (b * b - a * a) / 2.0, m2 = (b * b * b - a * a * a) / 3.0;
  return ea * m1 + (eb - ea) / (b - a) * (m2 - a * m1);
}

double ss_dielectric_ms_albedo(const ss_dielectric_ms *ms, int side, double mu) {
  double x = fmin(fmax(mu, 0.0), 1.0) * SS_DIELECTRIC_MS_NODES;
  int k = ss_table_cell(x, SS_DIELECTRIC_MS_NODES);
  if (k < 0) {
    return ms->e[side][SS_DIELECTRIC_MS_NODES];
  }
  double f = x - k;
  return (1.0 - f) * ms->e[side][k] + f * ms->e[side][k + 1];
}

void ss_dielectric_ms_node(const ss_bsdf *single, int side, int k, double *e, double *trans) {
  ss_bsdf ss = *single;
  ss.mode = SS_TRANSPORT_IMPORTANCE; /* no radiance scaling: the path's albedo */
  /* Grazing node: the albedo just above grazing (wo.z = 0 scatters nothing).
   * Each node has its own seed: a table is the same for any number of
   * threads, and the same at every roughness. */
  double mu = fmax((double)k / SS_DIELECTRIC_MS_NODES, 1e-3);
  ss_rng rng;
  ss_rng_seed(&rng, (uint64_t)k, (uint64_t)side);
  *e = fmin(albedo(&ss, mu, side == 0 ? 1.0 : -1.0, &rng, trans), 1.0);
}

double ss_dielectric_ms_average(const double *v) {
  double avg = 0.0;
  for (int k = 1; k <= SS_DIELECTRIC_MS_NODES; ++k) {
    double a = (double)(k - 1) / SS_DIELECTRIC_MS_NODES, b = (double)k / SS_DIELECTRIC_MS_NODES;
    avg += 2.0 * segment_moment(a, b, v[k - 1], v[k]);
  }
  return avg;
}

void ss_dielectric_ms_finish(ss_dielectric_ms *ms, double eta, const double t_avg[2]) {
  double lost0 = 1.0 - ms->e_avg[0], lost1 = 1.0 - ms->e_avg[1];
  if (!(lost0 > 1e-9) || !(lost1 > 1e-9)) {
    ms->x[0] = ms->x[1] = 0.0; /* nothing (measurable) is lost */
    ms->on = 0;
    return;
  }
  /* x_0 (1 - E_avg,0) = eta^2 x_1 (1 - E_avg,1), x_0 the transmitted share. */
  double x0 = ms->e_avg[0] > 0.0 ? t_avg[0] / ms->e_avg[0] : 0.0;
  double x1 = x0 * lost0 / (eta * eta * lost1);
  if (x1 > 1.0) {
    x0 /= x1;
    x1 = 1.0;
  }
  ms->x[0] = x0;
  ms->x[1] = x1;
  ms->on = 1;
}

void ss_dielectric_ms_build(ss_dielectric_ms *ms, const ss_bsdf *single) {
  enum { NODES = SS_DIELECTRIC_MS_NODES + 1 };
  double trans[2][NODES];
#pragma omp parallel for schedule(dynamic)
  for (int node = 0; node < 2 * NODES; ++node) {
    int side = node / NODES, k = node % NODES;
    ss_dielectric_ms_node(single, side, k, &ms->e[side][k], &trans[side][k]);
  }
  double t_avg[2];
  for (int side = 0; side < 2; ++side) {
    ms->e_avg[side] = ss_dielectric_ms_average(ms->e[side]);
    t_avg[side] = ss_dielectric_ms_average(trans[side]);
  }
  ss_dielectric_ms_finish(ms, single->eta, t_avg);
}

/* The compensation lobe's value (f, radiance or importance as b->mode) and
 * its sampling density given that the compensation lobe is chosen. */
static double ms_value(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, double *pdf) {
  const ss_dielectric_ms *ms = &b->ms;
  int s = wo.z > 0.0 ? 0 : 1, reflect = wo.z * wi.z > 0.0, t = reflect ? s : 1 - s;
  double share = reflect ? 1.0 - ms->x[s] : ms->x[s];
  double mu_i = fabs(wi.z);
  *pdf = share * ss_pdf_cosine_hemisphere(mu_i);
  double f = share * (1.0 - ss_dielectric_ms_albedo(ms, s, fabs(wo.z))) *
             (1.0 - ss_dielectric_ms_albedo(ms, t, mu_i)) / (SS_PI * (1.0 - ms->e_avg[t]));
  if (!reflect && b->mode == SS_TRANSPORT_RADIANCE) {
    double etap = wo.z > 0.0 ? b->eta : 1.0 / b->eta;
    f /= etap * etap;
  }
  return f;
}

ss_vec3 ss_dielectric_ms_eval(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, ss_vec3 single) {
  if (wo.z == 0.0 || wi.z == 0.0) {
    return single;
  }
  double pdf, f = ms_value(b, wo, wi, &pdf);
  return ss_vec3_add(single, ss_vec3_make(f, f, f));
}

double ss_dielectric_ms_pdf(const ss_bsdf *b, ss_vec3 wo, ss_vec3 wi, double single) {
  if (wo.z == 0.0 || wi.z == 0.0) {
    return 0.0;
  }
  double e = ss_dielectric_ms_albedo(&b->ms, wo.z > 0.0 ? 0 : 1, fabs(wo.z)), pdf;
  ms_value(b, wo, wi, &pdf);
  return e * single + (1.0 - e) * pdf;
}

int ss_dielectric_ms_pick(const ss_bsdf *b, ss_vec3 wo, double *uc, double u1, double u2,
                          ss_vec3 *wi) {
  int s = wo.z > 0.0 ? 0 : 1;
  double e = ss_dielectric_ms_albedo(&b->ms, s, fabs(wo.z));
  if (*uc < e) {
    *uc /= e;
    return 0;
  }
  double v = (*uc - e) / (1.0 - e);
  ss_vec3 w = ss_sample_cosine_hemisphere(u1, u2);
  /* Reflection stays on wo's side; transmission crosses. */
  int reflect = v < 1.0 - b->ms.x[s];
  double sign = (wo.z > 0.0) == reflect ? 1.0 : -1.0;
  *wi = ss_vec3_make(w.x, w.y, sign * w.z);
  return 1;
}
