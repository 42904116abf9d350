/* Scene files: JSON in the spirit of Tungsten's format (docs/scene-format.md
 * documents every key). Top-level objects `camera`, `integrator`, `render`
 * and named arrays `media`, `materials`, `shapes`, `lights` that refer to
 * each other by name. Unknown keys, wrong types, missing references and
 * out-of-range values are SS_ERR_PARSE errors whose message reads
 * "FILE:LINE: key.path[2].key: what was expected". */
#ifndef SUBSURF_SCENE_IO_H
#define SUBSURF_SCENE_IO_H

#include "subsurf/scene.h"
#include "subsurf/status.h"

/* Reads and commits the scene in `path`; mesh files are found relative to
 * the scene file's directory. */
ss_status ss_scene_read_json(const char *path, ss_scene **out, ss_error *err);

/* The same from a string: `file` names it in messages, `base_dir` is where
 * relative mesh paths start ("." when NULL). */
ss_status ss_scene_parse_json(const char *text, const char *file, const char *base_dir,
                              ss_scene **out, ss_error *err);

/* Warnings of a reader: one line "FILE:LINE: what was ignored or
 * approximated", for the caller to show. */
typedef void (*ss_scene_warning_fn)(void *user, const char *message);

/* Reads a pbrt-v3 scene file (docs/pbrt-import.md lists what each directive
 * and parameter becomes). Files (Include, meshes, images) are found
 * relative to the directory of `path`, as pbrt-v3 does. Every directive or
 * parameter that is ignored or approximated is reported through `warn` (may
 * be NULL); syntax errors are SS_ERR_PARSE "FILE:LINE: what was expected". */
ss_status ss_scene_read_pbrt(const char *path, ss_scene **out, ss_scene_warning_fn warn, void *user,
                             ss_error *err);
ss_status ss_scene_parse_pbrt(const char *text, const char *file, const char *base_dir,
                              ss_scene **out, ss_scene_warning_fn warn, void *user, ss_error *err);

/* Caps for a reader of untrusted text that is only read, never rendered
 * (the fuzzers): a sphere's "subdivisions" above max_subdivisions are
 * lowered to it, a film side above max_resolution is lowered to it, and a
 * mesh (trianglemesh or plymesh) of more than max_triangles triangles is
 * an SS_ERR_PARSE error. 0 leaves a quantity uncapped. */
typedef struct {
  int max_subdivisions;
  int max_resolution;
  size_t max_triangles;
} ss_pbrt_limits;

/* ss_scene_parse_pbrt within `limits` (NULL: none). */
ss_status ss_scene_parse_pbrt_limited(const char *text, const char *file, const char *base_dir,
                                      const ss_pbrt_limits *limits, ss_scene **out,
                                      ss_scene_warning_fn warn, void *user, ss_error *err);

/* 1 when `path` ends in ".pbrt". */
int ss_scene_is_pbrt(const char *path);
/* A pbrt-v3 scene for a .pbrt path, else a JSON scene. */
ss_status ss_scene_read(const char *path, ss_scene **out, ss_scene_warning_fn warn, void *user,
                        ss_error *err);

#endif
