/* Names of a scene's shapes and lights (private to src/render): a hash set
 * of indices into an array of records that hold a name at one offset, so
 * that adding n named records costs O(n) lookups, not O(n^2) comparisons. */
#ifndef SUBSURF_RENDER_NAME_INDEX_H
#define SUBSURF_RENDER_NAME_INDEX_H

#include <stddef.h>

/* The records: the name of record i is (const char *)first + i * stride. */
typedef struct {
  const void *first;
  size_t stride;
} ss_named;

typedef struct ss_name_index ss_name_index;

/* The index of the record named `name`, or -1. */
int ss_name_index_find(const ss_name_index *ix, ss_named records, const char *name);
/* Adds record `index` (its name not yet present), creating *ix when NULL;
 * returns -1 when out of memory. */
int ss_name_index_add(ss_name_index **ix, ss_named records, int index);
void ss_name_index_destroy(ss_name_index *ix);

#endif
