/* A strict PLY reader (Turk 1994's format as documented by Paul Bourke):
 * ascii and binary of either byte order, vertex positions with optional
 * normals and texture coordinates, faces as index lists of any size
 * triangulated as fans. Every error names the file and the line (ascii
 * header and body) or the element (binary body) and says what was expected.
 * The header is checked against the file before anything is allocated from
 * it: element names are unique, every element has properties, and the data
 * the counts announce fits in the bytes that follow the header. */
#include "core/input_file.h"
#include "mesh_io_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_INVALID } ply_type;

enum { R_NONE, R_X, R_Y, R_Z, R_NX, R_NY, R_NZ, R_U, R_V, R_INDICES };

typedef struct {
  char name[64];
  ply_type type; /* the item type of a list */
  int is_list;
  ply_type count_type;
  int role;
} ply_prop;

typedef struct {
  char name[64];
  size_t count;
  ply_prop *props;
  size_t nprops;
} ply_element;

typedef enum { F_ASCII, F_BINARY_LE, F_BINARY_BE } ply_format;

typedef struct {
  const char *path;
  FILE *f;
  uint64_t file_size;
  ss_error *err;
  size_t line;
  ply_format format;
  int swap;
  ply_element *elems;
  size_t nelems;
  char *buf; /* current ascii line */
  size_t bufcap;
  /* output */
  size_t nv;
  float *pos, *nrm, *uv;
  ss_index_buffer tris;
  size_t npolys;
} ply_reader;

static const struct {
  const char *name;
  ply_type type;
  size_t size;
} type_names[] = {
    {"char", T_I8, 1},   {"int8", T_I8, 1},     {"uchar", T_U8, 1},   {"uint8", T_U8, 1},
    {"short", T_I16, 2}, {"int16", T_I16, 2},   {"ushort", T_U16, 2}, {"uint16", T_U16, 2},
    {"int", T_I32, 4},   {"int32", T_I32, 4},   {"uint", T_U32, 4},   {"uint32", T_U32, 4},
    {"float", T_F32, 4}, {"float32", T_F32, 4}, {"double", T_F64, 8}, {"float64", T_F64, 8}};

static ply_type parse_type(const char *s) {
  for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; ++i) {
    if (strcmp(s, type_names[i].name) == 0) {
      return type_names[i].type;
    }
  }
  return T_INVALID;
}

static size_t type_size(ply_type t) {
  static const size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[t];
}

static int is_integer_type(ply_type t) { return t != T_F32 && t != T_F64; }

static ss_status fail_line(ply_reader *r, const char *fmt, const char *detail) {
  return ss_error_set(r->err, SS_ERR_PARSE, "%s: line %zu: %s%s", r->path, r->line, fmt,
                      detail ? detail : "");
}

/* Reads one line into r->buf without its newline; returns 0 at end of file. */
static int next_line(ply_reader *r) {
  ssize_t n = getline(&r->buf, &r->bufcap, r->f);
  if (n < 0) {
    return 0;
  }
  r->line++;
  while (n > 0 && (r->buf[n - 1] == '\n' || r->buf[n - 1] == '\r')) {
    r->buf[--n] = '\0';
  }
  return 1;
}

static int vertex_role(const char *name) {
  static const struct {
    const char *name;
    int role;
  } roles[] = {{"x", R_X},         {"y", R_Y},        {"z", R_Z},         {"nx", R_NX},
               {"ny", R_NY},       {"nz", R_NZ},      {"u", R_U},         {"v", R_V},
               {"s", R_U},         {"t", R_V},        {"texture_u", R_U}, {"texture_v", R_V},
               {"texture_s", R_U}, {"texture_t", R_V}};
  for (size_t i = 0; i < sizeof roles / sizeof roles[0]; ++i) {
    if (strcmp(name, roles[i].name) == 0) {
      return roles[i].role;
    }
  }
  return R_NONE;
}

