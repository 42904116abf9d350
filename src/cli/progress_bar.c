/* The CLI's progress bar (progress_bar.h). */
#include "cli/progress_bar.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define SS_PROGRESS_BAR_WIDTH 30
#define SS_PROGRESS_MIN_INTERVAL 0.1 /* seconds between redraws: at most 10/s */

/* "12.3 s" below a minute, then "4 min 05 s", then "2 h 07 min". */
static void format_duration(char *buf, size_t size, double s) {
  if (!(s >= 0.0)) {
    snprintf(buf, size, "?");
  } else if (s < 60.0) {
    snprintf(buf, size, "%.1f s", s);
  } else if (s < 3600.0) {
    long t = (long)s;
    snprintf(buf, size, "%ld min %02ld s", t / 60, t % 60);
  } else {
    long t = (long)(s / 60.0);
    snprintf(buf, size, "%ld h %02ld min", t / 60, t % 60);
  }
}

/* A time-limited run ends at whichever comes first, the work or the limit, so
 * the bar shows the larger of the two fractions and the remaining time the
 * smaller of the two estimates. */
static void draw(const ss_progress *p, uint64_t done, double now, int final) {
  double elapsed = now - p->start_seconds;
  double fraction = p->total > 0 ? (double)done / (double)p->total : 0.0;
  if (p->time_limit > 0.0 && elapsed / p->time_limit > fraction) {
    fraction = elapsed / p->time_limit;
  }
  if (fraction > 1.0 || (final && p->total > 0 && done >= p->total)) {
    fraction = 1.0;
  }
  double remaining = -1.0;
  if (done > 0 && p->total > 0) {
    remaining = done >= p->total ? 0.0 : elapsed * (double)(p->total - done) / (double)done;
  }
  if (p->time_limit > 0.0) {
    double left = p->time_limit - elapsed;
    left = left > 0.0 ? left : 0.0;
    if (remaining < 0.0 || left < remaining) {
      remaining = left;
    }
  }
  if (final) {
    remaining = 0.0;
  }
  char bar[SS_PROGRESS_BAR_WIDTH + 1];
  int filled = (int)(fraction * SS_PROGRESS_BAR_WIDTH);
  for (int i = 0; i < SS_PROGRESS_BAR_WIDTH; ++i) {
    bar[i] = i < filled ? '=' : (i == filled ? '>' : ' ');
  }
  bar[SS_PROGRESS_BAR_WIDTH] = '\0';
  char el[32], left[32];
  format_duration(el, sizeof el, elapsed);
  format_duration(left, sizeof left, remaining);
  /* \r returns to the start of the line, ESC[K erases what a longer previous
   * line left behind. */
  fprintf(stderr, "\r%s [%s] %3d%%  %s elapsed, %s left\033[K", p->label ? p->label : "", bar,
          (int)(100.0 * fraction), el, left);
  fflush(stderr);
}

void ss_progress_begin(ss_progress *p, const char *label, uint64_t total, int enabled,
                       double time_limit) {
  memset(p, 0, sizeof *p);
  p->label = label;
  p->total = total;
  p->enabled = enabled && isatty(STDERR_FILENO);
  p->time_limit = time_limit > 0.0 ? time_limit : 0.0;
  p->start_seconds = ss_seconds();
  p->last_draw_seconds = p->start_seconds - SS_PROGRESS_MIN_INTERVAL;
}

void ss_progress_update(ss_progress *p, uint64_t done) {
  if (!p->enabled) {
    return;
  }
  double now = ss_seconds(), last;
  /* Most calls come too soon after the last redraw: an atomic read lets them
   * return without queueing on the critical section. Inside it the check is
   * repeated, so exactly one of several racing threads draws. */
#pragma omp atomic read
  last = p->last_draw_seconds;
  if (now - last < SS_PROGRESS_MIN_INTERVAL) {
    return;
  }
#pragma omp critical(ss_progress_draw)
  {
#pragma omp atomic read
    last = p->last_draw_seconds;
    if (now - last >= SS_PROGRESS_MIN_INTERVAL) {
#pragma omp atomic write
      p->last_draw_seconds = now;
      draw(p, done, now, 0);
    }
  }
}

void ss_progress_report(void *ctx, uint64_t done, uint64_t total) {
  ss_progress *p = ctx;
  p->total = total;
  p->done = done;
  ss_progress_update(p, done);
}

void ss_progress_end(ss_progress *p, uint64_t done) {
  if (!p->enabled) {
    return;
  }
#pragma omp critical(ss_progress_draw)
  {
    double now = ss_seconds();
#pragma omp atomic write
    p->last_draw_seconds = now;
    draw(p, done, now, 1);
    fputc('\n', stderr);
    fflush(stderr);
  }
}
