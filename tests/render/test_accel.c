#include "subsurf/accel.h"
#include "subsurf/mesh.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <criterion/criterion.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

static ss_mesh *icosphere(double r, unsigned k) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_icosphere(r, k, &m, &err), SS_OK, "%s", err.message);
  return m;
}

static ss_mesh *cube(double side, unsigned n) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_shape_cube(ss_vec3_make(side, side, side), n, &m, &err), SS_OK, "%s",
               err.message);
  return m;
}

static ss_accel *build(const ss_mesh *const *meshes, size_t n) {
  ss_accel *a = NULL;
  ss_error err;
  cr_assert_eq(ss_accel_create(meshes, n, &a, &err), SS_OK, "%s", err.message);
  return a;
}

/* Moeller & Trumbore 1997 in double: the reference for Embree's answers. */
static int brute_intersect(const ss_mesh *m, ss_vec3 o, ss_vec3 d, double *t_best, size_t *count) {
  *t_best = INFINITY;
  *count = 0;
  for (size_t i = 0; i < m->num_triangles; ++i) {
    ss_vec3 p[3];
    ss_mesh_triangle(m, i, p);
    ss_vec3 e1 = ss_vec3_sub(p[1], p[0]), e2 = ss_vec3_sub(p[2], p[0]);
    ss_vec3 pv = ss_vec3_cross(d, e2);
    double det = ss_vec3_dot(e1, pv);
    if (det == 0.0) {
      continue;
    }
    ss_vec3 tv = ss_vec3_sub(o, p[0]);
    double u = ss_vec3_dot(tv, pv) / det;
    ss_vec3 qv = ss_vec3_cross(tv, e1);
    double v = ss_vec3_dot(d, qv) / det, t = ss_vec3_dot(e2, qv) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0 || t <= 0.0) {
      continue;
    }
    (*count)++;
    *t_best = fmin(*t_best, t);
  }
  return isfinite(*t_best);
}

static ss_vec3 random_dir(ss_rng *rng) {
  return ss_sample_uniform_sphere(ss_rng_uniform(rng), ss_rng_uniform(rng));
}

Test(accel, closest_hit_matches_brute_force_and_the_analytic_sphere) {
  ss_mesh *m = icosphere(1.0, 3);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_rng rng;
  ss_rng_seed(&rng, 7, 1);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    ss_vec3 o = ss_vec3_scale(random_dir(&rng), 3.0);
    ss_vec3 target = ss_vec3_scale(random_dir(&rng), 1.2 * ss_rng_uniform(&rng));
    ss_vec3 d = ss_vec3_normalize(ss_vec3_sub(target, o));
    ss_ray ray = {o, d, 0.0, INFINITY};
    ss_hit h;
    double t_ref;
    size_t n;
    int hit = ss_accel_intersect(a, &ray, &h);
    int ref = brute_intersect(m, o, d, &t_ref, &n);
    /* Rays that graze within float precision of a silhouette may disagree. */
    if (hit != ref) {
      double b = ss_vec3_dot(o, d), c = ss_vec3_dot(o, o) - 1.0;
      cr_assert_lt(fabs(b * b - c), 0.02, "ray %d: embree %d, brute force %d", i, hit, ref);
      continue;
    }
    if (!hit) {
      continue;
    }
    ++hits;
    /* Float t and p lose accuracy as 1/cos at grazing incidence. */
    double tol = 1e-6 * (1.0 + 1.0 / fabs(ss_vec3_dot(d, h.ng)));
    cr_assert_float_eq(h.t, t_ref, tol, "ray %d", i);
    cr_assert_eq(h.geom_id, 0u);
    ss_vec3 p = ss_vec3_madd(o, d, h.t);
    cr_assert_lt(ss_vec3_length(ss_vec3_sub(p, h.p)), tol, "ray %d", i);
    /* Front hits from outside; normals within the tessellation error. */
    cr_assert_lt(ss_vec3_dot(d, h.ng), 0.0);
    ss_vec3 radial = ss_vec3_normalize(h.p);
    cr_assert_gt(ss_vec3_dot(h.ng, radial), 0.99);
    cr_assert_gt(ss_vec3_dot(h.ns, radial), 0.9999);
    cr_assert_float_eq(ss_vec3_length(h.ns), 1.0, 1e-12);
    /* Analytic sphere: the inscribed polyhedron is hit at most a sagitta later. */
    double b = ss_vec3_dot(o, d), c = ss_vec3_dot(o, o) - 1.0, disc = b * b - c;
    if (disc > 0.01) {
      double t_sphere = -b - sqrt(disc);
      cr_assert(h.t >= t_sphere - 1e-6 && h.t < t_sphere + 0.02 / sqrt(disc), "ray %d", i);
    }
  }
  cr_assert_gt(hits, 1000);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

