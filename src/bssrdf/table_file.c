#include "subsurf/table_file.h"

#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/little_endian.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static const char magic[8] = {'S', 'S', 'B', 'S', 'S', 'R', 'D', 'F'};

static uint32_t crc_of(const unsigned char *data, size_t n) {
  uLong crc = crc32(0L, Z_NULL, 0);
  while (n > 0) {
    uInt chunk = n > (1u << 30) ? (1u << 30) : (uInt)n;
    crc = crc32(crc, data, chunk);
    data += chunk;
    n -= chunk;
  }
  return (uint32_t)crc;
}

/* The 64-byte header: magic, then the fields of ss_table_file_info at fixed
 * offsets (include/subsurf/table_file.h), zero padding. */
static void put_header(unsigned char *p, const ss_table_file_info *h) {
  memset(p, 0, SS_TABLE_FILE_HEADER);
  memcpy(p, magic, sizeof magic);
  ss_le_put_u32(p + 8, h->version);
  ss_le_put_u32(p + 12, h->kind);
  ss_le_put_u32(p + 16, h->fit);
  ss_le_put_u32(p + 20, h->n_rho);
  ss_le_put_u32(p + 24, h->n_theta);
  ss_le_put_u32(p + 28, h->n_r);
  ss_le_put_u32(p + 32, h->n_rs);
  ss_le_put_u32(p + 36, h->n_shape);
  ss_le_put_f64(p + 40, h->eta);
  ss_le_put_f64(p + 48, h->g);
  ss_le_put_u64(p + 56, h->count);
}
static void get_header(const unsigned char *p, ss_table_file_info *h) {
  h->version = ss_le_get_u32(p + 8);
  h->kind = ss_le_get_u32(p + 12);
  h->fit = ss_le_get_u32(p + 16);
  h->n_rho = ss_le_get_u32(p + 20);
  h->n_theta = ss_le_get_u32(p + 24);
  h->n_r = ss_le_get_u32(p + 28);
  h->n_rs = ss_le_get_u32(p + 32);
  h->n_shape = ss_le_get_u32(p + 36);
  h->eta = ss_le_get_f64(p + 40);
  h->g = ss_le_get_f64(p + 48);
  h->count = ss_le_get_u64(p + 56);
}

/* A file is its header, the count values it announces (float32) and the
 * CRC, nothing more or less; a count above 2^32 is refused before it is
 * multiplied. */
static ss_status check_length(const char *path, uint64_t count, uint64_t bytes, ss_error *err) {
  if (count <= ((uint64_t)1 << 32) && bytes == SS_TABLE_FILE_HEADER + 4 * count + 4) {
    return SS_OK;
  }
  return ss_error_set(err, SS_ERR_PARSE,
                      "table file '%s': truncated or padded: header announces %llu values "
                      "(%llu bytes), file has %llu bytes",
                      path, (unsigned long long)count,
                      (unsigned long long)(SS_TABLE_FILE_HEADER + 4 * count + 4),
                      (unsigned long long)bytes);
}

/* Serialises header + values + CRC and writes them as core/atomic_file.h
 * writes outputs (a regular file through a temporary file renamed into
 * place, so a failed write leaves no partial table; a device or FIFO
 * directly, never replaced). */
static ss_status write_table(const char *path, const ss_table_file_info *h,
                             const float *const *arrays, const size_t *counts, int n_arrays,
                             ss_error *err) {
  size_t size = SS_TABLE_FILE_HEADER + 4 * (size_t)h->count + 4;
  unsigned char *buf = malloc(size);
  if (!buf) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "table file '%s': out of memory", path);
  }
  put_header(buf, h);
  unsigned char *p = buf + SS_TABLE_FILE_HEADER;
  for (int a = 0; a < n_arrays; ++a) {
    for (size_t i = 0; i < counts[a]; ++i, p += 4) {
      ss_le_put_f32(p, arrays[a][i]);
    }
  }
  ss_le_put_u32(p, crc_of(buf, size - 4));

  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_TABLE, err);
  if (st == SS_OK && (st = ss_atomic_file_write(&f, buf, size, err)) != SS_OK) {
    ss_atomic_file_abort(&f);
  } else if (st == SS_OK) {
    st = ss_atomic_file_commit(&f, err);
  }
  free(buf);
  return st;
}

