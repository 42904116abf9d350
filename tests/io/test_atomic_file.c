/* Output paths: a regular file is replaced atomically (also through a
 * symbolic link, which stays a link); a device, a FIFO, the process's own
 * stdout named by a path, or a dangling link is written directly, never
 * replaced by a regular file; a directory, and a regular file of another
 * kind than the one written, are refused before anything is written. */
#include "core/atomic_file.h"
#include "subsurf/image_io.h"
#include "subsurf/table_file.h"

#include "io/io_test_dir.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void) {
  snprintf(dir, sizeof dir, "/tmp/subsurf-atomic-XXXXXX");
  cr_assert_not_null(mkdtemp(dir));
}

static void remove_dir(void) {
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(atomic_file, .init = make_dir, .fini = remove_dir);

static size_t read_all(const char *path, unsigned char *buf, size_t cap) {
  FILE *f = fopen(path, "rb");
  cr_assert_not_null(f, "%s", path);
  size_t n = fread(buf, 1, cap, f);
  fclose(f);
  return n;
}

/* Writes `text`, a JSON file. */
static void write_text(const char *path, const char *text) {
  ss_atomic_file f;
  ss_error err;
  cr_assert_eq(ss_atomic_file_open(&f, path, SS_FILE_JSON, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_atomic_file_write(&f, text, strlen(text), &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_atomic_file_commit(&f, &err), SS_OK, "%s", err.message);
}

static ss_image *small_image(void) {
  ss_image *img = ss_image_create(7, 19, 3);
  for (int i = 0; i < 7 * 19 * 3; ++i) {
    img->data[i] = 0.01f * (float)i;
  }
  return img;
}

Test(atomic_file, a_link_to_a_regular_file_stays_a_link_to_the_new_content) {
  char sub[128], target[192], link[128];
  snprintf(sub, sizeof sub, "%s/real", dir);
  cr_assert_eq(mkdir(sub, 0755), 0);
  snprintf(target, sizeof target, "%s/out.txt", sub);
  snprintf(link, sizeof link, "%s/link.txt", dir);
  write_text(target, "[\"old\"]\n");
  cr_assert_eq(symlink(target, link), 0);
  write_text(link, "[\"new content\"]\n");
  struct stat sb;
  cr_assert_eq(lstat(link, &sb), 0);
  cr_assert(S_ISLNK(sb.st_mode), "the link is still a link");
  unsigned char buf[64] = {0};
  cr_assert_eq(read_all(target, buf, sizeof buf), 16u);
  cr_assert_str_eq((char *)buf, "[\"new content\"]\n");
  cr_assert_eq(io_test_count_entries(sub), 1, "no temporary file beside the target");
  cr_assert_eq(io_test_count_entries(dir), 2, "none beside the link");
}

Test(atomic_file, a_dangling_link_creates_its_target) {
  char target[128], link[128];
  snprintf(target, sizeof target, "%s/created.txt", dir);
  snprintf(link, sizeof link, "%s/dangling.txt", dir);
  cr_assert_eq(symlink(target, link), 0);
  write_text(link, "[\"through\"]\n");
  struct stat sb;
  cr_assert_eq(lstat(link, &sb), 0);
  cr_assert(S_ISLNK(sb.st_mode));
  unsigned char buf[16] = {0};
  cr_assert_eq(read_all(target, buf, sizeof buf), 12u);
}

Test(atomic_file, devices_are_written_not_replaced) {
  ss_image *img = small_image();
  ss_error err;
  cr_assert_eq(ss_image_write("/dev/null", img, 0.0, &err), SS_ERR_INVALID_ARGUMENT,
               "no extension: refused by format, as before");
  /* A link with an image extension to /dev/null. */
  char link[128];
  snprintf(link, sizeof link, "%s/null.exr", dir);
  cr_assert_eq(symlink("/dev/null", link), 0);
  cr_assert_eq(ss_image_write(link, img, 0.0, &err), SS_OK, "%s", err.message);
  struct stat sb;
  cr_assert_eq(stat("/dev/null", &sb), 0);
  cr_assert(S_ISCHR(sb.st_mode), "/dev/null is still a device");
  cr_assert_eq(lstat(link, &sb), 0);
  cr_assert(S_ISLNK(sb.st_mode));
  /* /dev/full: the write fails at commit and says why. */
  snprintf(link, sizeof link, "%s/full.png", dir);
  cr_assert_eq(symlink("/dev/full", link), 0);
  cr_assert_eq(ss_image_write(link, img, 0.0, &err), SS_ERR_IO);
  cr_assert(strstr(err.message, "No space left on device") != NULL, "%s", err.message);
  ss_image_destroy(img);
}

/* An EXR (whose writer patches its offset table) through a FIFO equals the
 * one written to a regular file. */
Test(atomic_file, an_exr_through_a_fifo_equals_the_regular_file) {
  ss_image *img = small_image();
  char regular[128], fifo[128], copy[128];
  snprintf(regular, sizeof regular, "%s/regular.exr", dir);
  snprintf(fifo, sizeof fifo, "%s/fifo.exr", dir);
  snprintf(copy, sizeof copy, "%s/copy.bin", dir);
  ss_error err;
  cr_assert_eq(ss_image_write(regular, img, 0.0, &err), SS_OK, "%s", err.message);
  cr_assert_eq(mkfifo(fifo, 0644), 0);
  pid_t child = fork();
  cr_assert_geq(child, 0);
  if (child == 0) {
    int in = open(fifo, O_RDONLY), out = open(copy, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    char buf[4096];
    ssize_t n;
    while ((n = read(in, buf, sizeof buf)) > 0) {
      if (write(out, buf, (size_t)n) != n) {
        _exit(1);
      }
    }
    _exit(close(out) != 0);
  }
  ss_status st = ss_image_write(fifo, img, 0.0, &err);
  int status;
  cr_assert_eq(waitpid(child, &status, 0), child);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  static unsigned char a[1 << 16], b[1 << 16];
  size_t na = read_all(regular, a, sizeof a), nb = read_all(copy, b, sizeof b);
  cr_assert_eq(na, nb);
  cr_assert_eq(memcmp(a, b, na), 0, "same bytes");
  struct stat sb;
  cr_assert_eq(stat(fifo, &sb), 0);
  cr_assert(S_ISFIFO(sb.st_mode), "the FIFO is still a FIFO");
  ss_image_destroy(img);
}

/* stdout redirected to a file, named again as the output (/dev/stdout):
 * written in place, so the redirection keeps its file. */
Test(atomic_file, stdout_named_as_a_path_is_written_in_place) {
  char path[128];
  snprintf(path, sizeof path, "%s/stdout.txt", dir);
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  cr_assert_geq(fd, 0);
  fflush(stdout);
  int saved = dup(1);
  cr_assert_eq(dup2(fd, 1), 1);
  close(fd);
  struct stat before, after;
  cr_assert_eq(fstat(1, &before), 0);
  write_text("/dev/stdout", "[\"to stdout\"]\n");
  cr_assert_eq(fstat(1, &after), 0);
  cr_assert_eq(dup2(saved, 1), 1);
  close(saved);
  cr_assert_eq(before.st_ino, after.st_ino);
  cr_assert_eq(after.st_nlink, 1u, "the redirected file was not unlinked");
  unsigned char buf[32] = {0};
  cr_assert_eq(read_all(path, buf, sizeof buf), 14u);
  cr_assert_str_eq((char *)buf, "[\"to stdout\"]\n");
}

Test(atomic_file, a_directory_is_refused_before_writing) {
  char target[128];
  snprintf(target, sizeof target, "%s/busy.exr", dir);
  cr_assert_eq(mkdir(target, 0755), 0);
  ss_atomic_file f;
  ss_error err;
  cr_assert_eq(ss_atomic_file_open(&f, target, SS_FILE_EXR, &err), SS_ERR_IO);
  cr_assert(strstr(err.message, target) != NULL && strstr(err.message, "Is a directory"), "%s",
            err.message);
  cr_assert_eq(ss_atomic_file_check(target, SS_FILE_EXR, &err), SS_ERR_IO);
  char missing[160];
  snprintf(missing, sizeof missing, "%s/none/x.exr", dir);
  cr_assert_eq(ss_atomic_file_check(missing, SS_FILE_EXR, &err), SS_ERR_IO);
  cr_assert(strstr(err.message, "No such file or directory"), "%s", err.message);
  cr_assert_eq(ss_atomic_file_check("/dev/null", SS_FILE_EXR, &err), SS_OK, "%s", err.message);
  snprintf(missing, sizeof missing, "%s/new.exr", dir);
  cr_assert_eq(ss_atomic_file_check(missing, SS_FILE_EXR, &err), SS_OK, "%s", err.message);
  cr_assert_eq(io_test_count_entries(dir), 1, "checking leaves nothing behind");
}

Test(atomic_file, positional_writes_fill_gaps_with_zeros_in_memory_too) {
  char link[128];
  snprintf(link, sizeof link, "%s/null.bin", dir);
  cr_assert_eq(symlink("/dev/null", link), 0);
  ss_atomic_file f;
  ss_error err;
  cr_assert_eq(ss_atomic_file_open(&f, link, SS_FILE_EXR, &err), SS_OK, "%s", err.message);
  cr_assert_lt(f.fd, 0, "a device is written directly");
  cr_assert_eq(ss_atomic_file_pwrite(&f, "xy", 2, 100000, &err), SS_OK);
  cr_assert_eq(ss_atomic_file_pwrite(&f, "ab", 2, 1, &err), SS_OK);
  cr_assert_eq(f.size, 100002u);
  cr_assert_eq(f.buf[0], 0);
  cr_assert_eq(f.buf[1], 'a');
  cr_assert_eq(f.buf[99999], 0);
  cr_assert_eq(f.buf[100001], 'y');
  cr_assert_eq(ss_atomic_file_commit(&f, &err), SS_OK, "%s", err.message);
}

/* Table files (src/bssrdf) are written the same way. */
Test(atomic_file, table_files_go_through_links_and_into_devices) {
  ss_table_radial *t = NULL;
  ss_error err;
  cr_assert_eq(ss_table_radial_build(1.33, 0.0, &t, &err), SS_OK, "%s", err.message);
  char target[128], link[128], null_link[128];
  snprintf(target, sizeof target, "%s/real.table", dir);
  snprintf(link, sizeof link, "%s/link.table", dir);
  snprintf(null_link, sizeof null_link, "%s/null.table", dir);
  cr_assert_eq(symlink(target, link), 0);
  cr_assert_eq(symlink("/dev/null", null_link), 0);
  cr_assert_eq(ss_table_radial_save(t, link, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_table_radial_save(t, null_link, &err), SS_OK, "%s", err.message);
  struct stat sb;
  cr_assert(lstat(link, &sb) == 0 && S_ISLNK(sb.st_mode), "the link stays a link");
  cr_assert(lstat(null_link, &sb) == 0 && S_ISLNK(sb.st_mode));
  cr_assert(stat("/dev/null", &sb) == 0 && S_ISCHR(sb.st_mode), "/dev/null stays a device");
  ss_table_radial *back = NULL;
  cr_assert_eq(ss_table_radial_load(target, &back, &err), SS_OK, "%s", err.message);
  ss_table_radial_destroy(back);
  ss_table_radial_destroy(t);
  cr_assert_eq(io_test_count_entries(dir), 3, "no temporary file is left");
}

/* Kind checks (core/file_kind.h): each writer replaces only its own kind. */
Test(atomic_file, a_file_of_another_kind_is_not_replaced) {
  char path[128];
  snprintf(path, sizeof path, "%s/notes.exr", dir);
  FILE *f = fopen(path, "w");
  cr_assert_not_null(f);
  fputs("my notes\n", f);
  fclose(f);
  ss_image *img = small_image();
  ss_error err;
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, path) && strstr(err.message, "not an OpenEXR image"), "%s",
            err.message);
  unsigned char buf[32] = {0};
  cr_assert_eq(read_all(path, buf, sizeof buf), 9u, "the notes are kept");
  cr_assert_eq(io_test_count_entries(dir), 1, "no temporary file");
  /* An image of its own kind, and an empty file, are replaced. */
  cr_assert_eq(truncate(path, 0), 0);
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  /* An EXR is not a PNG, nor a table file. */
  char png[128];
  snprintf(png, sizeof png, "%s/image.png", dir);
  cr_assert_eq(rename(path, png), 0);
  cr_assert_eq(ss_image_write(png, img, 0.0, &err), SS_ERR_INVALID_ARGUMENT);
  ss_table_radial *t = NULL;
  cr_assert_eq(ss_table_radial_build(1.33, 0.0, &t, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_table_radial_save(t, png, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "not a BSSRDF table file"), "%s", err.message);
  ss_table_radial_destroy(t);
  ss_image_destroy(img);
}