Test(accel, distance_only_hits_agree_with_full_records_and_complete_to_them) {
  ss_mesh *m = icosphere(1.0, 4);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_rng rng;
  ss_rng_seed(&rng, 11, 1);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    /* Rays from outside and from inside the sphere (both sides of the normal). */
    ss_vec3 o = ss_vec3_scale(random_dir(&rng), i % 2 ? 3.0 : 0.9 * ss_rng_uniform(&rng));
    ss_vec3 target = ss_vec3_scale(random_dir(&rng), 0.8 * ss_rng_uniform(&rng));
    ss_vec3 d = i % 2 ? ss_vec3_sub(target, o) : ss_vec3_scale(random_dir(&rng), 1.5);
    ss_ray ray = {o, d, 0.0, i % 3 ? INFINITY : 0.5};
    ss_hit full, lazy;
    int hit = ss_accel_intersect(a, &ray, &full);
    cr_assert_eq(ss_accel_intersect_distance(a, &ray, &lazy), hit, "ray %d", i);
    if (!hit) {
      continue;
    }
    ++hits;
    cr_assert_eq(lazy.t, full.t, "ray %d", i);
    cr_assert_eq(lazy.prim_id, full.prim_id, "ray %d", i);
    cr_assert_gt(ss_vec3_dot(lazy.ng, full.ng), 1.0 - 1e-6, "ray %d", i);
    double tol = 1e-6 * (1.0 + 1.0 / fabs(ss_vec3_dot(ss_vec3_normalize(d), full.ng)));
    cr_assert_lt(ss_vec3_length(ss_vec3_sub(lazy.p, full.p)), tol, "ray %d", i);
    ss_accel_hit_complete(a, &lazy);
    cr_assert_eq(memcmp(&lazy, &full, sizeof lazy), 0, "ray %d", i);
  }
  cr_assert_gt(hits, 1000);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

