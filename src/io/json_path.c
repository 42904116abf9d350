/* Key-path locations and typed accessors for JSON documents (json_path.h). */
#include "io/json_path.h"

#include "subsurf/number.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *skip_ws(const char *p) {
  while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') {
    ++p;
  }
  return p;
}

/* p at the opening quote; returns the character after the closing one. */
static const char *skip_string(const char *p) {
  for (++p; *p && *p != '"'; ++p) {
    if (*p == '\\' && p[1]) {
      ++p;
    }
  }
  return *p ? p + 1 : p;
}

static const char *skip_value(const char *p) {
  p = skip_ws(p);
  if (*p == '"') {
    return skip_string(p);
  }
  if (*p == '{' || *p == '[') {
    int depth = 0;
    for (; *p; ++p) {
      if (*p == '"') {
        p = skip_string(p) - 1;
      } else if (*p == '{' || *p == '[') {
        ++depth;
      } else if (*p == '}' || *p == ']') {
        if (--depth == 0) {
          return p + 1;
        }
      }
    }
    return p;
  }
  while (*p && *p != ',' && *p != '}' && *p != ']' && *p != ' ' && *p != '\n' && *p != '\r' &&
         *p != '\t') {
    ++p;
  }
  return p;
}

/* Compares the raw key text between quotes with `key` (keys in scene files
 * have no escapes). */
static int key_equals(const char *quote, const char *key) {
  size_t n = strlen(key);
  return !strncmp(quote + 1, key, n) && quote[1 + n] == '"';
}

long ss_json_locate(const char *text, const ss_json_elem *path, int depth) {
  const char *p = skip_ws(text);
  const char *found = p;
  for (int d = 0; d < depth; ++d) {
    if (path[d].key) {
      if (*p != '{') {
        return -1;
      }
      p = skip_ws(p + 1);
      const char *hit = NULL;
      while (*p == '"') {
        const char *key = p;
        p = skip_ws(skip_string(p));
        if (*p != ':') {
          return -1;
        }
        p = skip_ws(p + 1);
        if (key_equals(key, path[d].key)) {
          hit = key;
          break;
        }
        p = skip_ws(skip_value(p));
        if (*p == ',') {
          p = skip_ws(p + 1);
        }
      }
      if (!hit) {
        return -1;
      }
      found = hit;
    } else {
      if (*p != '[') {
        return -1;
      }
      p = skip_ws(p + 1);
      for (int i = 0; i < path[d].index; ++i) {
        if (*p == ']' || !*p) {
          return -1;
        }
        p = skip_ws(skip_value(p));
        if (*p == ',') {
          p = skip_ws(p + 1);
        }
      }
      if (*p == ']' || !*p) {
        return -1;
      }
      found = p;
    }
  }
  return (long)(found - text);
}

int ss_json_line(const char *text, long offset) {
  int line = 1;
  for (long i = 0; i < offset && text[i]; ++i) {
    line += text[i] == '\n';
  }
  return line;
}

void ss_json_push_key(ss_json_ctx *c, const char *key) {
  if (c->depth < SS_JSON_MAX_DEPTH) {
    c->path[c->depth].key = key;
    c->path[c->depth].index = -1;
  }
  c->depth++;
}

void ss_json_push_index(ss_json_ctx *c, int index) {
  if (c->depth < SS_JSON_MAX_DEPTH) {
    c->path[c->depth].key = NULL;
    c->path[c->depth].index = index;
  }
  c->depth++;
}

void ss_json_pop(ss_json_ctx *c) { c->depth--; }

static void format_path(const ss_json_ctx *c, char *buf, size_t size) {
  size_t used = 0;
  buf[0] = '\0';
  int depth = c->depth < SS_JSON_MAX_DEPTH ? c->depth : SS_JSON_MAX_DEPTH;
  for (int d = 0; d < depth && used < size; ++d) {
    int n = c->path[d].key ? snprintf(buf + used, size - used, "%s%s", d ? "." : "", c->path[d].key)
                           : snprintf(buf + used, size - used, "[%d]", c->path[d].index);
    if (n < 0) {
      return;
    }
    used += (size_t)n;
  }
}

/* Line of the deepest prefix of the current path present in the text. */
static int current_line(const ss_json_ctx *c) {
  int depth = c->depth < SS_JSON_MAX_DEPTH ? c->depth : SS_JSON_MAX_DEPTH;
  for (int d = depth; d >= 0; --d) {
    long off = ss_json_locate(c->text, c->path, d);
    if (off >= 0) {
      return ss_json_line(c->text, off);
    }
  }
  return 1;
}

static ss_status vfail(ss_json_ctx *c, ss_status status, const char *fmt, va_list ap) {
  char msg[SS_ERROR_MESSAGE_SIZE / 2], path[256];
  vsnprintf(msg, sizeof msg, fmt, ap);
  format_path(c, path, sizeof path);
  return ss_error_set(c->err, status, "%s:%d: %s%s%s", c->file, current_line(c), path,
                      path[0] ? ": " : "", msg);
}

ss_status ss_json_fail(ss_json_ctx *c, ss_status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  ss_status st = vfail(c, status, fmt, ap);
  va_end(ap);
  return st;
}

ss_status ss_json_fail_key(ss_json_ctx *c, const char *key, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  ss_json_push_key(c, key);
  ss_status st = vfail(c, SS_ERR_PARSE, fmt, ap);
  ss_json_pop(c);
  va_end(ap);
  return st;
}

ss_status ss_json_wrap(ss_json_ctx *c, ss_status status) {
  char path[256];
  format_path(c, path, sizeof path);
  ss_error_prefix(c->err, "%s:%d: %s%s", c->file, current_line(c), path, path[0] ? ": " : "");
  return status;
}

