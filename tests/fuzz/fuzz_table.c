/* libFuzzer harness: any byte string given to the BSSRDF table file readers
 * (header only, radial and gwc) is accepted or rejected with a message,
 * never a crash, an out-of-bounds read, a leak or an oversized allocation.
 * The trailing CRC-32 of a long enough input is set to match the rest, so
 * that mutations reach the checks behind it (the mismatch itself is tested
 * in tests/bssrdf). */
#include "input_file.h"
#include "subsurf/table_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = ss_fuzz_input_file_crc(data, size, SS_TABLE_FILE_HEADER + 4, ".table");
  if (!path) {
    return 0;
  }
  ss_error err;
  ss_table_file_info info;
  ss_table_file_info_read(path, &info, &err);
  ss_table_radial *radial = NULL;
  if (ss_table_radial_load(path, &radial, &err) == SS_OK) {
    ss_table_radial_destroy(radial);
  }
  ss_table_gwc *gwc = NULL;
  if (ss_table_gwc_load(path, &gwc, &err) == SS_OK) {
    ss_table_gwc_destroy(gwc);
  }
  return 0;
}
