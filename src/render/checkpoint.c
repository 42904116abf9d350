/* Render checkpoints (see checkpoint.h): streamed row by row, with the
 * CRC-32 kept as the bytes go, so a large film is never held twice. */
#include "subsurf/checkpoint.h"

#include "core/atomic_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

static const char magic[8] = {'S', 'S', 'R', 'E', 'N', 'D', 'C', 'K'};
#define BYTE_ORDER_MARK 0x01020304u
#define HEADER_SIZE (48 + SS_NAME_SIZE)
#define PIXEL_SIZE (8 + 6 * 8)

static uint32_t crc_add(uint32_t crc, const unsigned char *p, size_t n) {
  return (uint32_t)crc32(crc, p, (uInt)n);
}

static ss_status file_crc(const char *path, uint32_t *crc, ss_error *err) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    return ss_error_set(err, SS_ERR_IO, "checkpoint: cannot read the scene '%s': %s", path,
                        strerror(errno));
  }
  unsigned char buf[1 << 14];
  uint32_t c = (uint32_t)crc32(0L, Z_NULL, 0);
  for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) {
    c = crc_add(c, buf, n);
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    return ss_error_set(err, SS_ERR_IO, "checkpoint: cannot read the scene '%s'", path);
  }
  *crc = c;
  return SS_OK;
}

ss_status ss_checkpoint_key_init(ss_checkpoint_key *key, const char *scene_path,
                                 const ss_scene *scene, const ss_render_options *o, ss_error *err) {
  memset(key, 0, sizeof *key);
  key->spp = (uint32_t)o->spp;
  key->seed = o->seed;
  snprintf(key->integrator, sizeof key->integrator, "%s", scene->integrator.name);
  int full = !o->crop[0] && !o->crop[1] && !o->crop[2] && !o->crop[3];
  int32_t window[4] = {0, 0, scene->camera.width, scene->camera.height};
  for (int i = 0; i < 4; ++i) {
    key->window[i] = full ? window[i] : o->crop[i];
  }
  return file_crc(scene_path, &key->scene_crc, err);
}

static void header_bytes(const ss_checkpoint_key *k, unsigned char h[HEADER_SIZE]) {
  const uint32_t version = SS_CHECKPOINT_VERSION, bom = BYTE_ORDER_MARK;
  memset(h, 0, HEADER_SIZE);
  memcpy(h, magic, sizeof magic);
  memcpy(h + 8, &version, 4);
  memcpy(h + 12, &bom, 4);
  memcpy(h + 16, &k->scene_crc, 4);
  memcpy(h + 20, &k->spp, 4);
  memcpy(h + 24, &k->seed, 8);
  memcpy(h + 32, k->window, 16);
  memcpy(h + 48, k->integrator, sizeof k->integrator);
}

static void pixel_bytes(const ss_film_pixel_state *s, unsigned char *p) {
  memcpy(p, &s->n, 4);
  memcpy(p + 4, &s->rejected, 4);
  memcpy(p + 8, s->mean, 24);
  memcpy(p + 32, s->m2, 24);
}

static void pixel_from_bytes(const unsigned char *p, ss_film_pixel_state *s) {
  memcpy(&s->n, p, 4);
  memcpy(&s->rejected, p + 4, 4);
  memcpy(s->mean, p + 8, 24);
  memcpy(s->m2, p + 32, 24);
}

/* Header, pixel rows and CRC into the temporary file. */
static ss_status write_stream(ss_atomic_file *f, const ss_checkpoint_key *key, const ss_film *film,
                              unsigned char *row, ss_error *err) {
  unsigned char h[HEADER_SIZE];
  header_bytes(key, h);
  uint32_t crc = crc_add((uint32_t)crc32(0L, Z_NULL, 0), h, sizeof h);
  ss_status st = ss_atomic_file_write(f, h, sizeof h, err);
  const int w = ss_film_width(film);
  const size_t row_size = (size_t)w * PIXEL_SIZE;
  for (int y = 0; st == SS_OK && y < ss_film_height(film); ++y) {
    for (int x = 0; x < w; ++x) {
      ss_film_pixel_state s;
      ss_film_get_pixel_state(film, x, y, &s);
      pixel_bytes(&s, row + (size_t)x * PIXEL_SIZE);
    }
    crc = crc_add(crc, row, row_size);
    st = ss_atomic_file_write(f, row, row_size, err);
  }
  return st == SS_OK ? ss_atomic_file_write(f, &crc, 4, err) : st;
}

