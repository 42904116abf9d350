/* realpath is an X/Open extension of POSIX. */
#define _XOPEN_SOURCE 700

#include "core/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define SS_TMP_SUFFIX ".tmp-XXXXXX"

static ss_status fail(const ss_atomic_file *f, ss_error *err, int e) {
  return ss_error_set(err, SS_ERR_IO, "cannot write %s: %s", f->path, strerror(e));
}

/* The process's own stdout or stderr, named by a path (/dev/stdout, or a
 * redirection target named again): replacing it would orphan the stream. */
static int is_std_stream(const struct stat *sb) {
  for (int fd = 1; fd <= 2; ++fd) {
    struct stat s;
    if (fstat(fd, &s) == 0 && s.st_dev == sb->st_dev && s.st_ino == sb->st_ino) {
      return 1;
    }
  }
  return 0;
}

static ss_status open_temporary(ss_atomic_file *f, ss_error *err) {
  size_t len = strlen(f->target);
  f->tmp_path = malloc(len + sizeof SS_TMP_SUFFIX);
  if (!f->tmp_path) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "cannot write %s: out of memory", f->path);
  }
  memcpy(f->tmp_path, f->target, len);
  memcpy(f->tmp_path + len, SS_TMP_SUFFIX, sizeof SS_TMP_SUFFIX);
  f->fd = mkstemp(f->tmp_path);
  if (f->fd < 0) {
    return fail(f, err, errno);
  }
  /* mkstemp creates the file private (0600); an image is an ordinary output
   * file, readable by others like one made by fopen under the usual umask. */
  fchmod(f->fd, 0644);
  return SS_OK;
}

/* A regular file is replaced only by one of its own kind (file_kind.h). */
static ss_status check_kind(const ss_atomic_file *f, const struct stat *sb, ss_file_kind kind,
                            ss_error *err) {
  if (sb->st_size == 0) {
    return SS_OK;
  }
  unsigned char head[SS_FILE_KIND_HEAD];
  int fd = open(f->path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ssize_t n = fd >= 0 ? read(fd, head, sizeof head) : -1;
  int e = errno;
  if (fd >= 0) {
    close(fd);
  }
  if (n < 0) {
    return ss_error_set(err, SS_ERR_IO,
                        "cannot write '%s': it exists and cannot be read to tell what it holds: %s",
                        f->path, strerror(e));
  }
  if (!ss_file_kind_matches(kind, head, (size_t)n)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "cannot write '%s': it exists and is not %s, so it is not replaced "
                        "(remove it or choose another name)",
                        f->path, ss_file_kind_name(kind));
  }
  return SS_OK;
}

ss_status ss_atomic_file_open(ss_atomic_file *f, const char *path, ss_file_kind kind,
                              ss_error *err) {
  memset(f, 0, sizeof *f);
  f->path = path;
  f->fd = -1;
  struct stat sb, lsb;
  int exists = stat(path, &sb) == 0;
  int is_link = lstat(path, &lsb) == 0 && S_ISLNK(lsb.st_mode);
  ss_status st = SS_OK;
  if (exists && S_ISDIR(sb.st_mode)) {
    st = fail(f, err, EISDIR);
  } else if (exists && S_ISREG(sb.st_mode) && !is_std_stream(&sb)) {
    st = check_kind(f, &sb, kind, err);
    if (st == SS_OK) {
      /* Through a link, the temporary file goes beside the link's target. */
      f->target = is_link ? realpath(path, NULL) : strdup(path);
      st = f->target ? open_temporary(f, err) : fail(f, err, errno ? errno : ENOMEM);
    }
  } else if (exists || is_link) {
    f->target = strdup(path);
    f->create = !exists;
    if (!f->target) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "cannot write %s: out of memory", path);
    } else if (exists && access(path, W_OK) != 0) {
      st = fail(f, err, errno);
    }
  } else {
    f->target = strdup(path);
    st = f->target ? open_temporary(f, err) : fail(f, err, ENOMEM);
  }
  if (st != SS_OK) {
    ss_atomic_file_abort(f);
  }
  return st;
}

ss_status ss_atomic_file_check(const char *path, ss_file_kind kind, ss_error *err) {
  ss_atomic_file f;
  ss_status st = ss_atomic_file_open(&f, path, kind, err);
  if (st == SS_OK) {
    ss_atomic_file_abort(&f);
  }
  return st;
}

