/* `subsurf render` with volpath's manifold next-event estimation options (and
 * its guided-walk probability `guide`) out of range: one line
 * naming the option, exit 2, nothing written. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(mnee_cli);

Test(mnee_cli, bad_mnee_options_exit_2_naming_them) {
  static const struct {
    const char *extra, *needle;
  } cases[] = {
      {"\"mnee_iterations\": 0", "mnee_iterations"},
      {"\"mnee_iterations\": 1.5", "mnee_iterations"},
      {"\"mnee_iterations\": 1001", "mnee_iterations"},
      {"\"mnee_tolerance\": 0", "mnee_tolerance"},
      {"\"mnee_tolerance\": -1", "mnee_tolerance"},
      {"\"mnee_tolerance\": 0.5", "mnee_tolerance"},
      {"\"mnee\": 2", "mnee"},
      {"\"mnee\": -1", "mnee"},
      {"\"mnee_solid_angle\": 0", "mnee_solid_angle"},
      {"\"mnee_solid_angle\": -0.1", "mnee_solid_angle"},
      {"\"guide\": -0.1", "guide"},
      {"\"guide\": 1", "guide"},
      {"\"guide\": 2", "guide"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char text[1024];
    snprintf(text, sizeof text,
             "{\"camera\": {\"resolution\": [4, 4]},\n"
             " \"media\": [{\"name\": \"m\", \"sigma_s\": 1, \"sigma_a\": 0.1}],\n"
             " \"materials\": [{\"name\": \"t\", \"type\": \"translucent\", \"boundary\": "
             "\"smooth\", \"eta\": 1.3, \"medium\": \"m\"}],\n"
             " \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 2, \"material\": \"t\"}],\n"
             " \"lights\": [{\"type\": \"point\", \"position\": [3, 3, 3], \"intensity\": 5}],\n"
             " \"integrator\": {\"type\": \"volpath\", %s}}\n",
             cases[i].extra);
    cli_write_file(dir, "s.json", text);
    cli_expect_bad_input(&res, dir, "render s.json -o out.exr --quiet", cases[i].needle);
  }
}
