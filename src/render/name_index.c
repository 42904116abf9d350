/* Open addressing with linear probing over FNV-1a hashes (name_index.h);
 * the table doubles when half full. */
#include "render/name_index.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct ss_name_index {
  int *slot;       /* record index + 1; 0: empty */
  size_t capacity; /* a power of two */
  size_t count;
};

static const char *name_of(ss_named r, int i) {
  return (const char *)r.first + (size_t)i * r.stride;
}

/* FNV-1a, 64 bits (Fowler, Noll and Vo). */
static uint64_t hash(const char *s) {
  uint64_t h = 14695981039346656037ull;
  for (; *s; ++s) {
    h = (h ^ (unsigned char)*s) * 1099511628211ull;
  }
  return h;
}

int ss_name_index_find(const ss_name_index *ix, ss_named records, const char *name) {
  if (!ix) {
    return -1;
  }
  size_t mask = ix->capacity - 1;
  for (size_t k = hash(name) & mask; ix->slot[k]; k = (k + 1) & mask) {
    if (!strcmp(name_of(records, ix->slot[k] - 1), name)) {
      return ix->slot[k] - 1;
    }
  }
  return -1;
}

static void put(int *slot, size_t capacity, ss_named records, int index) {
  size_t k = hash(name_of(records, index)) & (capacity - 1);
  while (slot[k]) {
    k = (k + 1) & (capacity - 1);
  }
  slot[k] = index + 1;
}

int ss_name_index_add(ss_name_index **ixp, ss_named records, int index) {
  if (!*ixp && !(*ixp = calloc(1, sizeof **ixp))) {
    return -1;
  }
  ss_name_index *ix = *ixp;
  if (2 * (ix->count + 1) > ix->capacity) {
    size_t capacity = ix->capacity ? 2 * ix->capacity : 64;
    int *slot = calloc(capacity, sizeof *slot);
    if (!slot) {
      return -1;
    }
    for (size_t k = 0; k < ix->capacity; ++k) {
      if (ix->slot[k]) {
        put(slot, capacity, records, ix->slot[k] - 1);
      }
    }
    free(ix->slot);
    ix->slot = slot;
    ix->capacity = capacity;
  }
  put(ix->slot, ix->capacity, records, index);
  ix->count++;
  return 0;
}

void ss_name_index_destroy(ss_name_index *ix) {
  if (ix) {
    free(ix->slot);
    free(ix);
  }
}
