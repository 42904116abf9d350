/* PNG through stb_image_write: linear values scaled by 2^exposure, clamped to
 * [0, 1] and encoded with the sRGB transfer curve to 8 bits. */
#include "subsurf/image_io.h"

#include "core/atomic_file.h"
#include "io/image_io_internal.h"

#include <math.h>
#include <stb/stb_image_write.h>
#include <stdint.h>
#include <stdlib.h>

double ss_srgb_encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* NaN and infinite pixels (a diverged estimate) become black rather than
 * poisoning the conversion. */
static unsigned char to_byte(double v, int srgb) {
  if (!isfinite(v) || !(v > 0.0)) {
    return 0;
  }
  if (v > 1.0) {
    v = 1.0;
  }
  return (unsigned char)lrint((srgb ? ss_srgb_encode(v) : v) * 255.0);
}

typedef struct {
  ss_atomic_file *file;
  ss_error *err;
  ss_status status;
} png_sink;

static void png_sink_write(void *context, void *data, int size) {
  png_sink *s = context;
  if (s->status == SS_OK && size > 0) {
    s->status = ss_atomic_file_write(s->file, data, (size_t)size, s->err);
  }
}

ss_status ss_image_write_png(const char *path, const ss_image *img, double exposure,
                             ss_error *err) {
  ss_status st = ss_image_io_check(path, img, err);
  if (st != SS_OK) {
    return st;
  }
  if (!isfinite(exposure)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "cannot write %s: exposure must be finite (got %g)", path, exposure);
  }
  int nc = img->channels;
  size_t count = (size_t)img->width * (size_t)img->height * (size_t)nc;
  unsigned char *pixels = malloc(count);
  if (!pixels) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "cannot write %s: out of memory", path);
  }
  double scale = exp2(exposure);
  for (size_t i = 0; i < count; ++i) {
    /* Alpha is coverage, not light: neither exposed nor sRGB-encoded. */
    int alpha = nc == 4 && i % 4 == 3;
    pixels[i] = alpha ? to_byte(img->data[i], 0) : to_byte(img->data[i] * scale, 1);
  }
  ss_atomic_file f;
  if ((st = ss_atomic_file_open(&f, path, SS_FILE_PNG, err)) != SS_OK) {
    free(pixels);
    return st;
  }
  png_sink sink = {&f, err, SS_OK};
  int ok = stbi_write_png_to_func(png_sink_write, &sink, img->width, img->height, nc, pixels,
                                  img->width * nc);
  free(pixels);
  if (sink.status != SS_OK) {
    ss_atomic_file_abort(&f);
    return sink.status;
  }
  if (!ok) {
    ss_atomic_file_abort(&f);
    return ss_error_set(err, SS_ERR_IO, "cannot write %s: PNG encoding failed", path);
  }
  return ss_atomic_file_commit(&f, err);
}
