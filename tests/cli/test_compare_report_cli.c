/* `subsurf compare`'s report in a real browser: DIR/index.html opened from
 * the folder by headless Chromium (Debian's chromium, installed by
 * scripts/install-deps.sh) with the network off. One Chromium run both
 * dumps the DOM after the page's script ran (--dump-dom with a virtual time
 * budget) and takes a screenshot; its log (--enable-logging=stderr) carries
 * every console message as a ":CONSOLE" line. The page itself marks on
 * <body> the images it loaded and any script error or image that failed
 * (compare_html.c). Also: the SVG plots hold one line and one bar per
 * method, and a failed run leaves no index.html behind. */
#include "cli/cli_files.h"
#include "cli/cli_run.h"
#include "cli/compare_scene_fixture.h"

#include <math.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

CLI_SUITE(compare_report_cli);

static const char *const methods[] = {"volpath", "dipole", "pbd:beam_samples=20"};
#define NUM_METHODS 3

static void run_compare(void) {
  compare_fixture_write(dir);
  cli_run_in(&res, dir,
             "compare scene.json --methods volpath,dipole,pbd:beam_samples=20 --spp 2 "
             "--reference-spp 8 -o out --quiet",
             0.0);
  cr_assert_eq(res.status, 0, "exit %d: %s", res.status, res.err);
  cr_expect(strstr(res.out, "report: out/index.html") != NULL, "%s", res.out);
}

static int count(const char *text, const char *needle) {
  int n = 0;
  for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle)) {
    ++n;
  }
  return n;
}

Test(compare_report_cli, the_plots_have_a_line_and_a_bar_per_method_and_a_colour_bar) {
  run_compare();
  static char svg[1 << 16];
  char path[256];
  snprintf(path, sizeof path, "%s/out/convergence.svg", dir);
  cli_slurp(path, svg, sizeof svg);
  cr_expect_eq(count(svg, "<polyline"), NUM_METHODS, "%s", svg);
  for (int i = 0; i < NUM_METHODS; ++i) {
    cr_expect(strstr(svg, methods[i]) != NULL, "%s not in the legend", methods[i]);
  }
  for (const char *c = "rgb"; *c; ++c) {
    snprintf(path, sizeof path, "%s/out/mean-ratio-%c.svg", dir, *c);
    cli_slurp(path, svg, sizeof svg);
    cr_expect_eq(count(svg, "class=\"bar\""), NUM_METHODS, "%s", svg);
  }
  snprintf(path, sizeof path, "%s/out/error-colorbar.svg", dir);
  cli_slurp(path, svg, sizeof svg);
  cr_expect(strstr(svg, "linearGradient") && strstr(svg, "&#8805; 1"), "%s", svg);
}

/* Standard deviation of the screenshot's grey levels: a blank page is 0. */
static double screenshot_spread(const char *path) {
  int w, h, n;
  unsigned char *px = stbi_load(path, &w, &h, &n, 1);
  cr_assert_not_null(px, "no screenshot %s", path);
  double sum = 0.0, sq = 0.0, count = (double)w * h;
  for (int i = 0; i < w * h; ++i) {
    sum += px[i];
    sq += (double)px[i] * px[i];
  }
  stbi_image_free(px);
  return sqrt(fmax(sq / count - (sum / count) * (sum / count), 0.0));
}

Test(compare_report_cli, the_report_loads_offline_in_chromium_with_every_method_and_no_error) {
  run_compare();
  char cmd[2048];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && mkdir -p profile && timeout 120 chromium --headless --no-sandbox "
           "--disable-gpu --disable-quic --no-first-run --disable-background-networking "
           "--disable-component-update --disable-sync --user-data-dir=\"$PWD/profile\" "
           "--enable-logging=stderr --v=0 --virtual-time-budget=5000 --window-size=1200,1400 "
           "--screenshot=\"$PWD/shot.png\" --dump-dom \"file://$PWD/out/index.html\" "
           ">dom.html 2>chromium.log",
           dir);
  cr_assert_eq(system(cmd), 0, "chromium failed (is it installed? scripts/install-deps.sh)");
  static char dom[1 << 18], log[1 << 18];
  char path[256];
  snprintf(path, sizeof path, "%s/dom.html", dir);
  cli_slurp(path, dom, sizeof dom);
  snprintf(path, sizeof path, "%s/chromium.log", dir);
  cli_slurp(path, log, sizeof log);
  cr_expect(strstr(log, ":CONSOLE") == NULL, "console output: %s", strstr(log, ":CONSOLE"));
  cr_expect(strstr(dom, "data-status=\"ok\"") != NULL, "the page saw errors: %.300s",
            strstr(dom, "<body"));
  /* The reference, per method its image, flip image, error map and colour
   * bar, and the four plots. */
  char images[64];
  snprintf(images, sizeof images, "data-images=\"%d\"", 1 + 4 * NUM_METHODS + 4);
  cr_expect(strstr(dom, images) != NULL, "expected %s: %.300s", images, strstr(dom, "<body"));
  cr_expect_eq(count(dom, "<tr class=\"method\""), NUM_METHODS);
  cr_expect_eq(count(dom, "<figure class=\"flip\""), NUM_METHODS);
  for (int i = 0; i < NUM_METHODS; ++i) {
    char caption[128];
    snprintf(caption, sizeof caption, "<b>%s</b>", methods[i]);
    cr_expect_geq(count(dom, caption), 2, "%s: no image caption", methods[i]);
  }
  snprintf(path, sizeof path, "%s/shot.png", dir);
  double spread = screenshot_spread(path);
  cr_expect(spread > 20.0, "screenshot grey levels spread only %g", spread);
}

Test(compare_report_cli, a_failed_run_leaves_no_report) {
  run_compare();
  cr_assert(cli_file_exists(dir, "out/index.html"));
  /* Interrupted while rendering the reference: no index.html, old or new. */
  cli_run_signalled(&res, dir,
                    "compare scene.json --methods volpath --spp 2 --reference-spp 1000000 -o out",
                    2.0, SIGINT, 1, 0.0);
  cr_expect_eq(res.status, 130, "exit %d: %s", res.status, res.err);
  cr_expect(!cli_file_exists(dir, "out/index.html"), "a report of the earlier run is left");
}
