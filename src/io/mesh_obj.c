/* A strict Wavefront OBJ reader for triangle meshes: v, vt, vn and f
 * statements (polygons fanned into triangles); every other statement is
 * ignored. Errors name the file and the line and say what was expected. */
#include "core/input_file.h"
#include "mesh_io_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX

typedef struct {
  float *data;
  size_t size, capacity;
} float_buffer;

static int float_push(float_buffer *b, const float *v, size_t n) {
  if (b->size + n > b->capacity) {
    size_t cap = 2 * (b->size + n) + 64;
    float *grown = realloc(b->data, cap * sizeof *grown);
    if (!grown) {
      return -1;
    }
    b->data = grown;
    b->capacity = cap;
  }
  memcpy(b->data + b->size, v, n * sizeof *v);
  b->size += n;
  return 0;
}

typedef struct {
  const char *path;
  ss_error *err;
  size_t line;
  float_buffer v, vt, vn;
  ss_index_buffer refs;  /* (v, vt, vn) per face corner, NONE when absent */
  ss_index_buffer sizes; /* corners per face */
  size_t nv, nvt, nvn;
} obj_reader;

static ss_status fail(obj_reader *r, const char *what, const char *tok) {
  return ss_error_set(r->err, SS_ERR_PARSE, "%s: line %zu: %s%s%s", r->path, r->line, what,
                      tok ? ": " : "", tok ? tok : "");
}

static ss_status no_memory(obj_reader *r) {
  return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->path);
}

/* Parses n_min..n_max finite numbers from tok[1..]. */
static ss_status parse_numbers(obj_reader *r, char **tok, int ntok, int n_min, int n_max,
                               float *out, const char *expected) {
  int n = ntok - 1;
  if (n < n_min || n > n_max) {
    char msg[160];
    snprintf(msg, sizeof msg, "'%s' has %d values, expected %s", tok[0], n, expected);
    return fail(r, msg, NULL);
  }
  for (int i = 0; i < n; ++i) {
    char *end;
    errno = 0;
    double x = strtod(tok[i + 1], &end);
    if (*end != '\0' || end == tok[i + 1] || errno == ERANGE) {
      return fail(r, "expected a number", tok[i + 1]);
    }
    if (!isfinite(x)) {
      return fail(r, "expected a finite number", tok[i + 1]);
    }
    out[i] = (float)x;
  }
  return SS_OK;
}

/* One 1-based (or negative, relative) index; "" when absent. */
static ss_status parse_index(obj_reader *r, const char *s, size_t len, size_t count,
                             const char *kind, const char *ref, uint32_t *out) {
  char buf[32];
  if (len == 0) {
    *out = NONE;
    return SS_OK;
  }
  if (len >= sizeof buf) {
    return fail(r, "face reference too long", ref);
  }
  memcpy(buf, s, len);
  buf[len] = '\0';
  char *end;
  errno = 0;
  long long i = strtoll(buf, &end, 10);
  if (*end != '\0' || errno == ERANGE) {
    return fail(r, "expected an integer index in the face reference", ref);
  }
  long long idx = i > 0 ? i - 1 : (long long)count + i;
  if (i == 0 || idx < 0 || idx >= (long long)count) {
    char msg[200];
    snprintf(msg, sizeof msg,
             "%s index %lld out of range (%zu defined so far; expected 1..%zu or -1..-%zu)", kind,
             i, count, count, count);
    return fail(r, msg, ref);
  }
  if (idx >= (long long)NONE) {
    return fail(r, "index beyond 2^32 - 2 (meshes are indexed by 32 bits)", ref);
  }
  *out = (uint32_t)idx;
  return SS_OK;
}

/* v, v/vt, v//vn or v/vt/vn. */
static ss_status parse_ref(obj_reader *r, const char *ref, uint32_t out[3]) {
  const char *s1 = strchr(ref, '/');
  const char *s2 = s1 ? strchr(s1 + 1, '/') : NULL;
  if (s2 && strchr(s2 + 1, '/')) {
    return fail(r, "expected v, v/vt, v//vn or v/vt/vn", ref);
  }
  size_t lv = s1 ? (size_t)(s1 - ref) : strlen(ref);
  size_t lt = s1 ? (s2 ? (size_t)(s2 - s1 - 1) : strlen(s1 + 1)) : 0;
  size_t ln = s2 ? strlen(s2 + 1) : 0;
  if (lv == 0 || (s1 && !s2 && lt == 0) || (s2 && ln == 0)) {
    return fail(r, "expected v, v/vt, v//vn or v/vt/vn", ref);
  }
  ss_status st = parse_index(r, ref, lv, r->nv, "vertex", ref, &out[0]);
  if (st == SS_OK) {
    st = parse_index(r, s1 ? s1 + 1 : "", lt, r->nvt, "texture coordinate", ref, &out[1]);
  }
  if (st == SS_OK) {
    st = parse_index(r, s2 ? s2 + 1 : "", ln, r->nvn, "normal", ref, &out[2]);
  }
  return st;
}

