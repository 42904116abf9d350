/* The pbrt-v3 scene importer (private to src/io; docs/pbrt-import.md says
 * what each directive and parameter becomes). One importer state `ss_pbrt`
 * is shared by the lexer (pbrt_lexer.c), the parameter lists
 * (pbrt_params.c), the directives and graphics state (pbrt_parser.c), the
 * camera and render settings (pbrt_camera.c), shapes (pbrt_shapes.c),
 * materials, textures and media (pbrt_materials.c) and lights
 * (pbrt_lights.c).
 *
 * Errors are sticky: the first one is kept in `st`/`err` ("FILE:LINE:
 * what was expected") and every later call does nothing, so handlers check
 * `st` once at the end. Warnings ("FILE:LINE: ...") go to the caller's
 * callback. */
#ifndef SUBSURF_IO_PBRT_H
#define SUBSURF_IO_PBRT_H

#include "subsurf/scene.h"
#include "subsurf/scene_io.h"
#include "subsurf/transform.h"

#include <stddef.h>

/* ---- tokens (pbrt_lexer.c) */

typedef enum {
  SS_PBRT_EOF,
  SS_PBRT_WORD,   /* a bare word: a directive, or true/false */
  SS_PBRT_STRING, /* a quoted string, escapes decoded */
  SS_PBRT_NUMBER,
  SS_PBRT_LBRACKET,
  SS_PBRT_RBRACKET,
} ss_pbrt_token_kind;

#define SS_PBRT_TOKEN_SIZE 4096

typedef struct {
  ss_pbrt_token_kind kind;
  char text[SS_PBRT_TOKEN_SIZE]; /* word or decoded string */
  double number;
  int line;
} ss_pbrt_token;

/* One file being read; Include pushes another on top. */
typedef struct ss_pbrt_lexer {
  char *text; /* owned */
  size_t pos;
  int line;
  char file[SS_PATH_SIZE];
  int has_peek;
  ss_pbrt_token peek;
  struct ss_pbrt_lexer *parent;
} ss_pbrt_lexer;

/* ---- parameter lists (pbrt_params.c) */

typedef struct {
  char type[32], name[64];
  double *nums;
  size_t num_nums;
  char **strs;
  size_t num_strs;
  int line;
  int used;
} ss_pbrt_param;

typedef struct {
  ss_pbrt_param *items;
  size_t n;
  char file[SS_PATH_SIZE]; /* where the directive was */
  int line;
} ss_pbrt_params;

/* ---- textures, materials and graphics state */

/* A texture as a material parameter sees it: a constant, or a scene
 * texture (owned by the scene). */
typedef struct {
  char name[SS_NAME_SIZE];
  int is_float;
  ss_rgb value;          /* constant textures */
  const ss_texture *tex; /* or NULL */
} ss_pbrt_texture;

typedef enum {
  SS_PBRT_MAT_SURFACE,    /* matte, glass: no medium of its own */
  SS_PBRT_MAT_NONE,       /* "none": only a boundary between media */
  SS_PBRT_MAT_SUBSURFACE, /* subsurface, kdsubsurface: its own medium */
  SS_PBRT_MAT_BLACK,      /* a black surface (material -1) */
} ss_pbrt_material_kind;

typedef struct {
  ss_pbrt_material_kind kind;
  ss_material m; /* the scene material without the interior medium */
  char file[SS_PATH_SIZE];
  int line;
} ss_pbrt_material;

typedef struct {
  char name[SS_NAME_SIZE];
  int material; /* into ss_pbrt.materials */
} ss_pbrt_named;

typedef struct {
  ss_mat4 ctm;
  int material;        /* into ss_pbrt.materials */
  int inside, outside; /* scene media, -1: vacuum */
  int area;            /* an AreaLightSource "diffuse" is active */
  ss_rgb area_l;
  int reverse;
  size_t num_named, num_textures; /* scoped lists' lengths at AttributeBegin */
} ss_pbrt_gstate;

/* A shape kept by ObjectBegin, in the object's space. */
typedef struct {
  ss_mesh *mesh;
  int material; /* scene material or -1 */
} ss_pbrt_object_shape;

typedef struct {
  char name[SS_NAME_SIZE];
  ss_pbrt_object_shape *shapes;
  size_t n;
} ss_pbrt_object;

#define SS_PBRT_STACK_MAX 256
#define SS_PBRT_INCLUDE_MAX 32

typedef struct {
  /* error state */
  ss_status st;
  ss_error *err;
  ss_scene_warning_fn warn;
  void *user;
  ss_pbrt_lexer *lex;
  int include_depth;
  char search_dir[SS_PATH_SIZE]; /* the top-level file's directory */

  ss_scene *scene;
  int in_world, world_ended;
  ss_pbrt_gstate gs;
  ss_pbrt_gstate stack[SS_PBRT_STACK_MAX];
  char stack_kind[SS_PBRT_STACK_MAX]; /* 'a' AttributeBegin, 't' TransformBegin */
  int depth;
  /* pbrt's mirrored camera space undone by this world reflection (set by
   * Camera; pbrt_camera.c) */
  ss_mat4 mirror;
  struct {
    char name[SS_NAME_SIZE];
    ss_mat4 m;
  } * coord_systems;
  size_t num_coord_systems;

  ss_pbrt_material *materials;
  size_t num_materials;
  ss_pbrt_named *named;
  size_t num_named;
  ss_pbrt_texture *textures;
  size_t num_textures;
  /* scene materials made from (pbrt material, inside medium) */
  struct {
    int material, medium, scene_material;
  } * made;
  size_t num_made;

  ss_pbrt_object *objects;
  size_t num_objects;
  int object; /* the object being defined, or -1 */

  /* camera and options (pbrt_camera.c) */
  ss_mat4 camera_to_world;
  int has_camera;
  double fov, screen_aspect; /* fov on the shorter axis; 0: none */
  int camera_line;
  char camera_file[SS_PATH_SIZE];
  int width, height;
  double crop[4]; /* x0 x1 y0 y1 in [0, 1] */
  int integrator_line;
  char integrator_file[SS_PATH_SIZE];
  int integrator_path; /* pbrt "path": bssrdf with subsurface materials, else path */
  int has_subsurface;
  int num_shapes;
  ss_pbrt_limits limits; /* all 0: none (ss_scene_parse_pbrt_limited) */
} ss_pbrt;

