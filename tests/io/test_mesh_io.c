#include "subsurf/mesh.h"
#include "subsurf/mesh_io.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

static void make_dir(void) {
  const char *base = getenv("TMPDIR");
  snprintf(tmpdir, sizeof tmpdir, "%s/subsurf_mesh_io_XXXXXX", base ? base : "/tmp");
  cr_assert_not_null(mkdtemp(tmpdir));
}

static void remove_dir(void) {
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  cr_assert_eq(system(cmd), 0);
}

TestSuite(mesh_io, .init = make_dir, .fini = remove_dir);

static const char *write_file(const char *name, const void *data, size_t len) {
  static char path[400];
  snprintf(path, sizeof path, "%s/%s", tmpdir, name);
  FILE *f = fopen(path, "wb");
  cr_assert_not_null(f);
  cr_assert_eq(fwrite(data, 1, len, f), len);
  fclose(f);
  return path;
}

static const char *write_text(const char *name, const char *text) {
  return write_file(name, text, strlen(text));
}

/* Reads a file that must fail; checks the status and that the message names
 * the file and contains `where` and `what`. */
static void expect_error(const char *path, ss_status status, const char *where, const char *what) {
  ss_mesh *m = (ss_mesh *)&m;
  ss_error err;
  ss_error_clear(&err);
  ss_status st = ss_mesh_read(path, &m, NULL, &err);
  cr_assert_eq(st, status, "%s: status %d, expected %d (%s)", path, st, status, err.message);
  cr_assert_null(m);
  cr_assert(strstr(err.message, path) != NULL, "message lacks the path: %s", err.message);
  cr_assert(strstr(err.message, where) != NULL, "message lacks '%s': %s", where, err.message);
  cr_assert(strstr(err.message, what) != NULL, "message lacks '%s': %s", what, err.message);
}

static ss_mesh *read_ok(const char *path, ss_mesh_read_info *info) {
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_mesh_read(path, &m, info, &err), SS_OK, "%s", err.message);
  return m;
}

#define CUBE_PLY_HEADER(nv, nf)                                                                    \
  "ply\nformat ascii 1.0\ncomment unit cube\nelement vertex " #nv "\nproperty float x\n"           \
  "property float y\nproperty float z\nelement face " #nf "\n"                                     \
  "property list uchar int vertex_indices\nend_header\n"

static const char cube_vertices[] = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
static const char cube_faces[] = "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n"
                                 "4 0 4 7 3\n";

Test(mesh_io, ascii_ply_cube_is_fanned_closed_and_outward) {
  char text[1024];
  snprintf(text, sizeof text, "%s%s%s", CUBE_PLY_HEADER(8, 6), cube_vertices, cube_faces);
  ss_mesh_read_info info;
  ss_mesh *m = read_ok(write_text("cube.ply", text), &info);
  cr_assert_eq(m->num_vertices, 8u);
  cr_assert_eq(m->num_triangles, 12u);
  cr_assert_eq(info.num_polygons, 6u);
  cr_assert_eq(info.num_degenerate, 0u);
  cr_assert_null(m->normals);
  cr_assert_float_eq(ss_mesh_area(m), 6.0, 1e-6);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 1.0, 1e-6);
  ss_error err;
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  ss_mesh_destroy(m);
}

Test(mesh_io, ascii_ply_keeps_normals_and_uvs_and_skips_other_data) {
  const char *text = "ply\nformat ascii 1.0\nobj_info made by a test\n"
                     "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                     "property float nx\nproperty float ny\nproperty float nz\n"
                     "property uchar red\nproperty float s\nproperty float t\n"
                     "element face 1\nproperty list uchar uint vertex_index\n"
                     "property int flags\n"
                     "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                     "0 0 0 0 0 2 255 0 0\n1 0 0 0 0 2 255 1 0\n1 1 0 0 0 2 255 1 1\n"
                     "0 1 0 0 0 2 255 0 1\n4 0 1 2 3 7\n0 1\n";
  ss_mesh *m = read_ok(write_text("attrs.ply", text), NULL);
  cr_assert_eq(m->num_triangles, 2u);
  cr_assert_not_null(m->normals);
  cr_assert_not_null(m->uvs);
  cr_assert_float_eq(m->normals[3 * 2 + 2], 2.0, 0.0);
  cr_assert_float_eq(m->uvs[2 * 2], 1.0, 0.0);
  cr_assert_float_eq(m->uvs[2 * 3 + 1], 1.0, 0.0);
  ss_mesh_destroy(m);
}

