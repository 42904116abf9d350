/* `subsurf render` and `subsurf compare` with the hybrid integrator: a
 * negative depth, a depth that is not a number, a model that cannot take the
 * hand-over and an unknown model exit 2 naming the key; a good scene renders. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(hybrid_cli);

/* A small sphere lit by a sky; `extra` is appended to the integrator object,
 * `model` names the material's model. */
static void write_scene(const char *name, const char *model, const char *extra) {
  char text[2048];
  snprintf(text, sizeof text,
           "{\"camera\": {\"resolution\": [8, 8], \"position\": [0, 0, 4]},\n"
           " \"media\": [{\"name\": \"m\", \"sigma_s\": 4, \"sigma_a\": 0.5}],\n"
           " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": "
           "\"smooth\", \"eta\": 1.3, \"medium\": \"m\", \"bssrdf\": \"%s\"}],\n"
           " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\"}],\n"
           " \"lights\": [{\"type\": \"environment\", \"radiance\": 1}],\n"
           " \"integrator\": {\"type\": \"hybrid\"%s},\n"
           " \"render\": {\"spp\": 1}}\n",
           model, extra);
  cli_write_file(dir, name, text);
}

Test(hybrid_cli, bad_depths_and_models_exit_2_naming_the_key) {
  static const struct {
    const char *extra, *model, *needle;
  } cases[] = {
      {", \"depth\": -1", "dipole", "depth"},
      {", \"depth\": \"deep\"", "dipole", "integrator.depth"},
      {", \"deep\": 1", "dipole", "deep"},
      {"", "fwddip", "bssrdf"},
      {"", "dipole-brdf", "bssrdf"},
      {"", "nosuch", "materials[0].bssrdf"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    write_scene("s.json", cases[i].model, cases[i].extra);
    cli_expect_bad_input(&res, dir, "render s.json -o out.exr --quiet", cases[i].needle);
  }
  /* compare checks an integrator's options when it prepares the method,
   * after the reference: only the status and the message are asserted. */
  write_scene("s.json", "dipole", "");
  const char *methods[] = {"hybrid:depth=-2", "hybrid:depth=nan"};
  for (int i = 0; i < 2; ++i) {
    char args[256];
    snprintf(args, sizeof args, "compare s.json --methods %s --spp 1 --quiet -o cmp", methods[i]);
    cli_run_in(&res, dir, args, 0.0);
    cr_expect_eq(res.status, 2, "'%s' exited %d: %s", args, res.status, res.err);
    cr_expect(strstr(res.err, "depth") != NULL, "'%s': %s", args, res.err);
  }
}

Test(hybrid_cli, renders_at_depth_zero_default_and_infinite) {
  const char *extras[] = {", \"depth\": 0", "", ", \"depth\": 1e300"};
  for (int i = 0; i < 3; ++i) {
    write_scene("s.json", "dipole", extras[i]);
    cli_run_in(&res, dir, "render s.json -o out.exr --no-png --quiet", 0.0);
    cr_expect_eq(res.status, 0, "%s: %s", extras[i], res.err);
    cr_expect(cli_file_exists(dir, "out.exr"));
  }
}
