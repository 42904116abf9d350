/* Refinement where the medium varies (src/fem/fem_size_field.c): the size
 * field of a density step and of a turn of an anisotropic medium's axis,
 * the mesh it gives, and the solution's error against a mesh that conforms
 * to the step, at equal element count with a uniform mesh. */
#include "fem/fem_internal.h"
#include "subsurf/fem.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* An isotropic medium whose density is `ratio` for 0 <= x < width and 1
 * elsewhere (width INFINITY: a step at x = 0). */
typedef struct {
  double sigma_s_prime, sigma_a, ratio, width;
} step_medium;

static ss_status step(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  (void)err;
  const step_medium *m = ctx;
  double d = x.x >= 0.0 && x.x < m->width ? m->ratio : 1.0;
  *out = ss_fem_coeffs_isotropic(d * m->sigma_s_prime, d * m->sigma_a);
  return SS_OK;
}

/* An anisotropic medium (M = diag(1, 4, 4) about its axis) whose axis is x
 * for x < 0 and y from x = 0: the density is the same everywhere. */
static ss_status turn(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  (void)ctx;
  (void)err;
  ss_fem_coeffs c = {.M = {0}, .mu0 = 0.1};
  c.M[0] = x.x < 0.0 ? 1.0 : 4.0;
  c.M[4] = x.x < 0.0 ? 4.0 : 1.0;
  c.M[8] = 4.0;
  *out = c;
  return SS_OK;
}

static const ss_vec3 LO = {-4.0, -2.0, -2.0}, HI = {4.0, 2.0, 0.0};

static ss_fem_size_field *field(ss_fem_medium_fn fn, void *ctx, double size_min, double size_max) {
  ss_fem_size_options o = {.lo = LO,
                           .hi = HI,
                           .spacing = 0.125,
                           .tolerance = 0.1,
                           .size_min = size_min,
                           .size_max = size_max,
                           .grade = 0.5};
  ss_fem_size_field *f = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_fem_size_field_from_medium(fn, ctx, &o, &f, &err), SS_OK, "%s", err.message);
  return f;
}

Test(fem_medium_size, a_density_step_or_a_turn_of_the_axis_gets_small_sizes_graded_away) {
  step_medium med = {0.25, 0.025, 4.0, INFINITY};
  ss_fem_medium_fn fns[2] = {step, turn};
  for (int k = 0; k < 2; ++k) {
    ss_fem_size_field *f = field(fns[k], &med, 0.1, 0.8);
    cr_assert_float_eq(ss_fem_size_field_min(f), 0.1, 1e-6);
    for (double x = -3.9; x < 3.9; x += 0.05) {
      double s = ss_fem_size_field_at(f, ss_vec3_make(x, 0.3, -1.1)), d = fabs(x);
      /* size_min within the samples next to the step, then growing by at
       * most the grade (26-neighbour chamfer: within 10 % of Euclidean) */
      cr_assert(s >= 0.1 - 1e-6 && s <= 0.8 + 1e-6, "x %g: size %g", x, s);
      cr_assert_leq(s, 0.1 + 0.5 * (d + 0.125) + 1e-6, "x %g: size %g", x, s);
      cr_assert_geq(s, fmin(0.8, 0.1 + 0.5 * 0.9 * (d - 0.125)) - 1e-6, "x %g: size %g", x, s);
    }
    ss_fem_size_field_destroy(f);
  }
  /* a homogeneous medium needs no refinement */
  step_medium flat = {0.25, 0.025, 1.0, INFINITY};
  ss_fem_size_field *f = field(step, &flat, 0.1, 0.8);
  cr_assert_float_eq(ss_fem_size_field_min(f), 0.8, 1e-6);
  ss_fem_size_field_destroy(f);
}

Test(fem_medium_size, bad_options_are_named) {
  step_medium med = {0.25, 0.025, 4.0, INFINITY};
  ss_fem_size_options good = {LO, HI, 0.125, 0.1, 0.1, 0.8, 0.3};
  ss_fem_size_options bad[4] = {good, good, good, good};
  bad[0].hi = LO;
  bad[1].spacing = 0.0;
  bad[2].size_min = 1.0;
  bad[3].grade = NAN;
  const char *words[4] = {"box", "spacing", "sizes", "grade"};
  for (int i = 0; i < 4; ++i) {
    ss_fem_size_field *f = NULL;
    ss_error err = {0};
    cr_assert_eq(ss_fem_size_field_from_medium(step, &med, &bad[i], &f, &err),
                 SS_ERR_INVALID_ARGUMENT);
    cr_assert_null(f);
    cr_assert(strstr(err.message, words[i]), "%s", err.message);
  }
}

