/* Shared by the libFuzzer harnesses: the readers under test take paths, so
 * each input is written to one temporary file per process and read back from
 * there. */
#ifndef SUBSURF_FUZZ_INPUT_FILE_H
#define SUBSURF_FUZZ_INPUT_FILE_H

#include <stddef.h>
#include <stdint.h>

/* Replaces the content of this process's temporary file (named with
 * `suffix`, e.g. ".ply") by the input and returns its path; NULL when the
 * file cannot be written (the harness then skips the input). */
const char *ss_fuzz_input_file(const uint8_t *data, size_t size, const char *suffix);

#endif