static ss_status add_property(ply_reader *r, char **tok, int ntok) {
  if (r->nelems == 0) {
    return fail_line(r, "a property before any element", NULL);
  }
  ply_element *e = &r->elems[r->nelems - 1];
  ply_prop p;
  memset(&p, 0, sizeof p);
  const char *name;
  if (ntok >= 2 && strcmp(tok[1], "list") == 0) {
    if (ntok != 5) {
      return fail_line(r, "expected 'property list <count type> <item type> <name>'", NULL);
    }
    p.is_list = 1;
    p.count_type = parse_type(tok[2]);
    p.type = parse_type(tok[3]);
    if (p.count_type == T_INVALID || !is_integer_type(p.count_type)) {
      return fail_line(r, "unsupported list count type (expected an integer type): ", tok[2]);
    }
    if (p.type == T_INVALID) {
      return fail_line(r, "unsupported property type: ", tok[3]);
    }
    name = tok[4];
  } else {
    if (ntok != 3) {
      return fail_line(r, "expected 'property <type> <name>'", NULL);
    }
    p.type = parse_type(tok[1]);
    if (p.type == T_INVALID) {
      return fail_line(r, "unsupported property type: ", tok[1]);
    }
    name = tok[2];
  }
  snprintf(p.name, sizeof p.name, "%s", name);
  if (strcmp(e->name, "vertex") == 0) {
    p.role = vertex_role(name);
    if (p.role != R_NONE && p.is_list) {
      return fail_line(r, "vertex property must be a scalar, not a list: ", name);
    }
  } else if (strcmp(e->name, "face") == 0 &&
             (strcmp(name, "vertex_indices") == 0 || strcmp(name, "vertex_index") == 0)) {
    if (!p.is_list || !is_integer_type(p.type)) {
      return fail_line(r, "face property must be a list of integers: ", name);
    }
    p.role = R_INDICES;
  }
  for (size_t i = 0; i < e->nprops; ++i) {
    if (p.role != R_NONE && e->props[i].role == p.role) {
      return fail_line(r, "duplicate property: ", name);
    }
  }
  ply_prop *grown = realloc(e->props, (e->nprops + 1) * sizeof *grown);
  if (!grown) {
    return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->path);
  }
  e->props = grown;
  e->props[e->nprops++] = p;
  return SS_OK;
}

static ss_status add_element(ply_reader *r, char **tok, int ntok) {
  if (ntok != 3) {
    return fail_line(r, "expected 'element <name> <count>'", NULL);
  }
  char *end;
  errno = 0;
  long long count = strtoll(tok[2], &end, 10);
  if (*end != '\0' || errno != 0 || count < 0 || (unsigned long long)count >= UINT32_MAX) {
    return fail_line(r, "element count must be an integer in [0, 2^32 - 1): ", tok[2]);
  }
  for (size_t i = 0; i < r->nelems; ++i) {
    if (strcmp(r->elems[i].name, tok[1]) == 0) {
      return fail_line(r, "a second element of the same name: ", tok[1]);
    }
  }
  ply_element *grown = realloc(r->elems, (r->nelems + 1) * sizeof *grown);
  if (!grown) {
    return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->path);
  }
  r->elems = grown;
  ply_element *e = &r->elems[r->nelems++];
  memset(e, 0, sizeof *e);
  snprintf(e->name, sizeof e->name, "%s", tok[1]);
  e->count = (size_t)count;
  return SS_OK;
}

static int split(char *s, char **tok, int max) {
  int n = 0;
  char *save = NULL;
  for (char *t = strtok_r(s, " \t", &save); t; t = strtok_r(NULL, " \t", &save)) {
    if (n == max) {
      return max + 1;
    }
    tok[n++] = t;
  }
  return n;
}

