#include "core/file_kind.h"

#include <string.h>
#include <strings.h>

typedef struct {
  const char *bytes;
  size_t len;
} magic;

#define M(s)                                                                                       \
  { s, sizeof s - 1 }
#define MAX_MAGIC 4

/* What each format's writer puts first; the formats of our own carry the
 * magic their headers document (checkpoint.h, cache_file.h, table_file.h,
 * grid_io.h). */
static const struct {
  const char *name;
  int text; /* white space before the magic is skipped */
  magic magic[MAX_MAGIC];
} kinds[SS_FILE_KIND_COUNT] = {
    [SS_FILE_EXR] = {"an OpenEXR image", 0, {M("\x76\x2f\x31\x01")}},
    [SS_FILE_PNG] = {"a PNG image", 0, {M("\x89PNG\r\n\x1a\n")}},
    [SS_FILE_PFM] = {"a PFM image", 0, {M("PF\n"), M("Pf\n"), M("PF\r"), M("Pf\r")}},
    [SS_FILE_JSON] = {"a JSON file", 1, {M("{"), M("[")}},
    [SS_FILE_CSV] = {"subsurf compare's results.csv", 0, {M("method,seconds,")}},
    [SS_FILE_SVG] = {"an SVG image", 1, {M("<?xml"), M("<svg")}},
    [SS_FILE_PDF] = {"a PDF file", 0, {M("%PDF-")}},
    [SS_FILE_PS] = {"a PostScript file", 0, {M("%!PS")}},
    [SS_FILE_HTML] = {"an HTML page", 1, {M("<!DOCTYPE html"), M("<!doctype html"), M("<html")}},
    [SS_FILE_PLY] = {"a PLY mesh", 0, {M("ply\n"), M("ply\r\n")}},
    [SS_FILE_CHECKPOINT] = {"a render checkpoint", 0, {M("SSRENDCK")}},
    [SS_FILE_IRRADIANCE_CACHE] = {"an irradiance cache", 0, {M("SSIRRCH")}},
    [SS_FILE_FEM_CACHE] = {"an fem cache", 0, {M("SSFEMCH")}},
    [SS_FILE_TABLE] = {"a BSSRDF table file", 0, {M("SSBSSRDF")}},
    [SS_FILE_GRID] = {"a subsurf grid file", 0, {M("SSGRID1\n")}},
    [SS_FILE_VDB] = {"an OpenVDB file", 0, {M("\x20\x42\x44\x56\0\0\0\0")}},
    [SS_FILE_REFERENCE_KEY] = {"subsurf compare's reference.key", 0, {M("scene ")}},
};

const char *ss_file_kind_name(ss_file_kind kind) {
  return kind < SS_FILE_KIND_COUNT ? kinds[kind].name : "an unknown kind of file";
}

int ss_file_kind_matches(ss_file_kind kind, const unsigned char *head, size_t n) {
  if (kind >= SS_FILE_KIND_COUNT) {
    return 0;
  }
  if (kinds[kind].text) {
    while (n > 0 && *head && strchr(" \t\r\n", *head)) {
      ++head;
      --n;
    }
  }
  if (n == 0) {
    return 1;
  }
  for (int i = 0; i < MAX_MAGIC && kinds[kind].magic[i].bytes; ++i) {
    const magic *m = &kinds[kind].magic[i];
    if (n >= m->len && memcmp(head, m->bytes, m->len) == 0) {
      return 1;
    }
  }
  return 0;
}

ss_file_kind ss_file_kind_of_name(const char *path, ss_file_kind fallback) {
  static const struct {
    const char *ext;
    ss_file_kind kind;
  } by_ext[] = {{".svg", SS_FILE_SVG}, {".pdf", SS_FILE_PDF}, {".ps", SS_FILE_PS},
                {".exr", SS_FILE_EXR}, {".png", SS_FILE_PNG}, {".pfm", SS_FILE_PFM}};
  const char *dot = strrchr(path, '.');
  for (size_t i = 0; dot && !strchr(dot, '/') && i < sizeof by_ext / sizeof by_ext[0]; ++i) {
    if (!strcasecmp(dot, by_ext[i].ext)) {
      return by_ext[i].kind;
    }
  }
  return fallback;
}
