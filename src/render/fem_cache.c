/* The fem integrator's cache file (fem_cache.h). */
#include "subsurf/fem_cache.h"

#include "core/atomic_file.h"
#include "core/cache_file.h"
#include "core/input_file.h"
#include "subsurf/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#define MAGIC "SSFEMCH"
#define RECORD_HEAD_BYTES 32
enum { RECORD_MESH = 1, RECORD_SOLUTION = 2 };

struct ss_fem_cache {
  const char *path;
  unsigned char *data; /* the whole file */
  size_t num_records;
  struct record {
    uint32_t kind;
    uint64_t key, vertices, tets;
    const unsigned char *payload;
  } * records;
};

/* The code that turns keyed inputs into a mesh and a solution. */
static uint64_t code_key(void) {
  uint64_t h = SS_HASH_SEED;
  ss_hash_int(&h, SS_FEM_CACHE_VERSION);
  ss_hash_str(&h, ss_fem_libraries());
  return h;
}

static void hash_vec(uint64_t *h, ss_vec3 v) {
  ss_hash_double(h, v.x), ss_hash_double(h, v.y), ss_hash_double(h, v.z);
}

uint64_t ss_fem_cache_mesh_key(const float *positions, size_t num_vertices, const uint32_t *indices,
                               size_t num_triangles, const ss_fem_mesh_options *opt) {
  uint64_t h = code_key();
  ss_hash_int(&h, RECORD_MESH);
  ss_hash_int(&h, (int64_t)num_vertices), ss_hash_int(&h, (int64_t)num_triangles);
  ss_hash_bytes(&h, positions, 3 * num_vertices * sizeof *positions);
  ss_hash_bytes(&h, indices, 3 * num_triangles * sizeof *indices);
  ss_hash_double(&h, opt->size_max), ss_hash_double(&h, opt->size_min);
  hash_vec(&h, opt->refine_center);
  ss_hash_double(&h, opt->refine_radius), ss_hash_double(&h, opt->refine_grade);
  ss_hash_double(&h, opt->rim_radius), ss_hash_double(&h, opt->rim_size);
  ss_hash_int(&h, opt->medium_size != NULL);
  if (opt->medium_size) {
    ss_vec3 lo;
    double step[3];
    int n[3];
    const float *size = ss_fem_size_field_lattice(opt->medium_size, &lo, step, n);
    hash_vec(&h, lo);
    for (int a = 0; a < 3; ++a) {
      ss_hash_double(&h, step[a]), ss_hash_int(&h, n[a]);
    }
    ss_hash_bytes(&h, size, (size_t)n[0] * (size_t)n[1] * (size_t)n[2] * sizeof *size);
  }
  return h;
}

ss_status ss_fem_cache_hash_solve(uint64_t *h, const ss_fem_mesh *m, ss_fem_medium_fn medium,
                                  void *medium_ctx, const ss_fem_problem *pb,
                                  const ss_fem_solve_options *opt, ss_error *err) {
  ss_hash_int(h, RECORD_SOLUTION);
  for (size_t t = 0; t < m->num_tets; ++t) {
    const uint32_t *v = m->tets + 4 * t;
    ss_vec3 p[4];
    for (int k = 0; k < 4; ++k) {
      const double *x = m->positions + 3 * (size_t)v[k];
      p[k] = ss_vec3_make(x[0], x[1], x[2]);
    }
    /* the centroid exactly as fem_assemble.c's add_tet computes it */
    ss_vec3 c = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), ss_vec3_add(p[2], p[3])), 0.25);
    ss_fem_coeffs k;
    ss_status st = medium(medium_ctx, c, &k, err);
    if (st != SS_OK) {
      ss_error_prefix(err, "fem: medium at element %zu: ", t);
      return st;
    }
    for (int i = 0; i < 9; ++i) {
      ss_hash_double(h, k.M[i]);
    }
    ss_hash_double(h, k.mu0);
  }
  ss_hash_double(h, pb->eta);
  hash_vec(h, pb->spot_center);
  ss_hash_double(h, pb->spot_radius), ss_hash_double(h, pb->spot_power);
  hash_vec(h, pb->point);
  ss_hash_double(h, pb->point_power), ss_hash_double(h, pb->volume_source);
  ss_hash_int(h, pb->face_gamma != NULL);
  if (pb->face_gamma) {
    ss_hash_bytes(h, pb->face_gamma, m->num_faces * sizeof *pb->face_gamma);
  }
  ss_hash_int(h, (int64_t)pb->num_rays);
  for (size_t r = 0; pb->rays && r < pb->num_rays; ++r) {
    hash_vec(h, pb->rays[r].origin), hash_vec(h, pb->rays[r].dir);
    ss_hash_double(h, pb->rays[r].sigma), ss_hash_double(h, pb->rays[r].power);
  }
  ss_hash_int(h, opt->solver), ss_hash_double(h, opt->tolerance);
  ss_hash_int(h, opt->max_iterations);
  return SS_OK;
}

