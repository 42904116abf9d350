#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE */
#include "core/large_alloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

#define HUGE_PAGE ((size_t)2 << 20)

void *ss_large_alloc(size_t bytes) {
  if (bytes < HUGE_PAGE / 2 || bytes > SIZE_MAX - HUGE_PAGE) {
    return malloc(bytes > 0 ? bytes : 1);
  }
  size_t rounded = (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
  void *p;
  if (posix_memalign(&p, HUGE_PAGE, rounded) != 0) {
    return NULL;
  }
#ifdef MADV_HUGEPAGE
  /* Only advice: without transparent huge pages the block is an ordinary one. */
  (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}
