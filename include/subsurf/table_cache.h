/* Tables shared by every material of a scene: the tabulated
 * models' tables depend only on (kind, fit, eta, g), not on a material's
 * coefficients (the tables are in sigma_t = 1 over an albedo grid), so one
 * table serves every material with the same (model, eta, g, options).
 *
 * With a directory, each table is also kept on disk as a table file
 * (table_file.h) named after its key and written atomically
 * (core/atomic_file.h); a file is used only when it passes the table file's
 * checks (version, sizes, CRC-32, values) and its header's eta, g and fit
 * equal the key's exactly; otherwise (corrupt, truncated, stale) the table is
 * rebuilt and the file replaced, never trusted. A file that cannot be written
 * leaves the table in memory (counted in write_failures, with the reason). */
#ifndef SUBSURF_TABLE_CACHE_H
#define SUBSURF_TABLE_CACHE_H

#include "subsurf/status.h"
#include "subsurf/table_gwc.h"
#include "subsurf/table_radial.h"

#include <stddef.h>

typedef struct ss_table_cache ss_table_cache;

typedef struct {
  unsigned builds;                          /* tables computed */
  unsigned loads;                           /* tables read from the disk cache */
  unsigned rejected;                        /* disk files refused (corrupt, stale) and replaced */
  unsigned shared;                          /* requests served by a table already in memory */
  unsigned write_failures;                  /* tables that could not be written to disk */
  char last_failure[SS_ERROR_MESSAGE_SIZE]; /* the reason of the last write failure */
} ss_table_cache_stats;

/* dir: the disk cache's directory (created with its parents when missing),
 * or NULL / "" for a cache in memory only. */
ss_status ss_table_cache_create(const char *dir, ss_table_cache **out, ss_error *err);
void ss_table_cache_destroy(ss_table_cache *c);

/* The table of the key, owned by the cache (valid until it is destroyed). */
ss_status ss_table_cache_radial(ss_table_cache *c, double eta, double g,
                                const ss_table_radial **out, ss_error *err);
ss_status ss_table_cache_gwc(ss_table_cache *c, double eta, double g, int fit,
                             const ss_table_gwc **out, ss_error *err);

void ss_table_cache_get_stats(const ss_table_cache *c, ss_table_cache_stats *stats);
/* The disk file of a key ("" for a cache in memory only). */
void ss_table_cache_path(const ss_table_cache *c, int kind, int fit, double eta, double g,
                         char *buf, size_t size);

/* The user's cache directory for tables: $XDG_CACHE_HOME/subsurf, else
 * $HOME/.cache/subsurf; "" when neither variable is set. */
void ss_table_cache_user_dir(char *buf, size_t size);

#endif
