/* The renderer reports progress through the caller's callback, one thread at
 * a time, up to the total, and never draws anything itself. */
#include "render/scene_builder.h"

#include <criterion/criterion.h>

#include "subsurf/render.h"
#include "subsurf/scene.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

static ss_scene *floor_under_sky(void) {
  ss_scene *s;
  ss_error err;
  cr_assert_eq(ss_scene_create(&s, &err), SS_OK);
  test_sphere_view(s, 16, 12);
  test_add_floor(s, 0.0);
  test_add_light(s, "sky", SS_LIGHT_ENVIRONMENT, -1, ss_rgb_gray(1.0));
  snprintf(s->integrator.name, sizeof s->integrator.name, "path");
  cr_assert_eq(ss_scene_commit(s, &err), SS_OK, "%s", err.message);
  return s;
}

typedef struct {
  int calls, inside, overlapped, decreased;
  uint64_t last, total;
} reports;

static void on_progress(void *ctx, uint64_t done, uint64_t total) {
  reports *r = ctx;
  int inside;
#pragma omp atomic capture
  inside = ++r->inside;
  r->overlapped |= inside != 1;
  r->decreased |= done < r->last;
  r->last = done;
  r->total = total;
  r->calls++;
#pragma omp atomic
  r->inside--;
}

Test(render_progress, thread_counts_beyond_the_limit_and_spp_beyond_its_own_are_refused) {
  ss_scene *s = floor_under_sky();
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error err;
  o.threads = 4097;
  cr_expect_eq(ss_render(s, &o, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "render: threads must be in [0, 4096] (got 4097)"), "%s",
            err.message);
  cr_expect_null(film);
  o.threads = 1;
  o.spp = SS_RENDER_MAX_SPP + 1;
  cr_expect_eq(ss_render(s, &o, &film, &stats, &err), SS_ERR_INVALID_ARGUMENT);
  cr_expect(strstr(err.message, "spp must be in [1, 1073741824]"), "%s", err.message);
  cr_expect_null(film);
  ss_scene_destroy(s);
}

Test(render_progress, reports_reach_the_total_one_thread_at_a_time_and_nothing_is_printed) {
  ss_scene *s = floor_under_sky();
  ss_render_options o;
  ss_render_options_from_scene(s, &o);
  o.spp = 4;
  o.threads = 2;
  const int crop[4] = {2, 1, 14, 11};
  memcpy(o.crop, crop, sizeof o.crop);
  reports r = {0};
  o.progress = on_progress;
  o.progress_ctx = &r;
  fflush(stderr);
  FILE *capture = tmpfile();
  cr_assert(capture != NULL);
  int saved = dup(STDERR_FILENO);
  cr_assert(dup2(fileno(capture), STDERR_FILENO) >= 0);
  ss_film *film = NULL;
  ss_render_stats stats;
  ss_error err;
  ss_status st = ss_render(s, &o, &film, &stats, &err);
  fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(saved);
  cr_assert_eq(st, SS_OK, "%s", err.message);
  cr_assert_eq(fseek(capture, 0, SEEK_END), 0);
  cr_expect_eq(ftell(capture), 0, "the library wrote to stderr");
  fclose(capture);
  uint64_t total = 4u * 12u * 10u;
  cr_expect_eq(r.total, total);
  cr_expect_eq(r.last, total, "last report %llu of %llu", (unsigned long long)r.last,
               (unsigned long long)total);
  cr_expect_gt(r.calls, 1);
  cr_expect_eq(r.overlapped, 0, "reports overlapped");
  cr_expect_eq(r.decreased, 0, "done decreased");
  ss_film_destroy(film);
  ss_scene_destroy(s);
}