static ss_status bad(const char *path, const char *why, ss_error *err) {
  return ss_error_set(err, SS_ERR_PARSE, "fem cache '%s': %s", path, why);
}

/* Whether a record's vertex values (positions, or exitance) are all finite:
 * an image read through a NaN would be wrong without a word. */
static int finite_values(const struct record *r) {
  for (uint64_t i = 0; i < 3 * r->vertices; ++i) {
    double v;
    if (r->kind == RECORD_MESH) {
      memcpy(&v, r->payload + 8 * i, 8);
    } else {
      float f;
      memcpy(&f, r->payload + 4 * i, 4);
      v = f;
    }
    if (!isfinite(v)) {
      return 0;
    }
  }
  return 1;
}

/* The records after the header, each checked against the bytes left. */
static const char *parse_records(ss_fem_cache *c, uint64_t count, size_t size) {
  const unsigned char *p = c->data + SS_CACHE_HEADER_BYTES, *end = c->data + size - 4;
  if (count > (size_t)(end - p) / RECORD_HEAD_BYTES) {
    return "truncated or of the wrong size";
  }
  c->records = calloc(count + 1, sizeof *c->records);
  if (!c->records) {
    return "out of memory";
  }
  for (uint64_t i = 0; i < count; ++i) {
    if ((size_t)(end - p) < RECORD_HEAD_BYTES) {
      return "truncated or of the wrong size";
    }
    struct record *r = &c->records[i];
    r->kind = ss_cache_get_u32(p);
    r->key = ss_cache_get_u64(p + 8);
    r->vertices = ss_cache_get_u64(p + 16);
    r->tets = ss_cache_get_u64(p + 24);
    p += RECORD_HEAD_BYTES;
    uint64_t left = (uint64_t)(end - p);
    if (r->kind != RECORD_MESH && r->kind != RECORD_SOLUTION) {
      return "a record of an unknown kind";
    }
    if (ss_cache_get_u32(p - RECORD_HEAD_BYTES + 4) != 0 ||
        (r->kind == RECORD_SOLUTION && r->tets != 0)) {
      return "a malformed record";
    }
    /* each count is bounded alone before the sum, which then cannot overflow */
    uint64_t vertex_bytes = r->kind == RECORD_MESH ? 24 : 12;
    if (r->vertices > left / vertex_bytes || r->tets > left / 16 ||
        vertex_bytes * r->vertices + 16 * r->tets > left) {
      return "a record larger than the file (truncated)";
    }
    r->payload = p;
    if (!finite_values(r)) {
      return "a record with a value that is not finite";
    }
    p += vertex_bytes * r->vertices + 16 * r->tets;
    c->num_records++;
  }
  return p == end ? NULL : "truncated or of the wrong size";
}

ss_status ss_fem_cache_read(const char *path, ss_fem_cache **out, ss_error *err) {
  *out = NULL;
  char label[SS_PATH_SIZE + 32];
  snprintf(label, sizeof label, "fem cache '%s'", path);
  unsigned char *data;
  size_t size;
  ss_status st = ss_input_file_read(path, label, SS_INPUT_FEM_CACHE, &data, &size, err);
  if (st != SS_OK) {
    return st;
  }
  if (size < SS_CACHE_HEADER_BYTES + 4) {
    free(data);
    return bad(path, size ? "truncated" : "empty (truncated)", err);
  }
  ss_fem_cache *c = calloc(1, sizeof *c);
  if (!c) {
    free(data);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem cache '%s': out of memory", path);
  }
  c->path = path;
  c->data = data;
  /* the structure first (so that a cut file reads as truncated), then the
   * checksum (so that a damaged key reads as damage), then the key */
  const char *why = ss_cache_header_check(data, MAGIC, SS_FEM_CACHE_VERSION, "not an fem cache");
  if (!why) {
    why = parse_records(c, ss_cache_get_u64(data + 24), size);
  }
  if (!why && ss_cache_get_u32(data + size - 4) !=
                  (uint32_t)crc32_z(crc32(0L, Z_NULL, 0), data, (z_size_t)(size - 4))) {
    why = "checksum mismatch (damaged)";
  }
  if (!why && ss_cache_get_u64(data + 16) != code_key()) {
    why = "made by another version of the fem code, gmsh or CHOLMOD (stale)";
  }
  if (why) {
    ss_fem_cache_destroy(c);
    return bad(path, why, err);
  }
  *out = c;
  return SS_OK;
}

