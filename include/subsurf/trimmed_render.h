/* The robust per-pixel estimator of Frederickx2017 sec. 7.3
 * in the renderer: the spp samples of every pixel are split into
 * K independent passes of spp/K samples (pass k takes the pixel's samples
 * k spp/K .. (k+1) spp/K - 1 of the stream ss_render draws, so with trim 0
 * the result is the plain render's mean), and each pixel's value is the
 * trimmed mean (trimmed_mean.h) of its K pass means: the floor(trim K)
 * highest and lowest are dropped per channel. */
#ifndef SUBSURF_TRIMMED_RENDER_H
#define SUBSURF_TRIMMED_RENDER_H

#include "subsurf/render.h"

/* Renders pass `pass` of `passes` (o->spp a multiple of passes; no time
 * limit, checkpoint or film to resume). The film holds that pass's samples
 * only; stats are the pass's. */
ss_status ss_render_pass(const ss_scene *scene, const ss_render_options *o, int pass, int passes,
                         ss_film **film, ss_render_stats *stats, ss_error *err);

/* Combines K pass films of one size into a new film: per pixel and channel
 * the trimmed mean of the pass means; the sample counts are the passes'
 * sums, and the film's variance (ss_film_variance_image) is the spread of
 * the pass means, s_K^2 / K. trim in [0, 0.5), keeping at least one pass. */
ss_status ss_film_trimmed_combine(ss_film *const *passes, int k, double trim, ss_film **out,
                                  ss_error *err);

/* All passes, combined; o->progress sees the samples of every pass against
 * spp x pixels. On *o->cancel the passes finished so far are combined (the
 * unfinished pass alone when none is) and SS_ERR_INTERRUPTED is returned
 * with that film, as ss_render does. */
ss_status ss_render_trimmed(const ss_scene *scene, const ss_render_options *o, int passes,
                            double trim, ss_film **film, ss_render_stats *stats, ss_error *err);

#endif
