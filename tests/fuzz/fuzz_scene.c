/* libFuzzer harness: any text given to the scene reader is a scene or an
 * error message, never a crash, an out-of-bounds read, a leak or an
 * oversized allocation. Mesh paths resolve against SUBSURF_FUZZ_BASE_DIR
 * (scripts/fuzz.sh points it at the PLY and OBJ seeds) or ".". */
#include "input_file.h"
#include "subsurf/scene_io.h"

#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static ss_status parse_json(const char *text, const char *base_dir, ss_scene **out, ss_error *err) {
  return ss_scene_parse_json(text, "fuzz.json", base_dir, out, err);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_fuzz_parse_scene(data, size, parse_json);
  return 0;
}
