/* Which of many axis-aligned boxes overlap (private to src/render): the
 * broad phase of the scene's checks on its shapes (media_nesting.h), so that
 * n shapes cost O(n log n + pairs) instead of n^2 / 2 tests. */
#ifndef SUBSURF_RENDER_BOX_OVERLAPS_H
#define SUBSURF_RENDER_BOX_OVERLAPS_H

#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stddef.h>

typedef struct {
  size_t i, j; /* i < j */
} ss_box_pair;

/* The pairs of boxes (lo[k], hi[k]), k < n, that share a point (closed
 * boxes: touching counts), each once, sorted by (i, j); *pairs is malloc'd
 * (NULL when there are none). */
ss_status ss_box_overlaps(const ss_vec3 *lo, const ss_vec3 *hi, size_t n, ss_box_pair **pairs,
                          size_t *num_pairs, ss_error *err);

#endif