static int reserve(ss_atomic_file *f, size_t size) {
  if (size <= f->cap) {
    return 0;
  }
  size_t cap = f->cap ? f->cap : 65536;
  while (cap < size) {
    cap *= 2;
  }
  unsigned char *grown = realloc(f->buf, cap);
  if (!grown) {
    return -1;
  }
  f->buf = grown;
  f->cap = cap;
  return 0;
}

ss_status ss_atomic_file_pwrite(ss_atomic_file *f, const void *data, size_t size, uint64_t offset,
                                ss_error *err) {
  if (f->fd < 0) {
    if (offset > SIZE_MAX - size || reserve(f, (size_t)offset + size) != 0) {
      return ss_error_set(err, SS_ERR_NO_MEMORY, "cannot write %s: out of memory", f->path);
    }
    if (offset > f->size) {
      memset(f->buf + f->size, 0, (size_t)offset - f->size);
    }
    memcpy(f->buf + offset, data, size);
    if ((size_t)offset + size > f->size) {
      f->size = (size_t)offset + size;
    }
    return SS_OK;
  }
  const char *p = data;
  while (size > 0) {
    ssize_t n = pwrite(f->fd, p, size, (off_t)offset);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      return fail(f, err, n < 0 ? errno : EIO);
    }
    p += n;
    offset += (uint64_t)n;
    size -= (size_t)n;
  }
  return SS_OK;
}

ss_status ss_atomic_file_write(ss_atomic_file *f, const void *data, size_t size, ss_error *err) {
  if (f->fd < 0) {
    return ss_atomic_file_pwrite(f, data, size, f->size, err);
  }
  const char *p = data;
  while (size > 0) {
    ssize_t n = write(f->fd, p, size);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      return fail(f, err, n < 0 ? errno : EIO);
    }
    p += n;
    size -= (size_t)n;
  }
  return SS_OK;
}

static void release(ss_atomic_file *f) {
  free(f->tmp_path);
  free(f->target);
  free(f->buf);
  f->tmp_path = f->target = NULL;
  f->buf = NULL;
  f->size = f->cap = 0;
  f->fd = -1;
}

/* A target that is not replaced: written in one go, in order. */
static ss_status commit_direct(ss_atomic_file *f, ss_error *err) {
  int flags = O_WRONLY | O_CLOEXEC | (f->create ? O_CREAT : 0);
  struct stat sb;
  if (stat(f->target, &sb) == 0 && S_ISREG(sb.st_mode)) {
    flags |= O_TRUNC;
  }
  int fd = open(f->target, flags, 0666);
  if (fd < 0) {
    return fail(f, err, errno);
  }
  const unsigned char *p = f->buf;
  size_t left = f->size;
  while (left > 0) {
    ssize_t n = write(fd, p, left);
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      int e = n < 0 ? errno : EIO;
      close(fd);
      return fail(f, err, e);
    }
    p += n;
    left -= (size_t)n;
  }
  return close(fd) == 0 ? SS_OK : fail(f, err, errno);
}

ss_status ss_atomic_file_commit(ss_atomic_file *f, ss_error *err) {
  if (f->fd < 0) {
    ss_status st = commit_direct(f, err);
    release(f);
    return st;
  }
  /* fsync before rename: after a crash the target is either the old file or
   * the complete new one, never a renamed but still empty file. */
  if (fsync(f->fd) != 0 && errno != EINVAL) {
    int e = errno;
    ss_atomic_file_abort(f);
    return fail(f, err, e);
  }
  if (close(f->fd) != 0) {
    int e = errno;
    f->fd = -1;
    ss_atomic_file_abort(f);
    return fail(f, err, e);
  }
  f->fd = -1;
  if (rename(f->tmp_path, f->target) != 0) {
    int e = errno;
    ss_atomic_file_abort(f);
    return fail(f, err, e);
  }
  release(f);
  return SS_OK;
}

void ss_atomic_file_abort(ss_atomic_file *f) {
  if (f->fd >= 0) {
    close(f->fd);
  }
  if (f->tmp_path) {
    unlink(f->tmp_path);
  }
  release(f);
}
