/* `subsurf render SCENE.pbrt`: the importer is picked by the extension, its
 * warnings reach stderr with FILE:LINE, the Film's filename and crop window
 * are used, and a syntax error exits 2 naming FILE:LINE. */
#include "cli/cli_run.h"

#include <criterion/criterion.h>

CLI_SUITE(pbrt_cli);

#define SCENE_HEAD                                                                                 \
  "Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 30\n"              \
  "Film \"image\" \"integer xresolution\" 16 \"integer yresolution\" 8\n"                          \
  "  \"string filename\" \"film.exr\" \"float cropwindow\" [0 0.5 0 1]\n"                          \
  "Sampler \"random\" \"integer pixelsamples\" 2\nIntegrator \"path\" \"integer maxdepth\" 3\n"    \
  "WorldBegin\nLightSource \"point\" \"rgb I\" [5 5 5] \"point from\" [0 0 5]\n"

Test(pbrt_cli, renders_with_warnings_naming_file_and_line) {
  cli_write_file(dir, "s.pbrt",
                 SCENE_HEAD "Material \"matte\" \"rgb Kd\" [0.5 0.5 0.5] \"float sigma\" 10\n"
                            "Shape \"sphere\" \"integer subdivisions\" 2\n"
                            "Shape \"disk\"\nWorldEnd\n");
  cli_run_in(&res, dir, "render s.pbrt", 0.0);
  cr_expect_eq(res.status, 0, "stderr: %s", res.err);
  cr_expect(strstr(res.err, "subsurf render: warning: s.pbrt:10: Material \"matte\": sigma"), "%s",
            res.err);
  cr_expect(strstr(res.err, "subsurf render: warning: s.pbrt:12: Shape \"disk\" is not "
                            "supported"),
            "%s", res.err);
  cr_expect(cli_path_exists(dir, "film.exr") && cli_path_exists(dir, "film.png"));
  /* the crop window [0, 0.5] x [0, 1] of 16 x 8: an 8 x 8 image */
  cr_expect(strstr(res.out, "8 x 8"), "%s", res.out);
}

Test(pbrt_cli, syntax_error_exits_2_naming_file_and_line) {
  cli_write_file(dir, "bad.pbrt", SCENE_HEAD "Shape \"sphere\" \"float radius [1]\nWorldEnd\n");
  cli_expect_bad_input(&res, dir, "render bad.pbrt -o out.exr --quiet",
                       "bad.pbrt:10: unterminated string");
  cr_expect(!cli_path_exists(dir, "out.exr"));
}
