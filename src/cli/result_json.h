/* The JSON keys shared by `subsurf halfspace` and the model commands, so that
 * their outputs compare key by key:
 *   "paths", "seconds", "reflectance", "transmittance", "specular", "absorbed",
 *   "truncated" ({"value", "stderr"} each), "radial" {"r_lo", "r_hi",
 *   "value", "stderr"}, "directions" [{"theta_o", "x_lo", "x_hi", "value",
 *   "stderr"}]. */
#ifndef SUBSURF_CLI_RESULT_JSON_H
#define SUBSURF_CLI_RESULT_JSON_H

#include "subsurf/halfspace.h"

#include <cjson/cJSON.h>

/* Adds the keys above to `obj`. */
void ss_result_add_json(cJSON *obj, const ss_halfspace_result *r);

/* 0 when every number in `json` (or in the result's keys) is finite, else
 * -1 after printing "subsurf CMD: the result holds NaN or Inf at KEY ...":
 * no output may carry NaN or Inf silently. */
int ss_json_check_finite(const cJSON *json, const char *cmd);
int ss_result_check_finite(const ss_halfspace_result *r, const char *cmd);

/* Writes `json` to `path` ("-" for stdout) through a temporary file renamed
 * on success; refuses (-1) a tree that fails ss_json_check_finite. Returns 0,
 * or -1 after printing an error naming the path. */
int ss_json_write_file(const cJSON *json, const char *path, const char *cmd);

#endif
