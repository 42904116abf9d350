#include "core/input_file.h"

#include "core/input_registry.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind_of(mode_t mode) {
  return S_ISDIR(mode)    ? "a directory"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISFIFO(mode) ? "a FIFO (pipe)"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a regular file";
}

ss_status ss_input_file_open(const char *path, const char *label, FILE **out, uint64_t *size,
                             ss_error *err) {
  *out = NULL;
  /* O_NONBLOCK: opening a FIFO must not wait for a writer before the type
   * check refuses it. */
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return ss_error_set(err, SS_ERR_IO, "%s: cannot open: %s", label, strerror(errno));
  }
  struct stat sb;
  if (fstat(fd, &sb) != 0) {
    int e = errno;
    close(fd);
    return ss_error_set(err, SS_ERR_IO, "%s: cannot open: %s", label, strerror(e));
  }
  if (!S_ISREG(sb.st_mode)) {
    close(fd);
    return ss_error_set(err, SS_ERR_IO, "%s: is %s (expected a regular file)", label,
                        kind_of(sb.st_mode));
  }
  int flags = fcntl(fd, F_GETFL);
  FILE *f = flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0 ? NULL : fdopen(fd, "rb");
  if (!f) {
    int e = errno;
    close(fd);
    return ss_error_set(err, SS_ERR_IO, "%s: cannot open: %s", label, strerror(e));
  }
  if (size) {
    *size = (uint64_t)sb.st_size;
  }
  ss_input_registry_add(sb.st_dev, sb.st_ino, path);
  *out = f;
  return SS_OK;
}

static const struct {
  uint64_t bytes;
  const char *name;
  const char *hint;
} caps[] = {
    [SS_INPUT_SCENE] = {(uint64_t)64 << 20, "a scene file", " (geometry belongs in mesh files)"},
    [SS_INPUT_MESH] = {(uint64_t)1 << 30, "a mesh file", ""},
    [SS_INPUT_TEXTURE] = {(uint64_t)512 << 20, "a texture image", ""},
    [SS_INPUT_ALBEDO_TABLE] = {(uint64_t)1 << 20, "an albedo table", ""},
    [SS_INPUT_PROFILE_TABLE] = {(uint64_t)4 << 20, "a profile table", ""},
    [SS_INPUT_BSSRDF_TABLE] = {(uint64_t)4 << 30, "a table file", ""},
    [SS_INPUT_GRID] = {(uint64_t)8 << 30, "a density grid", ""},
    [SS_INPUT_FEM_CACHE] = {(uint64_t)4 << 30, "an fem cache", ""},
};

uint64_t ss_input_cap(ss_input_kind kind) { return caps[kind].bytes; }

static ss_status too_large(const char *label, ss_input_kind kind, ss_error *err) {
  return ss_error_set(err, SS_ERR_PARSE, "%s: more than %llu MiB, the limit for %s%s", label,
                      (unsigned long long)(caps[kind].bytes >> 20), caps[kind].name,
                      caps[kind].hint);
}

ss_status ss_input_file_read(const char *path, const char *label, ss_input_kind kind,
                             unsigned char **data, size_t *size, ss_error *err) {
  *data = NULL;
  *size = 0;
  FILE *f;
  uint64_t reported;
  ss_status st = ss_input_file_open(path, label, &f, &reported, err);
  if (st != SS_OK) {
    return st;
  }
  const uint64_t cap = caps[kind].bytes;
  if (reported > cap) {
    fclose(f);
    return too_large(label, kind, err);
  }
  /* The reported size is only the first guess of the buffer's size; the
   * buffer holds at most cap + 1 bytes (one past the cap tells a file that
   * is too large) and the NUL. */
  uint64_t want = reported + 1 > 4096 ? reported + 1 : 4096;
  unsigned char *buf = NULL;
  uint64_t n = 0;
  for (;;) {
    if (!buf || (n == want && want <= cap)) {
      want = !buf ? want : want > cap / 2 ? cap + 1 : 2 * want;
      unsigned char *grown = want + 1 <= SIZE_MAX ? realloc(buf, (size_t)want + 1) : NULL;
      if (!grown) {
        free(buf);
        fclose(f);
        return ss_error_set(err, SS_ERR_NO_MEMORY, "%s: out of memory for %llu bytes", label,
                            (unsigned long long)want);
      }
      buf = grown;
    }
    size_t got = n < want ? fread(buf + n, 1, (size_t)(want - n), f) : 0;
    n += got;
    if (got == 0) {
      break;
    }
  }
  int failed = ferror(f);
  fclose(f);
  if (failed) {
    free(buf);
    return ss_error_set(err, SS_ERR_IO, "%s: read error", label);
  }
  if (n > cap) {
    free(buf);
    return too_large(label, kind, err);
  }
  buf[n] = '\0';
  *data = buf;
  *size = (size_t)n;
  return SS_OK;
}
