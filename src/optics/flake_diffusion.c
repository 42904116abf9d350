/* The diffusion matrix and absorption term of micro-flake media (Jakob2010
 * sec. 5.3, eq. 28-34). */
#include "subsurf/flake_diffusion.h"

#include "subsurf/quadrature.h"
#include "subsurf/sampling.h"

#include <math.h>

#define THETA_PANELS 8 /* 8-point panels per segment of the polar angle */
#define PHI_NODES 16   /* trapezoidal azimuth: exact for trigonometric degree < 16 */

typedef struct {
  const ss_microflake *mf;
  int i, j; /* the entry (i, j) of m m^T in the axis frame */
} moment_ctx;

static double local_component(ss_vec3 m, int i) { return ss_vec3_component(m, i); }

/* int_0^{2 pi} m_i m_j D(m) dphi at polar angle theta about the axis, times
 * sin(theta); m in the axis frame, D evaluated at the world direction. */
static double moment_integrand(void *vctx, double theta) {
  moment_ctx *x = vctx;
  double total = 0.0;
  for (int k = 0; k < PHI_NODES; ++k) {
    ss_vec3 local = ss_spherical_direction(cos(theta), 2.0 * SS_PI * k / PHI_NODES);
    ss_vec3 m = ss_frame_to_world(x->mf->frame, local);
    total +=
        local_component(local, x->i) * local_component(local, x->j) * ss_microflake_D(x->mf, m);
  }
  return total * (2.0 * SS_PI / PHI_NODES) * sin(theta);
}

/* theta = e + (o - e) t^2 over t in [0, 1] for a segment [e, o] (either
 * order) from a pole or the equator e, where D may behave like |cos|^p or
 * sin^p for a small non-integer p: the integrand becomes smooth in t. */
typedef struct {
  moment_ctx *x;
  double e, o;
} graded_ctx;

static double graded_integrand(void *vctx, double t) {
  graded_ctx *g = vctx;
  return moment_integrand(g->x, g->e + (g->o - g->e) * t * t) * 2.0 * fabs(g->o - g->e) * t;
}

/* Segments from the poles and the equator (the peaks of surface- and
 * fibre-like D, and where |cos|^p or sin^p is not smooth for a non-integer
 * p) to six peak widths 1 / sqrt(p + 1) away. */
static double integrate_theta(moment_ctx *x) {
  double w = fmin(0.25 * SS_PI, 6.0 / sqrt(x->mf->p + 1.0)), h = 0.5 * SS_PI;
  const double ends[4][2] = {{0.0, w}, {h, h - w}, {h, h + w}, {SS_PI, SS_PI - w}};
  double total = 0.0;
  for (int k = 0; k < 4; ++k) {
    graded_ctx g = {x, ends[k][0], ends[k][1]};
    total += ss_gl_integrate(graded_integrand, &g, 0.0, 1.0, THETA_PANELS);
  }
  if (h - w - w > 1e-12) {
    total += ss_gl_integrate(moment_integrand, x, w, h - w, THETA_PANELS) +
             ss_gl_integrate(moment_integrand, x, h + w, SS_PI - w, THETA_PANELS);
  }
  return total;
}

ss_mat3 ss_flake_second_moment(const ss_microflake *mf) {
  /* In the axis frame (s, t, v), then rotated: mu2 = F L F^T, F's columns
   * the frame's axes. */
  ss_mat3 local;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      moment_ctx x = {mf, i, j};
      local.m[i][j] = local.m[j][i] = integrate_theta(&x);
    }
  }
  ss_mat3 f = {{{mf->frame.s.x, mf->frame.t.x, mf->frame.n.x},
                {mf->frame.s.y, mf->frame.t.y, mf->frame.n.y},
                {mf->frame.s.z, mf->frame.t.z, mf->frame.n.z}}};
  return ss_mat3_mul(f, ss_mat3_mul(local, ss_mat3_transpose(f)));
}

ss_flake_albedo_moments ss_flake_albedo_constants(const ss_microflake *mf) {
  /* With alpha(c) = alpha0 + (alpha1 - alpha0) c^k and c = |cos theta|,
   * eq. 29, 32 and 33 integrate in closed form over c in [0, 1]:
   * alpha_hat = 2 int alpha c, c1 = 2 int alpha c (1 - c^2),
   * c2 = 4 int alpha c^3 (alpha, alpha / 2, alpha for a constant albedo). */
  const ss_flake_albedo *a = &mf->albedo;
  double d = a->alpha1 - a->alpha0, k = a->k;
  if (a->alpha0 == a->alpha1 || k == 0.0) {
    d = 0.0;
  }
  double base = d == 0.0 ? a->alpha1 : a->alpha0;
  ss_flake_albedo_moments r = {base + d * 2.0 / (k + 2.0),
                               0.5 * base + d * 2.0 * (1.0 / (k + 2.0) - 1.0 / (k + 4.0)),
                               base + d * 4.0 / (k + 4.0)};
  return r;
}

ss_mat3 ss_flake_diffusion_matrix(const ss_microflake *mf, double density) {
  ss_flake_albedo_moments c = ss_flake_albedo_constants(mf);
  /* Jakob et al. 2010, eq. 31 (eq. 34 when alpha is constant). */
  double k = 9.0 * density / 8.0;
  ss_mat3 mu2 = ss_flake_second_moment(mf);
  return ss_mat3_add(ss_mat3_scale(mu2, k * (1.0 + 2.0 * c.c1 + 2.0 * c.c2)),
                     ss_mat3_scale(ss_mat3_identity(), k * (1.0 - 2.0 * c.c1)));
}

double ss_flake_diffusion_mu0(const ss_microflake *mf, double density) {
  /* Jakob et al. 2010, eq. 28. */
  return 2.0 * density * SS_PI * (1.0 - ss_flake_albedo_constants(mf).alpha_hat);
}

double ss_flake_medium_density(double sigma_s, double sigma_a) { return 2.0 * (sigma_s + sigma_a); }

ss_flake_first_event ss_flake_reduced_first_event(const ss_microflake *mf, double density,
                                                  ss_vec3 w) {
  double alpha = ss_microflake_collision_albedo(mf, w);
  double wg = ss_vec3_dot(w, ss_microflake_scattered_mean_lookup(mf, w));
  double reduced = 1.0 - alpha * wg; /* > 0: |w.g| < 1 and alpha <= 1 */
  return (ss_flake_first_event){density * ss_microflake_sigma_t(mf, w) * reduced,
                                reduced > 0.0 ? alpha * (1.0 - wg) / reduced : 0.0};
}