#define OBJ_SPACE " \t\r\n"

static ss_status parse_face(obj_reader *r, char **save) {
  uint32_t n = 0;
  size_t first = r->refs.size;
  for (char *t = strtok_r(NULL, OBJ_SPACE, save); t; t = strtok_r(NULL, OBJ_SPACE, save)) {
    uint32_t ref[3];
    ss_status st = parse_ref(r, t, ref);
    if (st != SS_OK) {
      return st;
    }
    if (ss_index_buffer_push(&r->refs, ref, 3) != 0) {
      return no_memory(r);
    }
    ++n;
  }
  if (n < 3) {
    r->refs.size = first;
    char msg[64];
    snprintf(msg, sizeof msg, "a face has %u vertices, expected at least 3", n);
    return fail(r, msg, NULL);
  }
  if (ss_index_buffer_push(&r->sizes, &n, 1) != 0) {
    return no_memory(r);
  }
  return SS_OK;
}

static ss_status parse_line(obj_reader *r, char *line) {
  char *hash = strchr(line, '#');
  if (hash) {
    *hash = '\0';
  }
  char *save = NULL;
  char *kw = strtok_r(line, OBJ_SPACE, &save);
  if (!kw) {
    return SS_OK;
  }
  if (strcmp(kw, "f") == 0) {
    return parse_face(r, &save);
  }
  int is_v = strcmp(kw, "v") == 0, is_vt = strcmp(kw, "vt") == 0;
  int is_vn = strcmp(kw, "vn") == 0;
  if (!is_v && !is_vt && !is_vn) {
    return SS_OK; /* o, g, s, usemtl, mtllib, l, p, ...: not geometry we use */
  }
  /* At most 7 values: one more than any accepted form, to report excess. */
  char *tok[9];
  int ntok = 1;
  tok[0] = kw;
  for (char *t = strtok_r(NULL, OBJ_SPACE, &save); t && ntok < 9;
       t = strtok_r(NULL, OBJ_SPACE, &save)) {
    tok[ntok++] = t;
  }
  float x[8];
  ss_status st;
  if (is_v) {
    if (ntok == 6) {
      return fail(r, "'v' has 5 values, expected x y z [w] or x y z r g b", NULL);
    }
    st = parse_numbers(r, tok, ntok, 3, 6, x, "x y z [w] or x y z r g b");
    if (st == SS_OK && float_push(&r->v, x, 3) != 0) {
      return no_memory(r);
    }
    r->nv++;
  } else if (is_vt) {
    x[1] = 0.0f;
    st = parse_numbers(r, tok, ntok, 1, 3, x, "u [v [w]]");
    if (st == SS_OK && float_push(&r->vt, x, 2) != 0) {
      return no_memory(r);
    }
    r->nvt++;
  } else {
    st = parse_numbers(r, tok, ntok, 3, 3, x, "x y z");
    if (st == SS_OK && float_push(&r->vn, x, 3) != 0) {
      return no_memory(r);
    }
    r->nvn++;
  }
  return st;
}

/* ---- Assembly: one output vertex per distinct (v, vt, vn) actually used. */

typedef struct {
  uint32_t *keys; /* 3 per slot; keys[3 s] == NONE marks an empty slot */
  uint32_t *vals;
  size_t mask;
} corner_map;

static uint64_t hash3(const uint32_t *k) {
  uint64_t h = k[0] * 0x9E3779B97F4A7C15ULL;
  h ^= (k[1] + 0x632BE59BD9B4E019ULL) * 0xC2B2AE3D27D4EB4FULL;
  h ^= (k[2] + 0x85EBCA77C2B2AE63ULL) * 0x165667B19E3779F9ULL;
  return h ^ (h >> 29);
}

