/* Shared by the libFuzzer harnesses: the readers under test take paths, so
 * each input is written to one temporary file per process and read back from
 * there. */
#ifndef SUBSURF_FUZZ_INPUT_FILE_H
#define SUBSURF_FUZZ_INPUT_FILE_H

#include "subsurf/scene.h"

#include <stddef.h>
#include <stdint.h>

/* Replaces the content of this process's temporary file (named with
 * `suffix`, e.g. ".ply") by the input and returns its path; NULL when the
 * file cannot be written (the harness then skips the input). */
const char *ss_fuzz_input_file(const uint8_t *data, size_t size, const char *suffix);

/* ss_fuzz_input_file with the input's last 4 bytes replaced by the CRC-32
 * (zlib's) of the rest when it has at least `min_size` bytes, so that
 * mutations reach the checks behind a reader's checksum. */
const char *ss_fuzz_input_file_crc(const uint8_t *data, size_t size, size_t min_size,
                                   const char *suffix);

/* A scene reader of text: `base_dir` is where its relative paths start. */
typedef ss_status (*ss_fuzz_scene_parser)(const char *text, const char *base_dir, ss_scene **out,
                                          ss_error *err);

/* Gives the input, NUL-terminated, to `parse` with SUBSURF_FUZZ_BASE_DIR
 * (scripts/fuzz.sh points it at the PLY and OBJ seeds) or "." as the base
 * directory, and destroys the scene it makes. */
void ss_fuzz_parse_scene(const uint8_t *data, size_t size, ss_fuzz_scene_parser parse);

#endif
