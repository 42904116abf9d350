#include "core/input_file.h"

#include "core/input_registry.h"

#include <errno.h>
#include <fcntl.h>
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
