/* Strict JSON (RFC 8259) before cJSON, which is lenient: it accepts leading
 * zeros, "1.", raw control characters and invalid UTF-8 in strings. The
 * checker walks the grammar once and reports the first departure with its
 * line; duplicate keys are found afterwards on the parsed tree, with their
 * key path (json_strict.h). */
#include "io/json_strict.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Deeper documents are refused rather than recursed into. */
#define MAX_NESTING 256

typedef struct {
  const char *text;
  const char *p;
  const char *what; /* the first error, NULL while none */
} checker;

static int failed(checker *c, const char *what) {
  if (!c->what) {
    c->what = what;
  }
  return 0;
}

static void skip_ws(checker *c) {
  while (*c->p == ' ' || *c->p == '\t' || *c->p == '\n' || *c->p == '\r') {
    c->p++;
  }
}

static int is_digit(char ch) { return ch >= '0' && ch <= '9'; }

static int hex4(const char *s, unsigned *out) {
  unsigned v = 0;
  for (int i = 0; i < 4; ++i) {
    char ch = s[i];
    unsigned d = is_digit(ch)               ? (unsigned)(ch - '0')
                 : (ch >= 'a' && ch <= 'f') ? (unsigned)(ch - 'a' + 10)
                 : (ch >= 'A' && ch <= 'F') ? (unsigned)(ch - 'A' + 10)
                                            : 16u;
    if (d == 16u) {
      return 0;
    }
    v = 16u * v + d;
  }
  *out = v;
  return 1;
}

/* One UTF-8 sequence at c->p (first byte >= 0x80): shortest form, no
 * surrogates, at most U+10FFFF (RFC 3629). */
static int utf8(checker *c) {
  const unsigned char *s = (const unsigned char *)c->p;
  int n = s[0] >= 0xF0 ? 3 : s[0] >= 0xE0 ? 2 : s[0] >= 0xC0 ? 1 : -1;
  if (n < 0 || s[0] > 0xF4) {
    return failed(c, "invalid UTF-8 in a string");
  }
  uint32_t cp = s[0] & (0x3Fu >> n);
  for (int i = 1; i <= n; ++i) {
    if ((s[i] & 0xC0) != 0x80) {
      return failed(c, "invalid UTF-8 in a string");
    }
    cp = (cp << 6) | (s[i] & 0x3Fu);
  }
  static const uint32_t min[4] = {0, 0x80, 0x800, 0x10000};
  if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
    return failed(c, "invalid UTF-8 in a string (overlong, surrogate or beyond U+10FFFF)");
  }
  c->p += n + 1;
  return 1;
}

static int escape(checker *c) {
  char e = c->p[1];
  if (strchr("\"\\/bfnrt", e) && e) {
    c->p += 2;
    return 1;
  }
  unsigned u, lo;
  if (e != 'u' || !hex4(c->p + 2, &u)) {
    return failed(c, "invalid escape in a string");
  }
  c->p += 6;
  if (u == 0) {
    return failed(c, "\\u0000 in a string (strings cannot hold NUL)");
  }
  if (u >= 0xDC00 && u <= 0xDFFF) {
    return failed(c, "\\u escape of a lone low surrogate");
  }
  if (u >= 0xD800 && u <= 0xDBFF) {
    if (c->p[0] != '\\' || c->p[1] != 'u' || !hex4(c->p + 2, &lo) || lo < 0xDC00 || lo > 0xDFFF) {
      return failed(c, "\\u escape of a high surrogate without its low surrogate");
    }
    c->p += 6;
  }
  return 1;
}

static int string(checker *c) {
  c->p++; /* the opening quote */
  for (;;) {
    unsigned char ch = (unsigned char)*c->p;
    if (ch == '"') {
      c->p++;
      return 1;
    }
    if (ch == '\0') {
      return failed(c, "unterminated string");
    }
    if (ch < 0x20) {
      return failed(c, "a control character in a string (write it as an escape such as \\n)");
    }
    if (ch == '\\') {
      if (!escape(c)) {
        return 0;
      }
    } else if (ch >= 0x80) {
      if (!utf8(c)) {
        return 0;
      }
    } else {
      c->p++;
    }
  }
}

/* -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)? */
static int number(checker *c) {
  if (*c->p == '-') {
    c->p++;
  }
  if (*c->p == '0') {
    c->p++;
    if (is_digit(*c->p)) {
      return failed(c, "a number with a leading zero");
    }
  } else if (is_digit(*c->p)) {
    while (is_digit(*c->p)) {
      c->p++;
    }
  } else {
    return failed(c, "expected a digit in a number");
  }
  if (*c->p == '.') {
    c->p++;
    if (!is_digit(*c->p)) {
      return failed(c, "expected a digit after the decimal point");
    }
    while (is_digit(*c->p)) {
      c->p++;
    }
  }
  if (*c->p == 'e' || *c->p == 'E') {
    c->p++;
    if (*c->p == '+' || *c->p == '-') {
      c->p++;
    }
    if (!is_digit(*c->p)) {
      return failed(c, "expected a digit in the exponent");
    }
    while (is_digit(*c->p)) {
      c->p++;
    }
  }
  return 1;
}