/* A structured mesh of the box (cubes of side h, six tetrahedra each around
 * the cube's diagonal): its faces lie on the planes x = k h, so with h
 * dividing 4 every tetrahedron is on one side of the step. */
static ss_fem_mesh *conforming_box(double h) {
  int n[3] = {(int)lround((HI.x - LO.x) / h), (int)lround((HI.y - LO.y) / h),
              (int)lround((HI.z - LO.z) / h)};
  size_t nv = (size_t)(n[0] + 1) * (size_t)(n[1] + 1) * (size_t)(n[2] + 1);
  size_t nc = (size_t)n[0] * (size_t)n[1] * (size_t)n[2];
  double *pos = malloc(3 * nv * sizeof *pos);
  uint32_t *tets = malloc(24 * nc * sizeof *tets);
  cr_assert(pos && tets);
#define VID(i, j, k) ((uint32_t)(((k) * (n[1] + 1) + (j)) * (n[0] + 1) + (i)))
  for (int k = 0; k <= n[2]; ++k) {
    for (int j = 0; j <= n[1]; ++j) {
      for (int i = 0; i <= n[0]; ++i) {
        double *p = pos + 3 * VID(i, j, k);
        p[0] = LO.x + i * h;
        p[1] = LO.y + j * h;
        p[2] = LO.z + k * h;
      }
    }
  }
  static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  size_t t = 0;
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        for (int p = 0; p < 6; ++p) {
          int c[3] = {i, j, k};
          tets[t++] = VID(c[0], c[1], c[2]);
          for (int s = 0; s < 2; ++s) {
            c[perm[p][s]]++;
            tets[t++] = VID(c[0], c[1], c[2]);
          }
          tets[t++] = VID(i + 1, j + 1, k + 1);
        }
      }
    }
  }
#undef VID
  ss_fem_mesh *m = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_fem_mesh_create(pos, nv, tets, 6 * nc, &m, &err), SS_OK, "%s", err.message);
  free(pos);
  free(tets);
  return m;
}

static ss_fem_solution *solve(const ss_fem_mesh *m, step_medium *med) {
  ss_fem_problem pb = {.eta = 1.3, .point = {-2.0, 0.1, -1.05}, .point_power = 1.0};
  ss_fem_solve_options so = {.solver = SS_FEM_PCG, .tolerance = 1e-10, .max_iterations = 100000};
  ss_fem_solution *s = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_fem_solve(m, step, med, &pb, &so, &s, &err), SS_OK, "%s", err.message);
  return s;
}

/* The fluence of (m, s) at the points of a regular lattice inside the box
 * (80 x 40 x 20, cell centres): *out (allocated). */
#define PX 80
#define PY 40
#define PZ 20
static double *on_points(const ss_fem_mesh *m, const ss_fem_solution *s) {
  ss_fem_grid g;
  ss_error err = {0};
  cr_assert_eq(ss_fem_grid_build(m, &g, &err), SS_OK, "%s", err.message);
  double *v = malloc(PX * PY * PZ * sizeof *v);
  cr_assert(v);
  for (int k = 0; k < PZ; ++k) {
    for (int j = 0; j < PY; ++j) {
      for (int i = 0; i < PX; ++i) {
        ss_vec3 x = ss_vec3_make(LO.x + (i + 0.5) * (HI.x - LO.x) / PX,
                                 LO.y + (j + 0.5) * (HI.y - LO.y) / PY,
                                 LO.z + (k + 0.5) * (HI.z - LO.z) / PZ);
        size_t t;
        double l[4], f = 0.0;
        cr_assert(ss_fem_grid_locate(&g, m, x, &t, l), "point %g %g %g", x.x, x.y, x.z);
        for (int a = 0; a < 4; ++a) {
          f += l[a] * s->fluence[m->tets[4 * t + (size_t)a]];
        }
        v[(k * PY + j) * PX + i] = f;
      }
    }
  }
  ss_fem_grid_free(&g);
  return v;
}

/* Over the lattice's points beyond x = 0.5: the light that crossed the
 * layer. */
