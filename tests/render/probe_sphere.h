/* The fixture of the entry-sampler tests: probe rays (probe.h) from a point
 * of a unit icosphere (level 4) under a BSSRDF model, where chords cross the
 * curved surface more than once. */
#ifndef SUBSURF_TESTS_PROBE_SPHERE_H
#define SUBSURF_TESTS_PROBE_SPHERE_H

#include "subsurf/accel.h"
#include "subsurf/bssrdf.h"
#include "subsurf/mesh.h"
#include "subsurf/probe.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>

typedef struct {
  ss_mesh *mesh;
  ss_accel *accel;
  ss_bssrdf *bssrdf;
  ss_probe probe;
} probe_sphere;

/* The exit point x_o is where the ray down -z from (0.3, 0.2, 5) meets the
 * sphere, seen from direction w_o. */
static inline void probe_sphere_setup(probe_sphere *f, const char *model, const ss_bssrdf_params *p,
                                      ss_vec3 w_o) {
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(1.0, 4, &f->mesh, &err), SS_OK, "%s", err.message);
  const ss_mesh *meshes[] = {f->mesh};
  cr_assert_eq(ss_accel_create(meshes, 1, &f->accel, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_bssrdf_create(model, p, &f->bssrdf, &err), SS_OK, "%s", err.message);
  ss_ray ray = {ss_vec3_make(0.3, 0.2, 5.0), ss_vec3_make(0.0, 0.0, -1.0), 0.0, INFINITY};
  ss_hit hit;
  cr_assert(ss_accel_intersect(f->accel, &ray, &hit));
  ss_probe_init(&f->probe, f->accel, hit.geom_id, f->bssrdf, hit.p, ss_frame_from_normal(hit.ng),
                w_o);
}

static inline void probe_sphere_teardown(probe_sphere *f) {
  ss_bssrdf_destroy(f->bssrdf);
  ss_accel_destroy(f->accel);
  ss_mesh_destroy(f->mesh);
}

/* The five random numbers of one entry sample. */
static inline void probe_sphere_uniforms(ss_rng *rng, double u[5]) {
  for (int k = 0; k < 5; ++k) {
    u[k] = ss_rng_uniform(rng);
  }
}

/* An entry sampler of the probe (ss_probe_sample_entry's signature). */
typedef int (*probe_sphere_sampler)(const ss_probe *p, const double u[5], ss_probe_sample *out,
                                    unsigned long long *queries);

/* n draws of `sample`: 1/p and 1/p^2 of each entry point summed into its
 * shell of |x - x_o| over [0, dmax) in `shells` equal shells. A point beyond
 * dmax fails the test, or with last_takes_beyond counts in the last shell. */
static inline void probe_sphere_shell_sums(const probe_sphere *f, probe_sphere_sampler sample,
                                           ss_rng *rng, int n, double dmax, int shells,
                                           int last_takes_beyond, double *sum, double *sum2) {
  for (int i = 0; i < n; ++i) {
    double u[5];
    probe_sphere_uniforms(rng, u);
    ss_probe_sample s;
    unsigned long long q = 0;
    if (!sample(&f->probe, u, &s, &q)) {
      continue;
    }
    double d = ss_vec3_length(ss_vec3_sub(s.hit.p, f->probe.x_o));
    int k = (int)(d / dmax * shells);
    if (last_takes_beyond) {
      k = k < shells ? k : shells - 1;
    }
    cr_assert_lt(k, shells, "an entry point beyond %g of x_o", dmax);
    sum[k] += 1.0 / s.pdf;
    sum2[k] += 1.0 / (s.pdf * s.pdf);
  }
}

#endif
