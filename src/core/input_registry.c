#include "core/input_registry.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct {
  dev_t dev;
  ino_t ino;
  char *path; /* NULL: an empty slot */
} input;

/* Readers run on several threads (meshes, textures): one short lock around
 * an open-addressing hash set, so that a scene of 10^5 files costs 10^5
 * look-ups, not 10^10. */
static atomic_flag lock = ATOMIC_FLAG_INIT;
static input *slots;
static size_t num_inputs, num_slots; /* num_slots: 0 or a power of 2 */

static void acquire(void) {
  while (atomic_flag_test_and_set_explicit(&lock, memory_order_acquire)) {
  }
}

static void release(void) { atomic_flag_clear_explicit(&lock, memory_order_release); }

/* The slot of (dev, ino), or the empty one where it would go. */
static input *slot_of(input *table, size_t n, dev_t dev, ino_t ino) {
  size_t h = ((size_t)ino * (size_t)0x9E3779B97F4A7C15ull) ^ (size_t)dev;
  for (size_t i = h & (n - 1);; i = (i + 1) & (n - 1)) {
    if (!table[i].path || (table[i].dev == dev && table[i].ino == ino)) {
      return &table[i];
    }
  }
}

/* Doubles the table; 0 when out of memory (it stays as it was). */
static int grow(void) {
  size_t n = num_slots ? 2 * num_slots : 64;
  input *table = calloc(n, sizeof *table);
  if (!table) {
    return 0;
  }
  for (size_t i = 0; i < num_slots; ++i) {
    if (slots[i].path) {
      *slot_of(table, n, slots[i].dev, slots[i].ino) = slots[i];
    }
  }
  free(slots);
  slots = table;
  num_slots = n;
  return 1;
}

void ss_input_registry_add(dev_t dev, ino_t ino, const char *path) {
  acquire();
  if (2 * (num_inputs + 1) <= num_slots || grow()) {
    input *s = slot_of(slots, num_slots, dev, ino);
    if (!s->path && (s->path = strdup(path)) != NULL) {
      s->dev = dev;
      s->ino = ino;
      ++num_inputs;
    }
  }
  release();
}

const char *ss_input_registry_find(dev_t dev, ino_t ino) {
  const char *path = NULL;
  acquire();
  if (num_slots) {
    path = slot_of(slots, num_slots, dev, ino)->path;
  }
  release();
  /* An inode freed and reused by another file is no input. */
  struct stat sb;
  if (path && !(stat(path, &sb) == 0 && sb.st_dev == dev && sb.st_ino == ino)) {
    path = NULL;
  }
  return path;
}