/* Reads the file and checks everything that does not depend on its kind. */
static ss_status read_checked(const char *path, ss_table_file_info *h, unsigned char **data,
                              ss_error *err) {
  *data = NULL;
  char label[64 + SS_ERROR_MESSAGE_SIZE];
  snprintf(label, sizeof label, "table file '%s'", path);
  unsigned char *buf;
  size_t size;
  ss_status st = ss_input_file_read(path, label, SS_INPUT_BSSRDF_TABLE, &buf, &size, err);
  if (st != SS_OK) {
    return st;
  }
  if (size < sizeof magic || memcmp(buf, magic, sizeof magic) != 0) {
    free(buf);
    return ss_error_set(err, SS_ERR_PARSE,
                        "table file '%s': not a subsurf BSSRDF table (no SSBSSRDF magic)", path);
  }
  if (size < SS_TABLE_FILE_HEADER + 4) {
    free(buf);
    return ss_error_set(err, SS_ERR_PARSE, "table file '%s': truncated header (%zu bytes)", path,
                        size);
  }
  get_header(buf, h);
  if (h->version != SS_TABLE_FILE_VERSION) {
    free(buf);
    return ss_error_set(err, SS_ERR_UNSUPPORTED,
                        "table file '%s': format version %u, this build reads version %d", path,
                        h->version, SS_TABLE_FILE_VERSION);
  }
  if ((st = check_length(path, h->count, (uint64_t)size, err)) != SS_OK) {
    free(buf);
    return st;
  }
  uint32_t stored = ss_le_get_u32(buf + size - 4), computed = crc_of(buf, (size_t)size - 4);
  if (stored != computed) {
    free(buf);
    return ss_error_set(err, SS_ERR_PARSE,
                        "table file '%s': corrupt: CRC-32 mismatch (stored %08x, computed %08x)",
                        path, stored, computed);
  }
  if (!(isfinite(h->eta) && h->eta > 0.0) || !(isfinite(h->g) && fabs(h->g) < 1.0)) {
    free(buf);
    return ss_error_set(err, SS_ERR_PARSE, "table file '%s': invalid eta %g or g %g", path, h->eta,
                        h->g);
  }
  *data = buf;
  return SS_OK;
}

ss_status ss_table_file_info_read(const char *path, ss_table_file_info *info, ss_error *err) {
  unsigned char *buf;
  ss_status st = read_checked(path, info, &buf, err);
  free(buf);
  return st;
}

/* Copies count float32 values, rejecting non-finite or negative energies. */
static ss_status copy_values(const char *path, const unsigned char *p, float *dst, size_t count,
                             int non_negative, ss_error *err) {
  for (size_t i = 0; i < count; ++i, p += 4) {
    float v = ss_le_get_f32(p);
    if (!isfinite(v) || (non_negative && v < 0.0f)) {
      return ss_error_set(err, SS_ERR_PARSE, "table file '%s': corrupt: value %zu is %g", path, i,
                          (double)v);
    }
    dst[i] = v;
  }
  return SS_OK;
}

ss_status ss_table_radial_save(const ss_table_radial *t, const char *path, ss_error *err) {
  ss_table_file_info h = {.version = SS_TABLE_FILE_VERSION,
                          .kind = SS_TABLE_KIND_RADIAL,
                          .n_rho = (uint32_t)t->n_rho,
                          .n_theta = 1,
                          .n_r = (uint32_t)t->n_r,
                          .eta = t->eta,
                          .g = t->g,
                          .count = (uint64_t)(t->n_rho * t->n_r)};
  const float *arrays[1] = {t->profile};
  size_t counts[1] = {t->n_rho * t->n_r};
  return write_table(path, &h, arrays, counts, 1, err);
}

ss_status ss_table_gwc_save(const ss_table_gwc *t, const char *path, ss_error *err) {
  size_t ne = t->n_rho * t->n_theta * t->n_r, ns = t->n_rho * t->n_theta * t->n_rs * t->n_shape;
  ss_table_file_info h = {.version = SS_TABLE_FILE_VERSION,
                          .kind = SS_TABLE_KIND_GWC,
                          .fit = (uint32_t)t->fit,
                          .n_rho = (uint32_t)t->n_rho,
                          .n_theta = (uint32_t)t->n_theta,
                          .n_r = (uint32_t)t->n_r,
                          .n_rs = (uint32_t)t->n_rs,
                          .n_shape = (uint32_t)t->n_shape,
                          .eta = t->eta,
                          .g = t->g,
                          .count = (uint64_t)(ne + ns)};
  const float *arrays[2] = {t->energy, t->shape};
  size_t counts[2] = {ne, ns};
  return write_table(path, &h, arrays, counts, 2, err);
}

