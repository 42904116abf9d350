/* Numbers in files as little-endian bytes whatever the machine's order, so
 * that the files move between machines (subsurf's BSSRDF tables,
 * bssrdf/table_file.c, and raw grids, io/grid_raw.c); floats as their IEEE
 * 754 bits. p points at 4 (u32, f32) or 8 (u64, f64) bytes. */
#ifndef SUBSURF_CORE_LITTLE_ENDIAN_H
#define SUBSURF_CORE_LITTLE_ENDIAN_H

#include <stdint.h>
#include <string.h>

static inline void ss_le_put_u32(unsigned char *p, uint32_t v) {
  for (int i = 0; i < 4; ++i) {
    p[i] = (unsigned char)(v >> (8 * i));
  }
}

static inline void ss_le_put_u64(unsigned char *p, uint64_t v) {
  for (int i = 0; i < 8; ++i) {
    p[i] = (unsigned char)(v >> (8 * i));
  }
}

static inline uint32_t ss_le_get_u32(const unsigned char *p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) {
    v |= (uint32_t)p[i] << (8 * i);
  }
  return v;
}

static inline uint64_t ss_le_get_u64(const unsigned char *p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) {
    v |= (uint64_t)p[i] << (8 * i);
  }
  return v;
}

static inline void ss_le_put_f32(unsigned char *p, float f) {
  uint32_t v;
  memcpy(&v, &f, sizeof v);
  ss_le_put_u32(p, v);
}

static inline void ss_le_put_f64(unsigned char *p, double d) {
  uint64_t v;
  memcpy(&v, &d, sizeof v);
  ss_le_put_u64(p, v);
}

static inline float ss_le_get_f32(const unsigned char *p) {
  uint32_t v = ss_le_get_u32(p);
  float f;
  memcpy(&f, &v, sizeof f);
  return f;
}

static inline double ss_le_get_f64(const unsigned char *p) {
  uint64_t v = ss_le_get_u64(p);
  double d;
  memcpy(&d, &v, sizeof d);
  return d;
}

#endif
