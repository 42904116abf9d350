/* libFuzzer harness: any text given to the pbrt-v3 importer is a scene or an
 * error message, never a crash, an out-of-bounds read, a leak or an
 * oversized allocation. Include and mesh paths resolve against
 * SUBSURF_FUZZ_BASE_DIR (scripts/fuzz.sh points it at the PLY and OBJ
 * seeds) or ".". The scene is capped (ss_pbrt_limits) so that an input
 * builds a small scene: the time goes into the parser, not into
 * tessellating spheres (5 subdivisions by default) or checking big meshes. */
#include "input_file.h"
#include "subsurf/scene_io.h"

#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static ss_status parse_pbrt(const char *text, const char *base_dir, ss_scene **out, ss_error *err) {
  static const ss_pbrt_limits limits = {
      .max_subdivisions = 1, .max_resolution = 64, .max_triangles = 4096};
  return ss_scene_parse_pbrt_limited(text, "fuzz.pbrt", base_dir, &limits, out, NULL, NULL, err);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_fuzz_parse_scene(data, size, parse_pbrt);
  return 0;
}
