/* pbrt-v3's tokenizer: '#' comments to the end of the line, quoted strings
 * (with pbrt's backslash escapes, never across a line), '[' and ']', and
 * bare words that are numbers or directives (pbrt.h). */
#include "io/pbrt.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_pbrt_lexer_push(ss_pbrt *P, char *text, const char *file) {
  ss_pbrt_lexer *l = calloc(1, sizeof *l);
  if (!l) {
    free(text);
    ss_pbrt_fail(P, file, 0, "out of memory");
    return;
  }
  l->text = text;
  l->line = 1;
  snprintf(l->file, sizeof l->file, "%s", file);
  l->parent = P->lex;
  P->lex = l;
}

int ss_pbrt_lexer_pop(ss_pbrt *P) {
  ss_pbrt_lexer *l = P->lex;
  if (!l) {
    return 0;
  }
  P->lex = l->parent;
  free(l->text);
  free(l);
  return P->lex != NULL;
}

static int is_delim(int c) {
  return c == '\0' || isspace(c) || c == '"' || c == '[' || c == ']' || c == '#';
}

static void read_string(ss_pbrt *P, ss_pbrt_lexer *l, ss_pbrt_token *t) {
  size_t n = 0;
  ++l->pos;
  for (;;) {
    char c = l->text[l->pos];
    if (c == '\0' || c == '\n') {
      ss_pbrt_fail(P, l->file, t->line, "unterminated string (expected '\"' before the %s)",
                   c ? "end of the line" : "end of the file");
      return;
    }
    ++l->pos;
    if (c == '"') {
      break;
    }
    if (c == '\\') {
      char e = l->text[l->pos];
      static const char from[] = "bfnrt\\'\"", to[] = "\b\f\n\r\t\\'\"";
      const char *k = e ? strchr(from, e) : NULL;
      if (!k) {
        ss_pbrt_fail(P, l->file, t->line, "unknown escape '\\%c' in a string", e ? e : ' ');
        return;
      }
      c = to[k - from];
      ++l->pos;
    }
    if (n + 1 >= sizeof t->text) {
      ss_pbrt_fail(P, l->file, t->line, "string longer than %zu bytes", sizeof t->text - 1);
      return;
    }
    t->text[n++] = c;
  }
  t->text[n] = '\0';
  t->kind = SS_PBRT_STRING;
}

static void read_token(ss_pbrt *P, ss_pbrt_token *t) {
  memset(t, 0, offsetof(ss_pbrt_token, text) + 1);
  t->kind = SS_PBRT_EOF;
  ss_pbrt_lexer *l = P->lex;
  if (P->st != SS_OK || !l) {
    return;
  }
  for (;;) {
    char c = l->text[l->pos];
    if (c == '\n') {
      ++l->line;
      ++l->pos;
    } else if (isspace((unsigned char)c)) {
      ++l->pos;
    } else if (c == '#') {
      while (l->text[l->pos] && l->text[l->pos] != '\n') {
        ++l->pos;
      }
    } else {
      break;
    }
  }
  t->line = l->line;
  char c = l->text[l->pos];
  if (c == '\0') {
    return;
  }
  if (c == '"') {
    read_string(P, l, t);
    return;
  }
  if (c == '[' || c == ']') {
    ++l->pos;
    t->kind = c == '[' ? SS_PBRT_LBRACKET : SS_PBRT_RBRACKET;
    t->text[0] = c;
    t->text[1] = '\0';
    return;
  }
  size_t start = l->pos;
  while (!is_delim((unsigned char)l->text[l->pos])) {
    ++l->pos;
  }
  size_t n = l->pos - start;
  if (n >= sizeof t->text) {
    ss_pbrt_fail(P, l->file, t->line, "word longer than %zu bytes", sizeof t->text - 1);
    return;
  }
  memcpy(t->text, l->text + start, n);
  t->text[n] = '\0';
  if (isdigit((unsigned char)c) || c == '-' || c == '+' || c == '.') {
    char *end = NULL;
    t->number = strtod(t->text, &end);
    if (*end || !isfinite(t->number)) {
      ss_pbrt_fail(P, l->file, t->line, "expected a finite number, got '%s'", t->text);
      return;
    }
    t->kind = SS_PBRT_NUMBER;
    return;
  }
  t->kind = SS_PBRT_WORD;
}

void ss_pbrt_next(ss_pbrt *P, ss_pbrt_token *t) {
  if (P->lex && P->lex->has_peek) {
    *t = P->lex->peek;
    P->lex->has_peek = 0;
    return;
  }
  read_token(P, t);
}

void ss_pbrt_peek(ss_pbrt *P, ss_pbrt_token *t) {
  if (P->lex && !P->lex->has_peek) {
    read_token(P, &P->lex->peek);
    P->lex->has_peek = 1;
  }
  if (P->lex) {
    *t = P->lex->peek;
  } else {
    memset(t, 0, offsetof(ss_pbrt_token, text) + 1);
  }
}
