/* The irradiance cache file (irradiance_cache.h). */
#include "subsurf/irradiance_cache.h"

#include "core/atomic_file.h"
#include "core/cache_file.h"
#include "core/input_file.h"
#include "subsurf/grid.h"
#include "subsurf/texture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#define MAGIC "SSIRRCH"
#define RECORD_BYTES (10 * 8 + 4)

static void hash_rgb(uint64_t *h, ss_rgb c) {
  for (int k = 0; k < 3; ++k) {
    ss_hash_double(h, c.c[k]);
  }
}
static void hash_vec(uint64_t *h, ss_vec3 v) {
  ss_hash_double(h, v.x), ss_hash_double(h, v.y), ss_hash_double(h, v.z);
}

/* A texture by its values at a fixed grid of look-ups (textures are opaque;
 * an edit that changes none of these values goes unseen). */
static void hash_texture(uint64_t *h, const ss_texture *t) {
  ss_hash_int(h, t ? (int64_t)ss_texture_get_type(t) : -1);
  for (int i = 0; t && i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      ss_texcoord tc = {(i + 0.5) / 8.0, (j + 0.5) / 8.0, ss_vec3_make(i - 3.5, j - 3.5, i + j)};
      hash_rgb(h, ss_texture_eval(t, tc));
    }
  }
}

static void hash_material(uint64_t *h, const ss_material *m) {
  ss_hash_int(h, m->kind), hash_rgb(h, m->albedo), ss_hash_int(h, m->by_albedo),
      hash_rgb(h, m->mfp);
  ss_hash_int(h, m->albedo_inversion), ss_hash_int(h, m->boundary), ss_hash_double(h, m->eta);
  ss_hash_int(h, m->mf.type), ss_hash_double(h, m->mf.alpha),
      ss_hash_int(h, m->energy_compensation);
  ss_hash_int(h, m->medium), ss_hash_int(h, m->priority), ss_hash_str(h, m->bssrdf);
  ss_hash_int(h, m->bssrdf_single), ss_hash_int(h, m->lod),
      ss_hash_int(h, m->bssrdf_options.n_options);
  for (int k = 0; k < m->bssrdf_options.n_options; ++k) {
    const ss_option_value *o = &m->bssrdf_options.options[k];
    ss_hash_str(h, o->name ? o->name : ""), ss_hash_double(h, o->number), ss_hash_str(h, o->text);
  }
  for (int k = 0; k < SS_PARAM_COUNT; ++k) {
    hash_texture(h, m->textures[k]);
  }
}

static void hash_medium(uint64_t *h, const ss_medium *m) {
  const ss_medium_optics *o = &m->optics;
  hash_rgb(h, o->sigma_s), hash_rgb(h, o->sigma_a), hash_rgb(h, o->g), ss_hash_int(h, o->phase);
  ss_hash_int(h, o->flakes.type), ss_hash_double(h, o->flakes.p), hash_vec(h, o->flakes.axis);
  ss_hash_double(h, o->flakes.albedo_falloff), ss_hash_double(h, o->flakes.albedo_exponent);
  const ss_grid *g = m->grid;
  ss_hash_int(h, g != NULL);
  if (g) {
    size_t n = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
    ss_hash_int(h, g->n[0]), ss_hash_int(h, g->n[1]), ss_hash_int(h, g->n[2]);
    hash_vec(h, g->lo), hash_vec(h, g->hi), ss_hash_bytes(h, g->density, n * sizeof *g->density);
    ss_hash_int(h, g->axis != NULL);
    if (g->axis) {
      ss_hash_bytes(h, g->axis, 2 * n * sizeof *g->axis);
    }
  }
}

static void hash_mesh(uint64_t *h, const ss_mesh *m) {
  ss_hash_int(h, (int64_t)m->num_vertices), ss_hash_int(h, (int64_t)m->num_triangles);
  ss_hash_bytes(h, m->positions, 3 * m->num_vertices * sizeof *m->positions);
  ss_hash_bytes(h, m->indices, 3 * m->num_triangles * sizeof *m->indices);
  ss_hash_int(h, m->normals != NULL), ss_hash_int(h, m->uvs != NULL);
  if (m->normals) {
    ss_hash_bytes(h, m->normals, 3 * m->num_vertices * sizeof *m->normals);
  }
  if (m->uvs) {
    ss_hash_bytes(h, m->uvs, 2 * m->num_vertices * sizeof *m->uvs);
  }
}

