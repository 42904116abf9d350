/* The irradiance octree (irradiance_octree.h; Jensen & Buhler 2002, sec. 3). */
#include "subsurf/irradiance_octree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  ss_irradiance_octree *t;
  size_t cap;
  ss_irradiance_point *tmp;
} builder;

static int new_node(builder *b, int32_t *index) {
  if (b->t->num_nodes == b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 64;
    ss_octree_node *n = realloc(b->t->nodes, cap * sizeof *n);
    if (!n) {
      return 0;
    }
    b->t->nodes = n;
    b->cap = cap;
  }
  *index = (int32_t)b->t->num_nodes++;
  return 1;
}

static ss_vec3 vmin(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}

static ss_vec3 vmax(ss_vec3 a, ss_vec3 b) {
  return ss_vec3_make(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}

/* The node's bounds and aggregates, summed over its range in order. */
static void aggregate(ss_octree_node *node, const ss_irradiance_point *p) {
  ss_vec3 lo = p[node->begin].p, hi = lo, cw = ss_vec3_make(0, 0, 0), ca = cw, nw = cw, na = cw;
  double wsum = 0.0;
  node->power = ss_rgb_gray(0.0);
  node->area = 0.0;
  for (uint32_t i = node->begin; i < node->end; ++i) {
    lo = vmin(lo, p[i].p);
    hi = vmax(hi, p[i].p);
    node->power = ss_rgb_add(node->power, p[i].power);
    node->area += p[i].area;
    double w = ss_rgb_luminance(p[i].power);
    wsum += w;
    cw = ss_vec3_madd(cw, p[i].p, w);
    nw = ss_vec3_madd(nw, p[i].n, w);
    ca = ss_vec3_madd(ca, p[i].p, p[i].area);
    na = ss_vec3_madd(na, p[i].n, p[i].area);
  }
  node->lo = lo;
  node->hi = hi;
  int by_power = wsum > 0.0 && isfinite(wsum);
  node->centroid = by_power ? ss_vec3_scale(cw, 1.0 / wsum)
                            : ss_vec3_scale(ca, node->area > 0.0 ? 1.0 / node->area : 0.0);
  ss_vec3 n = by_power ? nw : na;
  double len = ss_vec3_length(n);
  node->normal = len > 0.0 ? ss_vec3_scale(n, 1.0 / len) : p[node->begin].n;
}

static int octant(ss_vec3 p, ss_vec3 c) {
  return (p.x > c.x) | (p.y > c.y) << 1 | (p.z > c.z) << 2;
}

static int build(builder *b, uint32_t begin, uint32_t end, int depth, int32_t *index) {
  if (!new_node(b, index)) {
    return 0;
  }
  ss_irradiance_point *p = (ss_irradiance_point *)b->t->points;
  ss_octree_node node;
  memset(&node, 0, sizeof node);
  node.begin = begin;
  node.end = end;
  for (int k = 0; k < 8; ++k) {
    node.child[k] = -1;
  }
  aggregate(&node, p);
  ss_vec3 ext = ss_vec3_sub(node.hi, node.lo);
  int leaf = end - begin <= SS_OCTREE_LEAF_POINTS || depth >= SS_OCTREE_MAX_DEPTH ||
             !(fmax(ext.x, fmax(ext.y, ext.z)) > 0.0);
  b->t->nodes[*index] = node;
  if (leaf) {
    return 1;
  }
  /* the children reorder the range: the aggregates are summed again after them */
  /* a stable partition by octant of the bounds' centre */
  ss_vec3 c = ss_vec3_scale(ss_vec3_add(node.lo, node.hi), 0.5);
  uint32_t start[9] = {0};
  for (uint32_t i = begin; i < end; ++i) {
    start[octant(p[i].p, c) + 1]++;
  }
  for (int k = 0; k < 8; ++k) {
    start[k + 1] += start[k];
  }
  uint32_t fill[8];
  memcpy(fill, start, sizeof fill);
  for (uint32_t i = begin; i < end; ++i) {
    b->tmp[fill[octant(p[i].p, c)]++] = p[i];
  }
  memcpy(p + begin, b->tmp, (size_t)(end - begin) * sizeof *p);
  for (int k = 0; k < 8; ++k) {
    if (start[k + 1] > start[k]) {
      int32_t child;
      if (!build(b, begin + start[k], begin + start[k + 1], depth + 1, &child)) {
        return 0;
      }
      b->t->nodes[*index].child[k] = child;
    }
  }
  aggregate(&b->t->nodes[*index], p);
  return 1;
}

ss_status ss_irradiance_octree_build(ss_irradiance_point *points, size_t n,
                                     ss_irradiance_octree *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (n == 0 || n > UINT32_MAX) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "octree: %zu points (1 to 2^32 - 1)", n);
  }
  out->points = points;
  out->num_points = n;
  builder b = {.t = out, .cap = 0, .tmp = malloc(n * sizeof *points)};
  int32_t root;
  if (!b.tmp || !build(&b, 0, (uint32_t)n, 0, &root)) {
    free(b.tmp);
    ss_irradiance_octree_destroy(out);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "octree: out of memory for %zu points", n);
  }
  free(b.tmp);
  return SS_OK;
}

