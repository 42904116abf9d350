/* A flat interface for foreign-function callers (the Python module of
 * python/subsurf, through ctypes): opaque handles, plain arrays of double and
 * int, option names and values as text, and errors as one line of text in a
 * caller's buffer. Everything here is a thin layer over the library's own
 * interfaces (bssrdf.h, halfspace.h, scene_io.h, render.h, image_io.h), whose
 * structs a foreign caller should not have to mirror.
 *
 * Conventions: colour quantities are 3 doubles (RGB); arrays of n points are
 * n doubles per coordinate; per-point RGB outputs are n x 3, row-major.
 * Functions returning int return 0 on success and a non-zero ss_status on
 * failure (SS_ERR_INVALID_ARGUMENT for an argument outside its range), with
 * the message in err (err_size bytes, always terminated). Every argument is
 * checked against the same ranges as the command line's. */
#ifndef SUBSURF_FFI_H
#define SUBSURF_FFI_H

#include <stddef.h>
#include <stdint.h>

/* The library's version, "MAJOR.MINOR.PATCH". */
const char *ss_ffi_version(void);

/* Reads `text` as the number argument `name` of a command ("halfspace" or
 * "render": the tables ss_halfspace_args and ss_render_args that `subsurf
 * halfspace` and `subsurf render` read, e.g. name "threads", text "8") into
 * *value; on failure the message says what was expected and what was given
 * ("expected a whole number in [0, 4096], got '100000'"), for the caller to
 * put the argument's own name in front. */
int ss_ffi_arg_parse(const char *command, const char *name, const char *text, double *value,
                     char *err, size_t err_size);

/* Names, separated by '\n', written into buf (truncated at size). */
void ss_ffi_model_names(char *buf, size_t size);
void ss_ffi_preset_names(char *buf, size_t size);

/* A measured preset (media.h) scaled by `scale` for a Henyey-Greenstein g:
 * sigma_s = sigma_s' scale / (1 - g), sigma_a = sigma_a scale (per mm at
 * scale 1) and the preset's eta; scale in (0, 1e6] (`--scale`), g in (-1, 1). */
int ss_ffi_preset(const char *name, double scale, double g, double sigma_s[3], double sigma_a[3],
                  double *eta, char *err, size_t err_size);

typedef struct ss_ffi_model ss_ffi_model;

/* A BSSRDF model by registry name for a homogeneous medium (Henyey-Greenstein
 * phase of mean cosine g per channel) behind a boundary of relative index
 * eta (each channel within the ranges of `subsurf model`: sigma_s and
 * sigma_a in [0, 1e6], eta in [0.1, 10]), with n_options options as
 * name/value text pairs (the model's own
 * option table: `subsurf model --help MODEL`). NULL on error, with the
 * ss_status in *status (when not NULL). */
ss_ffi_model *ss_ffi_model_create(const char *name, const double sigma_s[3],
                                  const double sigma_a[3], const double g[3], double eta,
                                  const char *const *option_names, const char *const *option_values,
                                  int n_options, int *status, char *err, size_t err_size);
void ss_ffi_model_destroy(ss_ffi_model *m);

/* The model's flags (SS_BSSRDF_RADIAL, SS_BSSRDF_BRDF, ... of bssrdf.h). */
unsigned ss_ffi_model_flags(const ss_ffi_model *m);

/* The radial profile at normal incidence for one channel (0, 1, 2) at n
 * radii in [0, 1e6] (the reference's length limit, SS_HALFSPACE_MAX_LENGTH):
 * value, multiple- and single-scattering parts (ss_bssrdf_profile). */
int ss_ffi_model_profile(const ss_ffi_model *m, int channel, const double *r, size_t n,
                         double *value, double *ms, double *ss, char *err, size_t err_size);

/* Total diffuse reflectance for light arriving at cos_i in (0, 1] (theta-i
 * in [0, 90) degrees), 3 values. */
int ss_ffi_model_total_reflectance(const ss_ffi_model *m, double cos_i, double out[3], char *err,
                                   size_t err_size);

/* Exitance M(x, y) per unit incident power of a beam entering at the origin
 * at cos_i (travelling toward +x), at n points with |x|, |y| <= 1e6; out is
 * n x 3. */
int ss_ffi_model_exitance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                          size_t n, double *out, char *err, size_t err_size);

/* Exitant radiance S at n points (x, y) in directions w_o (n x 3, unit
 * vectors within 1e-6, pointing away from the surface: z > 0) for the same
 * beam; out is n x 3. */
int ss_ffi_model_radiance(const ss_ffi_model *m, double cos_i, const double *x, const double *y,
                          const double *w_o, size_t n, double *out, char *err, size_t err_size);

/* The half-space reference (halfspace.h) for one channel of a medium: a
 * beam at theta_i (radians) into a half-space (thickness INFINITY) or a
 * slab (thickness in (0, 1e6]), `paths` paths at `seed` on `threads` threads (0: all). Each of
 * the totals is value and standard error: out_totals[0..1] diffuse
 * reflectance, [2..3] transmittance, [4..5] specular, [6..7] absorbed. The
 * radial exitance over rbins bins from rmin to rmax (halfspace.h's binning)
 * goes to r_lo, r_hi, radial and radial_error (rbins values each; any may
 * be NULL). */
int ss_ffi_halfspace(const double sigma_s[3], const double sigma_a[3], const double g[3],
                     int channel, double eta, double theta_i, double thickness, uint64_t paths,
                     uint64_t seed, int threads, double rmin, double rmax, int rbins,
                     double out_totals[8], double *r_lo, double *r_hi, double *radial,
                     double *radial_error, char *err, size_t err_size);

typedef struct ss_ffi_scene ss_ffi_scene;

/* A scene file (docs/scene-format.md; pbrt-v3 for a .pbrt path, as ss_scene_read), loaded and
 * committed. */
ss_ffi_scene *ss_ffi_scene_load(const char *path, char *err, size_t err_size);
void ss_ffi_scene_destroy(ss_ffi_scene *s);
/* The camera's image size. */
void ss_ffi_scene_size(const ss_ffi_scene *s, int *width, int *height);

/* Renders the whole image into rgb (height x width x 3, row-major, top row
 * first) with the scene's integrator, or `integrator` when not NULL/empty;
 * spp 0 and seed NULL take the scene's values (else spp in [1, 2^30]);
 * threads 0: all cores, at most 4096.
 * stats_out (may be NULL): seconds, samples, NaN/Inf samples dropped. */
int ss_ffi_render(ss_ffi_scene *s, const char *integrator, int spp, const uint64_t *seed,
                  int threads, float *rgb, double stats_out[3], char *err, size_t err_size);

/* An image file (EXR, PFM or PNG, as ss_image_read): its size and channel count, then its
 * pixels (height x width x channels floats) when data is not NULL. Call
 * once with data NULL for the size, then again with a buffer. */
int ss_ffi_image_read(const char *path, int *width, int *height, int *channels, float *data,
                      size_t data_floats, char *err, size_t err_size);

#endif