/* Appends a value in the requested byte order. */
static void put(unsigned char **p, const void *v, size_t n, int big_endian) {
  const unsigned char *b = v;
  for (size_t i = 0; i < n; ++i) {
    (*p)[i] = b[big_endian ? n - 1 - i : i];
  }
  *p += n;
}

/* A binary square pyramid: 5 vertices (float xyz), a quad base and four
 * triangles, with a pentagon-free mix of list sizes. Returns the length. */
static size_t binary_pyramid(unsigned char *buf, int big_endian, int nan_vertex, int bad_index) {
  const uint16_t probe = 1;
  int host_le = *(const unsigned char *)&probe == 1;
  int swap = big_endian == host_le; /* put() reverses bytes when asked */
  char header[512];
  int hl = snprintf(header, sizeof header,
                    "ply\nformat %s 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 5\nproperty list uchar int vertex_indices\n"
                    "end_header\n",
                    big_endian ? "binary_big_endian" : "binary_little_endian");
  memcpy(buf, header, (size_t)hl);
  unsigned char *p = buf + hl;
  const float v[5][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 5; ++i) {
    for (int k = 0; k < 3; ++k) {
      float x = (nan_vertex && i == 2 && k == 1) ? NAN : v[i][k];
      put(&p, &x, 4, swap);
    }
  }
  const int faces[5][5] = {{4, 0, 3, 2, 1}, {3, 0, 1, 4}, {3, 1, 2, 4}, {3, 2, 3, 4}, {3, 3, 0, 4}};
  for (int f = 0; f < 5; ++f) {
    unsigned char n = (unsigned char)faces[f][0];
    *p++ = n;
    for (int k = 1; k <= n; ++k) {
      int32_t idx = (bad_index && f == 3 && k == 2) ? 5 : faces[f][k];
      put(&p, &idx, 4, swap);
    }
  }
  return (size_t)(p - buf);
}

Test(mesh_io, binary_ply_of_both_byte_orders_reads_the_same_mesh) {
  unsigned char buf[1024];
  for (int be = 0; be <= 1; ++be) {
    size_t n = binary_pyramid(buf, be, 0, 0);
    ss_mesh *m = read_ok(write_file(be ? "be.ply" : "le.ply", buf, n), NULL);
    cr_assert_eq(m->num_vertices, 5u);
    cr_assert_eq(m->num_triangles, 6u);
    cr_assert_float_eq(m->positions[3 * 4 + 2], 1.0, 0.0);
    cr_assert_float_eq(m->positions[3 * 1], 1.0, 0.0);
    cr_assert_float_eq(ss_mesh_signed_volume(m), 4.0 / 3.0, 1e-6);
    ss_error err;
    cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
    ss_mesh_destroy(m);
  }
}

Test(mesh_io, binary_ply_errors_name_the_element) {
  unsigned char buf[1024];
  size_t n = binary_pyramid(buf, 0, 0, 0);
  expect_error(write_file("trunc_face.ply", buf, n - 3), SS_ERR_PARSE, "binary face element 4",
               "truncated");
  size_t header = (size_t)((unsigned char *)strstr((char *)buf, "end_header\n") - buf) + 11;
  /* Caught from the header: 5 vertices cannot fit in 30 bytes. */
  expect_error(write_file("trunc_vertex.ply", buf, header + 30), SS_ERR_PARSE,
               "5 'vertex' elements", "truncated");
  n = binary_pyramid(buf, 1, 1, 0);
  expect_error(write_file("nan.ply", buf, n), SS_ERR_PARSE, "binary vertex element 2", "finite");
  n = binary_pyramid(buf, 1, 0, 1);
  expect_error(write_file("range.ply", buf, n), SS_ERR_PARSE, "binary face element 3",
               "out of range");
  n = binary_pyramid(buf, 0, 0, 0);
  buf[n] = 0;
  expect_error(write_file("long.ply", buf, n + 1), SS_ERR_PARSE, "long.ply",
               "after the last declared element");
}