static ss_status read_header(ply_reader *r) {
  if (!next_line(r) || strcmp(r->buf, "ply") != 0) {
    r->line = 1;
    return fail_line(r, "not a PLY file (expected the magic line 'ply')", NULL);
  }
  int have_format = 0;
  for (;;) {
    if (!next_line(r)) {
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: line %zu: the header ends without 'end_header'", r->path, r->line);
    }
    char *tok[8];
    int n = split(r->buf, tok, 6);
    if (n == 0) {
      continue;
    }
    if (strcmp(tok[0], "end_header") == 0) {
      break;
    } else if (strcmp(tok[0], "comment") == 0 || strcmp(tok[0], "obj_info") == 0) {
      continue;
    } else if (strcmp(tok[0], "format") == 0) {
      if (n != 3 || strcmp(tok[2], "1.0") != 0) {
        return fail_line(r, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'",
                         NULL);
      }
      if (strcmp(tok[1], "ascii") == 0) {
        r->format = F_ASCII;
      } else if (strcmp(tok[1], "binary_little_endian") == 0) {
        r->format = F_BINARY_LE;
      } else if (strcmp(tok[1], "binary_big_endian") == 0) {
        r->format = F_BINARY_BE;
      } else {
        return fail_line(r, "unknown format: ", tok[1]);
      }
      have_format = 1;
    } else if (strcmp(tok[0], "element") == 0) {
      ss_status st = add_element(r, tok, n);
      if (st != SS_OK) {
        return st;
      }
    } else if (strcmp(tok[0], "property") == 0) {
      ss_status st = add_property(r, tok, n);
      if (st != SS_OK) {
        return st;
      }
    } else {
      return fail_line(r, "unknown header keyword: ", tok[0]);
    }
  }
  if (!have_format) {
    return fail_line(r, "the header has no 'format' line", NULL);
  }
  const uint16_t probe = 1;
  int host_le = *(const uint8_t *)&probe == 1;
  r->swap = (r->format == F_BINARY_LE && !host_le) || (r->format == F_BINARY_BE && host_le);
  return SS_OK;
}

/* The fewest bytes one element can take: binary, its scalars and list
 * counts; ascii, one character and one separator per value. */
static uint64_t min_element_bytes(const ply_reader *r, const ply_element *e) {
  uint64_t bytes = 0;
  for (size_t i = 0; i < e->nprops; ++i) {
    const ply_prop *p = &e->props[i];
    bytes += r->format == F_ASCII ? 2 : type_size(p->is_list ? p->count_type : p->type);
  }
  return bytes;
}

/* Every element has properties, and the elements fit in what follows the
 * header (so that no count can make us allocate more than the file holds). */
static ss_status check_sizes(ply_reader *r) {
  long start = ftell(r->f);
  uint64_t left =
      start >= 0 && (uint64_t)start <= r->file_size ? r->file_size - (uint64_t)start : 0;
  for (size_t i = 0; i < r->nelems; ++i) {
    if (r->elems[i].nprops == 0 && r->elems[i].count > 0) {
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: element '%s' has no properties (expected at least one)", r->path,
                          r->elems[i].name);
    }
  }
  uint64_t need = 0;
  for (size_t i = 0; i < r->nelems; ++i) {
    const ply_element *e = &r->elems[i];
    uint64_t per = min_element_bytes(r, e);
    if (e->count > 0 && per > 0 && (e->count > (left - need) / per)) {
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: the header declares %zu '%s' elements of at least %llu bytes "
                          "each, but only %llu bytes follow the header (wrong count or "
                          "truncated file?)",
                          r->path, e->count, e->name, (unsigned long long)per,
                          (unsigned long long)left);
    }
    need += (uint64_t)e->count * per;
  }
  return SS_OK;
}

/* Checks the header's vertex and face elements and allocates the output
 * (check_sizes has bounded the counts by the file's size). */
