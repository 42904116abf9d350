/* Probe-ray entry sampling (probe.h) on a curved mesh: the MIS weights of the
 * nine (axis, channel) techniques sum to one, and the density the sampler
 * reports is the density it lands with (a brute-force histogram over
 * distance shells against uniform area sampling of the mesh). */
#include "subsurf/mesh.h"
#include "subsurf/probe.h"
#include "subsurf/rng.h"

#include "render/probe_sphere.h"
#include "render/shell_histogram.h"

#include <criterion/criterion.h>
#include <math.h>

/* A chromatic dipole whose probe radius is comparable to the unit sphere,
 * so that chords cross the curved surface more than once. */
static void setup(probe_sphere *f) {
  ss_bssrdf_params p;
  ss_bssrdf_params_default(&p);
  const double ss[3] = {20.0, 14.0, 10.0}, sa[3] = {2.0, 1.4, 2.8};
  for (int c = 0; c < 3; ++c) {
    p.medium.sigma_s.c[c] = ss[c];
    p.medium.sigma_a.c[c] = sa[c];
  }
  p.eta = 1.33;
  probe_sphere_setup(f, "dipole", &p, ss_vec3_make(0.0, 0.0, 1.0));
  cr_assert(f->probe.radius > 0.8 && f->probe.radius < 1.9, "probe radius %g", f->probe.radius);
}

/* The balance-heuristic weights of the nine (axis, channel) techniques at
 * the entry point x of density pdf sum to one, and the technique that drew
 * x (axis, channel) has a density > 0; hits is technique_pdf's hit count
 * argument (0: one-hit densities; 1: intensities). */
static void expect_weights_sum_to_one(const probe_sphere *f, const ss_hit *x, double pdf, int axis,
                                      int channel, int hits, unsigned long long *q) {
  double sum = 0.0, own = 0.0;
  for (int a = 0; a < SS_PROBE_AXES; ++a) {
    for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
      double p = ss_probe_technique_pdf(&f->probe, a, c, x, hits, q);
      sum += p / pdf;
      own = a == axis && c == channel ? p : own;
    }
  }
  cr_assert(fabs(sum - 1.0) < 1e-9, "weights sum to %.12g", sum);
  cr_assert_gt(own, 0.0, "the sampled technique has density 0");
}

Test(probe, mis_weights_over_axes_channels_hits_sum_to_one) {
  probe_sphere f;
  setup(&f);
  ss_rng rng;
  ss_rng_seed(&rng, 1, 2);
  int samples = 0, multi = 0;
  for (int i = 0; i < 4000; ++i) {
    double u[5];
    probe_sphere_uniforms(&rng, u);
    ss_probe_sample s;
    unsigned long long q = 0;
    if (!ss_probe_sample_entry(&f.probe, u, &s, &q)) {
      continue;
    }
    expect_weights_sum_to_one(&f, &s.hit, s.pdf, s.axis, s.channel, 0, &q);
    samples++;
    multi += s.hits > 1;
  }
  cr_assert_gt(samples, 2000);
  cr_assert_gt(multi, 20, "no chord crossed the sphere twice: the test is not curved enough");
  probe_sphere_teardown(&f);
}

#define SHELLS 6

/* E[1{x_i in shell} / p(x_i)] is the mesh area in the shell: measured from
 * the sampler, and by uniform area sampling of the mesh (brute force). */
Test(probe, density_matches_a_brute_force_histogram_on_a_sphere) {
  probe_sphere f;
  setup(&f);
  double R = f.probe.radius;
  double sum[SHELLS] = {0}, sum2[SHELLS] = {0};
  ss_rng rng;
  ss_rng_seed(&rng, 3, 4);
  const int n = 150000;
  probe_sphere_shell_sums(&f, ss_probe_sample_entry, &rng, n, R, SHELLS, 0, sum, sum2);
  long count[SHELLS] = {0};
  const int m = 400000;
  shell_histogram_brute_force(f.mesh, f.probe.x_o, R, SHELLS, m, &rng, count);
  shell_histogram_expect_match(sum, sum2, n, count, m, ss_mesh_area(f.mesh), SHELLS, "probe");
  probe_sphere_teardown(&f);
}

/* Every hit of a chord (ss_probe_sample_hits): one query per chord, and a
 * hit's density D(x_j) is the sum of the nine techniques' intensities (their
 * one-hit densities with a hit count of 1), the sampled technique's > 0, so
 * the balance-heuristic weights intensity / D sum to one. */
Test(probe, all_hits_weights_over_axes_channels_sum_to_one) {
  probe_sphere f;
  setup(&f);
  ss_rng rng;
  ss_rng_seed(&rng, 5, 6);
  int samples = 0, multi = 0;
  for (int i = 0; i < 3000; ++i) {
    double u[5];
    probe_sphere_uniforms(&rng, u);
    ss_probe_hits h;
    unsigned long long q = 0;
    size_t n = ss_probe_sample_hits(&f.probe, u, &h, &q);
    cr_assert_leq(q, 1, "%llu queries for one chord", q);
    for (size_t j = 0; j < n; ++j) {
      expect_weights_sum_to_one(&f, &h.hit[j], h.pdf[j], h.axis, h.channel, 1, &q);
    }
    samples += n > 0;
    multi += n > 1;
  }
  cr_assert_gt(samples, 1500);
  cr_assert_gt(multi, 20, "no chord crossed the sphere twice: the test is not curved enough");
  probe_sphere_teardown(&f);
}

/* E[sum_j 1{x_j in shell} / D(x_j)] over all hits of a chord is the mesh
 * area in the shell (against uniform area sampling, as above). */
Test(probe, all_hits_density_matches_a_brute_force_histogram_on_a_sphere) {
  probe_sphere f;
  setup(&f);
  double R = f.probe.radius;
  double sum[SHELLS] = {0}, sum2[SHELLS] = {0};
  ss_rng rng;
  ss_rng_seed(&rng, 3, 4);
  const int n = 150000;
  for (int i = 0; i < n; ++i) {
    double u[5];
    probe_sphere_uniforms(&rng, u);
    ss_probe_hits h;
    unsigned long long q = 0;
    double t[SHELLS] = {0};
    size_t hits = ss_probe_sample_hits(&f.probe, u, &h, &q);
    for (size_t j = 0; j < hits; ++j) {
      int k = (int)(ss_vec3_length(ss_vec3_sub(h.hit[j].p, f.probe.x_o)) / R * SHELLS);
      cr_assert_lt(k, SHELLS, "an entry point beyond the probe radius");
      t[k] += 1.0 / h.pdf[j];
    }
    for (int k = 0; k < SHELLS; ++k) {
      sum[k] += t[k];
      sum2[k] += t[k] * t[k];
    }
  }
  long count[SHELLS] = {0};
  const int m = 400000;
  shell_histogram_brute_force(f.mesh, f.probe.x_o, R, SHELLS, m, &rng, count);
  shell_histogram_expect_match(sum, sum2, n, count, m, ss_mesh_area(f.mesh), SHELLS, "all hits");
  probe_sphere_teardown(&f);
}