uint64_t ss_checkpoint_bytes(int width, int height) {
  return HEADER_SIZE + (uint64_t)width * (uint64_t)height * PIXEL_SIZE + 4;
}

ss_status ss_checkpoint_write(const char *path, const ss_checkpoint_key *key, const ss_film *film,
                              ss_error *err) {
  unsigned char *row = malloc((size_t)ss_film_width(film) * PIXEL_SIZE);
  if (!row) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "checkpoint '%s': out of memory", path);
  }
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_CHECKPOINT, err);
  if (st == SS_OK && (st = write_stream(&f, key, film, row, err)) != SS_OK) {
    ss_atomic_file_abort(&f);
  } else if (st == SS_OK) {
    st = ss_atomic_file_commit(&f, err);
  }
  free(row);
  if (st != SS_OK) {
    ss_error_prefix(err, "checkpoint: ");
  }
  return st;
}

/* Format, version and byte order of a header. */
static ss_status check_header(const char *path, const unsigned char *h, ss_error *err) {
  uint32_t version, bom;
  memcpy(&version, h + 8, 4);
  memcpy(&bom, h + 12, 4);
  if (memcmp(h, magic, sizeof magic) != 0) {
    return ss_error_set(err, SS_ERR_PARSE, "checkpoint '%s': not a subsurf render checkpoint",
                        path);
  }
  if (bom != BYTE_ORDER_MARK) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "checkpoint '%s': written on a machine of another byte order", path);
  }
  if (version != SS_CHECKPOINT_VERSION) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "checkpoint '%s': format version %u, this subsurf reads version %d", path,
                        version, SS_CHECKPOINT_VERSION);
  }
  return SS_OK;
}

/* The saved key against the expected one, naming the first difference. */
static ss_status check_key(const char *path, const ss_checkpoint_key *got,
                           const ss_checkpoint_key *want, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  const char *pre = "checkpoint";
  if (got->scene_crc != want->scene_crc) {
    return ss_error_set(err, bad,
                        "%s '%s' belongs to another scene (the scene file's contents "
                        "differ)",
                        pre, path);
  }
  if (strncmp(got->integrator, want->integrator, sizeof got->integrator) != 0) {
    return ss_error_set(err, bad, "%s '%s' was made with integrator '%s', not '%s'", pre, path,
                        got->integrator, want->integrator);
  }
  if (got->spp != want->spp || got->seed != want->seed) {
    return ss_error_set(err, bad,
                        "%s '%s' was made with --spp %u --seed %llu, not --spp %u "
                        "--seed %llu",
                        pre, path, got->spp, (unsigned long long)got->seed, want->spp,
                        (unsigned long long)want->seed);
  }
  if (memcmp(got->window, want->window, sizeof got->window) != 0) {
    const int32_t *a = got->window, *b = want->window;
    return ss_error_set(err, bad, "%s '%s' covers the window %d,%d,%d,%d, not %d,%d,%d,%d", pre,
                        path, a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]);
  }
  return SS_OK;
}

static ss_status read_key(const char *path, FILE *f, ss_checkpoint_key *key, uint32_t *crc,
                          ss_error *err) {
  unsigned char h[HEADER_SIZE];
  if (fread(h, 1, sizeof h, f) != sizeof h) {
    return ss_error_set(err, SS_ERR_PARSE, "checkpoint '%s': truncated header", path);
  }
  ss_status st = check_header(path, h, err);
  if (st != SS_OK) {
    return st;
  }
  memset(key, 0, sizeof *key);
  memcpy(&key->scene_crc, h + 16, 4);
  memcpy(&key->spp, h + 20, 4);
  memcpy(&key->seed, h + 24, 8);
  memcpy(key->window, h + 32, 16);
  memcpy(key->integrator, h + 48, sizeof key->integrator);
  key->integrator[sizeof key->integrator - 1] = '\0';
  *crc = crc_add((uint32_t)crc32(0L, Z_NULL, 0), h, sizeof h);
  return SS_OK;
}

