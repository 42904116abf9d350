/* The kinds of file subsurf writes, told by their first bytes (magic
 * numbers), so that an output replaces only a file of its own kind: an EXR
 * replaces an EXR, never a scene, a mesh or someone's notes. Text formats
 * are told by their first characters after any white space. An empty file
 * is of every kind: it holds nothing to lose. */
#ifndef SUBSURF_CORE_FILE_KIND_H
#define SUBSURF_CORE_FILE_KIND_H

#include <stddef.h>

typedef enum {
  SS_FILE_EXR,
  SS_FILE_PNG,
  SS_FILE_PFM,
  SS_FILE_JSON,
  SS_FILE_CSV, /* `subsurf compare`'s results.csv */
  SS_FILE_SVG,
  SS_FILE_PDF,
  SS_FILE_PS,
  SS_FILE_HTML,
  SS_FILE_PLY,
  SS_FILE_CHECKPOINT,       /* checkpoint.h */
  SS_FILE_IRRADIANCE_CACHE, /* irradiance_cache.h */
  SS_FILE_FEM_CACHE,        /* fem_cache.h */
  SS_FILE_TABLE,            /* table_file.h */
  SS_FILE_GRID,             /* grid_io.h, subsurf's raw grid */
  SS_FILE_VDB,
  SS_FILE_REFERENCE_KEY, /* `subsurf compare`'s reference.key */
  SS_FILE_KIND_COUNT
} ss_file_kind;

/* The bytes read to tell a file's kind. */
#define SS_FILE_KIND_HEAD 64

/* "an OpenEXR image", "a render checkpoint", ... */
const char *ss_file_kind_name(ss_file_kind kind);

/* 1 when a file whose first bytes are head[0..n) (the whole file when it is
 * shorter than SS_FILE_KIND_HEAD) is of `kind`. */
int ss_file_kind_matches(ss_file_kind kind, const unsigned char *head, size_t n);

/* The kind of a plot or image file told by its name's extension: .svg,
 * .pdf, .ps, .exr, .png or .pfm; `fallback` for any other. */
ss_file_kind ss_file_kind_of_name(const char *path, ss_file_kind fallback);

#endif
