/* The text of the `layers` model's "layers" option (bssrdf_layers.h). */
#include "subsurf/bssrdf_layers.h"

#include "subsurf/number.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* DonnerJensen2005 Table 3: epidermis, upper dermis, bloody dermis. */
static const ss_bssrdf_layer skin[3] = {
    {{48.0, 60.0, 65.0}, {2.1, 2.1, 5.0}, {0.0, 0.0, 0.0}, 1.4, 0.03},
    {{32.0, 40.0, 46.0}, {0.16, 0.19, 0.30}, {0.25, 0.25, 0.25}, 1.34, 0.05},
    {{4.5, 4.7, 4.8}, {0.085, 1.0, 25.0}, {0.8, 0.8, 0.8}, 1.4, INFINITY},
};

/* One number of number.h's grammar, or "inf", in the first len characters. */
static int parse_value(const char *s, size_t len, double *v) {
  if (len == 3 && !strncmp(s, "inf", 3)) {
    *v = INFINITY;
    return 1;
  }
  return ss_number_parse_n(s, len, v);
}

/* "x" or "x,y,z" (the whole of `text`) into v[3]. */
static int parse_values(const char *text, double v[3], int want3) {
  const char *s = text;
  for (int i = 0; i < 3; ++i) {
    const char *comma = strchr(s, ',');
    size_t len = comma ? (size_t)(comma - s) : strlen(s);
    if (!parse_value(s, len, &v[i])) {
      return 0;
    }
    if (!comma && i == 0) {
      v[1] = v[2] = v[0];
      return 1;
    }
    if (!comma) {
      return i == 2;
    }
    if (!want3) {
      return 0;
    }
    s = comma + 1;
  }
  return 0;
}

enum { KEY_SIGMA_S, KEY_SIGMA_A, KEY_G, KEY_ETA, KEY_D, KEYS };
static const char *const key_names[KEYS] = {"sigma_s", "sigma_a", "g", "eta", "d"};

/* One "key=value" item of layer k. */
static ss_status parse_item(const char *item, int k, ss_bssrdf_layer *ly, unsigned *seen,
                            ss_error *err) {
  const char *eq = strchr(item, '=');
  size_t n = eq ? (size_t)(eq - item) : 0;
  for (int key = 0; eq && key < KEYS; ++key) {
    if (strlen(key_names[key]) != n || strncmp(item, key_names[key], n)) {
      continue;
    }
    double v[3];
    double *dst[KEYS] = {ly->sigma_s, ly->sigma_a, ly->g, &ly->eta, &ly->thickness};
    int three = key <= KEY_G;
    if (!parse_values(eq + 1, v, three)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "layer %d: %s: expected %s, got '%s'", k,
                          key_names[key],
                          three ? "one number or three comma-separated" : "a number", eq + 1);
    }
    memcpy(dst[key], v, (three ? 3 : 1) * sizeof v[0]);
    *seen |= 1u << key;
    return SS_OK;
  }
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "layer %d: expected sigma_s=, sigma_a=, g=, eta= or d=, got '%s'", k, item);
}

static ss_status parse_layer(char *text, int k, ss_bssrdf_layer *ly, ss_error *err) {
  memset(ly, 0, sizeof *ly);
  unsigned seen = 1u << KEY_G;
  for (char *save = NULL, *item = strtok_r(text, " \t\n", &save); item;
       item = strtok_r(NULL, " \t\n", &save)) {
    ss_status st = parse_item(item, k, ly, &seen, err);
    if (st != SS_OK) {
      return st;
    }
  }
  for (int key = 0; key < KEYS; ++key) {
    if (!(seen & (1u << key))) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "layer %d: missing %s=", k, key_names[key]);
    }
  }
  return SS_OK;
}

ss_status ss_bssrdf_layer_stack_parse(const char *text, ss_bssrdf_layer_stack *s, ss_error *err) {
  memset(s, 0, sizeof *s);
  if (!strcmp(text, "skin")) {
    s->layer_count = 3;
    memcpy(s->layers, skin, sizeof skin);
    return SS_OK;
  }
  char *copy = strdup(text);
  if (!copy) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory");
  }
  ss_status st = SS_OK;
  for (char *save = NULL, *layer = strtok_r(copy, ";", &save); layer && st == SS_OK;
       layer = strtok_r(NULL, ";", &save)) {
    if (s->layer_count == SS_BSSRDF_MAX_LAYERS) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "at most %d layers", SS_BSSRDF_MAX_LAYERS);
    } else {
      st = parse_layer(layer, s->layer_count, &s->layers[s->layer_count], err);
      s->layer_count++;
    }
  }
  free(copy);
  if (st == SS_OK && s->layer_count == 0) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "expected 'skin' or layers separated by ';'");
  }
  return st;
}

int ss_bssrdf_layer_stack_format(const ss_bssrdf_layer_stack *s, char *buf, size_t size) {
  int used = 0;
  for (int k = 0; k < s->layer_count; ++k) {
    const ss_bssrdf_layer *l = &s->layers[k];
    size_t at = (size_t)used;
    int n = snprintf(at < size ? buf + at : NULL, at < size ? size - at : 0,
                     "%ssigma_s=%.17g,%.17g,%.17g sigma_a=%.17g,%.17g,%.17g "
                     "g=%.17g,%.17g,%.17g "
                     "eta=%.17g d=%.17g",
                     k ? "; " : "", l->sigma_s[0], l->sigma_s[1], l->sigma_s[2], l->sigma_a[0],
                     l->sigma_a[1], l->sigma_a[2], l->g[0], l->g[1], l->g[2], l->eta, l->thickness);
    if (n < 0) {
      return n;
    }
    used += n;
  }
  return used;
}
