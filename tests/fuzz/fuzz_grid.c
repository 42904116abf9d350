/* libFuzzer harness: any byte string given to the raw grid reader
 * (grid_io.h) is accepted or rejected with a message, never a
 * crash, an out-of-bounds read, a leak or an allocation the input's size
 * does not justify (the header's dimensions must match the size exactly
 * before anything is allocated). OpenVDB files are OpenVDB's to parse and
 * are not fuzzed here. */
#include "subsurf/grid_io.h"

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_grid *g = NULL;
  ss_error err;
  if (ss_grid_read_raw_memory(data, size, "fuzz.ssgrid", &g, &err) == SS_OK) {
    ss_grid_destroy(g);
  }
  return 0;
}
