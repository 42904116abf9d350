/* The micro-flake phase function's sampler (Jakob2010 sec. 4;
 * microflake.h), private to the library: always inlined into the
 * walks that draw it every event: as a call, the new direction came back
 * through memory on the chain from one event to the next (the half-space
 * walk's rate with and without the call: bench/RESULTS.md). */
#ifndef SUBSURF_OPTICS_MICROFLAKE_SAMPLE_H
#define SUBSURF_OPTICS_MICROFLAKE_SAMPLE_H

#include "subsurf/microflake.h"
#include "subsurf/sampling.h"

#include <math.h>

/* The function envelope e bounds, at |u| (microflake.c; called only where
 * the squeeze cannot decide). */
double ss_flake_envelope_value(const ss_microflake *mf, const ss_flake_envelope *e, double u);

/* |u| in [0, 1] with density f / integral, f the envelope's function: the
 * top 8 bits of one draw pick the alias column, the low 24 bits decide
 * between the column's cell and its alias and, rescaled, place u uniformly
 * in the cell the bound is constant over; a second draw thins by f, tested
 * against the linear squeeze first (f is evaluated on few draws:
 * build_envelope). */
static inline __attribute__((always_inline)) double
ss_flake_envelope_sample(const ss_microflake *mf, const ss_flake_envelope *e, ss_rng *rng) {
  const int n = SS_MICROFLAKE_ENVELOPE;
  for (;;) {
    uint32_t bits = ss_rng_next_u32(rng);
    int j = (int)(bits >> 24);
    double x = (double)(bits & 0xffffffu) * 0x1p-24;
    int kept = x < e->keep[j];
    int k = kept ? j : e->alias[j];
    double in_cell = kept ? x * e->inv_keep[j] : (x - e->keep[j]) * e->inv_rest[j];
    double u = (k + in_cell) * (1.0 / n);
    double y = ss_rng_uniform(rng) * e->bound[k];
    if (y < e->squeeze[k] + in_cell * e->squeeze_slope[k] ||
        y < ss_flake_envelope_value(mf, e, u)) {
      return u;
    }
  }
}

/* A flake normal in the axis frame with u = m.v >= 0 and density
 * 2 |w.m| D(m) / sigma(w) over that hemisphere, wl being w in the axis
 * frame: m and -m reflect alike and D(m) = D(-m), so this is the visible
 * normal up to its sign. Drawn from the envelope D(m) (s r |cos psi| + c u)
 * (microflake.h) and thinned by |w.m| over it; *wm_out is w.m. */
static inline __attribute__((always_inline)) ss_vec3
ss_microflake_sample_flake(const ss_microflake *mf, ss_vec3 wl, ss_rng *rng, double *wm_out) {
  double c = fabs(wl.z), s2 = wl.x * wl.x + wl.y * wl.y, s = sqrt(s2);
  /* 1/s as s (1/s2): the division runs beside the square root, not after it. */
  int tilted = s2 > 0x1p-1000;
  double inv_s = tilted ? s * (1.0 / s2) : 0.0;
  double cos_w = tilted ? wl.x * inv_s : 1.0, sin_w = wl.y * inv_s;
  /* Mixture weights: int D s r |cos psi| dm = 4 s int_0^1 r D du and
   * int D c u dm = 2 pi c int_0^1 u D du over the hemisphere. */
  double across = 4.0 * s * mf->across.integral;
  double total = across + 2.0 * SS_PI * c * mf->along.integral;
  for (;;) {
    /* 31 bits choose the component, the last one the sign of cos psi. */
    uint32_t bits = ss_rng_next_u32(rng);
    double u, cos_psi, sin_psi;
    if ((bits >> 1) * 0x1p-31 * total < across) {
      u = ss_flake_envelope_sample(mf, &mf->across, rng);
      /* psi with density |cos psi| / 4: sin psi uniform, either sign of cos. */
      sin_psi = 2.0 * ss_rng_uniform(rng) - 1.0;
      double c2 = 1.0 - sin_psi * sin_psi;
      cos_psi = (c2 > 0.0 ? sqrt(c2) : 0.0) * (1.0 - 2.0 * (double)(bits & 1u));
    } else {
      u = ss_flake_envelope_sample(mf, &mf->along, rng);
      ss_sample_uniform_azimuth(rng, &cos_psi, &sin_psi);
    }
    double r2 = 1.0 - u * u, r = r2 > 0.0 ? sqrt(r2) : 0.0;
    double wm = s * r * cos_psi + wl.z * u, envelope = s * r * fabs(cos_psi) + c * u;
    if (ss_rng_uniform(rng) * envelope < fabs(wm)) {
      *wm_out = wm;
      return ss_vec3_make(r * (cos_w * cos_psi - sin_w * sin_psi),
                          r * (sin_w * cos_psi + cos_w * sin_psi), u);
    }
  }
}

/* A scattering event in the axis frame (ss_microflake_sample_phase's,
 * with w_in and the result in mf->frame, the axis its z): a walk that keeps
 * its direction there changes frames only when it needs a world direction,
 * off the chain from one event to the next. */
static inline __attribute__((always_inline)) ss_vec3
ss_microflake_sample_phase_local(const ss_microflake *mf, ss_vec3 wl, ss_rng *rng) {
  const ss_flake_albedo *a = &mf->albedo;
  double alpha_max = a->alpha0 > a->alpha1 ? a->alpha0 : a->alpha1; /* no call to fmax */
  int constant = ss_flake_albedo_is_constant(a) || !(alpha_max > 0.0);
  /* |o|^2 = |w|^2 + 4 (w.m)^2 (|m|^2 - 1): scaling by 1.5 - |w|^2 / 2 undoes
   * the incoming direction's rounding to first order, and the flake adds
   * only its own few ulps, so lengths do not drift over a walk. The factor
   * is known before the flake is drawn (it is off the event's critical path). */
  double renorm = 1.5 - 0.5 * ss_vec3_dot(wl, wl);
  for (;;) {
    double wm;
    ss_vec3 m = ss_microflake_sample_flake(mf, wl, rng, &wm);
    if (constant || ss_rng_uniform(rng) * alpha_max < ss_microflake_albedo(mf, wm)) {
      /* Mirror reflection of the propagation direction about the flake:
       * no square root or division per event. */
      return ss_vec3_scale(ss_vec3_sub(wl, ss_vec3_scale(m, 2.0 * wm)), renorm);
    }
  }
}

#endif