static ss_status assemble(obj_reader *r, ss_mesh **out, ss_mesh_read_info *info) {
  size_t ncorners = r->refs.size / 3;
  if (ncorners >= NONE) {
    return ss_error_set(r->err, SS_ERR_UNSUPPORTED,
                        "%s: %zu face corners, more than 2^32 - 2 (meshes are indexed by 32 bits)",
                        r->path, ncorners);
  }
  int has_t = ncorners > 0, has_n = ncorners > 0;
  for (size_t c = 0; c < ncorners; ++c) {
    has_t &= r->refs.data[3 * c + 1] != NONE;
    has_n &= r->refs.data[3 * c + 2] != NONE;
  }
  size_t cap = 16;
  while (cap < 2 * ncorners) {
    cap <<= 1;
  }
  corner_map map = {malloc(3 * cap * sizeof(uint32_t)), malloc(cap * sizeof(uint32_t)), cap - 1};
  uint32_t *corner_vertex = malloc((ncorners + 1) * sizeof *corner_vertex);
  float *pos = malloc((3 * ncorners + 1) * sizeof *pos);
  float *nrm = has_n ? malloc((3 * ncorners + 1) * sizeof *nrm) : NULL;
  float *uv = has_t ? malloc((2 * ncorners + 1) * sizeof *uv) : NULL;
  ss_index_buffer tris = {NULL, 0, 0};
  ss_status st = SS_OK;
  if (!map.keys || !map.vals || !corner_vertex || !pos || (has_n && !nrm) || (has_t && !uv)) {
    st = no_memory(r);
    goto done;
  }
  memset(map.keys, 0xFF, 3 * cap * sizeof(uint32_t));
  size_t nv = 0;
  for (size_t c = 0; c < ncorners; ++c) {
    uint32_t key[3] = {r->refs.data[3 * c], has_t ? r->refs.data[3 * c + 1] : 0,
                       has_n ? r->refs.data[3 * c + 2] : 0};
    size_t s = (size_t)hash3(key) & map.mask;
    while (map.keys[3 * s] != NONE && memcmp(map.keys + 3 * s, key, sizeof key) != 0) {
      s = (s + 1) & map.mask;
    }
    if (map.keys[3 * s] == NONE) {
      memcpy(map.keys + 3 * s, key, sizeof key);
      map.vals[s] = (uint32_t)nv;
      memcpy(pos + 3 * nv, r->v.data + 3 * (size_t)key[0], 3 * sizeof(float));
      if (has_n) {
        memcpy(nrm + 3 * nv, r->vn.data + 3 * (size_t)key[2], 3 * sizeof(float));
      }
      if (has_t) {
        memcpy(uv + 2 * nv, r->vt.data + 2 * (size_t)key[1], 2 * sizeof(float));
      }
      ++nv;
    }
    corner_vertex[c] = map.vals[s];
  }
  if (ss_index_buffer_reserve(&tris, 3 * ncorners) != 0) {
    st = no_memory(r);
    goto done;
  }
  size_t c0 = 0;
  for (size_t f = 0; f < r->sizes.size; ++f) {
    uint32_t n = r->sizes.data[f];
    for (uint32_t k = 2; k < n; ++k) {
      uint32_t t[3] = {corner_vertex[c0], corner_vertex[c0 + k - 1], corner_vertex[c0 + k]};
      ss_index_buffer_push(&tris, t, 3);
    }
    c0 += n;
  }
  st = ss_mesh_io_finish(r->path, nv, &pos, &nrm, &uv, &tris, r->sizes.size, out, info, r->err);
done:
  free(map.keys);
  free(map.vals);
  free(corner_vertex);
  free(pos);
  free(nrm);
  free(uv);
  ss_index_buffer_free(&tris);
  return st;
}

ss_status ss_mesh_read_obj(const char *path, ss_mesh **out, ss_mesh_read_info *info,
                           ss_error *err) {
  *out = NULL;
  unsigned char *data;
  size_t size;
  ss_status st = ss_input_file_read(path, path, SS_INPUT_MESH, &data, &size, err);
  if (st != SS_OK) {
    return st;
  }
  obj_reader r;
  memset(&r, 0, sizeof r);
  r.path = path;
  r.err = err;
  char *end = (char *)data + size;
  for (char *line = (char *)data; st == SS_OK && line < end;) {
    char *nl = memchr(line, '\n', (size_t)(end - line));
    char *next = nl ? nl + 1 : end;
    if (nl) {
      *nl = '\0';
    }
    r.line++;
    st = parse_line(&r, line);
    line = next;
  }
  if (st == SS_OK) {
    st = assemble(&r, out, info);
  }
  free(data);
  free(r.v.data);
  free(r.vt.data);
  free(r.vn.data);
  ss_index_buffer_free(&r.refs);
  ss_index_buffer_free(&r.sizes);
  return st;
}