/* A pixel state a render can have produced. */
static int pixel_valid(const ss_film_pixel_state *s, uint32_t spp) {
  if ((uint64_t)s->n + s->rejected > spp) {
    return 0;
  }
  for (int c = 0; c < 3; ++c) {
    if (!isfinite(s->mean[c]) || !(s->m2[c] >= 0.0) || !isfinite(s->m2[c])) {
      return 0;
    }
  }
  return 1;
}

/* Pixel rows into a new film, then the CRC. */
static ss_status read_film(const char *path, FILE *f, const ss_checkpoint_key *key, uint32_t crc,
                           ss_film **out, ss_error *err) {
  const int w = key->window[2] - key->window[0], h = key->window[3] - key->window[1];
  ss_film *film = NULL;
  ss_status st = ss_film_create(w, h, &film, err);
  unsigned char *row = st == SS_OK ? malloc((size_t)w * PIXEL_SIZE) : NULL;
  if (st == SS_OK && !row) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "checkpoint '%s': out of memory", path);
  }
  for (int y = 0; st == SS_OK && y < h; ++y) {
    if (fread(row, 1, (size_t)w * PIXEL_SIZE, f) != (size_t)w * PIXEL_SIZE) {
      st = ss_error_set(err, SS_ERR_PARSE, "checkpoint '%s': truncated at pixel row %d", path, y);
      break;
    }
    crc = crc_add(crc, row, (size_t)w * PIXEL_SIZE);
    for (int x = 0; x < w; ++x) {
      ss_film_pixel_state s;
      pixel_from_bytes(row + (size_t)x * PIXEL_SIZE, &s);
      ss_film_set_pixel_state(film, x, y, &s);
    }
  }
  uint32_t stored;
  if (st == SS_OK && fread(&stored, 1, 4, f) != 4) {
    st = ss_error_set(err, SS_ERR_PARSE, "checkpoint '%s': truncated checksum", path);
  } else if (st == SS_OK && stored != crc) {
    st = ss_error_set(err, SS_ERR_PARSE,
                      "checkpoint '%s': corrupt: CRC-32 mismatch (stored %08x, computed %08x)",
                      path, stored, crc);
  }
  for (int y = 0; st == SS_OK && y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ss_film_pixel_state s;
      ss_film_get_pixel_state(film, x, y, &s);
      if (!pixel_valid(&s, key->spp)) {
        st = ss_error_set(err, SS_ERR_PARSE, "checkpoint '%s': pixel %d,%d is not a render's", path,
                          x, y);
        break;
      }
    }
  }
  free(row);
  if (st != SS_OK) {
    ss_film_destroy(film);
    return st;
  }
  *out = film;
  return SS_OK;
}

/* The file's size against the one its header's window implies (before
 * anything is allocated from the header). */
static ss_status check_size(const char *path, FILE *f, const ss_checkpoint_key *key,
                            ss_error *err) {
  const int32_t *win = key->window;
  long size = -1;
  if (fseek(f, 0, SEEK_END) == 0) {
    size = ftell(f);
  }
  if (size < 0 || fseek(f, HEADER_SIZE, SEEK_SET) != 0) {
    return ss_error_set(err, SS_ERR_IO, "checkpoint '%s': cannot seek: %s", path, strerror(errno));
  }
  double w = (double)win[2] - win[0], h = (double)win[3] - win[1];
  if (!(w >= 1.0 && h >= 1.0) || HEADER_SIZE + w * h * PIXEL_SIZE + 4.0 != (double)size) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "checkpoint '%s': %ld bytes do not hold the film of window %d,%d,%d,%d "
                        "(truncated or corrupt)",
                        path, size, win[0], win[1], win[2], win[3]);
  }
  return SS_OK;
}

ss_status ss_checkpoint_read(const char *path, const ss_checkpoint_key *expect, ss_film **film,
                             ss_error *err) {
  *film = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) {
    return ss_error_set(err, SS_ERR_IO, "checkpoint '%s': cannot open: %s", path, strerror(errno));
  }
  ss_checkpoint_key key;
  uint32_t crc = 0;
  ss_status st = read_key(path, f, &key, &crc, err);
  if (st == SS_OK) {
    st = check_size(path, f, &key, err);
  }
  if (st == SS_OK) {
    st = read_film(path, f, &key, crc, film, err);
  }
  fclose(f);
  if (st == SS_OK && (st = check_key(path, &key, expect, err)) != SS_OK) {
    ss_film_destroy(*film);
    *film = NULL;
  }
  return st;
}
