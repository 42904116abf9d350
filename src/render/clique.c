/* Finding a k-clique (clique.h): vertices are ranked by degree, and each
 * clique is searched from its lowest-ranked vertex among that vertex's
 * higher-ranked neighbours (the ordering of ChibaNishizeki1985), so that a
 * vertex of high degree (a container holding many shapes) is only ever a
 * candidate, never the start of a search over all its neighbours; branches
 * that cannot reach k vertices are cut. */
#include "render/clique.h"

#include <stdlib.h>

typedef struct {
  size_t *start, *adj; /* compressed rows, each sorted by vertex */
  size_t *rank;        /* position in the order of (degree, vertex) */
  int k;
  size_t chosen[64];
  size_t **level; /* candidate lists, one per depth */
} graph;

static int adjacent(const graph *g, size_t u, size_t v) {
  size_t lo = g->start[u], hi = g->start[u + 1];
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (g->adj[mid] == v) {
      return 1;
    }
    if (g->adj[mid] < v) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return 0;
}

/* Extends the `depth` chosen vertices by k - depth of the n candidates
 * (each joined to all chosen ones). */
static int extend(graph *g, int depth, const size_t *cand, size_t n) {
  if (depth == g->k) {
    return 1;
  }
  for (size_t a = 0; a < n && (size_t)depth + (n - a) >= (size_t)g->k; ++a) {
    size_t *next = g->level[depth], m = 0;
    for (size_t b = a + 1; b < n; ++b) {
      if (adjacent(g, cand[a], cand[b])) {
        next[m++] = cand[b];
      }
    }
    g->chosen[depth] = cand[a];
    if ((size_t)depth + 1 + m >= (size_t)g->k && extend(g, depth + 1, next, m)) {
      return 1;
    }
  }
  return 0;
}

typedef struct {
  size_t degree, v;
} ranked;

static int by_degree(const void *pa, const void *pb) {
  const ranked *a = pa, *b = pb;
  if (a->degree != b->degree) {
    return a->degree < b->degree ? -1 : 1;
  }
  return a->v < b->v ? -1 : (a->v > b->v);
}

static int compare_size(const void *pa, const void *pb) {
  size_t a = *(const size_t *)pa, b = *(const size_t *)pb;
  return a < b ? -1 : (a > b);
}

static int build(graph *g, size_t n, const ss_box_pair *edges, size_t m) {
  g->start = calloc(n + 2, sizeof *g->start);
  g->adj = malloc((2 * m + 1) * sizeof *g->adj);
  g->rank = malloc((n + 1) * sizeof *g->rank);
  ranked *order = malloc((n + 1) * sizeof *order);
  if (!g->start || !g->adj || !g->rank || !order) {
    free(order);
    return -1;
  }
  for (size_t e = 0; e < m; ++e) {
    g->start[edges[e].i + 2]++;
    g->start[edges[e].j + 2]++;
  }
  for (size_t v = 0; v < n; ++v) {
    g->start[v + 2] += g->start[v + 1];
  }
  for (size_t e = 0; e < m; ++e) {
    g->adj[g->start[edges[e].i + 1]++] = edges[e].j;
    g->adj[g->start[edges[e].j + 1]++] = edges[e].i;
  }
  for (size_t v = 0; v < n; ++v) {
    qsort(g->adj + g->start[v], g->start[v + 1] - g->start[v], sizeof *g->adj, compare_size);
    order[v] = (ranked){g->start[v + 1] - g->start[v], v};
  }
  qsort(order, n, sizeof *order, by_degree);
  for (size_t r = 0; r < n; ++r) {
    g->rank[order[r].v] = r;
  }
  free(order);
  return 0;
}

int ss_clique_find(size_t n, const ss_box_pair *edges, size_t m, int k, size_t *clique) {
  graph g = {NULL, NULL, NULL, k, {0}, NULL};
  size_t *levels = NULL, *cand = NULL;
  size_t *level_ptr[64];
  int found = -1;
  if (build(&g, n, edges, m) != 0) {
    goto done;
  }
  size_t widest = 0;
  for (size_t v = 0; v < n; ++v) {
    size_t d = g.start[v + 1] - g.start[v];
    widest = d > widest ? d : widest;
  }
  levels = malloc(((size_t)k * widest + 1) * sizeof *levels);
  cand = malloc((widest + 1) * sizeof *cand);
  if (!levels || !cand) {
    goto done;
  }
  for (int d = 0; d < k; ++d) {
    level_ptr[d] = levels + (size_t)d * widest;
  }
  g.level = level_ptr;
  found = 0;
  for (size_t v = 0; v < n && !found; ++v) {
    size_t c = 0;
    for (size_t e = g.start[v]; e < g.start[v + 1]; ++e) {
      if (g.rank[g.adj[e]] > g.rank[v]) {
        cand[c++] = g.adj[e];
      }
    }
    g.chosen[0] = v;
    found = (size_t)c + 1 >= (size_t)k && extend(&g, 1, cand, c);
  }
  if (found) {
    for (int d = 0; d < k; ++d) {
      clique[d] = g.chosen[d];
    }
    qsort(clique, (size_t)k, sizeof *clique, compare_size);
  }
done:
  free(levels);
  free(cand);
  free(g.start);
  free(g.adj);
  free(g.rank);
  return found;
}
