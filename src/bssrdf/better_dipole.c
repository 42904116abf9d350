/* d'Eon's "better dipole" (dEon2014).
 *
 * | option     | meaning                                                    |
 * |------------|------------------------------------------------------------|
 * | sigma_s, g | reduced scattering sigma_s' = (1 - g) sigma_s              |
 * | sigma_a    | absorption                                                 |
 * | eta        | n_inside / n_outside: Fresnel factors, C1, C2, A           |
 *
 * Compared with the classical dipole it uses Grosjean's diffusion
 * coefficient D_G, the extrapolated boundary z_b = 2 A D_G with
 * A = (1 + 3 C2)/(1 - 2 C1), and it counts both the fluence (C_phi) and the
 * flux (C_E) through the boundary. C1 and C2 are the moments of the Fresnel
 * reflectance of light arriving from inside (fresnel.h); appleseed's
 * betterdipolebssrdf.cpp passes outside/inside to its fit, which evaluates
 * the moments of light arriving from outside, a choice we do not follow
 * because the boundary condition concerns light reflected back inside.
 *
 * R(r) is the exitance per unit power entering, so S = Ft(w_i) R(r) Ft(w_o)
 * / (pi (1 - 2 C1(1/eta))): the exit lobe is normalised (as in pbrt-v3's
 * SeparableBSSRDF) and M(x_o) = Ft(w_i) R(r). */
#include "bssrdf/radial_model.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  ss_radial_model base;
  double c_phi, c_e;
  double alpha_prime[SS_BSSRDF_CHANNELS], sigma_tr[SS_BSSRDF_CHANNELS], D[SS_BSSRDF_CHANNELS];
  double z_r[SS_BSSRDF_CHANNELS], z_v[SS_BSSRDF_CHANNELS];
} better_dipole;

/* dEon2014's R(r) without its alpha'^2, for channel c:
 * the flux and fluence terms of a real source at depth z_r >= 0 and its image
 * at z_v < 0,
 *     (1/(4 pi)) [(C_E z_r (1 + s d_r)/d_r^2 + C_phi/D) e^{-s d_r}/d_r
 *                 - (C_E z_v (1 + s d_v)/d_v^2 + C_phi/D) e^{-s d_v}/d_v]. */
static double dipole_pair(const better_dipole *b, int c, double z_r, double z_v, double r2) {
  double s = b->sigma_tr[c];
  /* a source on the surface (z_r = 0, the hand-over's clamp) stays finite at r = 0 */
  double dr = fmax(sqrt(r2 + z_r * z_r), 1e-9 * b->z_r[c]), dv = sqrt(r2 + z_v * z_v);
  double kr = b->c_e * z_r * (1.0 + s * dr) / (dr * dr) + b->c_phi / b->D[c];
  double kv = b->c_e * z_v * (1.0 + s * dv) / (dv * dv) + b->c_phi / b->D[c];
  return (kr * exp(-s * dr) / dr - kv * exp(-s * dv) / dv) / (4.0 * SS_PI);
}

/* R(r) = alpha'^2 (pair at z_r, z_v). */
static void better_rd(const void *state, double r, double scale, double out[SS_BSSRDF_CHANNELS]) {
  const better_dipole *b = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double a2 = b->alpha_prime[c] * b->alpha_prime[c];
    out[c] = scale * a2 * dipole_pair(b, c, b->z_r[c], b->z_v[c], r * r);
  }
}

/* The point source at depth z (bssrdf.h): the pair with its real source at
 * z and the image mirrored about the extrapolated boundary, z_v = -(z +
 * 4 A D_G), times the one alpha' of d'Eon's point source that is not the
 * source's strength (Ferrier2016, table 4: R_phi^d and R_E^d carry rho'
 * besides Q's), so that R(r) = alpha' M(r; z_r). Its plane integral is
 * alpha' [C_E (e^{-s z} + e^{-s z_v'})/2 + C_phi (e^{-s z} - e^{-s z_v'})
 * / (2 D s)], z_v' = z + 4 A D_G: alpha' (C_E + 2 A C_phi) = 1 for any z
 * without absorption. */
static void better_point_source(const void *state, double z, double r,
                                double out[SS_BSSRDF_CHANNELS]) {
  const better_dipole *b = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    double two_z_b = -b->z_v[c] - b->z_r[c];
    out[c] = b->alpha_prime[c] * dipole_pair(b, c, z, -(z + two_z_b), r * r);
  }
}

static ss_status better_create(const ss_bssrdf_params *p, void **state, ss_error *err) {
  better_dipole *b = calloc(1, sizeof *b);
  if (!b) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "better-dipole: out of memory");
  }
  ss_radial_model_init(&b->base, p->eta, SS_RADIAL_EXIT_NORMALISED, better_rd);
  double c1 = ss_fresnel_moment(1, p->eta), c2 = ss_fresnel_moment(2, p->eta);
  b->c_phi = 0.25 * (1.0 - 2.0 * c1);
  b->c_e = 0.5 * (1.0 - 3.0 * c2);
  double A = (1.0 + 3.0 * c2) / (1.0 - 2.0 * c1);
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    ss_bssrdf_coeffs k =
        ss_bssrdf_coeffs_make(p->medium.sigma_s.c[c], p->medium.sigma_a.c[c], p->medium.g.c[c]);
    b->alpha_prime[c] = k.alpha_prime;
    b->sigma_tr[c] = k.sigma_tr_g;
    b->D[c] = k.D_g;
    b->z_r[c] = 1.0 / k.sigma_t_prime;
    b->z_v[c] = -b->z_r[c] - 4.0 * A * k.D_g;
    /* Plane integrals of each term: 2 pi int r z(1+s d)e^{-s d}/d^3 dr =
     * 2 pi sgn(z) e^{-s|z|}, 2 pi int r e^{-s d}/d dr = 2 pi e^{-s|z|}/s; the
     * difference of the latter is written with expm1 so that s -> 0 works. */
    double s = k.sigma_tr_g, zr = b->z_r[c], zv = fabs(b->z_v[c]);
    double flux = 0.5 * b->c_e * (exp(-s * zr) + exp(-s * zv));
    double gap = zv - zr;
    double fluence_diff = s > 0.0 ? -exp(-s * zr) * expm1(-s * gap) / s : gap;
    double fluence = 0.5 * b->c_phi / k.D_g * fluence_diff;
    b->base.total[c] = k.alpha_prime * k.alpha_prime * (flux + fluence);
    ss_radial_model_set_diffusion_sampler(&b->base, c, s, k.sigma_t_prime);
  }
  ss_radial_model_fit_sampler(&b->base, p);
  *state = b;
  return SS_OK;
}

const ss_bssrdf_ops ss_bssrdf_model_better_dipole = {
    .name = "better-dipole",
    .summary = "d'Eon's improved dipole: Grosjean D, fluence + flux boundary terms (d'Eon 2012)",
    .flags = SS_BSSRDF_RADIAL,
    .create = better_create,
    .destroy = free,
    .eval = ss_radial_model_eval,
    .sample_entry = ss_profile_sampler_sample_entry,
    .pdf_entry = ss_profile_sampler_pdf_entry,
    .max_radius = ss_profile_sampler_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = ss_radial_model_rd,
    .profile = ss_radial_model_profile,
    .exitance = ss_radial_model_exitance,
    .radiance_line = ss_radial_model_radiance_line,
    .brdf = ss_radial_model_brdf,
    .point_source_exitance = better_point_source,
};