Test(accel, cube_hits_are_exact_with_face_normals_and_uvs) {
  ss_mesh *m = cube(2.0, 4);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_rng rng;
  ss_rng_seed(&rng, 8, 1);
  for (int i = 0; i < 1000; ++i) {
    /* Aim along -z at the top face from above. */
    double x = 1.98 * ss_rng_uniform(&rng) - 0.99, y = 1.98 * ss_rng_uniform(&rng) - 0.99;
    ss_ray ray = {ss_vec3_make(x, y, 5.0), ss_vec3_make(0, 0, -2.0), 0.0, INFINITY};
    ss_hit h;
    cr_assert(ss_accel_intersect(a, &ray, &h));
    cr_assert_float_eq(h.t, 2.0, 1e-6); /* t in units of |d| = 2 */
    cr_assert_float_eq(h.ng.z, 1.0, 1e-12);
    cr_assert_float_eq(h.ns.z, 1.0, 1e-12);
    cr_assert_float_eq(h.p.x, x, 1e-6);
    cr_assert_float_eq(h.st[0], 0.5 * (x + 1.0), 1e-5);
    cr_assert_float_eq(h.st[1], 0.5 * (y + 1.0), 1e-5);
  }
  ss_ray miss = {ss_vec3_make(1.5, 0, 5.0), ss_vec3_make(0, 0, -1), 0.0, INFINITY};
  ss_hit h;
  cr_assert_not(ss_accel_intersect(a, &miss, &h));
  ss_ray short_ray = {ss_vec3_make(0, 0, 5.0), ss_vec3_make(0, 0, -1), 0.0, 3.9};
  cr_assert_not(ss_accel_intersect(a, &short_ray, &h));
  ss_ray late = {ss_vec3_make(0, 0, 5.0), ss_vec3_make(0, 0, -1), 4.5, INFINITY};
  cr_assert(ss_accel_intersect(a, &late, &h));
  cr_assert_float_eq(h.t, 6.0, 1e-6);
  cr_assert_lt(h.ng.z, -0.999); /* the bottom face, seen from inside */
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

Test(accel, shadow_rays_respect_tmax_and_geometry) {
  ss_mesh *m = icosphere(1.0, 3);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_vec3 zero = ss_vec3_make(0, 0, 0);
  ss_ray through = ss_ray_spawn_to(ss_vec3_make(-3, 0, 0), zero, ss_vec3_make(3, 0, 0), zero);
  cr_assert(ss_accel_occluded(a, &through));
  ss_ray beside = ss_ray_spawn_to(ss_vec3_make(-3, 1.1, 0), zero, ss_vec3_make(3, 1.1, 0), zero);
  cr_assert_not(ss_accel_occluded(a, &beside));
  ss_ray before = {ss_vec3_make(-3, 0, 0), ss_vec3_make(1, 0, 0), 0.0, 1.9};
  cr_assert_not(ss_accel_occluded(a, &before));
  before.tmax = 2.1;
  cr_assert(ss_accel_occluded(a, &before));
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

Test(accel, all_hits_count_the_crossings_of_random_segments) {
  ss_mesh *m = icosphere(1.0, 4);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_rng rng;
  ss_rng_seed(&rng, 9, 1);
  ss_hit hits[8];
  for (int i = 0; i < 3000; ++i) {
    ss_vec3 o = ss_vec3_scale(random_dir(&rng), 0.2 + 2.8 * ss_rng_uniform(&rng));
    ss_vec3 d = random_dir(&rng);
    double len = 4.0 * ss_rng_uniform(&rng);
    ss_ray ray = {o, d, 0.0, len};
    double t_ref;
    size_t n_ref;
    brute_intersect(m, o, d, &t_ref, &n_ref);
    /* Brute force counts the whole half-line: count its hits within len. */
    size_t n_seg = 0;
    for (size_t t = 0; t < m->num_triangles; ++t) {
      ss_mesh mt = *m;
      mt.indices = m->indices + 3 * t;
      mt.num_triangles = 1;
      double tt;
      size_t c;
      if (brute_intersect(&mt, o, d, &tt, &c) && tt < len) {
        ++n_seg;
      }
    }
    size_t n = ss_accel_intersect_all(a, &ray, 0, hits, 8);
    cr_assert_eq(n, n_seg, "segment %d: %zu hits, brute force %zu", i, n, n_seg);
    for (size_t k = 1; k < n && k < 8; ++k) {
      cr_assert_lt(hits[k - 1].t, hits[k].t, "hits must be sorted by t");
    }
  }
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

/* A segment through a vertex or an edge hits several triangles at the same
 * point; each crossing must count once. */
static void assert_crossings(const ss_accel *a, ss_vec3 from, ss_vec3 to, size_t expected,
                             const char *what) {
  ss_ray ray = {from, ss_vec3_sub(to, from), 0.0, 1.0};
  ss_hit hits[16];
  size_t n = ss_accel_intersect_all(a, &ray, 0, hits, 16);
  cr_assert_eq(n, expected, "%s: %zu crossings, expected %zu", what, n, expected);
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      cr_assert_neq(hits[i].prim_id, hits[j].prim_id, "%s: duplicate triangle", what);
    }
  }
}

Test(accel, all_hits_count_vertex_and_edge_crossings_once) {
  ss_mesh *c = cube(1.0, 1);
  const ss_mesh *cs[1] = {c};
  ss_accel *a = build(cs, 1);
  /* Through two opposite corners, two opposite edges, a face diagonal (the
   * edge between a face's two triangles) and the centre of a face. */
  assert_crossings(a, ss_vec3_make(-1, -1, -1), ss_vec3_make(1, 1, 1), 2, "corners");
  assert_crossings(a, ss_vec3_make(-1, -1, 0.3), ss_vec3_make(1, 1, 0.3), 2, "edges");
  assert_crossings(a, ss_vec3_make(0.2, 0.2, -2), ss_vec3_make(0.2, 0.2, 2), 2, "diagonal");
  assert_crossings(a, ss_vec3_make(0, 0, -2), ss_vec3_make(0, 0, 0), 1, "half");
  assert_crossings(a, ss_vec3_make(0.1, -0.2, -0.3), ss_vec3_make(0.3, 0.2, 0.1), 0, "inside");
  ss_accel_destroy(a);
  ss_mesh_destroy(c);

  ss_mesh *s = icosphere(1.0, 3);
  const ss_mesh *ss[1] = {s};
  a = build(ss, 1);
  ss_rng rng;
  ss_rng_seed(&rng, 10, 1);
  for (int i = 0; i < 500; ++i) {
    /* Aim from outside at a vertex, or at the midpoint of an edge. */
    size_t tri = ss_rng_next_u32(&rng) % s->num_triangles;
    ss_vec3 p[3];
    ss_mesh_triangle(s, tri, p);
    ss_vec3 target = (i % 2) ? p[0] : ss_vec3_scale(ss_vec3_add(p[0], p[1]), 0.5);
    ss_vec3 from = ss_vec3_madd(target, random_dir(&rng), 3.0);
    if (ss_vec3_length(from) < 1.1) {
      continue;
    }
    ss_vec3 dir = ss_vec3_normalize(ss_vec3_sub(target, from));
    /* A ray nearly tangent at the target may miss the rest of the sphere. */
    if (ss_vec3_dot(dir, ss_vec3_normalize(target)) > -0.2) {
      continue;
    }
    ss_vec3 to = ss_vec3_madd(target, dir, 3.0);
    assert_crossings(a, from, to, 2, (i % 2) ? "icosphere vertex" : "icosphere edge");
  }
  ss_accel_destroy(a);
  ss_mesh_destroy(s);
}

/* `count` copies of the unit cube [-0.5, 0.5]^3 along x, merged into one
 * mesh: copy k scaled by scale_x in x and moved by k step. */
static ss_mesh *cubes_along_x(size_t count, float scale_x, float step) {
  ss_mesh *one = cube(1.0, 1), *m = NULL;
  ss_error err;
  size_t nv = one->num_vertices, nt = one->num_triangles;
  cr_assert_eq(ss_mesh_create(count * nv, count * nt, 0, &m, &err), SS_OK);
  for (size_t k = 0; k < count; ++k) {
    for (size_t v = 0; v < nv; ++v) {
      float *q = m->positions + 3 * (k * nv + v);
      q[0] = scale_x * one->positions[3 * v] + step * (float)k;
      q[1] = one->positions[3 * v + 1];
      q[2] = one->positions[3 * v + 2];
    }
    for (size_t i = 0; i < 3 * nt; ++i) {
      m->indices[k * 3 * nt + i] = one->indices[i] + (uint32_t)(k * nv);
    }
  }
  ss_mesh_destroy(one);
  return m;
}

/* Three cubes along x, merged into one mesh, plus another object. */
Test(accel, all_hits_ignore_other_objects_and_sample_uniformly) {
  ss_mesh *m = cubes_along_x(3, 1.0f, 2.0f), *shell = icosphere(10.0, 2);
  const ss_mesh *ms[2] = {m, shell};
  ss_accel *a = build(ms, 2);
  ss_ray ray = {ss_vec3_make(-5, 0.1, 0.2), ss_vec3_make(1, 0, 0), 0.0, 15.0};
  ss_hit hits[8];
  size_t n = ss_accel_intersect_all(a, &ray, 0, hits, 8);
  cr_assert_eq(n, 6u);
  for (size_t k = 0; k < 6; ++k) {
    double expected = 5.0 - 0.5 + (double)(k / 2) * 2.0 + (double)(k % 2);
    cr_assert_float_eq(hits[k].t, expected, 1e-5);
    cr_assert_eq(hits[k].geom_id, 0u);
    cr_assert_float_eq(hits[k].ng.x, (k % 2) ? 1.0 : -1.0, 1e-12);
  }
  cr_assert_eq(ss_accel_intersect_all(a, &ray, 1, hits, 8), 1u); /* the shell, once */
  cr_assert_eq(ss_accel_intersect_all(a, &ray, 7, hits, 8), 0u); /* no such object */
  /* Fewer slots than hits: the closest are kept, the count is complete. */
  cr_assert_eq(ss_accel_intersect_all(a, &ray, 0, hits, 2), 6u);
  cr_assert_float_eq(hits[1].t, 5.5, 1e-5);

  /* Each hit is picked with probability 1/6: counts within 5 sigma. */
  enum { N = 60000 };
  size_t counts[6] = {0};
  ss_rng rng;
  ss_rng_seed(&rng, 11, 1);
  for (int i = 0; i < N; ++i) {
    ss_hit h;
    cr_assert_eq(ss_accel_intersect_sample(a, &ray, 0, ss_rng_uniform(&rng), &h), 6u);
    counts[(size_t)lround(h.t - 4.5)]++;
  }
  double mean = N / 6.0, sigma = sqrt(N * (1.0 / 6.0) * (5.0 / 6.0));
  for (int k = 0; k < 6; ++k) {
    cr_assert_lt(fabs((double)counts[k] - mean), 5.0 * sigma, "hit %d picked %zu times", k,
                 counts[k]);
  }
  ss_hit h;
  ss_ray away = {ss_vec3_make(-5, 3, 0), ss_vec3_make(1, 0, 0), 0.0, 15.0};
  cr_assert_eq(ss_accel_intersect_sample(a, &away, 0, 0.5, &h), 0u);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
  ss_mesh_destroy(shell);
}

Test(accel, all_hits_beyond_the_buffer_are_counted_and_sampled) {
  /* 50 thin slabs crossed by one ray: 100 crossings, more than the buffer. */
  const int slabs = 50;
  ss_mesh *m = cubes_along_x(slabs, 0.5f, 1.0f);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_ray ray = {ss_vec3_make(-1, 0.1, 0.1), ss_vec3_make(1, 0, 0), 0.0, 100.0};
  ss_hit hits[4];
  cr_assert_eq(ss_accel_intersect_all(a, &ray, 0, hits, 4), (size_t)(2 * slabs));
  ss_rng rng;
  ss_rng_seed(&rng, 12, 1);
  double sum_t = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    ss_hit h;
    cr_assert_eq(ss_accel_intersect_sample(a, &ray, 0, ss_rng_uniform(&rng), &h),
                 (size_t)(2 * slabs));
    sum_t += h.t;
  }
  /* Crossings at t = 1 + k +- 0.25: mean 25.5, sd of one pick ~14.4. */
  cr_assert_lt(fabs(sum_t / n - 25.5), 5.0 * 14.44 / sqrt(n), "mean t %g", sum_t / n);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

/* A ray leaving a surface point, offset with ss_ray_spawn, must not hit the
 * triangle it starts on: outward rays escape a convex mesh, inward rays
 * reach the far side. */
static void check_offsets(ss_vec3 centre, double radius, uint64_t seed) {
  ss_mesh *m = icosphere(radius, 4);
  ss_error err;
  cr_assert_eq(ss_mesh_transform(m, ss_mat4_translate(centre), &err), SS_OK);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  ss_rng rng;
  ss_rng_seed(&rng, seed, 1);
  for (int i = 0; i < 20000; ++i) {
    size_t tri = ss_rng_next_u32(&rng) % m->num_triangles;
    ss_vec3 p[3];
    ss_mesh_triangle(m, tri, p);
    double b1, b2;
    ss_sample_uniform_triangle(ss_rng_uniform(&rng), ss_rng_uniform(&rng), &b1, &b2);
    ss_vec3 x = ss_vec3_add(ss_vec3_scale(p[0], 1.0 - b1 - b2),
                            ss_vec3_add(ss_vec3_scale(p[1], b1), ss_vec3_scale(p[2], b2)));
    ss_vec3 ng = ss_vec3_normalize(ss_mesh_triangle_normal(m, tri));
    ss_vec3 d = random_dir(&rng);
    ss_ray ray = ss_ray_spawn(x, ng, d);
    ss_hit h;
    int hit = ss_accel_intersect(a, &ray, &h);
    if (ss_vec3_dot(d, ng) > 0.0) {
      cr_assert_not(hit, "outward ray %d re-hit triangle %u at t = %g", i, h.prim_id, h.t);
    } else {
      cr_assert(hit, "inward ray %d escaped the closed mesh", i);
      cr_assert_gt(ss_vec3_dot(h.ng, d), 0.0, "inward ray %d hit a front face", i);
      cr_assert(h.prim_id != tri || h.t > 1e-3 * radius, "inward ray %d self-hit", i);
      /* The inside probe from the offset point sees exactly one crossing. */
      ss_ray probe = {ray.o, d, 0.0, 3.0 * radius};
      ss_hit one;
      cr_assert_eq(ss_accel_intersect_all(a, &probe, 0, &one, 1), 1u, "probe %d", i);
    }
    /* A shadow ray between two surface points travels inside, unoccluded. */
    size_t tri2 = ss_rng_next_u32(&rng) % m->num_triangles;
    if (tri2 != tri) {
      ss_vec3 q[3];
      ss_mesh_triangle(m, tri2, q);
      ss_vec3 y = ss_vec3_scale(ss_vec3_add(q[0], ss_vec3_add(q[1], q[2])), 1.0 / 3.0);
      ss_vec3 ng2 = ss_mesh_triangle_normal(m, tri2);
      ss_ray s = ss_ray_spawn_to(x, ng, y, ng2);
      cr_assert_not(ss_accel_occluded(a, &s), "shadow ray %d inside the sphere is blocked", i);
    }
  }
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

Test(accel, offset_rays_never_self_intersect_near_the_origin) {
  check_offsets(ss_vec3_make(0, 0, 0), 1.0, 13);
  check_offsets(ss_vec3_make(0, 0, 0), 0.01, 14);
}

Test(accel, offset_rays_never_self_intersect_far_from_the_origin) {
  check_offsets(ss_vec3_make(1000, -2000, 500), 3.0, 15);
}

Test(accel, concurrent_queries_match_serial_ones) {
  ss_mesh *m = icosphere(1.0, 5);
  const ss_mesh *ms[1] = {m};
  ss_accel *a = build(ms, 1);
  enum { N = 20000 };
  double *serial = malloc(N * sizeof *serial), *parallel = malloc(N * sizeof *parallel);
  for (int pass = 0; pass < 2; ++pass) {
    double *out = pass ? parallel : serial;
#pragma omp parallel for num_threads(pass ? 2 : 1) schedule(dynamic, 64)
    for (int i = 0; i < N; ++i) {
      ss_rng rng;
      ss_rng_seed(&rng, 16, (uint64_t)i);
      ss_vec3 o = ss_vec3_scale(random_dir(&rng), 3.0);
      ss_ray ray = {o, ss_vec3_sub(ss_vec3_scale(random_dir(&rng), 0.5), o), 0.0, INFINITY};
      ss_hit h, s;
      double v = ss_accel_intersect(a, &ray, &h) ? h.t : -1.0;
      v += 10.0 * (double)ss_accel_intersect_sample(a, &ray, 0, ss_rng_uniform(&rng), &s);
      v += 100.0 * ss_accel_occluded(a, &ray);
      out[i] = v;
    }
  }
  cr_assert_eq(memcmp(serial, parallel, N * sizeof *serial), 0);
  free(serial);
  free(parallel);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
}

/* ss_accel_refine swaps in a high-quality BVH: every query (closest hit,
 * all hits, occlusion) answers as before, also for queries that run while
 * another thread builds it, and a second refine changes nothing. */
Test(accel, refined_bvh_answers_as_the_first_one_during_and_after_the_rebuild) {
  ss_mesh *m = icosphere(1.0, 5), *c = cube(0.5, 3);
  const ss_mesh *ms[2] = {m, c};
  ss_accel *a = build(ms, 2);
  cr_assert_eq(ss_accel_triangle_count(a), m->num_triangles + c->num_triangles);
  enum { N = 20000 };
  double *before = malloc(N * sizeof *before), *during = malloc(N * sizeof *during);
  double *after = malloc(N * sizeof *after);
  ss_status refined = SS_ERR_UNSUPPORTED;
  for (int pass = 0; pass < 3; ++pass) {
    double *out = pass == 0 ? before : pass == 1 ? during : after;
#pragma omp parallel for num_threads(2) schedule(dynamic, 64)
    for (int i = 0; i < N; ++i) {
      if (pass > 0 && i == N / 4) {
        ss_error err;
        ss_status st = ss_accel_refine(a, &err);
        if (pass == 1) {
          refined = st;
        }
      }
      ss_rng rng;
      ss_rng_seed(&rng, 17, (uint64_t)i);
      ss_vec3 o = ss_vec3_scale(random_dir(&rng), 3.0);
      ss_ray ray = {o, ss_vec3_sub(ss_vec3_scale(random_dir(&rng), 0.5), o), 0.0, INFINITY};
      ss_hit h, s;
      double v = ss_accel_intersect(a, &ray, &h) ? h.t + 1000.0 * h.geom_id + h.prim_id : -1.0;
      v += 1e7 * (double)ss_accel_intersect_sample(a, &ray, 0, ss_rng_uniform(&rng), &s);
      v += 1e8 * ss_accel_occluded(a, &ray);
      out[i] = v;
    }
  }
  cr_assert_eq(refined, SS_OK);
  cr_assert_eq(memcmp(before, during, N * sizeof *before), 0);
  cr_assert_eq(memcmp(before, after, N * sizeof *before), 0);
  free(before);
  free(during);
  free(after);
  ss_accel_destroy(a);
  ss_mesh_destroy(m);
  ss_mesh_destroy(c);
}

Test(accel, create_rejects_invalid_meshes_with_their_index) {
  ss_mesh *good = cube(1.0, 1), *bad = cube(1.0, 1);
  bad->indices[4] = 1000;
  const ss_mesh *ms[2] = {good, bad};
  ss_accel *a = NULL;
  ss_error err;
  cr_assert_eq(ss_accel_create(ms, 2, &a, &err), SS_ERR_PARSE);
  cr_assert(strstr(err.message, "mesh 1") != NULL, "%s", err.message);
  cr_assert_null(a);
  cr_assert_eq(ss_accel_create(ms, 0, &a, &err), SS_ERR_INVALID_ARGUMENT);
  ss_mesh_destroy(good);
  ss_mesh_destroy(bad);
}

/* The dedup tolerance follows the probe segment, not the scene: two tiny
 * cubes 0.2 mm apart inside a 1 km shell keep their four crossings. */
Test(accel, all_hits_resolve_small_features_in_large_scenes) {
  ss_mesh *a1 = cube(5e-4, 1), *a2 = cube(5e-4, 1), *shell = icosphere(1000.0, 2), *both = NULL;
  ss_error err;
  cr_assert_eq(ss_mesh_transform(a2, ss_mat4_translate(ss_vec3_make(7e-4, 0, 0)), &err), SS_OK);
  size_t nv = a1->num_vertices, nt = a1->num_triangles;
  cr_assert_eq(ss_mesh_create(2 * nv, 2 * nt, 0, &both, &err), SS_OK);
  memcpy(both->positions, a1->positions, 3 * nv * sizeof(float));
  memcpy(both->positions + 3 * nv, a2->positions, 3 * nv * sizeof(float));
  for (size_t i = 0; i < 3 * nt; ++i) {
    both->indices[i] = a1->indices[i];
    both->indices[3 * nt + i] = a2->indices[i] + (uint32_t)nv;
  }
  const ss_mesh *ms[2] = {both, shell};
  ss_accel *a = build(ms, 2);
  ss_ray ray = {ss_vec3_make(-1e-3, 1e-5, 2e-5), ss_vec3_make(1, 0, 0), 0.0, 3e-3};
  ss_hit hits[8];
  cr_assert_eq(ss_accel_intersect_all(a, &ray, 0, hits, 8), 4u);
  cr_assert_float_eq(hits[2].t, 1e-3 + 4.5e-4, 1e-8);
  ss_accel_destroy(a);
  ss_mesh_destroy(a1);
  ss_mesh_destroy(a2);
  ss_mesh_destroy(shell);
  ss_mesh_destroy(both);
}
