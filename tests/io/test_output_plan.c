/* The output plan (core/output_plan.h): every refusal is made before any
 * work, names the option and the file, and leaves nothing behind. */
#include "core/input_file.h"
#include "core/output_plan.h"
#include "subsurf/image_io.h"
#include "subsurf/table_file.h"

#include "io/io_test_dir.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void) { io_test_make_dir(dir, sizeof dir, "subsurf-plan"); }
static void remove_dir(void) { io_test_remove_dir(dir); }

TestSuite(output_plan, .init = make_dir, .fini = remove_dir);

static int count_entries(void) {
  int n = 0;
  DIR *d = opendir(dir);
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  }
  closedir(d);
  return n;
}

/* The plan of one output; its status, with the message in err. */
static ss_status check_one(const char *label, const char *path, ss_file_kind kind, unsigned flags,
                           uint64_t bytes, ss_error *err) {
  ss_output_plan p;
  ss_output_plan_init(&p);
  ss_output_plan_add(&p, label, path, kind, flags, bytes);
  ss_status st = ss_output_plan_check(&p, err);
  ss_output_plan_free(&p);
  return st;
}

static void write_image(const char *path) {
  ss_image *img = ss_image_create(4, 3, 3);
  memset(img->data, 0, 4 * 3 * 3 * sizeof *img->data);
  ss_error err;
  cr_assert_eq(ss_image_write(path, img, 0.0, &err), SS_OK, "%s", err.message);
  ss_image_destroy(img);
}

static void read_as_input(const char *path) {
  FILE *f = NULL;
  ss_error err;
  cr_assert_eq(ss_input_file_open(path, path, &f, NULL, &err), SS_OK, "%s", err.message);
  fclose(f);
}

/* A texture is an EXR like the output: only the record of the run's inputs
 * tells them apart, by device and inode, whatever the spelling or link. */
