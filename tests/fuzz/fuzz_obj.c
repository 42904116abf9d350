/* libFuzzer harness: any byte string given to the OBJ reader either reads as
 * a valid mesh or fails with a message; it never crashes, reads out of
 * bounds, leaks or allocates more than the input can describe. */
#include "input_file.h"
#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = ss_fuzz_input_file(data, size, ".obj");
  if (path) {
    ss_mesh *m = NULL;
    ss_error err;
    if (ss_mesh_read_obj(path, &m, NULL, &err) == SS_OK) {
      ss_mesh_destroy(m);
    }
  }
  return 0;
}
