/* A rendering method for comparisons: an integrator, or a BSSRDF model with
 * its options rendered by the `bssrdf` integrator. Text form:
 *     volpath                 an integrator by name (integrator.h)
 *     pbd                     the bssrdf integrator with model pbd
 *     pbd:beam_samples=50     ... and model options, NAME=VALUE after ':'
 *     table-gwc:a=1:b=2       several options
 *     volpath:max_depth=64    integrator options (max_depth, rr_depth and the
 *     pbd:max_depth=8         integrator's own, integrator.h), also after a
 *                             model's (a name the model declares is the model's)
 * Applying a method to a committed scene sets its integrator and, for a
 * model, makes every translucent material use that model with those options
 * at the level of detail "bssrdf" (the scene's own model options dropped);
 * integrator options replace the scene's. */
#ifndef SUBSURF_METHOD_H
#define SUBSURF_METHOD_H

#include "subsurf/bssrdf.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

typedef struct {
  char text[SS_NAME_SIZE * 4];   /* as given */
  char integrator[SS_NAME_SIZE]; /* "volpath", "bssrdf", ... */
  char model[SS_NAME_SIZE];      /* "" for an integrator method */
  ss_bssrdf_params options;      /* the model options (coefficients unused) */
  int num_integrator_options;
  ss_integrator_option integrator_options[SS_INTEGRATOR_MAX_OPTIONS];
} ss_method;

/* Parses `text`; SS_ERR_INVALID_ARGUMENT naming the method and what was
 * expected (unknown name, option without '=', unknown option, bad value:
 * max_depth and rr_depth are integers in [0, 1e8], other integrator options
 * finite numbers). */
ss_status ss_method_parse(const char *text, ss_method *m, ss_error *err);

/* Sets the method on a committed scene, rebuilds its BSSRDFs and checks the
 * integrator's options against the scene (ss_integrator_check), so that a
 * bad value fails here rather than when rendering starts. */
ss_status ss_method_apply(const ss_method *m, ss_scene *scene, ss_error *err);

/* `text` with every character other than [A-Za-z0-9._-] made '_' (a file
 * name for the method's outputs). */
void ss_method_file_name(const ss_method *m, char *buf, size_t size);

#endif
