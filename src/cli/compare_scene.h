/* `subsurf compare`: the parts shared by its files (compare_scene.c runs the
 * renders, compare_reference.c gets the reference, compare_scene_report.c
 * writes the results, compare_plots.c the plots, compare_html.c the report). */
#ifndef SUBSURF_CLI_COMPARE_SCENE_H
#define SUBSURF_CLI_COMPARE_SCENE_H

#include "subsurf/image.h"
#include "subsurf/image_metrics.h"
#include "subsurf/method.h"
#include "subsurf/render.h"
#include "subsurf/scene.h"

#define SS_COMPARE_MAX_METHODS 32
#define SS_COMPARE_MAX_PASSES 40

/* One pass of a method's render: the image after `spp` samples per pixel. */
typedef struct {
  unsigned spp;
  double seconds; /* wall time of the render so far */
  double rel_mse;
} ss_compare_pass;

typedef struct {
  ss_method method;
  char file[SS_NAME_SIZE * 4]; /* base name of its images */
  ss_image_error error;        /* of the final image */
  double seconds;              /* wall time of its preparation and all its passes */
  int prepares;                /* integrator preparations (ss_render_stats.prepares) */
  unsigned long long samples;  /* camera samples */
  unsigned spp;                /* fewest samples of any pixel */
  int num_passes;
  ss_compare_pass passes[SS_COMPARE_MAX_PASSES];
} ss_compare_result;

/* The reference: given, or rendered by volpath (and cached). */
typedef struct {
  const char *file; /* its name in the results: the --reference path or "reference.exr" */
  int rendered;     /* 1: rendered now or reused from the cache */
  unsigned spp;     /* rendered: fewest samples of any pixel */
  double seconds;   /* rendered: wall time when it was rendered */
  double rel_error; /* rendered: estimated relative standard error over the mask
                       (ss_image_rel_std_error) */
} ss_compare_reference;

typedef struct {
  const char *scene, *methods, *reference, *dir;
  int spp, ref_spp, threads, quiet, has_seed;
  double time, ref_time, ref_rel_error;
  unsigned long long seed;
  int num_methods;
  ss_compare_result results[SS_COMPARE_MAX_METHODS];
  ss_compare_reference ref;
} ss_compare_options;

/* Under mpirun the ranks render the tiles of every pass (render's split,
 * mpi_job.h) and rank 0 collects them after each: all ranks stop together
 * when one fails, and agree whether a time budget ran out (stats). Returns
 * st, or a failure of another rank or of the exchange. */
ss_status ss_compare_pass_end(ss_status st, ss_film *film, ss_render_stats *stats, ss_error *err);
/* st on every rank when all are SS_OK, else a failure on all (under mpirun). */
ss_status ss_compare_agree(ss_status st, ss_error *err);

/* The scene file read and committed; NULL with *err set. */
ss_scene *ss_compare_load_scene(const char *path, ss_error *err);

/* The scene's render options with --threads, --seed and Ctrl-C applied. */
void ss_compare_render_options(const ss_scene *scene, const ss_compare_options *o,
                               ss_render_options *ro);

/* Checks every file the run writes in DIR (a w x h image's each) before
 * any render: none may replace a file of another kind or an input (the
 * scene, its meshes and textures, the --reference image). 0, or 2 after
 * printing one line. */
int ss_compare_check_outputs(const ss_compare_options *o, int width, int height);

/* Writes DIR/NAME.exr and DIR/NAME.png. */
ss_status ss_compare_write_images(const char *dir, const char *name, const ss_image *img,
                                  double exposure, ss_error *err);

/* The --reference image checked against the scene's size; NULL after
 * printing why. */
ss_image *ss_compare_read_reference(const ss_compare_options *o, const ss_scene *scene);

/* Renders the volpath reference (--reference-spp, --reference-time or
 * --reference-rel-error) into DIR/reference.exr/.png and DIR/reference.key,
 * or reuses the one there when the key matches; fills o->ref. */
ss_status ss_compare_render_reference(ss_compare_options *o, const ss_scene *loaded,
                                      const ss_image *mask, ss_image **out, ss_error *err);

/* What the passes say about a method (error_curve.h). */
typedef struct {
  int points; /* passes in the log-log fit of relMSE over time */
  double slope, intercept;
  double time_to_volpath; /* seconds to volpath's final relMSE; INFINITY: never,
                             NAN: no volpath */
  double converged;       /* the relMSE the passes converge to */
} ss_compare_curve;

/* The curve of r against `volpath` (NULL: none in the list). */
void ss_compare_curve_of(const ss_compare_result *r, const ss_compare_result *volpath,
                         ss_compare_curve *c);

/* The volpath method of the list, NULL when there is none. */
const ss_compare_result *ss_compare_find_volpath(const ss_compare_result *r, int n);

/* The colour of method i in the plots and the report. */
const char *ss_compare_method_colour(int i);

/* Writes DIR/convergence.svg, DIR/mean-ratio-{r,g,b}.svg and
 * DIR/error-colorbar.svg (compare_plots.c); 0, or 1 after printing why. */
int ss_compare_write_plots(const ss_compare_options *o);

/* Writes DIR/index.html, the report (compare_html.c), for images of
 * width x height; 0, or 1 after printing why. */
int ss_compare_write_html(const ss_compare_options *o, int width, int height);

/* Writes DIR/results.json and DIR/results.csv; 0, or 1 after printing why. */
int ss_compare_write_results(const ss_compare_options *o);

#endif