static double relative_l2_beyond(const double *a, const double *ref) {
  double num = 0.0, den = 0.0;
  for (int i = 0; i < PX * PY * PZ; ++i) {
    if (LO.x + (i % PX + 0.5) * (HI.x - LO.x) / PX < 0.5) {
      continue;
    }
    num += (a[i] - ref[i]) * (a[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return sqrt(num / den);
}

static ss_fem_mesh *gmsh_box(double size, const ss_fem_size_field *f) {
  ss_fem_mesh_options o = {.size_max = size, .size_min = size, .medium_size = f};
  ss_fem_mesh *m = NULL;
  ss_error err = {0};
  cr_assert_eq(ss_fem_mesh_box(LO, HI, &o, &m, &err), SS_OK, "%s", err.message);
  return m;
}

/* The mean longest edge of the tetrahedra crossing x = 0 and of those
 * beyond |x| > 3. */
static void edges_at_step(const ss_fem_mesh *m, double *at, double *far) {
  double sum[2] = {0, 0};
  size_t count[2] = {0, 0};
  for (size_t t = 0; t < m->num_tets; ++t) {
    double lo = INFINITY, hi = -INFINITY, e = 0.0;
    for (int a = 0; a < 4; ++a) {
      const double *p = m->positions + 3 * m->tets[4 * t + (size_t)a];
      lo = fmin(lo, p[0]);
      hi = fmax(hi, p[0]);
      for (int b = 0; b < a; ++b) {
        const double *q = m->positions + 3 * m->tets[4 * t + (size_t)b];
        e = fmax(e, sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                         (p[2] - q[2]) * (p[2] - q[2])));
      }
    }
    int which = lo < 0.0 && hi > 0.0 ? 0 : (lo > 3.0 || hi < -3.0 ? 1 : -1);
    if (which >= 0) {
      sum[which] += e;
      count[which]++;
    }
  }
  *at = sum[0] / (double)count[0];
  *far = sum[1] / (double)count[1];
}

Test(fem_medium_size, refining_at_a_dense_layer_beats_uniform_elements_of_equal_count,
     .timeout = 600) {
  /* a dense layer (two steps 0.25 apart: a membrane, a latewood band),
   * transport mean free paths 4 outside and 0.2 inside; the light of a
   * point source at x = -2 crosses it. The conforming mesh of 0.125 is the
   * reference (with 0.0625 instead the errors below move by 3 %). */
  step_medium med = {0.25, 0.0025, 20.0, 0.25};
  ss_fem_mesh *ref = conforming_box(0.125);
  ss_fem_solution *rs = solve(ref, &med);
  double *rv = on_points(ref, rs);

  ss_fem_size_field *f = field(step, &med, 0.1, 0.8);
  ss_fem_mesh *graded = gmsh_box(0.8, f);
  double at, far;
  edges_at_step(graded, &at, &far);
  cr_log_info("graded: %zu tetrahedra, mean longest edge %g at the step, %g beyond |x| > 3",
              graded->num_tets, at, far);
  cr_assert_lt(at, 2.5 * 0.1, "longest edges at the step %g", at);
  cr_assert_gt(far, 0.6 * 0.8, "longest edges far from it %g", far);

  /* a uniform mesh of at least as many tetrahedra (within 20 %) */
  double h = 0.8 * cbrt(2.0 * (8.0 * 4.0 * 2.0) / (0.8 * 0.8 * 0.8) / (double)graded->num_tets);
  ss_fem_mesh *uniform = NULL;
  for (int tries = 0; tries < 6; ++tries) {
    uniform = gmsh_box(h, NULL);
    double ratio = (double)uniform->num_tets / (double)graded->num_tets;
    if (ratio >= 1.0 && ratio <= 1.2) {
      break;
    }
    ss_fem_mesh_destroy(uniform);
    uniform = NULL;
    h *= cbrt(ratio / 1.1);
  }
  cr_assert_not_null(uniform, "no uniform mesh of about %zu tetrahedra", graded->num_tets);

  ss_fem_solution *gs = solve(graded, &med), *us = solve(uniform, &med);
  double *gv = on_points(graded, gs), *uv = on_points(uniform, us);
  double eg = relative_l2_beyond(gv, rv), eu = relative_l2_beyond(uv, rv);
  cr_log_info("relative L2 error: graded %g (%zu tetrahedra), uniform %g (%zu, h %g)", eg,
              graded->num_tets, eu, uniform->num_tets, h);
  cr_assert_lt(eg, 0.5 * eu, "graded %g, uniform %g", eg, eu);

  free(rv);
  free(gv);
  free(uv);
  ss_fem_solution_destroy(rs);
  ss_fem_solution_destroy(gs);
  ss_fem_solution_destroy(us);
  ss_fem_mesh_destroy(ref);
  ss_fem_mesh_destroy(graded);
  ss_fem_mesh_destroy(uniform);
  ss_fem_size_field_destroy(f);
}