Test(mesh_io, ascii_ply_errors_name_the_line) {
  char text[1024];
  /* 8 vertices declared, 7 given: the first face line is read as a vertex. */
  snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n%s",
           CUBE_PLY_HEADER(8, 6), cube_faces);
  expect_error(write_text("count.ply", text), SS_ERR_PARSE, "line 18 (vertex 7)", "more values");
  /* Fewer faces declared than present. */
  snprintf(text, sizeof text, "%s%s%s", CUBE_PLY_HEADER(8, 5), cube_vertices, cube_faces);
  expect_error(write_text("extra.ply", text), SS_ERR_PARSE, "line 24",
               "after the last declared element");
  /* Truncated: the last faces are missing. */
  snprintf(text, sizeof text, "%s%s4 0 3 2 1\n4 4 5 6 7\n", CUBE_PLY_HEADER(8, 6), cube_vertices);
  expect_error(write_text("trunc.ply", text), SS_ERR_PARSE, "line 21", "truncated");
  /* Truncated before the faces: the header's counts cannot fit (one
   * character and a separator per value), found before reading. */
  snprintf(text, sizeof text, "%s%s", CUBE_PLY_HEADER(8, 6), cube_vertices);
  expect_error(write_text("trunc2.ply", text), SS_ERR_PARSE, "6 'face' elements", "truncated");
  /* A NaN coordinate. */
  snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n1 nan 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n%s",
           CUBE_PLY_HEADER(8, 6), cube_faces);
  expect_error(write_text("nan.ply", text), SS_ERR_PARSE, "line 13 (vertex 2)", "finite");
  /* An index out of range. */
  snprintf(text, sizeof text, "%s%s4 0 3 2 1\n4 4 5 6 8\n", CUBE_PLY_HEADER(8, 2), cube_vertices);
  expect_error(write_text("range.ply", text), SS_ERR_PARSE, "line 20 (face 1)", "out of range");
  /* A face with two vertices. */
  snprintf(text, sizeof text, "%s%s2 0 1\n", CUBE_PLY_HEADER(8, 1), cube_vertices);
  expect_error(write_text("short.ply", text), SS_ERR_PARSE, "line 19", "expected 3");
  /* A malformed number. */
  snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n1 1x 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n%s",
           CUBE_PLY_HEADER(8, 6), cube_faces);
  expect_error(write_text("num.ply", text), SS_ERR_PARSE, "line 13", "'y' is not a valid number");
}

