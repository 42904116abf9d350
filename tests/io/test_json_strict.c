/* Scene files are strict JSON (RFC 8259): every departure cJSON would let
 * through is an error naming the line; duplicate keys are errors anywhere,
 * also where a section takes free keys, and also when spelled differently
 * ("a" and "\u0061"). */
#include "io/json_strict.h"
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#define SHAPES "\"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 1}]"

static void expect_invalid(const char *text, int line, const char *what) {
  ss_error err;
  ss_error_clear(&err);
  cr_assert_eq(ss_json_check_strict(text, "t.json", &err), SS_ERR_PARSE, "accepted: %s", text);
  char where[32];
  snprintf(where, sizeof where, "t.json:%d: invalid JSON", line);
  cr_assert(strstr(err.message, where) != NULL, "'%s' lacks '%s'", err.message, where);
  cr_assert(strstr(err.message, what) != NULL, "'%s' lacks '%s'", err.message, what);
  ss_scene *s = NULL;
  cr_assert_eq(ss_scene_parse_json(text, "t.json", NULL, &s, &err), SS_ERR_PARSE,
               "the scene reader accepted: %s", text);
}

static void expect_valid(const char *text) {
  ss_error err;
  ss_error_clear(&err);
  cr_assert_eq(ss_json_check_strict(text, "t.json", &err), SS_OK, "%s: %s", text, err.message);
}

Test(json_strict, numbers_follow_the_grammar) {
  expect_invalid("{\n\"a\": 030}", 2, "leading zero");
  expect_invalid("{\"a\": -01}", 1, "leading zero");
  expect_invalid("{\"a\": 1.}", 1, "after the decimal point");
  expect_invalid("{\"a\": .5}", 1, "expected a value");
  expect_invalid("{\"a\": +5}", 1, "expected a value");
  expect_invalid("{\"a\": 1e}", 1, "exponent");
  expect_invalid("{\"a\": 0x10}", 1, "expected ',' or '}'");
  expect_invalid("{\"a\": NaN}", 1, "expected a value");
  expect_invalid("{\"a\": Infinity}", 1, "expected a value");
  expect_valid("{\"a\": [0, -0, 0.5, -1.25e-3, 1E+9, 10, 7e0]}");
}

Test(json_strict, strings_are_valid_utf8_without_control_characters) {
  expect_invalid("{\"a\": \"tab\there\"}", 1, "control character");
  expect_invalid("{\"a\":\n \"new\nline\"}", 2, "control character");
  expect_invalid("{\"a\": \"\xff\"}", 1, "invalid UTF-8");
  expect_invalid("{\"a\": \"\xc3\"}", 1, "invalid UTF-8");
  expect_invalid("{\"a\": \"\xc0\xaf\"}", 1, "overlong");
  expect_invalid("{\"a\": \"\xed\xa0\x80\"}", 1, "surrogate");
  expect_invalid("{\"a\": \"\xf4\x90\x80\x80\"}", 1, "U+10FFFF");
  expect_invalid("{\"a\": \"\\ud800\"}", 1, "high surrogate");
  expect_invalid("{\"a\": \"\\udc00\"}", 1, "low surrogate");
  expect_invalid("{\"a\": \"\\u0000\"}", 1, "NUL");
  expect_invalid("{\"a\": \"\\x41\"}", 1, "invalid escape");
  expect_invalid("{\"a\": \"open}", 1, "unterminated");
  expect_valid(
      "{\"a\": \"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80 \\u00e9 \\ud83d\\ude00 \\n\\\"\"}");
}

Test(json_strict, structure_has_no_trailing_commas_or_extra_text) {
  expect_invalid("{\"a\": 1,}", 1, "comma before '}'");
  expect_invalid("{\"a\": [1, 2,]}", 1, "comma before ']'");
  expect_invalid("{\"a\": 1}\n{}", 2, "after the end");
  expect_invalid("{\"a\" 1}", 1, "expected ':'");
  expect_invalid("{a: 1}", 1, "expected a key");
  expect_invalid("", 1, "expected a value");
  char deep[1200];
  memset(deep, '[', 600);
  memset(deep + 600, ']', 600);
  deep[1199] = '\0';
  expect_invalid(deep, 1, "256 levels");
  expect_valid(" \r\n\t{\"a\": [true, false, null, {}, []]} \n");
}

Test(json_strict, duplicate_keys_are_errors_everywhere) {
  const char *texts[3] = {
      "{" SHAPES ",\n\"integrator\": {\"type\": \"volpath\",\n\"rr_depth\": 3, \"rr_depth\": 4}}",
      "{" SHAPES ",\n\"description\": \"x\",\n\"descr\\u0069ption\": \"y\"}",
      "{" SHAPES
      ",\n\"lights\": [{\"type\": \"point\"},\n{\"type\": \"point\", \"type\": \"spot\"}]}"};
  const char *paths[3] = {"integrator.rr_depth", "description", "lights[1].type"};
  for (int i = 0; i < 3; ++i) {
    ss_scene *s = NULL;
    ss_error err;
    cr_assert_eq(ss_scene_parse_json(texts[i], "t.json", NULL, &s, &err), SS_ERR_PARSE, "%s",
                 texts[i]);
    cr_assert(strstr(err.message, paths[i]) && strstr(err.message, "duplicate key"), "%s",
              err.message);
  }
}
