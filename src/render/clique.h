/* A clique of a given size in a sparse graph (private to src/render): k
 * shapes whose regions pairwise overlap, the most a point may lie in
 * (media_nesting.h). */
#ifndef SUBSURF_RENDER_CLIQUE_H
#define SUBSURF_RENDER_CLIQUE_H

#include "render/box_overlaps.h"

/* Looks for k vertices of the graph on n vertices with the m undirected
 * edges (i < j, sorted, unique) that are pairwise joined; writes them to
 * clique[0 .. k-1]. Returns 1 when found, 0 when there is none, -1 when out
 * of memory. 2 <= k <= 64. */
int ss_clique_find(size_t n, const ss_box_pair *edges, size_t m, int k, size_t *clique);

#endif