static const char *type_name(const cJSON *item) {
  if (cJSON_IsObject(item)) {
    return "an object";
  }
  if (cJSON_IsArray(item)) {
    return "an array";
  }
  if (cJSON_IsString(item)) {
    return "a string";
  }
  if (cJSON_IsNumber(item)) {
    return "a number";
  }
  if (cJSON_IsBool(item)) {
    return "a boolean";
  }
  return "null";
}

ss_status ss_json_expect_object(ss_json_ctx *c, const cJSON *item) {
  if (!cJSON_IsObject(item)) {
    return ss_json_fail(c, SS_ERR_PARSE, "expected an object, got %s", type_name(item));
  }
  return SS_OK;
}

ss_status ss_json_check_keys(ss_json_ctx *c, const cJSON *obj, const char *const *allowed) {
  const cJSON *m;
  cJSON_ArrayForEach(m, obj) {
    int ok = 0;
    for (const char *const *a = allowed; *a && !ok; ++a) {
      ok = !strcmp(*a, m->string);
    }
    if (!ok) {
      char list[512];
      size_t used = 0;
      list[0] = '\0';
      for (const char *const *a = allowed; *a && used < sizeof list; ++a) {
        int n = snprintf(list + used, sizeof list - used, "%s%s", a == allowed ? "" : ", ", *a);
        used += n > 0 ? (size_t)n : 0;
      }
      return ss_json_fail_key(c, m->string, "unknown key (allowed here: %s)", list);
    }
  }
  return SS_OK;
}

ss_status ss_json_require(ss_json_ctx *c, const cJSON *obj, const char *key) {
  if (!cJSON_GetObjectItemCaseSensitive(obj, key)) {
    return ss_json_fail(c, SS_ERR_PARSE, "missing required key '%s'", key);
  }
  return SS_OK;
}

ss_status ss_json_number(ss_json_ctx *c, const cJSON *obj, const char *key, double lo, double hi,
                         double *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (!cJSON_IsNumber(v)) {
    return ss_json_fail_key(c, key, "expected a number, got %s", type_name(v));
  }
  if (!isfinite(v->valuedouble) || v->valuedouble < lo || v->valuedouble > hi) {
    return ss_json_fail_key(c, key, "%g is out of range [%g, %g]", v->valuedouble, lo, hi);
  }
  *out = v->valuedouble;
  return SS_OK;
}

ss_status ss_json_int(ss_json_ctx *c, const cJSON *obj, const char *key, long lo, long hi,
                      long *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble)) {
    return ss_json_fail_key(c, key, "expected an integer, got %s",
                            cJSON_IsNumber(v) ? "a fraction" : type_name(v));
  }
  if (v->valuedouble < (double)lo || v->valuedouble > (double)hi) {
    char got[32];
    ss_number_format(v->valuedouble, got, sizeof got);
    return ss_json_fail_key(c, key, "%s is out of range [%ld, %ld]", got, lo, hi);
  }
  *out = (long)v->valuedouble;
  return SS_OK;
}

ss_status ss_json_bool(ss_json_ctx *c, const cJSON *obj, const char *key, int *out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (!cJSON_IsBool(v)) {
    return ss_json_fail_key(c, key, "expected true or false, got %s", type_name(v));
  }
  *out = cJSON_IsTrue(v);
  return SS_OK;
}

ss_status ss_json_string(ss_json_ctx *c, const cJSON *obj, const char *key, char *out,
                         size_t size) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (!cJSON_IsString(v)) {
    return ss_json_fail_key(c, key, "expected a string, got %s", type_name(v));
  }
  if (strlen(v->valuestring) >= size) {
    return ss_json_fail_key(c, key, "string longer than %zu characters", size - 1);
  }
  snprintf(out, size, "%s", v->valuestring);
  return SS_OK;
}

static ss_status read_triple(ss_json_ctx *c, const cJSON *obj, const char *key, int allow_scalar,
                             double lo, double out[3]) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
  if (!v) {
    return SS_OK;
  }
  if (allow_scalar && cJSON_IsNumber(v)) {
    if (!isfinite(v->valuedouble) || v->valuedouble < lo) {
      return ss_json_fail_key(c, key, "%g is out of range (must be >= %g)", v->valuedouble, lo);
    }
    out[0] = out[1] = out[2] = v->valuedouble;
    return SS_OK;
  }
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3) {
    return ss_json_fail_key(c, key, "expected %san array of 3 numbers, got %s",
                            allow_scalar ? "a number or " : "",
                            cJSON_IsArray(v) ? "an array of another length" : type_name(v));
  }
  for (int i = 0; i < 3; ++i) {
    const cJSON *e = cJSON_GetArrayItem(v, i);
    if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || e->valuedouble < lo) {
      ss_json_push_key(c, key);
      ss_json_push_index(c, i);
      ss_status st = cJSON_IsNumber(e)
                         ? ss_json_fail(c, SS_ERR_PARSE, "%g is out of range (must be >= %g)",
                                        e->valuedouble, lo)
                         : ss_json_fail(c, SS_ERR_PARSE, "expected a number, got %s", type_name(e));
      c->depth -= 2;
      return st;
    }
    out[i] = e->valuedouble;
  }
  return SS_OK;
}

ss_status ss_json_vec3(ss_json_ctx *c, const cJSON *obj, const char *key, ss_vec3 *out) {
  double v[3] = {out->x, out->y, out->z};
  ss_status st = read_triple(c, obj, key, 0, -HUGE_VAL, v);
  *out = ss_vec3_make(v[0], v[1], v[2]);
  return st;
}

ss_status ss_json_rgb(ss_json_ctx *c, const cJSON *obj, const char *key, double lo, ss_rgb *out) {
  return read_triple(c, obj, key, 1, lo, out->c);
}
