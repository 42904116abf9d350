/* Cell indices of tables from floating-point coordinates.
 *
 * Converting a double to an integer is undefined when the value does not
 * fit (NaN, infinities, 1e300, or a finite ratio r / h of a large radius over
 * a small cell): on x86 it gives INT_MIN, which passes an `index >= n` test
 * and reads far outside the table. These compare in floating point first, so
 * the conversion only ever sees a value in [0, n). Every table lookup that
 * turns a coordinate into an index goes through them. */
#ifndef SUBSURF_TABLE_INDEX_H
#define SUBSURF_TABLE_INDEX_H

#include <stddef.h>

/* floor(u) when 0 <= u < n, else -1 (negative, too large, NaN). */
static inline int ss_table_cell(double u, int n) { return u >= 0.0 && u < (double)n ? (int)u : -1; }

/* floor(u) clamped to [0, n - 1]; NaN gives 0. */
static inline int ss_table_cell_clamped(double u, int n) {
  if (!(u >= 0.0)) {
    return 0;
  }
  return u < (double)n ? (int)u : n - 1;
}

/* ss_table_cell_clamped for a size_t count. */
static inline size_t ss_table_cell_clamped_size(double u, size_t n) {
  if (!(u >= 0.0)) {
    return 0;
  }
  return u < (double)n ? (size_t)u : n - 1;
}

#endif
