/* Checksummed text tables (checked_text.h). */
#include "optics/checked_text.h"

#include "core/input_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

ss_status ss_checked_text_verify(const char *text, size_t size, const char *label, size_t *body,
                                 ss_error *err) {
  if (memchr(text, '\0', size)) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: contains a NUL byte (not a text table)", label);
  }
  size_t b = size && text[size - 1] == '\n' ? size - 1 : size;
  while (b && text[b - 1] != '\n') {
    --b;
  }
  char tail[32] = "";
  size_t tail_n = size - b < sizeof tail - 1 ? size - b : sizeof tail - 1;
  memcpy(tail, text + b, tail_n);
  unsigned stored;
  char extra;
  if (sscanf(tail, "crc32 %8x%c", &stored, &extra) != 2 || extra != '\n' || tail_n != 15) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: truncated or not a table (no 'crc32 XXXXXXXX' last line)", label);
  }
  uint32_t crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)text, (uInt)b);
  if (crc != stored) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: checksum mismatch (stored %08x, computed %08x): the file is corrupt",
                        label, stored, (unsigned)crc);
  }
  *body = b;
  return SS_OK;
}

ss_status ss_checked_text_read(const char *path, ss_input_kind kind, char **text, size_t *size,
                               ss_error *err) {
  unsigned char *data;
  ss_status st = ss_input_file_read(path, path, kind, &data, size, err);
  *text = (char *)data;
  return st;
}