static void hash_light(uint64_t *h, const ss_light *l) {
  ss_hash_int(h, l->type), hash_rgb(h, l->value), hash_vec(h, l->position);
  hash_vec(h, l->direction), ss_hash_double(h, l->cone_angle), ss_hash_double(h, l->falloff_angle);
  ss_hash_double(h, l->radius), ss_hash_int(h, l->shape), ss_hash_int(h, l->spot_smoothstep);
  ss_hash_int(h, l->map != NULL);
  if (l->map) {
    ss_envmap_hash(l->map, h);
  }
}

/* A placed point (not its irradiance), mixed by splitmix64's finaliser
 * (Steele et al. 2014) so that the sum over the points, which does not
 * depend on their order, keeps every bit of each. */
static uint64_t point_hash(const ss_irradiance_point *p) {
  uint64_t h = SS_HASH_SEED;
  hash_vec(&h, p->p), hash_vec(&h, p->n), ss_hash_double(&h, p->area), ss_hash_int(&h, p->shape);
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ULL;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBULL;
  return h ^ (h >> 31);
}

uint64_t ss_irradiance_cache_key(const ss_scene *scene, const ss_irradiance_pass1 *pass1) {
  uint64_t h = SS_HASH_SEED, points = 0;
  for (size_t i = 0; i < pass1->count; ++i) {
    points += point_hash(&pass1->placed[i]);
  }
  ss_hash_int(&h, SS_IRRADIANCE_CACHE_VERSION), ss_hash_int(&h, (int64_t)pass1->count);
  ss_hash_int(&h, (int64_t)points), ss_hash_int(&h, pass1->samples),
      ss_hash_int(&h, (int64_t)pass1->seed);
  ss_hash_int(&h, scene->integrator.max_depth), ss_hash_int(&h, scene->integrator.rr_depth);
  ss_hash_int(&h, (int64_t)scene->num_media), ss_hash_int(&h, (int64_t)scene->num_materials);
  ss_hash_int(&h, (int64_t)scene->num_shapes), ss_hash_int(&h, (int64_t)scene->num_lights);
  for (size_t i = 0; i < scene->num_media; ++i) {
    hash_medium(&h, &scene->media[i]);
  }
  for (size_t i = 0; i < scene->num_materials; ++i) {
    hash_material(&h, &scene->materials[i]);
  }
  for (size_t i = 0; i < scene->num_shapes; ++i) {
    ss_hash_int(&h, scene->shapes[i].material), ss_hash_int(&h, scene->shapes[i].light);
    hash_mesh(&h, scene->shapes[i].mesh);
  }
  for (size_t i = 0; i < scene->num_lights; ++i) {
    hash_light(&h, &scene->lights[i]);
  }
  return h;
}

static void put_record(unsigned char *b, const ss_irradiance_point *p) {
  double v[10] = {p->p.x, p->p.y,  p->p.z,    p->n.x,    p->n.y,
                  p->n.z, p->area, p->E.c[0], p->E.c[1], p->E.c[2]};
  memcpy(b, v, sizeof v);
  ss_cache_put_u32(b + sizeof v, p->shape);
}

/* 0 when a value is not finite or the shape is out of range. */
static int get_record(const unsigned char *b, size_t num_shapes, ss_irradiance_point *p) {
  double v[10];
  memcpy(v, b, sizeof v);
  for (int k = 0; k < 10; ++k) {
    if (!isfinite(v[k])) {
      return 0;
    }
  }
  p->p = ss_vec3_make(v[0], v[1], v[2]);
  p->n = ss_vec3_make(v[3], v[4], v[5]);
  p->area = v[6];
  p->E = ss_rgb_make(v[7], v[8], v[9]);
  p->power = ss_rgb_scale(p->E, p->area);
  p->shape = ss_cache_get_u32(b + sizeof v);
  return p->shape < num_shapes && p->area >= 0.0;
}

ss_status ss_irradiance_cache_write(const char *path, const ss_scene *scene,
                                    const ss_irradiance_pass1 *pass1, const ss_irradiance_point *p,
                                    size_t count, ss_error *err) {
  uint64_t key = ss_irradiance_cache_key(scene, pass1);
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_IRRADIANCE_CACHE, err);
  if (st != SS_OK) {
    return st;
  }
  unsigned char head[SS_CACHE_HEADER_BYTES], rec[RECORD_BYTES];
  ss_cache_header_put(head, MAGIC, SS_IRRADIANCE_CACHE_VERSION, key, count);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, head, sizeof head);
  st = ss_atomic_file_write(&f, head, sizeof head, err);
  for (size_t i = 0; st == SS_OK && i < count; ++i) {
    put_record(rec, &p[i]);
    crc = crc32(crc, rec, sizeof rec);
    st = ss_atomic_file_write(&f, rec, sizeof rec, err);
  }
  return ss_cache_file_finish(&f, (uint32_t)crc, st, err);
}