Test(output_plan, an_input_of_the_same_kind_is_not_replaced) {
  char tex[128], alias[160], hard[128];
  snprintf(tex, sizeof tex, "%s/texture.exr", dir);
  snprintf(alias, sizeof alias, "%s/./texture.exr", dir);
  snprintf(hard, sizeof hard, "%s/hard.exr", dir);
  write_image(tex);
  cr_assert_eq(link(tex, hard), 0);
  ss_error err;
  cr_assert_eq(check_one("--output", alias, SS_FILE_EXR, 0, 0, &err), SS_OK, "not read yet: %s",
               err.message);
  read_as_input(tex);
  cr_assert_eq(check_one("--output", alias, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "--output: cannot write") && strstr(err.message, "an input"), "%s",
            err.message);
  cr_assert_eq(check_one("--output", hard, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT,
               "a hard link is the same file");
  cr_assert_eq(count_entries(), 2, "nothing left behind");
}

/* A cache is read, then rewritten: its own earlier version may be
 * replaced, a file of another kind may not. */
Test(output_plan, a_cache_replaces_its_own_earlier_version_only) {
  ss_table_radial *t = NULL;
  ss_error err;
  char table[128], image[128];
  snprintf(table, sizeof table, "%s/cache.table", dir);
  snprintf(image, sizeof image, "%s/image.exr", dir);
  cr_assert_eq(ss_table_radial_build(1.33, 0.0, &t, &err), SS_OK, "%s", err.message);
  cr_assert_eq(ss_table_radial_save(t, table, &err), SS_OK, "%s", err.message);
  ss_table_radial_destroy(t);
  read_as_input(table);
  cr_assert_eq(check_one("cache", table, SS_FILE_TABLE, SS_OUTPUT_CACHE, 0, &err), SS_OK, "%s",
               err.message);
  write_image(image);
  cr_assert_eq(check_one("cache", image, SS_FILE_TABLE, SS_OUTPUT_CACHE, 0, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "not a BSSRDF table file"), "%s", err.message);
}

Test(output_plan, a_named_input_and_a_second_output_are_refused) {
  char ref[128], other[160], fresh[128], fresh2[160];
  snprintf(ref, sizeof ref, "%s/volpath.exr", dir);
  snprintf(other, sizeof other, "%s/../%s/volpath.exr", dir, strrchr(dir, '/') + 1);
  snprintf(fresh, sizeof fresh, "%s/new.exr", dir);
  snprintf(fresh2, sizeof fresh2, "%s//new.exr", dir);
  write_image(ref);
  ss_output_plan p;
  ss_output_plan_init(&p);
  ss_output_plan_add_input(&p, "--reference", ref);
  ss_output_plan_add(&p, "--output", other, SS_FILE_EXR, 0, 0);
  ss_error err;
  cr_assert_eq(ss_output_plan_check(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "it is the --reference"), "%s", err.message);
  ss_output_plan_free(&p);
  /* Two options naming one file that does not exist yet. */
  ss_output_plan_init(&p);
  ss_output_plan_add(&p, "--output", fresh, SS_FILE_EXR, 0, 0);
  ss_output_plan_add(&p, "--checkpoint", fresh2, SS_FILE_CHECKPOINT, SS_OUTPUT_CACHE, 0);
  cr_assert_eq(ss_output_plan_check(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "--checkpoint") && strstr(err.message, "--output writes it too"),
            "%s", err.message);
  ss_output_plan_free(&p);
  cr_assert_eq(count_entries(), 1);
}

/* A FIFO or a device is written directly, but a cache must be a regular
 * file; a socket cannot be written at all. None of this blocks. */
Test(output_plan, non_regular_files, .timeout = 10) {
  char fifo[128], sock[80];
  snprintf(fifo, sizeof fifo, "%s/pipe.exr", dir);
  snprintf(sock, sizeof sock, "%s/sock.exr", dir);
  cr_assert_eq(mkfifo(fifo, 0644), 0);
  ss_error err;
  cr_assert_eq(check_one("--output", fifo, SS_FILE_EXR, 0, 0, &err), SS_OK, "%s", err.message);
  cr_assert_eq(check_one("--output", "/dev/null", SS_FILE_EXR, 0, 0, &err), SS_OK, "%s",
               err.message);
  cr_assert_eq(check_one("--checkpoint", fifo, SS_FILE_CHECKPOINT, SS_OUTPUT_CACHE, 0, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "--checkpoint") && strstr(err.message, "a FIFO"), "%s",
            err.message);
  cr_assert_eq(check_one("--checkpoint", "/dev/full", SS_FILE_CHECKPOINT, SS_OUTPUT_CACHE, 0, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "a character device"), "%s", err.message);
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  struct sockaddr_un addr = {.sun_family = AF_UNIX};
  snprintf(addr.sun_path, sizeof addr.sun_path, "%s", sock);
  cr_assert_eq(bind(fd, (struct sockaddr *)&addr, sizeof addr), 0);
  cr_assert_eq(check_one("--output", sock, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "a socket"), "%s", err.message);
  close(fd);
  struct stat sb;
  cr_assert(stat(fifo, &sb) == 0 && S_ISFIFO(sb.st_mode), "the FIFO is still a FIFO");
}

Test(output_plan, no_room_is_refused_before_writing) {
  char path[128];
  snprintf(path, sizeof path, "%s/huge.exr", dir);
  ss_error err;
  cr_assert_eq(check_one("--output", path, SS_FILE_EXR, 0, 1ull << 62, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "--output: cannot write") && strstr(err.message, "MB free"), "%s",
            err.message);
  cr_assert_eq(check_one("--output", path, SS_FILE_EXR, 0, 1 << 20, &err), SS_OK, "%s",
               err.message);
  /* Outputs on one file system add up: each of 0.4 of the room fits, three
   * do not. */
  struct statvfs vfs;
  cr_assert_eq(statvfs(dir, &vfs), 0);
  uint64_t room = (uint64_t)(geteuid() == 0 ? vfs.f_bfree : vfs.f_bavail) * vfs.f_frsize;
  uint64_t part = room / 5 * 2;
  ss_output_plan p;
  ss_output_plan_init(&p);
  for (int i = 0; i < 3; ++i) {
    char name[160];
    snprintf(name, sizeof name, "%s/part%d.exr", dir, i);
    cr_assert_eq(check_one("--output", name, SS_FILE_EXR, 0, part, &err), SS_OK, "%s", err.message);
    ss_output_plan_add(&p, "--output", name, SS_FILE_EXR, 0, part);
  }
  cr_assert_eq(ss_output_plan_check(&p, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "part2.exr"), "the third is refused: %s", err.message);
  ss_output_plan_free(&p);
  cr_assert_eq(count_entries(), 0, "nothing left behind");
}

/* The directory must exist and be writable (as the superuser, who may
 * write anywhere, the check runs as nobody). */
Test(output_plan, the_directory_must_exist_and_be_writable) {
  char path[160], ro[128];
  ss_error err;
  snprintf(path, sizeof path, "%s/none/x.exr", dir);
  cr_assert_eq(check_one("--output", path, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "does not exist"), "%s", err.message);
  cr_assert_eq(check_one("--output", "/dev/null/x.exr", SS_FILE_EXR, 0, 0, &err),
               SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "is not a directory"), "%s", err.message);
  snprintf(path, sizeof path, "%s/", dir);
  cr_assert_eq(check_one("--output", path, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "expected a file name"), "%s", err.message);
  cr_assert_eq(check_one("--output", dir, SS_FILE_EXR, 0, 0, &err), SS_ERR_INVALID_ARGUMENT);
  cr_assert(strstr(err.message, "is a directory"), "%s", err.message);
  snprintf(ro, sizeof ro, "%s/read-only", dir);
  cr_assert_eq(mkdir(ro, 0555), 0);
  cr_assert_eq(chmod(dir, 0755), 0);
  snprintf(path, sizeof path, "%s/x.exr", ro);
  pid_t child = fork();
  cr_assert_geq(child, 0);
  if (child == 0) {
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) {
      _exit(3);
    }
    ss_status st = check_one("--output", path, SS_FILE_EXR, 0, 0, &err);
    _exit(st == SS_ERR_INVALID_ARGUMENT && strstr(err.message, "is not writable") ? 0 : 1);
  }
  int status;
  cr_assert_eq(waitpid(child, &status, 0), child);
  cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "exit %d", WEXITSTATUS(status));
}
