/* realpath is an X/Open extension of POSIX. */
#define _XOPEN_SOURCE 700

#include "core/output_plan.h"

#include "core/atomic_file.h"
#include "core/input_registry.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

void ss_output_plan_init(ss_output_plan *p) { memset(p, 0, sizeof *p); }

static void add(ss_output_plan *p, ss_output_plan_file **files, size_t *n, size_t *cap,
                ss_output_plan_file file) {
  if (p->out_of_memory) {
    return;
  }
  if (*n == *cap) {
    size_t c = *cap ? 2 * *cap : 8;
    ss_output_plan_file *grown = realloc(*files, c * sizeof *grown);
    if (!grown) {
      p->out_of_memory = 1;
      return;
    }
    *files = grown;
    *cap = c;
  }
  file.label = strdup(file.label);
  file.path = strdup(file.path);
  if (!file.label || !file.path) {
    free(file.label);
    free(file.path);
    p->out_of_memory = 1;
    return;
  }
  (*files)[(*n)++] = file;
}

void ss_output_plan_add(ss_output_plan *p, const char *label, const char *path, ss_file_kind kind,
                        unsigned flags, uint64_t bytes) {
  if (strcmp(path, "-")) {
    ss_output_plan_file f = {(char *)label, (char *)path, kind, flags, bytes};
    add(p, &p->outputs, &p->num_outputs, &p->cap_outputs, f);
  }
}

void ss_output_plan_add_input(ss_output_plan *p, const char *label, const char *path) {
  ss_output_plan_file f = {(char *)label, (char *)path, SS_FILE_KIND_COUNT, 0, 0};
  add(p, &p->inputs, &p->num_inputs, &p->cap_inputs, f);
}

void ss_output_plan_free(ss_output_plan *p) {
  for (size_t i = 0; i < p->num_outputs; ++i) {
    free(p->outputs[i].label);
    free(p->outputs[i].path);
  }
  for (size_t i = 0; i < p->num_inputs; ++i) {
    free(p->inputs[i].label);
    free(p->inputs[i].path);
  }
  free(p->outputs);
  free(p->inputs);
  memset(p, 0, sizeof *p);
}

/* The directory `path` is (or would be) created in, into dir[size]. */
static void dir_of(const char *path, char *dir, size_t size) {
  const char *slash = strrchr(path, '/');
  if (!slash) {
    snprintf(dir, size, ".");
  } else if (slash == path) {
    snprintf(dir, size, "/");
  } else {
    snprintf(dir, size, "%.*s", (int)(slash - path), path);
  }
}

/* Which file an output is: the existing file (through links), else its
 * name in its directory; so two spellings of one name are one output. */
typedef struct {
  dev_t dev;
  ino_t ino;
  const char *name; /* NULL when the file exists */
} identity;

static int identify(const char *path, identity *id) {
  struct stat sb;
  if (stat(path, &sb) == 0) {
    *id = (identity){sb.st_dev, sb.st_ino, NULL};
    return 1;
  }
  char dir[4096];
  dir_of(path, dir, sizeof dir);
  const char *slash = strrchr(path, '/');
  if (stat(dir, &sb) != 0) {
    return 0;
  }
  *id = (identity){sb.st_dev, sb.st_ino, slash ? slash + 1 : path};
  return 1;
}

static int same(const identity *a, const identity *b) {
  return a->dev == b->dev && a->ino == b->ino && !a->name == !b->name &&
         (!a->name || !strcmp(a->name, b->name));
}

static const char *non_regular(mode_t mode) {
  return S_ISFIFO(mode)   ? "a FIFO"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a regular file";
}

/* The checks on the file as it exists now: its name, its directory, what
 * it is and whether it is an input. */
