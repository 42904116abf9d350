/* A stack of layers for the `layers` model (Donner & Jensen 2005, sec. 4),
 * written as the text of its "layers" option:
 *
 *     sigma_s=48,60,65 sigma_a=2.1,2.1,5 g=0 eta=1.4 d=0.03; sigma_s=... d=inf
 *
 * Layers top first, separated by ';'; each sets sigma_s, sigma_a, eta and d
 * (thickness, "inf" only for the last layer), and optionally g (default 0),
 * with one value for all three channels or three comma-separated ones. The
 * name "skin" stands for the three skin layers of DonnerJensen2005
 * Table 3 (mm^-1). */
#ifndef SUBSURF_BSSRDF_LAYERS_H
#define SUBSURF_BSSRDF_LAYERS_H

#include "subsurf/status.h"

#include <stddef.h>

#define SS_BSSRDF_MAX_LAYERS 8

typedef struct {
  double sigma_s[3]; /* scattering coefficient (unreduced) */
  double sigma_a[3];
  double g[3];
  double eta;       /* n_layer / n_outside */
  double thickness; /* INFINITY for a semi-infinite bottom layer */
} ss_bssrdf_layer;

typedef struct {
  int layer_count;
  ss_bssrdf_layer layers[SS_BSSRDF_MAX_LAYERS]; /* layers[0] is the top */
} ss_bssrdf_layer_stack;

/* Parses the text above; the message names the layer and key. Values are
 * checked for syntax only (the model checks the physics). */
ss_status ss_bssrdf_layer_stack_parse(const char *text, ss_bssrdf_layer_stack *s, ss_error *err);
/* Writes a stack as option text (exact: %.17g); returns the length it needs,
 * like snprintf. */
int ss_bssrdf_layer_stack_format(const ss_bssrdf_layer_stack *s, char *buf, size_t size);

#endif