static ss_status wrong_kind(const char *path, const ss_table_file_info *h, const char *want,
                            ss_error *err) {
  const char *kind = h->kind == SS_TABLE_KIND_RADIAL ? "radial"
                     : h->kind == SS_TABLE_KIND_GWC  ? "gwc"
                                                     : "unknown";
  return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "table file '%s': holds a %s table (kind %u), expected a %s table", path,
                      kind, h->kind, want);
}

ss_status ss_table_radial_load(const char *path, ss_table_radial **out, ss_error *err) {
  ss_table_file_info h;
  unsigned char *buf;
  ss_status st = read_checked(path, &h, &buf, err);
  if (st != SS_OK) {
    return st;
  }
  if (h.kind != SS_TABLE_KIND_RADIAL) {
    free(buf);
    return wrong_kind(path, &h, "radial", err);
  }
  if (h.n_rho != SS_TABLE_RHO_COUNT || h.n_r != SS_TABLE_RADIUS_COUNT ||
      h.count != (uint64_t)h.n_rho * h.n_r) {
    free(buf);
    return ss_error_set(err, SS_ERR_PARSE,
                        "table file '%s': unexpected grid %u x %u (expected %d x %d)", path,
                        h.n_rho, h.n_r, SS_TABLE_RHO_COUNT, SS_TABLE_RADIUS_COUNT);
  }
  ss_table_radial *t = NULL;
  st = ss_table_radial_alloc(h.eta, h.g, &t, err);
  if (st == SS_OK) {
    st = copy_values(path, buf + SS_TABLE_FILE_HEADER, t->profile, (size_t)h.count, 1, err);
  }
  free(buf);
  if (st != SS_OK) {
    ss_table_radial_destroy(t);
    return st;
  }
  ss_table_radial_finish(t);
  *out = t;
  return SS_OK;
}

ss_status ss_table_gwc_load(const char *path, ss_table_gwc **out, ss_error *err) {
  ss_table_file_info h;
  unsigned char *buf;
  ss_status st = read_checked(path, &h, &buf, err);
  if (st != SS_OK) {
    return st;
  }
  if (h.kind != SS_TABLE_KIND_GWC) {
    free(buf);
    return wrong_kind(path, &h, "gwc", err);
  }
  if (h.fit != SS_TABLE_GWC_ANCHORS && h.fit != SS_TABLE_GWC_TWO_LOBE) {
    free(buf);
    return ss_error_set(err, SS_ERR_UNSUPPORTED, "table file '%s': unknown azimuthal fit %u", path,
                        h.fit);
  }
  ss_table_gwc *t;
  st = ss_table_gwc_alloc(h.eta, h.g, (int)h.fit, &t, err);
  if (st != SS_OK) {
    free(buf);
    return st;
  }
  size_t ne = t->n_rho * t->n_theta * t->n_r, ns = t->n_rho * t->n_theta * t->n_rs * t->n_shape;
  if (h.n_rho != t->n_rho || h.n_theta != t->n_theta || h.n_r != t->n_r || h.n_rs != t->n_rs ||
      h.n_shape != t->n_shape || h.count != ne + ns) {
    st = ss_error_set(err, SS_ERR_PARSE,
                      "table file '%s': unexpected grid %u x %u x %u (shape %u x %u), expected "
                      "%zu x %zu x %zu (shape %zu x %zu)",
                      path, h.n_rho, h.n_theta, h.n_r, h.n_rs, h.n_shape, t->n_rho, t->n_theta,
                      t->n_r, t->n_rs, t->n_shape);
  }
  if (st == SS_OK) {
    st = copy_values(path, buf + SS_TABLE_FILE_HEADER, t->energy, ne, 1, err);
  }
  if (st == SS_OK) {
    st = copy_values(path, buf + SS_TABLE_FILE_HEADER + 4 * ne, t->shape, ns, 0, err);
  }
  free(buf);
  if (st != SS_OK) {
    ss_table_gwc_destroy(t);
    return st;
  }
  ss_table_gwc_finish(t);
  *out = t;
  return SS_OK;
}

ss_status ss_table_file_check_material(const char *path, double table_eta, double table_g,
                                       double eta, double g, ss_error *err) {
  if (fabs(table_eta - eta) > 1e-9 || fabs(table_g - g) > 1e-9) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "table file '%s' was built for eta %g, g %g but the material has eta %g, "
                        "g %g (rebuild with subsurf table build --eta %g --g %g)",
                        path, table_eta, table_g, eta, g, eta, g);
  }
  return SS_OK;
}
