/* subsurf's raw grid format (grid_io.h). */
#include "core/atomic_file.h"
#include "core/input_file.h"
#include "core/little_endian.h"
#include "io/grid_file_axis.h"
#include "subsurf/grid_io.h"

#include <stdlib.h>
#include <string.h>

/* Checks the header against the size before anything is allocated. */
static ss_status read_header(const unsigned char *data, size_t size, const char *name, int n[3],
                             uint32_t *channels, ss_vec3 *lo, ss_vec3 *hi, ss_error *err) {
  if (size < SS_GRID_RAW_HEADER || memcmp(data, SS_GRID_RAW_MAGIC, 8)) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: not a subsurf grid file (bad magic or shorter "
                        "than its %d-byte header)",
                        name, SS_GRID_RAW_HEADER);
  }
  uint32_t version = ss_le_get_u32(data + 8);
  *channels = ss_le_get_u32(data + 12);
  if (version != 1) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: grid format version %u (expected 1)", name,
                        version);
  }
  if (*channels != 1 && *channels != 4) {
    return ss_error_set(err, SS_ERR_PARSE, "%s: %u channels (expected 1 or 4)", name, *channels);
  }
  uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    uint32_t v = ss_le_get_u32(data + 16 + 4 * a);
    if (v < 1 || v > (uint32_t)SS_GRID_MAX_VOXELS || (count *= v) > (uint64_t)SS_GRID_MAX_VOXELS) {
      return ss_error_set(err, SS_ERR_PARSE,
                          "%s: grid dimensions %u x %u x %u: each must be >= "
                          "1 with at most 2^31 voxels",
                          name, ss_le_get_u32(data + 16), ss_le_get_u32(data + 20),
                          ss_le_get_u32(data + 24));
    }
    n[a] = (int)v;
  }
  uint64_t expect = SS_GRID_RAW_HEADER + count * *channels * 4;
  if (size != expect) {
    return ss_error_set(err, SS_ERR_PARSE,
                        "%s: %zu bytes, but a %d x %d x %d grid of %u "
                        "channels takes %llu (truncated or inconsistent)",
                        name, size, n[0], n[1], n[2], *channels, (unsigned long long)expect);
  }
  *lo = ss_vec3_make(ss_le_get_f64(data + 32), ss_le_get_f64(data + 40), ss_le_get_f64(data + 48));
  *hi = ss_vec3_make(ss_le_get_f64(data + 56), ss_le_get_f64(data + 64), ss_le_get_f64(data + 72));
  return SS_OK;
}

ss_status ss_grid_read_raw_memory(const unsigned char *data, size_t size, const char *name,
                                  ss_grid **out, ss_error *err) {
  *out = NULL;
  int n[3];
  uint32_t channels = 1;
  ss_vec3 lo, hi;
  ss_status st = read_header(data, size, name, n, &channels, &lo, &hi, err);
  ss_grid *g = NULL;
  if (st == SS_OK && (st = ss_grid_create(n, lo, hi, channels == 4, &g, err)) != SS_OK) {
    ss_error_prefix(err, "%s: ", name);
  }
  if (st != SS_OK) {
    return st;
  }
  const unsigned char *p = data + SS_GRID_RAW_HEADER;
  int64_t count = ss_grid_voxels(g);
  for (int64_t v = 0; v < count; ++v, p += 4 * channels) {
    g->density[v] = ss_le_get_f32(p);
    if (channels == 4) {
      ss_vec3 a = ss_vec3_make(ss_le_get_f32(p + 4), ss_le_get_f32(p + 8), ss_le_get_f32(p + 12));
      if ((st = ss_grid_set_file_axis(g, v, a, name, err)) != SS_OK) {
        ss_grid_destroy(g);
        return st;
      }
    }
  }
  if ((st = ss_grid_finish(g, err)) != SS_OK) {
    ss_error_prefix(err, "%s: ", name);
    ss_grid_destroy(g);
    return st == SS_ERR_INVALID_ARGUMENT ? SS_ERR_PARSE : st;
  }
  *out = g;
  return SS_OK;
}

/* VDB files begin with the 64-bit magic 0x56444220 (" BDV"). */
static int is_vdb(const unsigned char *head, size_t n) {
  static const unsigned char magic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
  return n >= 8 && !memcmp(head, magic, 8);
}

ss_status ss_grid_read(const char *path, ss_grid **out, ss_error *err) {
  *out = NULL;
  FILE *f;
  ss_status st = ss_input_file_open(path, path, &f, NULL, err);
  if (st != SS_OK) {
    return st;
  }
  unsigned char head[8] = {0};
  size_t got = fread(head, 1, sizeof head, f);
  fclose(f);
  if (is_vdb(head, got)) {
    return ss_grid_read_vdb(path, out, err);
  }
  unsigned char *data;
  size_t bytes;
  if ((st = ss_input_file_read(path, path, SS_INPUT_GRID, &data, &bytes, err)) != SS_OK) {
    return st;
  }
  st = ss_grid_read_raw_memory(data, bytes, path, out, err);
  free(data);
  return st;
}

ss_status ss_grid_write_raw(const char *path, const ss_grid *g, ss_error *err) {
  unsigned char h[SS_GRID_RAW_HEADER] = {0};
  uint32_t channels = g->axis ? 4 : 1;
  memcpy(h, SS_GRID_RAW_MAGIC, 8);
  ss_le_put_u32(h + 8, 1);
  ss_le_put_u32(h + 12, channels);
  for (int a = 0; a < 3; ++a) {
    ss_le_put_u32(h + 16 + 4 * a, (uint32_t)g->n[a]);
    ss_le_put_f64(h + 32 + 8 * a, ss_vec3_component(g->lo, a));
    ss_le_put_f64(h + 56 + 8 * a, ss_vec3_component(g->hi, a));
  }
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, SS_FILE_GRID, err);
  if (st != SS_OK) {
    return st;
  }
  st = ss_atomic_file_write(&f, h, sizeof h, err);
  enum { CHUNK = 4096 }; /* voxels per write */
  unsigned char buf[CHUNK * 16];
  int64_t count = ss_grid_voxels(g);
  for (int64_t i0 = 0; i0 < count && st == SS_OK; i0 += CHUNK) {
    unsigned char *v = buf;
    for (int64_t i = i0; i < count && i < i0 + CHUNK; ++i, v += 4 * channels) {
      ss_le_put_f32(v, g->density[i]);
      if (g->axis) {
        ss_vec3 a = ss_grid_axis_of(g, i);
        ss_le_put_f32(v + 4, (float)a.x);
        ss_le_put_f32(v + 8, (float)a.y);
        ss_le_put_f32(v + 12, (float)a.z);
      }
    }
    st = ss_atomic_file_write(&f, buf, (size_t)(v - buf), err);
  }
  if (st != SS_OK) {
    ss_atomic_file_abort(&f);
    return st;
  }
  return ss_atomic_file_commit(&f, err);
}
