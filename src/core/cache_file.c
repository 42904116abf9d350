/* The frame of subsurf's cache files (cache_file.h). */
#include "core/cache_file.h"

#define BYTE_ORDER_MARK 0x01020304u

void ss_cache_header_put(unsigned char head[SS_CACHE_HEADER_BYTES], const char *magic,
                         uint32_t version, uint64_t key, uint64_t count) {
  memset(head, 0, SS_CACHE_HEADER_BYTES);
  memcpy(head, magic, strlen(magic) < 8 ? strlen(magic) : 8);
  ss_cache_put_u32(head + 8, version);
  ss_cache_put_u32(head + 12, BYTE_ORDER_MARK);
  ss_cache_put_u64(head + 16, key);
  ss_cache_put_u64(head + 24, count);
}

const char *ss_cache_header_check(const unsigned char head[SS_CACHE_HEADER_BYTES],
                                  const char *magic, uint32_t version, const char *not_this) {
  unsigned char want[8] = {0};
  memcpy(want, magic, strlen(magic) < 8 ? strlen(magic) : 8);
  if (memcmp(head, want, 8)) {
    return not_this;
  }
  if (ss_cache_get_u32(head + 12) != BYTE_ORDER_MARK) {
    return "written on a machine of another byte order";
  }
  if (ss_cache_get_u32(head + 8) != version) {
    return "another version";
  }
  return NULL;
}

ss_status ss_cache_file_finish(ss_atomic_file *f, uint32_t crc, ss_status st, ss_error *err) {
  unsigned char tail[4];
  ss_cache_put_u32(tail, crc);
  if (st == SS_OK)
    st = ss_atomic_file_write(f, tail, sizeof tail, err);
  if (st != SS_OK) {
    ss_atomic_file_abort(f);
    return st;
  }
  return ss_atomic_file_commit(f, err);
}
