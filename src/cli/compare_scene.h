/* `subsurf compare`: the parts shared by its files (compare_scene.c runs the
 * renders, compare_scene_report.c writes the results). */
#ifndef SUBSURF_CLI_COMPARE_SCENE_H
#define SUBSURF_CLI_COMPARE_SCENE_H

#include "subsurf/image.h"
#include "subsurf/image_metrics.h"
#include "subsurf/method.h"

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
  double seconds;              /* wall time of all its passes */
  unsigned long long samples;  /* camera samples */
  unsigned spp;                /* fewest samples of any pixel */
  int num_passes;
  ss_compare_pass passes[SS_COMPARE_MAX_PASSES];
} ss_compare_result;

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

/* Writes DIR/results.json and DIR/results.csv; 0, or 1 after printing why. */
int ss_compare_write_results(const char *dir, const char *scene, const char *reference,
                             const ss_compare_result *r, int n);

#endif
