/* `subsurf compare`'s reference (compare_scene.h): the --reference image, or
 * a volpath render cached as DIR/reference.exr with DIR/reference.key, the
 * settings it was rendered with (first line) and what it reached (second). */
#include "cli/compare_scene.h"
#include "cli/mpi_job.h"
#include "cli/text_buf.h"

#include "subsurf/film.h"
#include "subsurf/image_io.h"
#include "subsurf/image_metrics.h"
#include "subsurf/scene_io.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#define CMD "compare"

/* First spp of a reference rendered until a relative error: fewer samples
 * underestimate the variance of heavy-tailed pixels (a firefly not yet seen). */
#define REL_ERROR_FIRST_SPP 16u

/* What the cached reference was rendered from: the scene file (path and
 * modification time), the budget, the seed and the size; one line. */
static void reference_key(const ss_compare_options *o, const ss_scene *scene, char *key,
                          size_t size) {
  struct stat sb;
  long long mtime = stat(o->scene, &sb) == 0 ? (long long)sb.st_mtime : 0;
  snprintf(key, size,
           "scene %s mtime %lld spp %d time %.17g rel_error %.17g seed %llu size %d x %d\n",
           o->scene, mtime, o->ref_spp, o->ref_time, o->ref_rel_error,
           o->has_seed ? o->seed : (unsigned long long)scene->render.seed, scene->camera.width,
           scene->camera.height);
}

/* The cached reference when DIR/reference.key starts with `key` (and says
 * what it reached), else NULL. */
static ss_image *cached_reference(ss_compare_options *o, const char *key, const ss_scene *scene) {
  char path[SS_PATH_SIZE + 32], text[SS_PATH_SIZE + 512] = "";
  snprintf(path, sizeof path, "%s/reference.key", o->dir);
  FILE *f = fopen(path, "r");
  if (!f) {
    return NULL;
  }
  size_t n = fread(text, 1, sizeof text - 1, f);
  fclose(f);
  text[n] = '\0';
  size_t len = strlen(key);
  ss_compare_reference *r = &o->ref;
  if (strncmp(text, key, len) || sscanf(text + len, "reached spp %u seconds %lf rel_error %lf",
                                        &r->spp, &r->seconds, &r->rel_error) != 3) {
    return NULL;
  }
  ss_image *img = NULL;
  ss_error err;
  snprintf(path, sizeof path, "%s/reference.exr", o->dir);
  if (ss_image_read(path, &img, &err) != SS_OK) {
    return NULL;
  }
  if (img->width != scene->camera.width || img->height != scene->camera.height ||
      img->channels < 3) {
    ss_image_destroy(img);
    return NULL;
  }
  return img;
}

/* The film's relative standard error over the mask (image_metrics.h). */
static ss_status film_rel_error(const ss_film *film, const ss_image *mask, double *out,
                                ss_error *err) {
  ss_image *img = ss_film_image(film), *var = ss_film_variance_image(film);
  ss_status st = img && var ? ss_image_rel_std_error(img, var, mask, out, err)
                            : ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for an image");
  ss_image_destroy(img);
  ss_image_destroy(var);
  return st;
}

/* Renders the reference film: --reference-spp or --reference-time in one
 * go, or --reference-rel-error in passes of doubling spp (16, 32, ...) until
 * the estimated relative standard error is below it in two passes in a row
 * (the estimate of one pass can be low by chance or for want of a rare
 * large sample; an honest one falls by sqrt(2) from pass to pass). */
