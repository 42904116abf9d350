/* Large arrays backed by transparent huge pages. A fresh 4 KiB page costs a
 * page fault at its first write (about 10-15 us each in a virtual machine:
 * a third of the set-up of a 327 k-triangle mesh went to 6 400 faults,
 * bench/RESULTS.md); a 2 MiB huge page costs one. Arrays of at
 * least 1 MiB are therefore allocated 2 MiB-aligned, rounded up to whole
 * huge pages (at most twice their size) and advised MADV_HUGEPAGE (Linux's
 * transparent huge pages in "madvise" mode, the common default). The
 * memory comes from malloc's family, so free() and realloc() apply as to
 * any malloc'ed block. */
#ifndef SUBSURF_CORE_LARGE_ALLOC_H
#define SUBSURF_CORE_LARGE_ALLOC_H

#include <stddef.h>

/* malloc(bytes), huge-page backed when bytes >= 1 MiB; NULL when out of
 * memory. The contents are uninitialised. */
void *ss_large_alloc(size_t bytes);

#endif
