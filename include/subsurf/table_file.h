/* Binary files of the tabulated BSSRDFs: a versioned little-endian header
 * (magic, version, kind, fit, grid sizes, eta, g, value count), float32
 * payload and a CRC-32 (zlib) of everything before it. Readers reject
 * foreign, truncated, corrupt and unexpected files with a message naming
 * the file and the problem; cdf tables are recomputed on load.
 *
 * Layout (byte offsets): 0 magic "SSBSSRDF", 8 u32 version (1), 12 u32 kind
 * (1 radial, 2 gwc), 16 u32 fit, 20 u32 n_rho, n_theta, n_r, n_rs, n_shape,
 * 40 f64 eta, 48 f64 g, 56 u64 value count, 64 payload (radial: profile;
 * gwc: energy then shape), then u32 CRC-32 of bytes [0, 64 + 4 count). */
#ifndef SUBSURF_TABLE_FILE_H
#define SUBSURF_TABLE_FILE_H

#include "subsurf/status.h"
#include "subsurf/table_gwc.h"
#include "subsurf/table_radial.h"

#include <stdint.h>

#define SS_TABLE_FILE_VERSION 1
#define SS_TABLE_FILE_HEADER 64

typedef enum {
  SS_TABLE_KIND_RADIAL = 1,
  SS_TABLE_KIND_GWC = 2,
} ss_table_kind;

typedef struct {
  uint32_t version, kind, fit;
  uint32_t n_rho, n_theta, n_r, n_rs, n_shape;
  double eta, g;
  uint64_t count;
} ss_table_file_info;

/* Writes as core/atomic_file.h does: no partial file on failure; a link or a
 * device given as the path is written through, never replaced. */
ss_status ss_table_radial_save(const ss_table_radial *t, const char *path, ss_error *err);
ss_status ss_table_gwc_save(const ss_table_gwc *t, const char *path, ss_error *err);

/* Reads and validates a whole file (header, sizes, checksum, values). */
ss_status ss_table_radial_load(const char *path, ss_table_radial **out, ss_error *err);
ss_status ss_table_gwc_load(const char *path, ss_table_gwc **out, ss_error *err);
/* Reads and validates only what the header says (kind unknown to caller). */
ss_status ss_table_file_info_read(const char *path, ss_table_file_info *info, ss_error *err);

/* Reports a material whose eta or g differs from the table's (by > 1e-9). */
ss_status ss_table_file_check_material(const char *path, double table_eta, double table_g,
                                       double eta, double g, ss_error *err);

#endif
