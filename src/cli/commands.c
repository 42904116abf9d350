#include "cli/commands.h"

#include <string.h>

const ss_cli_command ss_cli_commands[] = {
    {"halfspace", ss_cmd_halfspace,
     "exact Monte Carlo reference: a collimated beam into a half-space or slab"},
    {"layer", ss_cmd_layer,
     "a slab or stack of slabs as a surface: BRDF, BTDF and totals by adding-doubling"},
    {"render", ss_cmd_render, "render a JSON or pbrt-v3 (.pbrt) scene to EXR and PNG"},
    {"table", ss_cmd_table, "build a BSSRDF table file (Ferrier, pbrt) or check its accuracy"},
    {"model", ss_cmd_model, "a BSSRDF model's answer to the halfspace experiment (same JSON keys)"},
    {"compare-halfspace", ss_cmd_compare_halfspace,
     "run the halfspace reference and models with identical bins: error table and plot"},
    {"compare", ss_cmd_compare_scene,
     "render a scene with several methods against a reference: error and time table"},
    {"fem", ss_cmd_fem,
     "diffusion by finite elements in a box or closed mesh (gmsh, CHOLMOD): PLY"},
    {"diff", ss_cmd_diff,
     "one image against a reference: relMSE, mean ratio per channel, error map"},
    {NULL, NULL, NULL},
};

const ss_cli_command *ss_cli_command_find(const char *name) {
  for (const ss_cli_command *c = ss_cli_commands; c->name; ++c) {
    if (!strcmp(name, c->name)) {
      return c;
    }
  }
  return NULL;
}
