/* Portable float maps: "PF" (RGB) or "Pf" (grey), width and height, then a
 * scale whose sign gives the byte order (negative: little endian), then rows
 * of 32-bit floats from the bottom of the image to the top. */
#include "subsurf/image_io.h"

#include "core/atomic_file.h"
#include "io/image_io_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int host_is_little_endian(void) {
  const uint16_t one = 1;
  unsigned char first;
  memcpy(&first, &one, 1);
  return first == 1;
}

static float swap_float(float v) {
  unsigned char b[4], r[4];
  memcpy(b, &v, 4);
  r[0] = b[3];
  r[1] = b[2];
  r[2] = b[1];
  r[3] = b[0];
  memcpy(&v, r, 4);
  return v;
}

ss_status ss_image_write_pfm(const char *path, const ss_image *img, ss_error *err) {
  ss_status st = ss_image_io_check(path, img, err);
  if (st != SS_OK) {
    return st;
  }
  if (img->channels == 4) {
    return ss_error_set(err, SS_ERR_UNSUPPORTED,
                        "cannot write %s: PFM has no alpha channel (write .exr instead)", path);
  }
  ss_atomic_file f;
  if ((st = ss_atomic_file_open(&f, path, SS_FILE_PFM, err)) != SS_OK) {
    return st;
  }
  char header[96];
  int len = snprintf(header, sizeof header, "%s\n%d %d\n%s\n", img->channels == 3 ? "PF" : "Pf",
                     img->width, img->height, host_is_little_endian() ? "-1.0" : "1.0");
  st = ss_atomic_file_write(&f, header, (size_t)len, err);
  size_t row = (size_t)img->width * (size_t)img->channels;
  for (int y = img->height - 1; y >= 0 && st == SS_OK; --y) {
    st = ss_atomic_file_write(&f, img->data + (size_t)y * row, row * sizeof(float), err);
  }
  if (st != SS_OK) {
    ss_atomic_file_abort(&f);
    return st;
  }
  return ss_atomic_file_commit(&f, err);
}

/* Reads one whitespace-delimited header token. */
static int read_token(FILE *f, char *buf, size_t size) {
  int c;
  while ((c = fgetc(f)) != EOF && isspace(c)) {
  }
  size_t n = 0;
  while (c != EOF && !isspace(c)) {
    if (n + 1 >= size) {
      return 0;
    }
    buf[n++] = (char)c;
    c = fgetc(f);
  }
  buf[n] = '\0';
  /* The single whitespace character after the scale ends the header. */
  return n > 0 && c != EOF;
}

ss_status ss_image_read_pfm(const char *path, ss_image **out, ss_error *err) {
  *out = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) {
    return ss_error_set(err, SS_ERR_IO, "cannot read %s: %s", path, strerror(errno));
  }
  char magic[8], ws[16], hs[16], ss[32];
  ss_status st = SS_OK;
  if (!read_token(f, magic, sizeof magic) || !read_token(f, ws, sizeof ws) ||
      !read_token(f, hs, sizeof hs) || !read_token(f, ss, sizeof ss) ||
      (strcmp(magic, "PF") && strcmp(magic, "Pf"))) {
    fclose(f);
    return ss_error_set(err, SS_ERR_PARSE, "cannot read %s: malformed PFM header", path);
  }
  char *end1, *end2, *end3;
  long w = strtol(ws, &end1, 10), h = strtol(hs, &end2, 10);
  double scale = strtod(ss, &end3);
  if (*end1 || *end2 || *end3 || w <= 0 || h <= 0 || w > (1L << 20) || h > (1L << 20) ||
      scale == 0.0) {
    fclose(f);
    return ss_error_set(err, SS_ERR_PARSE,
                        "cannot read %s: PFM header has size '%s x %s' and scale '%s'", path, ws,
                        hs, ss);
  }
  int channels = strcmp(magic, "PF") == 0 ? 3 : 1;
  ss_image *img = ss_image_create((int)w, (int)h, channels);
  if (!img) {
    fclose(f);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "cannot read %s: out of memory", path);
  }
  int swap = (scale < 0.0) != host_is_little_endian();
  size_t row = (size_t)w * (size_t)channels;
  for (long y = h - 1; y >= 0; --y) {
    float *dst = img->data + (size_t)y * row;
    if (fread(dst, sizeof(float), row, f) != row) {
      st = ss_error_set(err, SS_ERR_PARSE, "cannot read %s: PFM data ends early", path);
      break;
    }
    if (swap) {
      for (size_t i = 0; i < row; ++i) {
        dst[i] = swap_float(dst[i]);
      }
    }
  }
  fclose(f);
  if (st != SS_OK) {
    ss_image_destroy(img);
    return st;
  }
  *out = img;
  return SS_OK;
}