static ss_status bad(const char *path, const char *why, ss_error *err) {
  return ss_error_set(err, SS_ERR_PARSE, "irradiance cache '%s': %s", path, why);
}

/* 1 when the irradiance of the first placed points, computed again (each
 * from its own stream), equals that of the same points in the cache bit
 * for bit. */
static int spot_check(const ss_scene *scene, const ss_irradiance_pass1 *pass1,
                      const ss_irradiance_point *cached, size_t n) {
  ss_irradiance_point fresh[SS_IRRADIANCE_CACHE_SPOT_CHECK];
  size_t k =
      pass1->count < SS_IRRADIANCE_CACHE_SPOT_CHECK ? pass1->count : SS_IRRADIANCE_CACHE_SPOT_CHECK;
  memcpy(fresh, pass1->placed, k * sizeof *fresh);
  ss_irradiance_points_compute(scene, fresh, k, pass1->eta_of_shape, pass1->samples, pass1->seed, 1,
                               NULL, NULL);
  for (size_t i = 0; i < k; ++i) {
    const ss_irradiance_point *a = &fresh[i];
    size_t j = 0;
    while (j < n && (memcmp(&cached[j].p, &a->p, sizeof a->p) ||
                     memcmp(&cached[j].n, &a->n, sizeof a->n) || cached[j].shape != a->shape)) {
      ++j;
    }
    if (j == n || memcmp(&cached[j].E, &a->E, sizeof a->E) ||
        memcmp(&cached[j].area, &a->area, sizeof a->area)) {
      return 0;
    }
  }
  return 1;
}

ss_status ss_irradiance_cache_read(const char *path, const ss_scene *scene,
                                   const ss_irradiance_pass1 *pass1, ss_irradiance_point **out,
                                   size_t *count, ss_error *err) {
  uint64_t key = ss_irradiance_cache_key(scene, pass1);
  size_t num_shapes = scene->num_shapes;
  *out = NULL;
  *count = 0;
  FILE *f;
  uint64_t size;
  char label[SS_PATH_SIZE + 32];
  snprintf(label, sizeof label, "irradiance cache '%s'", path);
  ss_status st = ss_input_file_open(path, label, &f, &size, err);
  if (st != SS_OK) {
    return st;
  }
  unsigned char head[SS_CACHE_HEADER_BYTES];
  if (size < SS_CACHE_HEADER_BYTES + 4 || fread(head, 1, sizeof head, f) != sizeof head) {
    fclose(f);
    return bad(path, "truncated", err);
  }
  uint64_t n = ss_cache_get_u64(head + 24);
  const char *why =
      ss_cache_header_check(head, MAGIC, SS_IRRADIANCE_CACHE_VERSION, "not an irradiance cache");
  if (!why && (n == 0 || n > (size - SS_CACHE_HEADER_BYTES - 4) / RECORD_BYTES ||
               size != SS_CACHE_HEADER_BYTES + 4 + n * RECORD_BYTES)) {
    why = "truncated or of the wrong size";
  }
  if (!why && (ss_cache_get_u64(head + 16) != key || n != pass1->count)) {
    why = "made for another scene, lighting or point set (stale)";
  }
  if (why) {
    fclose(f);
    return bad(path, why, err);
  }
  ss_irradiance_point *p = malloc(n * sizeof *p);
  if (!p) {
    fclose(f);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "irradiance cache '%s': out of memory", path);
  }
  uLong crc = crc32(crc32(0L, Z_NULL, 0), head, sizeof head);
  unsigned char rec[RECORD_BYTES], tail[4];
  for (uint64_t i = 0; i < n && !why; ++i) {
    if (fread(rec, 1, sizeof rec, f) != sizeof rec) {
      why = "truncated";
    } else {
      crc = crc32(crc, rec, sizeof rec);
      if (!get_record(rec, num_shapes, &p[i])) {
        why = "a point with a non-finite value or an unknown shape";
      }
    }
  }
  if (!why && (fread(tail, 1, 4, f) != 4 || ss_cache_get_u32(tail) != (uint32_t)crc)) {
    why = "checksum mismatch (damaged)";
  }
  fclose(f);
  if (!why && !spot_check(scene, pass1, p, (size_t)n)) {
    why = "its irradiance differs from this version's pass 1 (stale)";
  }
  if (why) {
    free(p);
    return bad(path, why, err);
  }
  *out = p;
  *count = (size_t)n;
  return SS_OK;
}