static int literal(checker *c, const char *word) {
  size_t n = strlen(word);
  if (strncmp(c->p, word, n) != 0) {
    return failed(c, "expected a value");
  }
  c->p += n;
  return 1;
}

static int value(checker *c, int depth);

/* An object or array: `close` ends it, members are separated by commas. */
static int container(checker *c, int depth, char close) {
  if (depth >= MAX_NESTING) {
    return failed(c, "nested more than 256 levels deep");
  }
  c->p++;
  skip_ws(c);
  if (*c->p == close) {
    c->p++;
    return 1;
  }
  for (;;) {
    skip_ws(c);
    if (close == '}') {
      if (*c->p != '"') {
        return failed(c, *c->p == '}' ? "a comma before '}'" : "expected a key (a string)");
      }
      if (!string(c)) {
        return 0;
      }
      skip_ws(c);
      if (*c->p != ':') {
        return failed(c, "expected ':' after a key");
      }
      c->p++;
      skip_ws(c);
    } else if (*c->p == ']') {
      return failed(c, "a comma before ']'");
    }
    if (!value(c, depth + 1)) {
      return 0;
    }
    skip_ws(c);
    if (*c->p == close) {
      c->p++;
      return 1;
    }
    if (*c->p != ',') {
      return failed(c, close == '}' ? "expected ',' or '}'" : "expected ',' or ']'");
    }
    c->p++;
  }
}

static int value(checker *c, int depth) {
  skip_ws(c);
  switch (*c->p) {
  case '{':
    return container(c, depth, '}');
  case '[':
    return container(c, depth, ']');
  case '"':
    return string(c);
  case 't':
    return literal(c, "true");
  case 'f':
    return literal(c, "false");
  case 'n':
    return literal(c, "null");
  default:
    return *c->p == '-' || is_digit(*c->p) ? number(c) : failed(c, "expected a value");
  }
}

static int line_of(const char *text, const char *p) {
  int line = 1;
  for (const char *s = text; s < p; ++s) {
    line += *s == '\n';
  }
  return line;
}

ss_status ss_json_check_strict(const char *text, const char *file, ss_error *err) {
  checker c = {text, text, NULL};
  if (value(&c, 0)) {
    skip_ws(&c);
    if (*c.p != '\0') {
      failed(&c, "text after the end of the document");
    }
  }
  if (!c.what) {
    return SS_OK;
  }
  return ss_error_set(err, SS_ERR_PARSE, "%s:%d: invalid JSON: %s", file, line_of(text, c.p),
                      c.what);
}

static int by_key(const void *a, const void *b) {
  return strcmp((*(const cJSON *const *)a)->string, (*(const cJSON *const *)b)->string);
}

/* Sorting the members finds a repeated key in n log n for any object. */
static ss_status unique_keys(ss_json_ctx *c, const cJSON *obj) {
  int n = cJSON_GetArraySize(obj);
  if (n < 2) {
    return SS_OK;
  }
  const cJSON **m = malloc((size_t)n * sizeof *m);
  if (!m) {
    return ss_error_set(c->err, SS_ERR_NO_MEMORY, "%s: out of memory", c->file);
  }
  int i = 0;
  for (const cJSON *e = obj->child; e; e = e->next) {
    m[i++] = e;
  }
  qsort(m, (size_t)n, sizeof *m, by_key);
  const char *dup = NULL;
  for (i = 1; i < n && !dup; ++i) {
    if (!strcmp(m[i - 1]->string, m[i]->string)) {
      dup = m[i]->string;
    }
  }
  free(m);
  return dup ? ss_json_fail_key(c, dup, "duplicate key") : SS_OK;
}

ss_status ss_json_check_unique_keys(ss_json_ctx *c, const cJSON *item) {
  if (cJSON_IsObject(item)) {
    ss_status st = unique_keys(c, item);
    for (const cJSON *e = item->child; e && st == SS_OK; e = e->next) {
      ss_json_push_key(c, e->string);
      st = ss_json_check_unique_keys(c, e);
      ss_json_pop(c);
    }
    return st;
  }
  int i = 0;
  for (const cJSON *e = cJSON_IsArray(item) ? item->child : NULL; e; e = e->next, ++i) {
    ss_json_push_index(c, i);
    ss_status st = ss_json_check_unique_keys(c, e);
    ss_json_pop(c);
    if (st != SS_OK) {
      return st;
    }
  }
  return SS_OK;
}