static ss_status prepare(ply_reader *r, int *has_n, int *has_uv) {
  const ply_element *v = NULL, *f = NULL;
  for (size_t i = 0; i < r->nelems; ++i) {
    if (strcmp(r->elems[i].name, "vertex") == 0) {
      v = &r->elems[i];
    } else if (strcmp(r->elems[i].name, "face") == 0) {
      f = &r->elems[i];
    }
  }
  if (!v || !f) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: the header declares no '%s' element (expected 'vertex' and 'face')",
                        r->path, v ? "face" : "vertex");
  }
  unsigned roles = 0;
  for (size_t i = 0; i < v->nprops; ++i) {
    roles |= 1u << v->props[i].role;
  }
  if ((roles & (1u << R_X | 1u << R_Y | 1u << R_Z)) != (1u << R_X | 1u << R_Y | 1u << R_Z)) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: the vertex element lacks one of the properties x, y, z", r->path);
  }
  unsigned nmask = 1u << R_NX | 1u << R_NY | 1u << R_NZ, tmask = 1u << R_U | 1u << R_V;
  *has_n = (roles & nmask) == nmask;
  *has_uv = (roles & tmask) == tmask;
  int has_idx = 0;
  for (size_t i = 0; i < f->nprops; ++i) {
    has_idx |= f->props[i].role == R_INDICES;
  }
  if (!has_idx) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: the face element has no 'vertex_indices' (or 'vertex_index') list",
                        r->path);
  }
  ss_status st = check_sizes(r);
  if (st != SS_OK) {
    return st;
  }
  r->nv = v->count;
  r->npolys = f->count;
  r->pos = malloc((3 * r->nv + 1) * sizeof *r->pos);
  r->nrm = *has_n ? malloc((3 * r->nv + 1) * sizeof *r->nrm) : NULL;
  r->uv = *has_uv ? malloc((2 * r->nv + 1) * sizeof *r->uv) : NULL;
  if (!r->pos || (*has_n && !r->nrm) || (*has_uv && !r->uv) ||
      ss_index_buffer_reserve(&r->tris, 3 * f->count) != 0) {
    return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory for %zu vertices", r->path,
                        r->nv);
  }
  return SS_OK;
}

/* ---- Values. Each reader returns 0 on success, -1 at the end of the data,
 * -2 on a malformed value. */

static int read_binary(ply_reader *r, ply_type t, double *out) {
  unsigned char b[8];
  size_t n = type_size(t);
  if (fread(b, 1, n, r->f) != n) {
    return -1;
  }
  if (r->swap) {
    for (size_t i = 0; i < n / 2; ++i) {
      unsigned char c = b[i];
      b[i] = b[n - 1 - i];
      b[n - 1 - i] = c;
    }
  }
  switch (t) {
  case T_I8:
    *out = (int8_t)b[0];
    break;
  case T_U8:
    *out = b[0];
    break;
  case T_I16: {
    int16_t x;
    memcpy(&x, b, 2);
    *out = x;
  } break;
  case T_U16: {
    uint16_t x;
    memcpy(&x, b, 2);
    *out = x;
  } break;
  case T_I32: {
    int32_t x;
    memcpy(&x, b, 4);
    *out = x;
  } break;
  case T_U32: {
    uint32_t x;
    memcpy(&x, b, 4);
    *out = x;
  } break;
  case T_F32: {
    float x;
    memcpy(&x, b, 4);
    *out = x;
  } break;
  case T_F64: {
    double x;
    memcpy(&x, b, 8);
    *out = x;
  } break;
  case T_INVALID:
    return -2;
  }
  return 0;
}

typedef struct {
  char *save;
  int started;
} token_cursor;

static int read_ascii(ply_reader *r, token_cursor *c, ply_type t, double *out) {
  char *tok = strtok_r(c->started ? NULL : r->buf, " \t", &c->save);
  c->started = 1;
  if (!tok) {
    return -1;
  }
  char *end;
  errno = 0;
  if (is_integer_type(t)) {
    long long x = strtoll(tok, &end, 10);
    *out = (double)x;
  } else {
    *out = strtod(tok, &end);
  }
  return (*end != '\0' || end == tok || errno == ERANGE) ? -2 : 0;
}

