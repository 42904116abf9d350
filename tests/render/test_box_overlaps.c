/* The broad phase of the scene's checks (box_overlaps.h) finds exactly the
 * pairs of boxes a test of all pairs finds, and the clique search
 * (clique.h) finds a set of k pairwise overlapping regions exactly when one
 * exists. */
#include "render/box_overlaps.h"
#include "render/clique.h"
#include "subsurf/rng.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

static int meet(ss_vec3 a0, ss_vec3 a1, ss_vec3 b0, ss_vec3 b1) {
  return a0.x <= b1.x && b0.x <= a1.x && a0.y <= b1.y && b0.y <= a1.y && a0.z <= b1.z &&
         b0.z <= a1.z;
}

Test(box_overlaps, finds_the_pairs_of_a_test_of_all_pairs) {
  enum { N = 600 };
  ss_vec3 *lo = malloc(N * sizeof *lo), *hi = malloc(N * sizeof *hi);
  ss_rng rng;
  ss_rng_seed(&rng, 7, 0);
  for (int k = 0; k < N; ++k) {
    /* Sizes spread over three decades, a few boxes touching exactly. */
    double s = 0.01 * pow(100.0, ss_rng_uniform(&rng));
    lo[k] =
        ss_vec3_make(ss_rng_uniform(&rng) * 4, ss_rng_uniform(&rng) * 4, ss_rng_uniform(&rng) * 4);
    hi[k] = ss_vec3_add(lo[k], ss_vec3_make(s, s, s));
  }
  for (int k = 0; k < 20; ++k) {
    lo[N - 1 - k] = ss_vec3_make(hi[k].x, lo[k].y, lo[k].z);
    hi[N - 1 - k] = ss_vec3_add(lo[N - 1 - k], ss_vec3_make(0.5, 0.5, 0.5));
  }
  ss_box_pair *pairs = NULL;
  size_t n = 0;
  ss_error err;
  cr_assert_eq(ss_box_overlaps(lo, hi, N, &pairs, &n, &err), SS_OK, "%s", err.message);
  size_t expected = 0, p = 0;
  for (size_t i = 0; i < N; ++i) {
    for (size_t j = i + 1; j < N; ++j) {
      if (!meet(lo[i], hi[i], lo[j], hi[j])) {
        continue;
      }
      ++expected;
      cr_assert(p < n && pairs[p].i == i && pairs[p].j == j, "pair (%zu, %zu) missing", i, j);
      ++p;
    }
  }
  cr_assert_eq(n, expected);
  cr_assert_gt(expected, 100);
  free(pairs);
  free(lo);
  free(hi);
}

Test(box_overlaps, one_box_or_none_has_no_pairs) {
  ss_vec3 lo = ss_vec3_make(0, 0, 0), hi = ss_vec3_make(1, 1, 1);
  ss_box_pair *pairs = NULL;
  size_t n = 7;
  ss_error err;
  cr_assert_eq(ss_box_overlaps(&lo, &hi, 1, &pairs, &n, &err), SS_OK);
  cr_assert_eq(n, 0);
  cr_assert_null(pairs);
}

/* The edges of a complete graph on the vertices listed, added to e. */
static size_t complete(const size_t *v, int k, ss_box_pair *e, size_t m) {
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      e[m++] = (ss_box_pair){v[a], v[b]};
    }
  }
  return m;
}

static int by_pair(const void *pa, const void *pb) {
  const ss_box_pair *a = pa, *b = pb;
  return a->i != b->i ? (a->i < b->i ? -1 : 1) : (a->j < b->j ? -1 : (a->j > b->j));
}

Test(clique, finds_a_hidden_clique_and_no_larger_one) {
  /* A ring of 200 vertices (each joined to its 3 next), a hub joined to all
   * of them, and a clique of 9 hidden among vertices 10, 20, ..., 90, 150. */
  enum { N = 201 };
  ss_box_pair *e = malloc(4000 * sizeof *e);
  size_t m = 0;
  for (size_t v = 0; v < 200; ++v) {
    for (size_t d = 1; d <= 3; ++d) {
      size_t w = (v + d) % 200;
      e[m++] = v < w ? (ss_box_pair){v, w} : (ss_box_pair){w, v};
    }
    e[m++] = (ss_box_pair){v, 200};
  }
  const size_t hidden[9] = {10, 20, 30, 40, 50, 60, 70, 80, 150};
  m = complete(hidden, 9, e, m);
  qsort(e, m, sizeof *e, by_pair);
  size_t u = 1;
  for (size_t k = 1; k < m; ++k) {
    if (by_pair(&e[k], &e[u - 1])) {
      e[u++] = e[k];
    }
  }
  size_t c[11];
  /* The hub completes the hidden clique to 10. */
  cr_assert_eq(ss_clique_find(N, e, u, 10, c), 1);
  for (int k = 0; k < 9; ++k) {
    cr_assert_eq(c[k], hidden[k]);
  }
  cr_assert_eq(c[9], 200);
  cr_assert_eq(ss_clique_find(N, e, u, 11, c), 0);
  free(e);
}

Test(clique, a_ring_holds_cliques_of_its_band_only) {
  /* Each of 200 vertices joined to its 3 next: cliques of 4, none of 5. */
  ss_box_pair e[600];
  size_t m = 0;
  for (size_t v = 0; v < 200; ++v) {
    for (size_t d = 1; d <= 3; ++d) {
      size_t w = (v + d) % 200;
      e[m++] = v < w ? (ss_box_pair){v, w} : (ss_box_pair){w, v};
    }
  }
  qsort(e, m, sizeof *e, by_pair);
  size_t c[5];
  cr_assert_eq(ss_clique_find(200, e, m, 4, c), 1);
  cr_assert_eq(c[1] - c[0] <= 3 || c[0] + 200 - c[3] <= 3, 1);
  cr_assert_eq(ss_clique_find(200, e, m, 5, c), 0);
}

Test(clique, a_graph_without_edges_has_no_pair) {
  size_t c[2];
  cr_assert_eq(ss_clique_find(5, NULL, 0, 2, c), 0);
}
