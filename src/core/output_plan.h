/* A run's output files, checked together before any work, so that a render
 * does not run for an hour and then fail to write, or write over something
 * that is not its own. A command registers each file it will write (with
 * the option or key that named it, its kind, and about how many bytes it
 * will hold) and each input file it knows by name, then checks the plan
 * once. The check refuses, with one message naming the option and the file:
 *   - a name that is empty, ends in '/', or is a directory;
 *   - a missing or unwritable directory;
 *   - an existing regular file that is one of the run's inputs, compared by
 *     device and inode (a path spelled differently or a hard link is the
 *     same file): the inputs registered here and every file this process
 *     read through core/input_file.h (scenes, includes, meshes, textures,
 *     grids, tables);
 *   - an existing non-empty regular file of another kind (file_kind.h);
 *   - two outputs that are the same file;
 *   - for a cache or a checkpoint (SS_OUTPUT_CACHE, a file read back later),
 *     anything but a regular file (a device, a FIFO, a socket);
 *   - a file system without room for what will be written there.
 * Other non-regular files (/dev/null, a FIFO, /dev/stdout) are written
 * directly and a symbolic link is written through (core/atomic_file.h). */
#ifndef SUBSURF_CORE_OUTPUT_PLAN_H
#define SUBSURF_CORE_OUTPUT_PLAN_H

#include "core/file_kind.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

/* A file that is read back (a checkpoint, a cache): it must be a regular
 * file, and its own earlier version, which the run reads, may be replaced. */
#define SS_OUTPUT_CACHE 1u

typedef struct {
  char *label, *path; /* "--checkpoint", "integrator.cache", ...; the file */
  ss_file_kind kind;
  unsigned flags;
  uint64_t bytes; /* estimated size; 0: unknown (then at least one block) */
} ss_output_plan_file;

typedef struct {
  ss_output_plan_file *outputs, *inputs;
  size_t num_outputs, num_inputs, cap_outputs, cap_inputs;
  int out_of_memory; /* an add failed: the check says so */
} ss_output_plan;

void ss_output_plan_init(ss_output_plan *p);
/* An output; "-" (stdout) is accepted and never checked. */
void ss_output_plan_add(ss_output_plan *p, const char *label, const char *path, ss_file_kind kind,
                        unsigned flags, uint64_t bytes);
/* An input the command names that may not have been read yet. */
void ss_output_plan_add_input(ss_output_plan *p, const char *label, const char *path);
/* SS_OK, or the first refusal: SS_ERR_INVALID_ARGUMENT (the outputs as
 * given cannot be written: bad input) or SS_ERR_NO_MEMORY, the message
 * "LABEL: ..." naming the file. Creates and removes one temporary file
 * beside each regular output; writes nothing else. */
ss_status ss_output_plan_check(const ss_output_plan *p, ss_error *err);
void ss_output_plan_free(ss_output_plan *p);

#endif
