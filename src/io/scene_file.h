/* Reading a scene description's text (JSON or pbrt) into memory (private to
 * src/io). */
#ifndef SUBSURF_IO_SCENE_FILE_H
#define SUBSURF_IO_SCENE_FILE_H

#include "subsurf/scene.h"
#include "subsurf/status.h"

/* Reads the whole file `path` (a regular file within SS_INPUT_SCENE's cap, without NUL
 * bytes; `what` names the expected kind in the NUL message, e.g. "a JSON text
 * file") into a NUL-terminated *text the caller frees, and the directory that
 * contains it into dir ("." for a bare name). */
ss_status ss_scene_file_read(const char *path, const char *what, char **text,
                             char dir[SS_PATH_SIZE], ss_error *err);

#endif