void ss_fem_cache_destroy(ss_fem_cache *c) {
  if (c) {
    free(c->records);
    free(c->data);
    free(c);
  }
}

static const struct record *find(const ss_fem_cache *c, uint32_t kind, uint64_t key) {
  for (size_t i = 0; c && i < c->num_records; ++i) {
    if (c->records[i].kind == kind && c->records[i].key == key) {
      return &c->records[i];
    }
  }
  return NULL;
}

ss_status ss_fem_cache_mesh(const ss_fem_cache *c, uint64_t key, ss_fem_mesh **out, ss_error *err) {
  *out = NULL;
  const struct record *r = find(c, RECORD_MESH, key);
  if (!r) {
    return SS_OK;
  }
  size_t nv = (size_t)r->vertices, nt = (size_t)r->tets;
  double *pos = malloc((3 * nv + 1) * sizeof *pos);
  uint32_t *tets = malloc((4 * nt + 1) * sizeof *tets);
  ss_status st = pos && tets ? SS_OK
                             : ss_error_set(err, SS_ERR_NO_MEMORY,
                                            "fem cache '%s': out of memory for a mesh", c->path);
  if (st == SS_OK) {
    memcpy(pos, r->payload, 3 * nv * sizeof *pos);
    memcpy(tets, r->payload + 3 * nv * sizeof *pos, 4 * nt * sizeof *tets);
  }
  if (st == SS_OK && (st = ss_fem_mesh_create(pos, nv, tets, nt, out, err)) != SS_OK) {
    ss_error_prefix(err, "fem cache '%s': ", c->path);
  }
  free(pos);
  free(tets);
  return st;
}

int ss_fem_cache_solution(const ss_fem_cache *c, uint64_t key, size_t num_vertices,
                          float *exitance) {
  const struct record *r = find(c, RECORD_SOLUTION, key);
  if (!r || r->vertices != num_vertices) {
    return 0;
  }
  memcpy(exitance, r->payload, 3 * num_vertices * sizeof *exitance);
  return 1;
}

/* Appends a record's head and payload parts, adding them to the CRC. */
static ss_status put(ss_atomic_file *f, uLong *crc, const void *data, size_t n, ss_error *err) {
  *crc = crc32_z(*crc, data, n);
  return ss_atomic_file_write(f, data, n, err);
}

static ss_status put_record(ss_atomic_file *f, uLong *crc, uint32_t kind, uint64_t key,
                            uint64_t vertices, uint64_t tets, ss_error *err) {
  unsigned char head[RECORD_HEAD_BYTES] = {0};
  ss_cache_put_u32(head, kind);
  ss_cache_put_u64(head + 8, key);
  ss_cache_put_u64(head + 16, vertices);
  ss_cache_put_u64(head + 24, tets);
  return put(f, crc, head, sizeof head, err);
}

ss_status ss_fem_cache_write(const char *path, const ss_fem_cache_entry *e, size_t n,
                             ss_error *err) {
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_FEM_CACHE, err);
  if (st != SS_OK) {
    return st;
  }
  unsigned char head[SS_CACHE_HEADER_BYTES];
  ss_cache_header_put(head, MAGIC, SS_FEM_CACHE_VERSION, code_key(), 2 * (uint64_t)n);
  uLong crc = crc32(0L, Z_NULL, 0);
  st = put(&f, &crc, head, sizeof head, err);
  for (size_t i = 0; i < n && st == SS_OK; ++i) {
    const ss_fem_mesh *m = e[i].mesh;
    size_t nv = m->num_vertices;
    st = put_record(&f, &crc, RECORD_MESH, e[i].mesh_key, nv, m->num_tets, err);
    if (st == SS_OK)
      st = put(&f, &crc, m->positions, 3 * nv * sizeof *m->positions, err);
    if (st == SS_OK)
      st = put(&f, &crc, m->tets, 4 * m->num_tets * sizeof *m->tets, err);
    if (st == SS_OK)
      st = put_record(&f, &crc, RECORD_SOLUTION, e[i].solution_key, nv, 0, err);
    if (st == SS_OK)
      st = put(&f, &crc, e[i].exitance, 3 * nv * sizeof *e[i].exitance, err);
  }
  return ss_cache_file_finish(&f, (uint32_t)crc, st, err);
}
