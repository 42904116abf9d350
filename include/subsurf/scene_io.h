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

#endif