static ss_status render_film(const ss_compare_options *o, const ss_scene *scene,
                             const ss_image *mask, ss_film **film, ss_compare_reference *r,
                             ss_error *err) {
  ss_render_options ro;
  ss_compare_render_options(scene, o, &ro);
  /* Its own seed, so that its noise is independent of the volpath method's. */
  ro.seed += 0x9e3779b97f4a7c15ULL;
  ro.time_limit = o->ref_time;
  unsigned spp = o->ref_rel_error > 0.0 ? REL_ERROR_FIRST_SPP
                 : o->ref_time > 0.0    ? 1u << 30
                                        : (unsigned)o->ref_spp;
  for (int below = 0;;) {
    ro.spp = (int)spp;
    ro.resume = *film;
    *film = NULL;
    ss_render_stats stats;
    ss_status st = ss_render(scene, &ro, film, &stats, err);
    st = ss_compare_pass_end(st, *film, &stats, err);
    if (st == SS_OK && ss_mpi_rank() == 0) {
      r->seconds += stats.seconds;
      r->spp = stats.min_spp;
      st = film_rel_error(*film, mask, &r->rel_error, err);
    }
    st = ss_compare_agree(st, err);
    /* Rank 0 alone holds the whole film: its count holds for all. */
    below = ss_mpi_any(ss_mpi_rank() == 0 && st == SS_OK && r->rel_error < o->ref_rel_error)
                ? below + 1
                : 0;
    if (st != SS_OK || !(o->ref_rel_error > 0.0) || below == 2) {
      return st;
    }
    if (spp >= 1u << 24) {
      return ss_error_set(err, SS_ERR_UNSUPPORTED,
                          "--reference-rel-error %g: not reached at %u spp (relative error %.3g)",
                          o->ref_rel_error, spp, r->rel_error);
    }
    if (!o->quiet) {
      printf("reference: %u spp, %.2f s, relative error %.3g\n", r->spp, r->seconds, r->rel_error);
      fflush(stdout);
    }
    spp *= 2;
  }
}

/* Writes DIR/reference.key: the settings line, then what was reached. */
static ss_status write_key(const ss_compare_options *o, const char *key, ss_error *err) {
  char path[SS_PATH_SIZE + 32];
  snprintf(path, sizeof path, "%s/reference.key", o->dir);
  ss_text_buf b = {0};
  ss_text_printf(&b, "%sreached spp %u seconds %.17g rel_error %.17g\n", key, o->ref.spp,
                 o->ref.seconds, o->ref.rel_error);
  ss_status st = ss_text_save(&b, path, SS_FILE_REFERENCE_KEY, err);
  ss_text_free(&b);
  return st;
}

static void rendered_reference(ss_compare_reference *r) {
  memset(r, 0, sizeof *r);
  r->file = "reference.exr";
  r->rendered = 1;
}

ss_status ss_compare_render_reference(ss_compare_options *o, const ss_scene *loaded,
                                      const ss_image *mask, ss_image **out, ss_error *err) {
  char key[SS_PATH_SIZE + 256];
  rendered_reference(&o->ref);
  reference_key(o, loaded, key, sizeof key);
  /* Rank 0 alone reads and writes the folder (and says whether it reuses). */
  if (ss_mpi_any(ss_mpi_rank() == 0 && (*out = cached_reference(o, key, loaded)) != NULL)) {
    if (!o->quiet) {
      printf("reference: reusing %s/reference.exr\n", o->dir);
    }
    return SS_OK;
  }
  rendered_reference(&o->ref);
  ss_scene *scene = ss_compare_load_scene(o->scene, err);
  if (!scene) {
    return SS_ERR_PARSE;
  }
  snprintf(scene->integrator.name, sizeof scene->integrator.name, "volpath");
  ss_film *film = NULL;
  ss_status st = render_film(o, scene, mask, &film, &o->ref, err);
  if (ss_mpi_rank() != 0) {
    ss_film_destroy(film);
    ss_scene_destroy(scene);
    return st;
  }
  if (st == SS_OK && !(*out = ss_film_image(film))) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the reference image");
  }
  if (st == SS_OK) {
    st = ss_compare_write_images(o->dir, "reference", *out, scene->render.exposure, err);
  }
  if (st == SS_OK) {
    st = write_key(o, key, err);
  }
  if (!o->quiet && st == SS_OK) {
    printf("reference: volpath, %u spp, %.2f s, relative error %.3g -> %s/reference.exr\n",
           o->ref.spp, o->ref.seconds, o->ref.rel_error, o->dir);
  }
  ss_film_destroy(film);
  ss_scene_destroy(scene);
  return st;
}

ss_image *ss_compare_read_reference(const ss_compare_options *o, const ss_scene *scene) {
  ss_image *img = NULL;
  ss_error err;
  if (ss_image_read(o->reference, &img, &err) != SS_OK) {
    fprintf(stderr, "subsurf " CMD ": --reference: %s\n", err.message);
    return NULL;
  }
  if (img->width != scene->camera.width || img->height != scene->camera.height ||
      img->channels < 3) {
    fprintf(stderr,
            "subsurf " CMD ": --reference: '%s' is %d x %d with %d channels, expected the scene's "
            "%d x %d RGB\n",
            o->reference, img->width, img->height, img->channels, scene->camera.width,
            scene->camera.height);
    ss_image_destroy(img);
    return NULL;
  }
  return img;
}
