/* The files this process has read as inputs (scenes, included files,
 * meshes, textures, grids, tables and caches, each opened through
 * core/input_file.h), remembered by device and inode with the path each was
 * opened by, so that no output replaces one of them (core/output_plan.h):
 * a path spelled differently or a hard link is the same file. */
#ifndef SUBSURF_CORE_INPUT_REGISTRY_H
#define SUBSURF_CORE_INPUT_REGISTRY_H

#include <sys/types.h>

/* Remembers a file read by `path`. Thread-safe. Out of memory, the file
 * goes unremembered (an output may then replace it: nothing else fails). */
void ss_input_registry_add(dev_t dev, ino_t ino, const char *path);

/* The path by which an input with this device and inode was opened, or
 * NULL when none was (or that path names another file since). */
const char *ss_input_registry_find(dev_t dev, ino_t ino);

#endif
