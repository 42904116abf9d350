/* The frame shared by subsurf's disk caches of precomputations (the
 * `hierarchical` integrator's irradiance points, irradiance_cache.h; the
 * `fem` integrator's meshes and solutions, fem_cache.h): a 32-byte header
 *   8-byte magic, u32 version, u32 byte-order mark 0x01020304, u64 key,
 *   u64 count,
 * the body, and a u32 CRC-32 (zlib's) of every byte before it. Numbers are
 * in the writer's byte order; the mark refuses a file of another. Keys are
 * 64-bit FNV-1a hashes (Fowler, Noll & Vo) of everything the cached result
 * depends on, fed value by value (never a struct's padding). */
#ifndef SUBSURF_CORE_CACHE_FILE_H
#define SUBSURF_CORE_CACHE_FILE_H

#include "core/atomic_file.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define SS_CACHE_HEADER_BYTES 32
/* FNV-1a's offset basis: the hash of nothing. */
#define SS_HASH_SEED 0xCBF29CE484222325ULL

static inline void ss_hash_bytes(uint64_t *h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; ++i) {
    *h = (*h ^ p[i]) * 0x100000001B3ULL;
  }
}
static inline void ss_hash_double(uint64_t *h, double v) { ss_hash_bytes(h, &v, sizeof v); }
static inline void ss_hash_int(uint64_t *h, int64_t v) { ss_hash_bytes(h, &v, sizeof v); }
static inline void ss_hash_str(uint64_t *h, const char *s) { ss_hash_bytes(h, s, strlen(s) + 1); }

static inline void ss_cache_put_u32(unsigned char *b, uint32_t v) { memcpy(b, &v, 4); }
static inline void ss_cache_put_u64(unsigned char *b, uint64_t v) { memcpy(b, &v, 8); }
static inline uint32_t ss_cache_get_u32(const unsigned char *b) {
  uint32_t v;
  memcpy(&v, b, 4);
  return v;
}
static inline uint64_t ss_cache_get_u64(const unsigned char *b) {
  uint64_t v;
  memcpy(&v, b, 8);
  return v;
}

/* Fills the header; `magic` is 7 characters (the 8th byte is its NUL). */
void ss_cache_header_put(unsigned char head[SS_CACHE_HEADER_BYTES], const char *magic,
                         uint32_t version, uint64_t key, uint64_t count);
/* Why the header is not one of this cache at this version: `not_this` (a
 * foreign magic, e.g. "not an irradiance cache"), "written on a machine of
 * another byte order" or "another version"; NULL when it is. The key and
 * count are the caller's to check. */
const char *ss_cache_header_check(const unsigned char head[SS_CACHE_HEADER_BYTES],
                                  const char *magic, uint32_t version, const char *not_this);

/* Ends a cache file whose bytes so far have the CRC-32 `crc`: appends it
 * and commits (ss_atomic_file_commit) when st is SS_OK, else aborts; returns
 * the first failure. */
ss_status ss_cache_file_finish(ss_atomic_file *f, uint32_t crc, ss_status st, ss_error *err);

#endif