static ss_status check_existing(const ss_output_plan *p, const ss_output_plan_file *o,
                                ss_error *err) {
  size_t len = strlen(o->path);
  if (len == 0 || o->path[len - 1] == '/') {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: expected a file name, got '%s'",
                        o->label, o->path);
  }
  struct stat sb;
  if (stat(o->path, &sb) != 0) {
    char dir[4096];
    dir_of(o->path, dir, sizeof dir);
    struct stat db;
    int e = stat(dir, &db) != 0             ? errno
            : !S_ISDIR(db.st_mode)          ? ENOTDIR
            : access(dir, W_OK | X_OK) != 0 ? errno
                                            : 0;
    if (e) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: cannot write '%s': directory '%s' %s",
                          o->label, o->path, dir,
                          e == ENOENT    ? "does not exist"
                          : e == ENOTDIR ? "is not a directory"
                                         : "is not writable");
    }
    return SS_OK;
  }
  if (S_ISDIR(sb.st_mode)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%s: '%s' is a directory, expected a file name", o->label, o->path);
  }
  /* A socket cannot be opened; a block device holds a file system. */
  if (S_ISSOCK(sb.st_mode) || S_ISBLK(sb.st_mode) ||
      (!S_ISREG(sb.st_mode) && (o->flags & SS_OUTPUT_CACHE))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "%s: cannot write '%s': it is %s%s", o->label,
                        o->path, non_regular(sb.st_mode),
                        S_ISSOCK(sb.st_mode) || S_ISBLK(sb.st_mode)
                            ? ""
                            : ", and a file read back later must be a regular file");
  }
  if (!S_ISREG(sb.st_mode)) {
    return SS_OK;
  }
  for (size_t i = 0; i < p->num_inputs; ++i) {
    struct stat in;
    if (stat(p->inputs[i].path, &in) == 0 && in.st_dev == sb.st_dev && in.st_ino == sb.st_ino) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: cannot write '%s': it is the %s ('%s'), an input of this run",
                          o->label, o->path, p->inputs[i].label, p->inputs[i].path);
    }
  }
  /* A cache's own earlier version is read as an input, then replaced; a
   * file of another kind was refused above. */
  const char *input = ss_input_registry_find(sb.st_dev, sb.st_ino);
  if (input && !(o->flags & SS_OUTPUT_CACHE)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%s: cannot write '%s': it is '%s', an input of this run", o->label,
                        o->path, input);
  }
  return SS_OK;
}

/* Room on each file system for everything written to it. */
typedef struct {
  unsigned long fsid;
  uint64_t need;
} fs_need;

static ss_status check_space(const ss_output_plan_file *o, fs_need *fs, size_t *num_fs,
                             ss_error *err) {
  struct stat sb;
  if (stat(o->path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
    return SS_OK;
  }
  char *real = realpath(o->path, NULL);
  char dir[4096];
  dir_of(real ? real : o->path, dir, sizeof dir);
  free(real);
  struct statvfs vfs;
  if (statvfs(dir, &vfs) != 0) {
    return SS_OK; /* the file system does not say; the write will */
  }
  uint64_t block = vfs.f_frsize ? vfs.f_frsize : vfs.f_bsize;
  uint64_t bytes = o->bytes > block ? o->bytes : block;
  size_t k = 0;
  while (k < *num_fs && fs[k].fsid != vfs.f_fsid) {
    ++k;
  }
  if (k == *num_fs) {
    fs[(*num_fs)++] = (fs_need){vfs.f_fsid, 0};
  }
  fs[k].need = fs[k].need > UINT64_MAX - bytes ? UINT64_MAX : fs[k].need + bytes;
  /* The superuser may use the blocks reserved for it. */
  uint64_t blocks = geteuid() == 0 ? vfs.f_bfree : vfs.f_bavail;
  uint64_t free_bytes = blocks > UINT64_MAX / block ? UINT64_MAX : blocks * block;
  if (fs[k].need > free_bytes) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "%s: cannot write '%s': the file system of '%s' has %.3g MB free, and "
                        "this run's outputs there need about %.3g MB",
                        o->label, o->path, dir, 1e-6 * (double)free_bytes,
                        1e-6 * (double)fs[k].need);
  }
  return SS_OK;
}

ss_status ss_output_plan_check(const ss_output_plan *p, ss_error *err) {
  if (p->out_of_memory) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory while checking the outputs");
  }
  identity *ids = calloc(p->num_outputs + 1, sizeof *ids);
  int *known = calloc(p->num_outputs + 1, sizeof *known);
  fs_need *fs = calloc(p->num_outputs + 1, sizeof *fs);
  size_t num_fs = 0;
  ss_status st = ids && known && fs ? SS_OK
                                    : ss_error_set(err, SS_ERR_NO_MEMORY,
                                                   "out of memory while checking the outputs");
  for (size_t i = 0; st == SS_OK && i < p->num_outputs; ++i) {
    const ss_output_plan_file *o = &p->outputs[i];
    st = check_existing(p, o, err);
    known[i] = st == SS_OK && identify(o->path, &ids[i]);
    for (size_t j = 0; st == SS_OK && known[i] && j < i; ++j) {
      if (known[j] && same(&ids[i], &ids[j])) {
        st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "%s: cannot write '%s': %s writes it too (as '%s')", o->label, o->path,
                          p->outputs[j].label, p->outputs[j].path);
      }
    }
    if (st == SS_OK && (st = ss_atomic_file_check(o->path, o->kind, err)) != SS_OK) {
      ss_error_prefix(err, "%s: ", o->label);
      if (st == SS_ERR_IO) {
        st = SS_ERR_INVALID_ARGUMENT;
      }
    }
    if (st == SS_OK) {
      st = check_space(o, fs, &num_fs, err);
    }
  }
  free(ids);
  free(known);
  free(fs);
  return st;
}