void ss_irradiance_octree_destroy(ss_irradiance_octree *t) {
  free(t->nodes);
  memset(t, 0, sizeof *t);
}

static void add_term(ss_rgb *acc, ss_octree_kernel_fn kernel, const void *ctx, ss_vec3 x_i,
                     ss_vec3 n_i, ss_rgb power) {
  double k[3];
  kernel(ctx, x_i, n_i, k);
  for (int c = 0; c < 3; ++c) {
    acc->c[c] += k[c] * power.c[c];
  }
}

static int inside(const ss_octree_node *n, ss_vec3 x) {
  return x.x >= n->lo.x && x.x <= n->hi.x && x.y >= n->lo.y && x.y <= n->hi.y && x.z >= n->lo.z &&
         x.z <= n->hi.z;
}

/* The squared distance from x to the node's bounds (0 inside). */
static double box_distance2(const ss_octree_node *n, ss_vec3 x) {
  double dx = fmax(fmax(n->lo.x - x.x, x.x - n->hi.x), 0.0);
  double dy = fmax(fmax(n->lo.y - x.y, x.y - n->hi.y), 0.0);
  double dz = fmax(fmax(n->lo.z - x.z, x.z - n->hi.z), 0.0);
  return dx * dx + dy * dy + dz * dz;
}

/* A leaf point: into the near field's sums when it lies within it, else
 * into acc. */
static void add_point(ss_rgb *acc, ss_octree_near *near, ss_octree_kernel_fn kernel,
                      const void *ctx, const ss_irradiance_point *p, ss_vec3 x) {
  ss_vec3 d = ss_vec3_sub(p->p, x);
  if (!near || !(ss_vec3_dot(d, d) < near->r2)) {
    add_term(acc, kernel, ctx, p->p, p->n, p->power);
    return;
  }
  double k[3];
  kernel(ctx, p->p, p->n, k);
  for (int c = 0; c < 3; ++c) {
    near->sum.c[c] += k[c] * p->power.c[c];
    near->weight[c] += k[c] * p->area;
  }
  near->count++;
  near->flat &= ss_vec3_dot(p->n, near->n) >= SS_OCTREE_NEAR_COS &&
                fabs(ss_vec3_dot(d, near->n)) <= SS_OCTREE_NEAR_OFFSET * sqrt(near->r2);
}

static ss_rgb walk(const ss_irradiance_octree *t, ss_vec3 x, double epsilon,
                   ss_octree_kernel_fn kernel, const void *ctx, ss_octree_near *near,
                   uint64_t *evals) {
  ss_rgb acc = ss_rgb_gray(0.0);
  int32_t stack[8 * SS_OCTREE_MAX_DEPTH + 8];
  int top = 0;
  uint64_t count = 0;
  if (t->num_nodes) {
    stack[top++] = 0;
  }
  while (top > 0) {
    const ss_octree_node *n = &t->nodes[stack[--top]];
    ss_vec3 d = ss_vec3_sub(n->centroid, x);
    /* Jensen & Buhler 2002, sec. 3: the node's solid angle dw = A / |x - c|^2;
     * a node that reaches into the near field is always opened */
    if (!inside(n, x) && n->area < epsilon * ss_vec3_dot(d, d) &&
        (!near || !(box_distance2(n, x) < near->r2))) {
      add_term(&acc, kernel, ctx, n->centroid, n->normal, n->power);
      count++;
      continue;
    }
    int leaf = 1;
    for (int k = 7; k >= 0; --k) {
      if (n->child[k] >= 0) {
        stack[top++] = n->child[k];
        leaf = 0;
      }
    }
    if (leaf) {
      for (uint32_t i = n->begin; i < n->end; ++i) {
        add_point(&acc, near, kernel, ctx, &t->points[i], x);
      }
      count += n->end - n->begin;
    }
  }
  if (evals) {
    *evals += count;
  }
  return acc;
}

ss_rgb ss_irradiance_octree_sum(const ss_irradiance_octree *t, ss_vec3 x, double epsilon,
                                ss_octree_kernel_fn kernel, const void *ctx, uint64_t *evals) {
  return walk(t, x, epsilon, kernel, ctx, NULL, evals);
}

ss_rgb ss_irradiance_octree_sum_near(const ss_irradiance_octree *t, ss_vec3 x, double epsilon,
                                     ss_octree_kernel_fn kernel, const void *ctx,
                                     ss_octree_near *near, uint64_t *evals) {
  near->sum = ss_rgb_gray(0.0);
  near->weight[0] = near->weight[1] = near->weight[2] = 0.0;
  near->count = 0;
  near->flat = 1;
  return walk(t, x, epsilon, kernel, ctx, near, evals);
}

ss_rgb ss_irradiance_direct_sum(const ss_irradiance_point *points, size_t n, ss_vec3 x,
                                ss_octree_kernel_fn kernel, const void *ctx) {
  ss_rgb acc = ss_rgb_gray(0.0);
  for (size_t i = 0; i < n; ++i) {
    add_term(&acc, kernel, ctx, points[i].p, points[i].n, points[i].power);
  }
  return acc;
}

size_t ss_irradiance_octree_bytes(const ss_irradiance_octree *t) {
  return t->num_nodes * sizeof *t->nodes;
}