/* ---- pbrt_parser.c */
ss_status ss_pbrt_fail(ss_pbrt *P, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
void ss_pbrt_warn(ss_pbrt *P, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* A path in the file: absolute, else relative to the top-level file's
 * directory (pbrt-v3's search directory). */
void ss_pbrt_resolve(const ss_pbrt *P, const char *name, char out[SS_PATH_SIZE]);
/* W * ctm: object space to subsurf's world. */
ss_mat4 ss_pbrt_to_world(const ss_pbrt *P, ss_mat4 ctm);

/* ---- pbrt_lexer.c */
/* Pushes a file's text (taking ownership) as the current lexer. */
void ss_pbrt_lexer_push(ss_pbrt *P, char *text, const char *file);
/* Pops the current lexer; returns 0 when none is left. */
int ss_pbrt_lexer_pop(ss_pbrt *P);
/* The next token of the current file (EOF at its end); errors are sticky. */
void ss_pbrt_next(ss_pbrt *P, ss_pbrt_token *t);
void ss_pbrt_peek(ss_pbrt *P, ss_pbrt_token *t);

/* ---- pbrt_params.c */
/* Reads "type name" value pairs up to the next directive. */
void ss_pbrt_params_read(ss_pbrt *P, ss_pbrt_params *ps);
void ss_pbrt_params_free(ss_pbrt_params *ps);
/* Warns once for each parameter nobody asked for: "WHAT: parameter
 * \"TYPE NAME\" is not supported (ignored)". */
void ss_pbrt_params_report(ss_pbrt *P, const ss_pbrt_params *ps, const char *what);
/* Each returns 1 and fills *out when the parameter is there (marking it
 * used), 0 when it is absent; a wrong type or count is an error. */
int ss_pbrt_float(ss_pbrt *P, ss_pbrt_params *ps, const char *name, double *out);
int ss_pbrt_int(ss_pbrt *P, ss_pbrt_params *ps, const char *name, long lo, long hi, long *out);
int ss_pbrt_bool(ss_pbrt *P, ss_pbrt_params *ps, const char *name, int *out);
int ss_pbrt_string(ss_pbrt *P, ss_pbrt_params *ps, const char *name, char *out, size_t size);
int ss_pbrt_point(ss_pbrt *P, ss_pbrt_params *ps, const char *name, ss_vec3 *out);
/* An RGB value ("rgb"/"color", or an approximated "blackbody"/"spectrum",
 * with a warning). */
int ss_pbrt_rgb(ss_pbrt *P, ss_pbrt_params *ps, const char *name, ss_rgb *out);
/* Any array of numbers of `type` (e.g. "integer", "point", "float"),
 * borrowed from the list. */
const ss_pbrt_param *ss_pbrt_array(ss_pbrt *P, ss_pbrt_params *ps, const char *name,
                                   const char *const *types);
/* A texturable parameter: a constant (rgb, color, float...) or "texture
 * NAME"; *tex is set for a scene texture, else *value. */
int ss_pbrt_texturable(ss_pbrt *P, ss_pbrt_params *ps, const char *name, int is_float,
                       ss_rgb *value, const ss_texture **tex);

/* ---- directive handlers */
void ss_pbrt_camera(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_film(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_sampler(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_integrator(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_pixel_filter(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
/* pbrt-v3's defaults for the scene's camera, film, sampler and integrator. */
void ss_pbrt_options_defaults(ss_pbrt *P);
/* At WorldBegin: the scene's camera (and the mirror that undoes pbrt's
 * handedness), film and integrator from what was read. */
void ss_pbrt_finish_options(ss_pbrt *P);
/* After WorldEnd: the integrator, which depends on the materials. */
void ss_pbrt_finish_integrator(ss_pbrt *P);

void ss_pbrt_shape(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_object_instance(ss_pbrt *P, const char *name, const char *file, int line);

/* Material and MakeNamedMaterial (name NULL for Material). */
void ss_pbrt_material_directive(ss_pbrt *P, const char *type, const char *name, ss_pbrt_params *ps);
void ss_pbrt_texture_directive(ss_pbrt *P, const char *name, const char *kind, const char *type,
                               ss_pbrt_params *ps);
void ss_pbrt_named_medium(ss_pbrt *P, const char *name, ss_pbrt_params *ps);
/* The scene material for the current material and inside medium, or -1;
 * *skip is set when the shape is to be left out (a "none" material without
 * a medium). */
int ss_pbrt_scene_material(ss_pbrt *P, const char *file, int line, int *skip);
/* The default material (matte, Kd 0.5) as materials[0]. */
void ss_pbrt_default_material(ss_pbrt *P);
/* pbrt-v3's roughness remapping (RoughnessToAlpha). */
double ss_pbrt_roughness_to_alpha(double roughness);

void ss_pbrt_light(ss_pbrt *P, const char *type, ss_pbrt_params *ps);
void ss_pbrt_area_light(ss_pbrt *P, const char *type, ss_pbrt_params *ps);

#endif
