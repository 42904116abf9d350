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
/* Candidates are tried tile by tile (tiles of 2^TILE_BITS cells a side, in
 * Morton order), in their random order within a tile, so that the grid's
 * cells a query reads are in cache: a random order over the whole object
 * spent most of the placement waiting on memory. */
#define TILE_BITS 3

typedef struct {
  double cell;
  size_t mask;   /* table size - 1 (a power of two) */
  int64_t *head; /* per bucket: the last point inserted, -1 when empty */
  int64_t *next; /* per point: the previous point of its bucket */
  ss_vec3 *pos;  /* per point: its position (packed: the queries' memory traffic) */
} grid;

static size_t bucket(const grid *g, int64_t x, int64_t y, int64_t z) {
  uint64_t h = ss_hash64((uint64_t)x * 0x9E3779B97F4A7C15ULL ^ (uint64_t)y * 0xC2B2AE3D27D4EB4FULL ^
                         (uint64_t)z * 0x165667B19E3779F9ULL);
  return (size_t)(h & g->mask);
}

static int64_t cell_of(const grid *g, double v) { return (int64_t)floor(v / g->cell); }

/* 1 when an accepted point lies within radius r of p (r <= g->cell): the
 * cells the box p +- r overlaps, 2 (at most 3) per axis. */
static int occupied(const grid *g, ss_vec3 p, double r) {
  int64_t x0 = cell_of(g, p.x - r), y0 = cell_of(g, p.y - r), z0 = cell_of(g, p.z - r);
  int64_t x1 = cell_of(g, p.x + r), y1 = cell_of(g, p.y + r), z1 = cell_of(g, p.z + r);
  for (int64_t x = x0; x <= x1; ++x) {
    for (int64_t y = y0; y <= y1; ++y) {
      for (int64_t z = z0; z <= z1; ++z) {
        for (int64_t i = g->head[bucket(g, x, y, z)]; i >= 0; i = g->next[i]) {
          ss_vec3 d = ss_vec3_sub(g->pos[i], p);
          if (ss_vec3_dot(d, d) < r * r) {
            return 1;
          }
        }
      }
    }
  }
  return 0;
}

static void insert(grid *g, int64_t i, ss_vec3 p) {
  g->pos[i] = p;
  size_t b = bucket(g, cell_of(g, p.x), cell_of(g, p.y), cell_of(g, p.z));
  g->next[i] = g->head[b];
  g->head[b] = i;
}

/* The Morton code of the low 21 bits of x, y and z, interleaved. */
static uint64_t morton(uint64_t x, uint64_t y, uint64_t z) {
  uint64_t code = 0;
  for (int b = 0; b < 21; ++b) {
    code |=
        ((x >> b & 1) << (3 * b)) | ((y >> b & 1) << (3 * b + 1)) | ((z >> b & 1) << (3 * b + 2));
  }
  return code;
}

typedef struct {
  uint64_t tile; /* Morton code of the candidate's tile */
  size_t index;  /* its place in the random order */
} tile_key;

static int by_tile(const void *a, const void *b) {
  const tile_key *x = a, *y = b;
  if (x->tile != y->tile) {
    return x->tile < y->tile ? -1 : 1;
  }
  return (x->index > y->index) - (x->index < y->index);
}

/* The candidates (position, normal pairs) reordered by tile, as drawn within
 * a tile, so that the passes read them in sequence. NULL when out of memory. */
static ss_vec3 *by_tiles(const grid *g, const ss_vec3 *cand, size_t pool) {
  tile_key *k = malloc(pool * sizeof *k);
  ss_vec3 *sorted = malloc(2 * pool * sizeof *sorted);
  if (!k || !sorted) {
    free(k), free(sorted);
    return NULL;
  }
  for (size_t i = 0; i < pool; ++i) {
    ss_vec3 p = cand[2 * i];
    k[i].tile =
        morton((uint64_t)cell_of(g, p.x) >> TILE_BITS, (uint64_t)cell_of(g, p.y) >> TILE_BITS,
               (uint64_t)cell_of(g, p.z) >> TILE_BITS);
    k[i].index = i;
  }
  qsort(k, pool, sizeof *k, by_tile);
  for (size_t i = 0; i < pool; ++i) {
    sorted[2 * i] = cand[2 * k[i].index];
    sorted[2 * i + 1] = cand[2 * k[i].index + 1];
  }
  free(k);
  return sorted;
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
  ss_vec3 *cand = malloc(2 * pool * sizeof *cand); /* position, normal */
  grid g = {.mask = table - 1, .head = malloc(table * sizeof(int64_t))};
  g.next = malloc(count * sizeof(int64_t));
  g.pos = malloc(count * sizeof *g.pos);
  unsigned char *used = calloc(pool, 1);
  if (!cand || !g.head || !g.next || !g.pos || !used) {
    free(cdf), free(cand), free(g.head), free(g.next), free(g.pos), free(used);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "poisson disk: out of memory for %zu points", count);
  }
  memset(g.head, 0xff, table * sizeof(int64_t));
  ss_rng rng;
  ss_rng_seed_item(&rng, seed, shape);
  for (size_t i = 0; i < pool; ++i) {
    candidate(mesh, cdf, total, &rng, &cand[2 * i], &cand[2 * i + 1]);
  }
  double r = sqrt(0.75 * total / (double)count);
  g.cell = r;
  ss_vec3 *drawn = cand;
  cand = by_tiles(&g, drawn, pool);
  free(drawn);
  if (!cand) {
    free(cdf), free(g.head), free(g.next), free(g.pos), free(used);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "poisson disk: out of memory for %zu points", count);
  }
  size_t accepted = 0;
  while (accepted < count) {
    for (size_t i = 0; i < pool && accepted < count; ++i) {
      if (!used[i] && !occupied(&g, cand[2 * i], r)) {
        used[i] = 1;
        memset(&out[accepted], 0, sizeof *out);
        out[accepted].p = cand[2 * i];
        out[accepted].n = cand[2 * i + 1];
        insert(&g, (int64_t)accepted++, cand[2 * i]);
      }
    }
    r *= RADIUS_SHRINK;
  }
  for (size_t i = 0; i < count; ++i) {
    out[i].area = total / (double)count;
    out[i].shape = shape;
  }
  free(cdf), free(cand), free(g.head), free(g.next), free(g.pos), free(used);
  return SS_OK;
}