Test(mesh_io, ply_header_errors_name_the_line) {
  expect_error(write_text("magic.ply", "plyx\n"), SS_ERR_PARSE, "line 1", "not a PLY file");
  expect_error(write_text("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                      "property float128 x\nend_header\n"),
               SS_ERR_PARSE, "line 4", "unsupported property type: float128");
  expect_error(write_text("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"),
               SS_ERR_PARSE, "line 2", "unknown format");
  expect_error(write_text("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"), SS_ERR_PARSE,
               "line 3", "end_header");
  expect_error(write_text("noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                        "property float x\nproperty float y\nproperty float z\n"
                                        "end_header\n0 0 0\n"),
               SS_ERR_PARSE, "noface.ply", "'face'");
  expect_error(write_text("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                     "property float x\nproperty float y\nelement face 0\n"
                                     "property list uchar int vertex_indices\nend_header\n"),
               SS_ERR_PARSE, "noz.ply", "x, y, z");
}

static const char cube_obj[] =
    "# a unit cube\nmtllib none.mtl\no cube\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn 1 0 0\nvn -1 0 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "g faces\ns off\nusemtl white\n"
    "f 1/1/1 4/2/1 3/3/1 2/4/1\n"
    "f 5/1/2 6/2/2 7/3/2 8/4/2\n"
    "f 1/1/3 2/2/3 6/3/3 5/4/3\n"
    "f -6/1/4 -5/2/4 -1/3/4 -2/4/4 # negative indices: 3 4 8 7\n"
    "f 2/1/5 3/2/5 7/3/5 6/4/5\n"
    "f 1/1/6 5/2/6 8/3/6 4/4/6\n";

Test(mesh_io, obj_cube_with_normals_uvs_and_negative_indices) {
  ss_mesh_read_info info;
  ss_mesh *m = read_ok(write_text("cube.obj", cube_obj), &info);
  cr_assert_eq(m->num_triangles, 12u);
  cr_assert_eq(info.num_polygons, 6u);
  cr_assert_eq(m->num_vertices, 24u); /* split per (v, vt, vn) */
  cr_assert_not_null(m->normals);
  cr_assert_not_null(m->uvs);
  cr_assert_float_eq(ss_mesh_signed_volume(m), 1.0, 1e-6);
  ss_error err;
  cr_assert_eq(ss_mesh_check_closed(m, &err), SS_OK, "%s", err.message);
  /* Normals agree with the winding (outward). */
  for (size_t t = 0; t < m->num_triangles; ++t) {
    ss_vec3 ng = ss_vec3_normalize(ss_mesh_triangle_normal(m, t));
    const float *n = m->normals + 3 * (size_t)m->indices[3 * t];
    cr_assert_float_eq(ss_vec3_dot(ng, ss_vec3_make(n[0], n[1], n[2])), 1.0, 1e-6, "tri %zu", t);
  }
  ss_mesh_destroy(m);
}

Test(mesh_io, obj_reference_forms_and_partial_attributes) {
  /* v, v//vn and v/vt mixed: neither normals nor uvs are complete, so both
   * are dropped and vertices are shared by position index only. */
  const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\nvn 0 0 1\nvt 0 0\n"
                     "f 1 2 3\nf 1//1 3//1 4//1\nf 1/1 2/1 4/1\n";
  ss_mesh *m = read_ok(write_text("mixed.obj", text), NULL);
  cr_assert_eq(m->num_triangles, 3u);
  cr_assert_eq(m->num_vertices, 4u);
  cr_assert_null(m->normals);
  cr_assert_null(m->uvs);
  ss_mesh_destroy(m);
}

Test(mesh_io, obj_errors_name_the_line) {
  expect_error(write_text("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), SS_ERR_PARSE,
               "line 4", "vertex index 4 out of range");
  expect_error(write_text("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n"), SS_ERR_PARSE,
               "line 4", "out of range");
  expect_error(write_text("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), SS_ERR_PARSE,
               "line 4", "out of range");
  expect_error(write_text("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), SS_ERR_PARSE,
               "line 2", "finite");
  expect_error(write_text("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n"), SS_ERR_PARSE,
               "line 3", "expected a number");
  expect_error(write_text("short.obj", "v 0 0\n"), SS_ERR_PARSE, "line 1", "expected x y z");
  expect_error(write_text("ref.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n"), SS_ERR_PARSE,
               "line 4", "v/vt/vn");
  expect_error(write_text("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n"),
               SS_ERR_PARSE, "line 5", "normal index 2 out of range");
  expect_error(write_text("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), SS_ERR_PARSE, "line 3",
               "expected at least 3");
  expect_error(write_text("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"), SS_ERR_PARSE,
               "line 4", "integer");
  expect_error(write_text("empty.obj", "v 0 0 0\n"), SS_ERR_PARSE, "empty.obj", "no faces");
}

Test(mesh_io, missing_files_and_unknown_extensions_are_reported) {
  char path[400];
  snprintf(path, sizeof path, "%s/none.ply", tmpdir);
  expect_error(path, SS_ERR_IO, "none.ply", "cannot open");
  expect_error(write_text("mesh.stl", "solid\n"), SS_ERR_UNSUPPORTED, "mesh.stl", ".ply or .obj");
}

Test(mesh_io, obj_polygons_of_any_size_are_fanned) {
  /* A regular 100-gon in the z = 0 plane. */
  static char text[8192];
  size_t len = 0;
  for (int i = 0; i < 100; ++i) {
    double a = 2.0 * 3.14159265358979323846 * i / 100.0;
    len += (size_t)snprintf(text + len, sizeof text - len, "v %.17g %.17g 0\n", cos(a), sin(a));
  }
  len += (size_t)snprintf(text + len, sizeof text - len, "f");
  for (int i = 1; i <= 100; ++i) {
    len += (size_t)snprintf(text + len, sizeof text - len, " %d", i);
  }
  snprintf(text + len, sizeof text - len, "\n");
  ss_mesh_read_info info;
  ss_mesh *m = read_ok(write_text("ngon.obj", text), &info);
  cr_assert_eq(info.num_polygons, 1u);
  cr_assert_eq(m->num_triangles, 98u);
  cr_assert_float_eq(ss_mesh_area(m), 50.0 * sin(2.0 * 3.14159265358979323846 / 100.0), 1e-5);
  ss_mesh_destroy(m);
}

Test(mesh_io, degenerate_triangles_are_kept_and_counted) {
  const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n";
  ss_mesh_read_info info;
  ss_mesh *m = read_ok(write_text("degen.obj", text), &info);
  cr_assert_eq(m->num_triangles, 2u);
  cr_assert_eq(info.num_degenerate, 1u);
  ss_mesh_destroy(m);
}

/* The header is checked against the file before anything is allocated: two
 * vertex elements (buffers sized from one, filled from the other), counts
 * near 2^31 and 2^32 that announce gigabytes the file does not hold, and
 * elements without properties are refused with a message. */
Test(mesh_io, ply_headers_that_the_file_cannot_back_are_refused_before_reading) {
  expect_error(write_text("twice.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2\n"
                                       "property float x\nproperty float y\nproperty float z\n"
                                       "element vertex 9\nproperty float x\nend_header\n"),
               SS_ERR_PARSE, "line 7", "a second element of the same name: vertex");
  const char *formats[3] = {"ascii", "binary_little_endian", "binary_big_endian"};
  const char *counts[4] = {"2147483647", "2147483648", "4294967294", "100"};
  /* 42 bytes: room for 3 vertices in any format, not for 100 of anything. */
  const char *body = "0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n";
  for (int f = 0; f < 3; ++f) {
    for (int c = 0; c < 4; ++c) {
      for (int which = 0; which < 2; ++which) {
        char text[512];
        snprintf(text, sizeof text,
                 "ply\nformat %s 1.0\nelement vertex %s\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %s\nproperty list uchar int vertex_indices\n"
                 "end_header\n%s",
                 formats[f], which ? "3" : counts[c], which ? counts[c] : "1", body);
        char where[64];
        snprintf(where, sizeof where, "declares %s '%s' elements", counts[c],
                 which ? "face" : "vertex");
        expect_error(write_text("huge.ply", text), SS_ERR_PARSE, where, "follow the header");
      }
    }
  }
  expect_error(write_text("empty_element.ply",
                          "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                          "property float x\nproperty float y\nproperty float z\n"
                          "element nothing 4000000000\nelement face 0\n"
                          "property list uchar int vertex_indices\nend_header\n"),
               SS_ERR_PARSE, "element 'nothing'", "no properties");
}

/* A directory, a device or a FIFO is not read as a (huge or endless) file. */
Test(mesh_io, inputs_that_are_not_regular_files_are_refused) {
  char path[400];
  snprintf(path, sizeof path, "%s/dir.ply", tmpdir);
  cr_assert_eq(mkdir(path, 0755), 0);
  expect_error(path, SS_ERR_IO, "dir.ply", "is a directory (expected a regular file)");
  snprintf(path, sizeof path, "%s/dir.obj", tmpdir);
  cr_assert_eq(mkdir(path, 0755), 0);
  expect_error(path, SS_ERR_IO, "dir.obj", "is a directory");
  snprintf(path, sizeof path, "%s/fifo.ply", tmpdir);
  cr_assert_eq(mkfifo(path, 0644), 0);
  expect_error(path, SS_ERR_IO, "fifo.ply", "is a FIFO");
  ss_mesh *m = NULL;
  ss_error err;
  cr_assert_eq(ss_mesh_read_obj("/dev/zero", &m, NULL, &err), SS_ERR_IO);
  cr_assert(strstr(err.message, "/dev/zero: is a character device") != NULL, "%s", err.message);
}
