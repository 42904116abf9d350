/* `subsurf render --checkpoint` / `--resume`: a render interrupted with
 * Ctrl-C (or stopped by its time limit) and resumed from its checkpoint
 * writes the very bytes of an uninterrupted render; a checkpoint of another
 * scene or options, or a damaged one, is refused with one line and exit 2. */
#include "cli_files.h"

#include <criterion/criterion.h>
#include <sys/stat.h>

static char dir[64];
static cli_result res;

/* About 1.6 s on one idle core: Ctrl-C sent as soon as the first checkpoint
 * exists (after 0.05 s of rendering) lands long before the render ends, on a
 * fast idle machine as on a loaded one. */
static const char *scene_text =
    "{\n"
    "  \"camera\": {\"position\": [0, 0, 4], \"fov\": 25, \"resolution\": [30, 20]},\n"
    "  \"materials\": [{\"name\": \"grey\", \"type\": \"diffuse\", \"albedo\": [0.8, 0.5, 0.2]}],\n"
    "  \"shapes\": [{\"type\": \"sphere\", \"subdivisions\": 3, \"material\": \"grey\"}],\n"
    "  \"lights\": [{\"type\": \"environment\", \"radiance\": [1, 0.7, 0.4]}],\n"
    "  \"integrator\": {\"type\": \"path\"},\n"
    "  \"render\": {\"spp\": 6000, \"seed\": 4}\n"
    "}\n";

static void setup(void) {
  cli_tmpdir(dir, sizeof dir);
  cr_assert(dir[0]);
  cli_write_text(dir, "scene.json", scene_text);
}

static void teardown(void) { cli_remove_dir(dir); }

TestSuite(render_checkpoint_cli, .init = setup, .fini = teardown);

static long file_size(const char *name) {
  char path[512];
  struct stat st;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static int same_bytes(const char *a, const char *b) {
  static char ta[1 << 16], tb[1 << 16];
  char pa[512], pb[512];
  snprintf(pa, sizeof pa, "%s/%s", dir, a);
  snprintf(pb, sizeof pb, "%s/%s", dir, b);
  long n = file_size(a);
  if (n <= 0 || n != file_size(b) || n > (long)sizeof ta) {
    return 0;
  }
  FILE *fa = fopen(pa, "rb"), *fb = fopen(pb, "rb");
  size_t ra = fread(ta, 1, sizeof ta, fa), rb = fread(tb, 1, sizeof tb, fb);
  fclose(fa);
  fclose(fb);
  return ra == rb && memcmp(ta, tb, ra) == 0;
}

static void render_uninterrupted(void) {
  cli_run_in(&res, dir, "render scene.json -o full.exr --quiet --no-png", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
}

Test(render_checkpoint_cli, ctrl_c_then_resume_writes_the_uninterrupted_image) {
  cli_run_signalled_after_file(&res, dir,
                               "render scene.json -o part.exr --quiet --no-png --checkpoint c.ckpt "
                               "--checkpoint-interval 0.05",
                               "c.ckpt", 0.01, SIGINT, 1, 0.0);
  cr_assert_eq(res.status, 130, "not interrupted (exit %d): %s", res.status, res.err);
  cr_expect(strstr(res.err, "--resume c.ckpt") != NULL, "%s", res.err);
  cr_assert_gt(file_size("c.ckpt"), 0);
  cli_run_in(&res, dir,
             "render scene.json -o part.exr --quiet --no-png --resume c.ckpt "
             "--threads 1",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  render_uninterrupted();
  cr_expect(same_bytes("part.exr", "full.exr"), "resumed EXR differs from the uninterrupted one");
}

Test(render_checkpoint_cli, a_time_limited_render_continues_from_its_checkpoint) {
  cli_run_in(&res, dir,
             "render scene.json -o part.exr --quiet --no-png --checkpoint c.ckpt "
             "--time-limit 0.2",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  cli_run_in(&res, dir, "render scene.json -o part.exr --quiet --no-png --resume c.ckpt", 0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  render_uninterrupted();
  cr_expect(same_bytes("part.exr", "full.exr"), "resumed EXR differs from the uninterrupted one");
}

static void expect_refused(const char *args, const char *needle) {
  cli_run_in(&res, dir, args, 0.0);
  cr_expect_eq(res.status, 2, "'%s': exit %d, stderr: %s", args, res.status, res.err);
  cr_expect(strstr(res.err, needle) != NULL, "'%s': expected '%s' in: %s", args, needle, res.err);
  cr_expect(strchr(res.err, '\n') == res.err + strlen(res.err) - 1, "'%s': not one line: %s", args,
            res.err);
  cr_expect_eq(file_size("out.exr"), -1, "'%s' wrote an image", args);
}

Test(render_checkpoint_cli, a_foreign_or_damaged_checkpoint_is_refused) {
  cli_run_in(&res, dir, "render scene.json -o a.exr --quiet --no-png --spp 2 --checkpoint c.ckpt",
             0.0);
  cr_assert_eq(res.status, 0, "stderr: %s", res.err);
  const char *base = "render scene.json -o out.exr --quiet --no-png --spp 2";
  const char *cases[][2] = {
      {"--seed 5 --resume c.ckpt", "--seed 5"},
      {"--crop 0,0,10,10 --resume c.ckpt", "window"},
      {"--integrator volpath --resume c.ckpt", "integrator 'path', not 'volpath'"},
      {"--resume missing.ckpt", "missing.ckpt"},
      {"--resume scene.json --checkpoint d.ckpt", "not a subsurf render checkpoint"},
      {"--resume scene.json", "--resume: cannot write 'scene.json': it is the scene"},
      {"--checkpoint no/such/dir/c.ckpt", "--checkpoint"},
  };
  char args[512];
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    snprintf(args, sizeof args, "%s %s", base, cases[i][0]);
    expect_refused(args, cases[i][1]);
  }
  char other[2048];
  snprintf(other, sizeof other, "%s", scene_text);
  memcpy(strstr(other, "0.8, 0.5"), "0.7", 3); /* another albedo, the same options */
  cli_write_text(dir, "scene.json", other);
  snprintf(args, sizeof args, "%s --resume c.ckpt", base);
  expect_refused(args, "another scene");
}