static int read_value(ply_reader *r, token_cursor *c, ply_type t, double *out) {
  return r->format == F_ASCII ? read_ascii(r, c, t, out) : read_binary(r, t, out);
}

/* Error context: "line N" for ascii, "<element> element N" for binary. */
static void where(const ply_reader *r, const ply_element *e, size_t k, char *s, size_t n) {
  if (r->format == F_ASCII) {
    snprintf(s, n, "line %zu (%s %zu)", r->line, e->name, k);
  } else {
    snprintf(s, n, "binary %s element %zu of %zu", e->name, k, e->count);
  }
}

static ss_status value_error(ply_reader *r, const ply_element *e, size_t k, const ply_prop *p,
                             int code) {
  char at[160];
  where(r, e, k, at, sizeof at);
  if (code == -1) {
    if (r->format == F_ASCII) {
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: %s: too few values, expected property '%s' (wrong count in the "
                          "header?)",
                          r->path, at, p->name);
    }
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: %s: the file ends early, expected property '%s' (truncated file?)",
                        r->path, at, p->name);
  }
  return ss_error_set(r->err, SS_ERR_PARSE, "%s: %s: property '%s' is not a valid %s", r->path, at,
                      p->name, is_integer_type(p->type) ? "integer" : "number");
}

static ss_status read_face_list(ply_reader *r, token_cursor *c, const ply_element *e, size_t k,
                                const ply_prop *p) {
  double cnt;
  int rc = read_value(r, c, p->count_type, &cnt);
  char at[160];
  where(r, e, k, at, sizeof at);
  if (rc != 0) {
    return value_error(r, e, k, p, rc);
  }
  if (p->role == R_INDICES && (cnt < 3 || cnt > 1e6)) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: %s: a face has %.0f vertices (expected 3 to 10^6)", r->path, at, cnt);
  }
  if (cnt < 0) {
    return ss_error_set(r->err, SS_ERR_PARSE, "%s: %s: negative list length %.0f", r->path, at,
                        cnt);
  }
  uint32_t first = 0, prev = 0;
  for (size_t i = 0; i < (size_t)cnt; ++i) {
    double x;
    rc = read_value(r, c, p->type, &x);
    if (rc != 0) {
      return value_error(r, e, k, p, rc);
    }
    if (p->role != R_INDICES) {
      continue;
    }
    if (!(x >= 0.0) || x >= (double)r->nv) {
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: %s: vertex index %.0f out of range (expected 0 to %zu)", r->path, at,
                          x, r->nv ? r->nv - 1 : 0);
    }
    uint32_t idx = (uint32_t)x;
    /* Fan triangulation: (v0, v[i-1], v[i]). */
    if (i == 0) {
      first = idx;
    } else if (i >= 2) {
      uint32_t tri[3] = {first, prev, idx};
      if (ss_index_buffer_push(&r->tris, tri, 3) != 0) {
        return ss_error_set(r->err, SS_ERR_NO_MEMORY, "%s: out of memory", r->path);
      }
    }
    prev = idx;
  }
  return SS_OK;
}

