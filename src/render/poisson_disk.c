/* Blue-noise points on a mesh by dart throwing (Cook 1986; the point sets of
 * Jensen & Buhler 2002, sec. 3): see irradiance_points.h. Candidates are
 * drawn uniformly by area; a candidate is accepted when no accepted point
 * lies within the current radius (a hashed grid of cells of the first radius
 * answers that); passes over the pool shrink the radius until the requested
 * number of points is reached. */
#include "subsurf/irradiance_points.h"

#include "subsurf/rng.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CANDIDATES_PER_POINT 6
#define RADIUS_SHRINK 0.9

typedef struct {
  double cell;
  size_t mask;   /* table size - 1 (a power of two) */
  int64_t *head; /* per bucket: the last point inserted, -1 when empty */
  int64_t *next; /* per point: the previous point of its bucket */
  const ss_irradiance_point *pts;
} grid;

static size_t bucket(const grid *g, int64_t x, int64_t y, int64_t z) {
  uint64_t h = ss_hash64((uint64_t)x * 0x9E3779B97F4A7C15ULL ^ (uint64_t)y * 0xC2B2AE3D27D4EB4FULL ^
                         (uint64_t)z * 0x165667B19E3779F9ULL);
  return (size_t)(h & g->mask);
}

static int64_t cell_of(const grid *g, double v) { return (int64_t)floor(v / g->cell); }

/* 1 when an accepted point lies within radius r of p (r <= g->cell). */
static int occupied(const grid *g, ss_vec3 p, double r) {
  int64_t cx = cell_of(g, p.x), cy = cell_of(g, p.y), cz = cell_of(g, p.z);
  for (int64_t dx = -1; dx <= 1; ++dx) {
    for (int64_t dy = -1; dy <= 1; ++dy) {
      for (int64_t dz = -1; dz <= 1; ++dz) {
        for (int64_t i = g->head[bucket(g, cx + dx, cy + dy, cz + dz)]; i >= 0; i = g->next[i]) {
          ss_vec3 d = ss_vec3_sub(g->pts[i].p, p);
          if (ss_vec3_dot(d, d) < r * r) {
            return 1;
          }
        }
      }
    }
  }
  return 0;
}

static void insert(grid *g, int64_t i) {
  ss_vec3 p = g->pts[i].p;
  size_t b = bucket(g, cell_of(g, p.x), cell_of(g, p.y), cell_of(g, p.z));
  g->next[i] = g->head[b];
  g->head[b] = i;
}

/* A uniform point on the mesh by area: the triangle from the cumulative
 * areas, then a uniform point on it (pbrt-v3 sec. 13.6.5). */
static void candidate(const ss_mesh *mesh, const double *cdf, double total, ss_rng *rng, ss_vec3 *p,
                      ss_vec3 *n) {
  double u = ss_rng_uniform(rng) * total;
  size_t lo = 0, hi = mesh->num_triangles - 1;
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    if (cdf[mid] <= u) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  ss_vec3 v[3];
  ss_mesh_triangle(mesh, lo, v);
  double su = sqrt(ss_rng_uniform(rng)), b1 = 1.0 - su, b2 = ss_rng_uniform(rng) * su;
  *p = ss_vec3_add(ss_vec3_scale(v[0], 1.0 - b1 - b2),
                   ss_vec3_add(ss_vec3_scale(v[1], b1), ss_vec3_scale(v[2], b2)));
  *n = ss_vec3_normalize(ss_mesh_triangle_normal(mesh, lo));
}

ss_status ss_poisson_disk_points(const ss_mesh *mesh, uint32_t shape, size_t count, uint64_t seed,
                                 ss_irradiance_point *out, ss_error *err) {
  if (count == 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "poisson disk: a point count of 0");
  }
  size_t nt = mesh->num_triangles;
  double *cdf = nt ? malloc(nt * sizeof *cdf) : NULL;
  if (nt && !cdf) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "poisson disk: out of memory");
  }
  double total = 0.0;
  for (size_t t = 0; t < nt; ++t) {
    total += ss_mesh_triangle_area(mesh, t);
    cdf[t] = total;
  }
  if (!(total > 0.0) || !isfinite(total)) {
    free(cdf);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "poisson disk: the mesh has no area");
  }
  size_t pool = count * CANDIDATES_PER_POINT;
  size_t table = 1;
  while (table < 2 * count) {
    table <<= 1;
  }
  ss_irradiance_point *cand = malloc(pool * sizeof *cand);
  grid g = {.mask = table - 1, .head = malloc(table * sizeof(int64_t)), .pts = out};
  g.next = malloc(count * sizeof(int64_t));
  unsigned char *used = calloc(pool, 1);
  if (!cand || !g.head || !g.next || !used) {
    free(cdf), free(cand), free(g.head), free(g.next), free(used);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "poisson disk: out of memory for %zu points", count);
  }
  memset(g.head, 0xff, table * sizeof(int64_t));
  ss_rng rng;
  ss_rng_seed_item(&rng, seed, shape);
  for (size_t i = 0; i < pool; ++i) {
    memset(&cand[i], 0, sizeof cand[i]);
    candidate(mesh, cdf, total, &rng, &cand[i].p, &cand[i].n);
  }
  double r = sqrt(0.75 * total / (double)count);
  g.cell = r;
  size_t accepted = 0;
  while (accepted < count) {
    for (size_t i = 0; i < pool && accepted < count; ++i) {
      if (!used[i] && !occupied(&g, cand[i].p, r)) {
        used[i] = 1;
        out[accepted] = cand[i];
        insert(&g, (int64_t)accepted++);
      }
    }
    r *= RADIUS_SHRINK;
  }
  for (size_t i = 0; i < count; ++i) {
    out[i].area = total / (double)count;
    out[i].shape = shape;
  }
  free(cdf), free(cand), free(g.head), free(g.next), free(used);
  return SS_OK;
}
