/* An entry sampler fitted to a model's own radial profile (private to
 * src/bssrdf): per channel, the radius is drawn from a tabulated inverse CDF
 * of the ring density 2 pi r R(r), linear between the nodes of a geometric
 * grid shared by the channels, blended with a small share of an exponential
 * mixture (defensive sampling, Hesterberg 1995) so that every radius the
 * model can reach keeps a non-zero density even where the tabulated shape
 * (e.g. one incidence of an angular model) is zero. The azimuth is uniform.
 * The pdf is exact for what is drawn: the table's piecewise-linear density
 * plus the mixture's. */
#ifndef SUBSURF_BSSRDF_PROFILE_SAMPLER_H
#define SUBSURF_BSSRDF_PROFILE_SAMPLER_H

#include "bssrdf/bssrdf_util.h"

#define SS_PROFILE_SAMPLER_NODES 512

typedef struct {
  /* nodes r_0 = 0, r_k = r1 q^(k-1) for k >= 1 */
  double r1, inv_log_q;
  double r[SS_PROFILE_SAMPLER_NODES];
  double f[SS_BSSRDF_CHANNELS][SS_PROFILE_SAMPLER_NODES];   /* 2 pi r R(r), normalised */
  double cdf[SS_BSSRDF_CHANNELS][SS_PROFILE_SAMPLER_NODES]; /* of the table, to node k */
  double table_weight[SS_BSSRDF_CHANNELS];                  /* 0 where the profile gave no shape */
  double max_radius[SS_BSSRDF_CHANNELS];
  ss_radial_mix mix[SS_BSSRDF_CHANNELS]; /* the defensive share */
} ss_profile_sampler;

/* One fills R(r) for the three channels (any scale per channel). */
typedef void (*ss_profile_shape_fn)(const void *ctx, double r, double out[SS_BSSRDF_CHANNELS]);

/* Tabulates `shape` from r_lo (below the core of every channel) to r_hi
 * (beyond the tail of every channel) and keeps `mix` (per channel) as the
 * defensive share of weight `defensive` in (0, 1]. */
void ss_profile_sampler_init(ss_profile_sampler *s, ss_profile_shape_fn shape, const void *ctx,
                             double r_lo, double r_hi, const ss_radial_mix mix[SS_BSSRDF_CHANNELS],
                             double defensive);
/* No table: the mixtures alone (what ss_radial_mix_sample draws, same pdf). */
void ss_profile_sampler_init_mixture(ss_profile_sampler *s,
                                     const ss_radial_mix mix[SS_BSSRDF_CHANNELS]);
/* The shape of a diffusion profile: r_lo = 0.005 / max sigma_t', r_hi = twice
 * the widest mixture's max radius. */
void ss_profile_sampler_init_diffusion(ss_profile_sampler *s, ss_profile_shape_fn shape,
                                       const void *ctx,
                                       const ss_radial_mix mix[SS_BSSRDF_CHANNELS]);

void ss_profile_sampler_sample(const ss_profile_sampler *s, int channel, double u1, double u2,
                               ss_bssrdf_entry *e);
/* Density per unit area of the tangent plane. */
double ss_profile_sampler_pdf(const ss_profile_sampler *s, int channel, double r);

/* The ops hooks of a model whose state begins with an ss_profile_sampler. */
int ss_profile_sampler_sample_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                    double u1, double u2, ss_bssrdf_entry *e);
double ss_profile_sampler_pdf_entry(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                                    double r, double phi);
double ss_profile_sampler_max_radius(const void *state, int channel);

#endif