static ss_status read_element(ply_reader *r, const ply_element *e, size_t k) {
  token_cursor c = {NULL, 0};
  int is_vertex = strcmp(e->name, "vertex") == 0;
  if (r->format == F_ASCII && !next_line(r)) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: line %zu: the file ends early, expected %s %zu of %zu (truncated "
                        "file?)",
                        r->path, r->line + 1, e->name, k, e->count);
  }
  for (size_t i = 0; i < e->nprops; ++i) {
    const ply_prop *p = &e->props[i];
    if (p->is_list) {
      ss_status st = read_face_list(r, &c, e, k, p);
      if (st != SS_OK) {
        return st;
      }
      continue;
    }
    double x;
    int rc = read_value(r, &c, p->type, &x);
    if (rc != 0) {
      return value_error(r, e, k, p, rc);
    }
    if (!is_vertex || p->role == R_NONE) {
      continue;
    }
    if (!isfinite(x)) {
      char at[160];
      where(r, e, k, at, sizeof at);
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: %s: property '%s' is %g (expected a finite "
                          "number)",
                          r->path, at, p->name, x);
    }
    switch (p->role) {
    case R_X:
    case R_Y:
    case R_Z:
      r->pos[3 * k + (size_t)(p->role - R_X)] = (float)x;
      break;
    case R_NX:
    case R_NY:
    case R_NZ:
      if (r->nrm) {
        r->nrm[3 * k + (size_t)(p->role - R_NX)] = (float)x;
      }
      break;
    case R_U:
    case R_V:
      if (r->uv) {
        r->uv[2 * k + (size_t)(p->role - R_U)] = (float)x;
      }
      break;
    default:
      break;
    }
  }
  if (r->format == F_ASCII) {
    double extra;
    if (read_ascii(r, &c, T_F64, &extra) != -1) {
      char at[160];
      where(r, e, k, at, sizeof at);
      return ss_error_set(r->err, SS_ERR_PARSE,
                          "%s: %s: more values than the header's %zu properties of '%s'", r->path,
                          at, e->nprops, e->name);
    }
  }
  return SS_OK;
}

static ss_status read_body(ply_reader *r) {
  for (size_t i = 0; i < r->nelems; ++i) {
    for (size_t k = 0; k < r->elems[i].count; ++k) {
      ss_status st = read_element(r, &r->elems[i], k);
      if (st != SS_OK) {
        return st;
      }
    }
  }
  /* Data past the declared elements means the counts are wrong. */
  if (r->format == F_ASCII) {
    while (next_line(r)) {
      for (const char *s = r->buf; *s; ++s) {
        if (!isspace((unsigned char)*s)) {
          return ss_error_set(r->err, SS_ERR_PARSE,
                              "%s: line %zu: data after the last declared element (wrong "
                              "element counts in the header?)",
                              r->path, r->line);
        }
      }
    }
  } else if (fgetc(r->f) != EOF) {
    return ss_error_set(r->err, SS_ERR_PARSE,
                        "%s: bytes after the last declared element (wrong element counts in "
                        "the header?)",
                        r->path);
  }
  if (ferror(r->f)) {
    return ss_error_set(r->err, SS_ERR_IO, "%s: read error", r->path);
  }
  return SS_OK;
}

ss_status ss_mesh_read_ply(const char *path, ss_mesh **out, ss_mesh_read_info *info,
                           ss_error *err) {
  *out = NULL;
  ply_reader r;
  memset(&r, 0, sizeof r);
  r.path = path;
  r.err = err;
  unsigned char *data;
  size_t size;
  ss_status st = ss_input_file_read(path, path, SS_INPUT_MESH, &data, &size, err);
  if (st != SS_OK) {
    return st;
  }
  /* the file's bytes as a stream: the reader counts what follows the header */
  r.file_size = size;
  if (!(r.f = fmemopen(data, size, "rb"))) {
    free(data);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory", path);
  }
  int has_n = 0, has_uv = 0;
  st = read_header(&r);
  if (st == SS_OK) {
    st = prepare(&r, &has_n, &has_uv);
  }
  if (st == SS_OK) {
    st = read_body(&r);
  }
  if (st == SS_OK) {
    st = ss_mesh_io_finish(path, r.nv, &r.pos, &r.nrm, &r.uv, &r.tris, r.npolys, out, info, err);
  }
  fclose(r.f);
  free(data);
  free(r.buf);
  for (size_t i = 0; i < r.nelems; ++i) {
    free(r.elems[i].props);
  }
  free(r.elems);
  free(r.pos);
  free(r.nrm);
  free(r.uv);
  ss_index_buffer_free(&r.tris);
  return st;
}
