/* libFuzzer harness: any text given to the pbrt-v3 importer is a scene or an
 * error message, never a crash, an out-of-bounds read, a leak or an
 * oversized allocation. Include and mesh paths resolve against
 * SUBSURF_FUZZ_BASE_DIR (scripts/fuzz.sh points it at the PLY and OBJ
 * seeds) or ".". */
#include "subsurf/scene.h"
#include "subsurf/scene_io.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *text = malloc(size + 1);
  if (!text) {
    return 0;
  }
  memcpy(text, data, size);
  text[size] = '\0';
  ss_scene *scene = NULL;
  ss_error err;
  if (ss_scene_parse_pbrt(text, "fuzz.pbrt", getenv("SUBSURF_FUZZ_BASE_DIR"), &scene, NULL, NULL,
                          &err) == SS_OK) {
    ss_scene_destroy(scene);
  }
  free(text);
  return 0;
}
