#include "subsurf/halfspace.h"

#include "subsurf/batch_runner.h"
#include "subsurf/fresnel.h"
#include "subsurf/microflake.h"
#include "subsurf/rng.h"
#include "subsurf/sampling.h"
#include "subsurf/stats.h"
#include "subsurf/table_index.h"
#include "subsurf/threads.h"
#include "subsurf/walk.h"

#include "optics/microflake_sample.h"
#include "transport/batch_stop.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* Weight below which Russian roulette plays, relative to the entering weight;
 * survivors continue with exactly this weight (unbiased: E[w'] = w). */
#define RR_THRESHOLD 0.1
/* Paths between two checks of the time limit and the cancel flag. */
#define CHECK_INTERVAL 64

/* Tally layout inside one flat array of doubles. */
enum { T_REFLECT, T_TRANSMIT, T_ABSORB, T_TRUNCATE, T_SPECULAR, T_SCALARS };

typedef struct {
  const ss_halfspace_params *p;
  ss_phase phase;
  double sigma_t, albedo, eta;
  /* Micro-flake media: extinction and albedo depend on the direction of
   * travel; density = a rho (microflake.h). */
  int has_flakes;
  ss_microflake flakes;
  double density;
  ss_vec3 entry_dir;         /* propagation direction just below the surface */
  double entry_weight;       /* 1 - Fr at entry */
  double log_rmin, log_step; /* radial bins 1.. are log-spaced */
  size_t off_radial, off_dirs, off_map, nbins;
  /* Per outgoing direction: the internal direction that refracts into it. */
  int dir_ok[SS_HALFSPACE_MAX_DIRECTIONS];
  double dir_sin_t[SS_HALFSPACE_MAX_DIRECTIONS], dir_cos_t[SS_HALFSPACE_MAX_DIRECTIONS];
  double dir_fr[SS_HALFSPACE_MAX_DIRECTIONS]; /* internal Fresnel at cos_t */
  /* sigma_t / cos_t along the internal direction going up and its mirror
   * image going down (they differ in an oriented micro-flake medium). */
  double dir_rate_up[SS_HALFSPACE_MAX_DIRECTIONS], dir_rate_down[SS_HALFSPACE_MAX_DIRECTIONS];
  double dir_factor[SS_HALFSPACE_MAX_DIRECTIONS]; /* (1 - Fr) / (eta^2 cos_t) */
} tracer;

void ss_halfspace_params_default(ss_halfspace_params *p) {
  memset(p, 0, sizeof *p);
  p->medium = ss_medium_optics_gray(1.0, 0.01, 0.0, SS_PHASE_ISOTROPIC);
  p->channel = 0;
  p->eta = 1.0;
  p->theta_i = 0.0;
  p->thickness = INFINITY;
  p->width = INFINITY;
  p->paths = 1000000;
  p->seed = 0;
  p->max_depth = 1000000;
  p->rmin = 0.01;
  p->rmax = 10.0;
  p->rbins = 64;
  p->xmin = -5.0;
  p->xmax = 5.0;
  p->xbins = 100;
  p->ymin = -5.0;
  p->ymax = 5.0;
  p->ybins = 100;
}

static int in_range(double x, double lo, double hi) { return x >= lo && x <= hi; }

static ss_status validate_medium(const ss_halfspace_params *p, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  if (p->channel < 0 || p->channel > 2) {
    return ss_error_set(err, bad, "channel must be 0, 1 or 2 (got %d)", p->channel);
  }
  const double cmax = SS_HALFSPACE_MAX_COEFF, lmax = SS_HALFSPACE_MAX_LENGTH;
  double sigma_s = p->medium.sigma_s.c[p->channel], sigma_a = p->medium.sigma_a.c[p->channel];
  if (!in_range(sigma_s, 0.0, cmax)) {
    return ss_error_set(err, bad, "sigma-s must be in [0, %g] (got %g)", cmax, sigma_s);
  }
  if (!in_range(sigma_a, 0.0, cmax)) {
    return ss_error_set(err, bad, "sigma-a must be in [0, %g] (got %g)", cmax, sigma_a);
  }
  if (!(sigma_s + sigma_a >= SS_HALFSPACE_MIN_SIGMA_T)) {
    return ss_error_set(err, bad, "sigma-s + sigma-a must be >= %g (the medium must interact)",
                        SS_HALFSPACE_MIN_SIGMA_T);
  }
  ss_phase phase;
  ss_error perr;
  if (ss_phase_init(&phase, p->medium.phase, p->medium.g.c[p->channel], &perr) != SS_OK) {
    return ss_error_set(err, bad, "g: %s", perr.message);
  }
  if (ss_medium_flakes_check(&p->medium.flakes, &perr) != SS_OK) {
    return ss_error_set(err, bad, "%s", perr.message);
  }
  if (p->medium.flakes.type != SS_FLAKE_NONE && p->medium.g.c[p->channel] != 0.0) {
    return ss_error_set(err, bad,
                        "g: a micro-flake medium scatters by its flakes, not by a phase "
                        "function with g (got g %g)",
                        p->medium.g.c[p->channel]);
  }
  if (!in_range(p->eta, SS_HALFSPACE_ETA_MIN, SS_HALFSPACE_ETA_MAX)) {
    return ss_error_set(err, bad, "eta must be in [%g, %g] (got %g)", SS_HALFSPACE_ETA_MIN,
                        SS_HALFSPACE_ETA_MAX, p->eta);
  }
  if (!isfinite(p->theta_i) || p->theta_i < 0.0 || p->theta_i >= 0.5 * SS_PI) {
    return ss_error_set(err, bad, "theta-i must be in [0, 90) degrees (got %g)",
                        p->theta_i * 180.0 / SS_PI);
  }
  if (!(p->thickness > 0.0) || (isfinite(p->thickness) && p->thickness > lmax)) {
    return ss_error_set(err, bad, "thickness must be in (0, %g] or inf (got %g)", lmax,
                        p->thickness);
  }
  if (!(p->width > 0.0) || (isfinite(p->width) && p->width > lmax)) {
    return ss_error_set(err, bad, "width must be in (0, %g] or inf (got %g)", lmax, p->width);
  }
  if (isfinite(p->width) && p->n_theta_o > 0) {
    return ss_error_set(err, bad, "exact outgoing directions need an unbounded width");
  }
  if (!(p->spot_radius >= 0.0) || !(p->spot_radius < 0.5 * p->width)) {
    return ss_error_set(err, bad, "spot radius must be in [0, width / 2) (got %g, width %g)",
                        p->spot_radius, p->width);
  }
  if (p->spot_radius > 0.0 && p->theta_i != 0.0) {
    return ss_error_set(err, bad, "theta-i must be 0 with a diffuse spot (it has no direction)");
  }
  return SS_OK;
}

static ss_status validate_run(const ss_halfspace_params *p, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  if (p->paths == 0) {
    return ss_error_set(err, bad, "paths must be >= 1");
  }
  if (!in_range(p->time_limit, 0.0, 1e9)) {
    return ss_error_set(err, bad, "time-limit must be in [0, 1e9] seconds (got %g)", p->time_limit);
  }
  if (ss_threads_check(p->threads, err) != SS_OK) {
    return bad;
  }
  if (p->max_depth == 0) {
    return ss_error_set(err, bad, "max-depth must be >= 1");
  }
  if (p->batch_stride < 0 || p->batch_offset < 0 ||
      (p->batch_stride > 1 && p->batch_offset >= p->batch_stride)) {
    return ss_error_set(err, bad, "batch_offset must be in [0, batch_stride) (got %d, %d)",
                        p->batch_offset, p->batch_stride);
  }
  return SS_OK;
}

/* Both ends of a bin range within the length limit, lo < hi. */
static int range_ok(double lo, double hi) {
  const double l = SS_HALFSPACE_MAX_LENGTH;
  return in_range(lo, -l, l) && in_range(hi, -l, l) && lo < hi;
}

static ss_status validate_bins(const ss_halfspace_params *p, ss_error *err) {
  const ss_status bad = SS_ERR_INVALID_ARGUMENT;
  if (!(p->rmin > 0.0) || !range_ok(p->rmin, p->rmax)) {
    return ss_error_set(err, bad,
                        "rmax: radial bins need 0 < rmin < rmax <= %g (got rmin %g, "
                        "rmax %g)",
                        SS_HALFSPACE_MAX_LENGTH, p->rmin, p->rmax);
  }
  if (p->rbins < 2 || p->rbins > SS_HALFSPACE_MAX_BINS) {
    return ss_error_set(err, bad, "rbins must be in [2, %d] (got %d)", SS_HALFSPACE_MAX_BINS,
                        p->rbins);
  }
  /* Log-spaced bins narrower than this collapse in floating point. */
  if (!(log(p->rmax / p->rmin) / (p->rbins - 1) >= 1e-9)) {
    return ss_error_set(err, bad,
                        "rmax: %d radial bins between rmin %g and rmax %g are "
                        "narrower than 1e-9 relative width",
                        p->rbins, p->rmin, p->rmax);
  }
  if (p->n_theta_o < 0 || p->n_theta_o > SS_HALFSPACE_MAX_DIRECTIONS) {
    return ss_error_set(err, bad, "theta-o: at most %d directions", SS_HALFSPACE_MAX_DIRECTIONS);
  }
  for (int i = 0; i < p->n_theta_o; ++i) {
    if (!isfinite(p->theta_o[i]) || fabs(p->theta_o[i]) >= 0.5 * SS_PI) {
      return ss_error_set(err, bad, "theta-o must be in (-90, 90) degrees (got %g)",
                          p->theta_o[i] * 180.0 / SS_PI);
    }
  }
  if (!range_ok(p->xmin, p->xmax)) {
    return ss_error_set(err, bad, "xmax: x bins need -%g <= xmin < xmax <= %g (got %g, %g)",
                        SS_HALFSPACE_MAX_LENGTH, SS_HALFSPACE_MAX_LENGTH, p->xmin, p->xmax);
  }
  if (!range_ok(p->ymin, p->ymax)) {
    return ss_error_set(err, bad, "ymax: y bins need -%g <= ymin < ymax <= %g (got %g, %g)",
                        SS_HALFSPACE_MAX_LENGTH, SS_HALFSPACE_MAX_LENGTH, p->ymin, p->ymax);
  }
  const int nmax = SS_HALFSPACE_MAX_BINS;
  if (p->xbins < 1 || p->xbins > nmax || p->ybins < 1 || p->ybins > nmax ||
      (p->want_map && (double)p->xbins * p->ybins > 1.6e7)) {
    return ss_error_set(err, bad,
                        "xbins and ybins must be in [1, %d] with at most "
                        "1.6e7 map cells (got %d x %d)",
                        nmax, p->xbins, p->ybins);
  }
  return SS_OK;
}

ss_status ss_halfspace_validate(const ss_halfspace_params *p, ss_error *err) {
  ss_status st = validate_medium(p, err);
  if (st == SS_OK) {
    st = validate_run(p, err);
  }
  return st == SS_OK ? validate_bins(p, err) : st;
}

/* A propagation direction in the frame the walk samples in: the flakes' axis
 * frame (their sampler and tables work there), else the world. `flakes` is
 * tr->has_flakes, a constant where trace_path is inlined. */
static inline ss_vec3 walk_frame(const tracer *tr, int flakes, ss_vec3 w) {
  return flakes ? ss_frame_to_local(tr->flakes.frame, w) : w;
}

/* sigma_t along the propagation direction wl (walk_frame's). */
static inline double extinction(const tracer *tr, int flakes, ss_vec3 wl) {
  return flakes ? tr->density * ss_microflake_table_at(tr->flakes.sigma_t, wl.z) : tr->sigma_t;
}

/* The probability of surviving a collision while travelling along wl. */
static inline double collision_albedo(const tracer *tr, int flakes, ss_vec3 wl) {
  return flakes ? ss_microflake_collision_albedo_at(&tr->flakes, wl.z) : tr->albedo;
}

/* The phase function from propagation direction w_in to w_out. */
static inline double phase_toward(const tracer *tr, ss_vec3 w_in, ss_vec3 w_out) {
  return tr->has_flakes ? ss_microflake_phase_eval(&tr->flakes, w_in, w_out)
                        : ss_phase_eval(&tr->phase, ss_vec3_dot(w_in, w_out));
}

static void tracer_init(tracer *tr, const ss_halfspace_params *p) {
  memset(tr, 0, sizeof *tr);
  tr->p = p;
  double sigma_s = p->medium.sigma_s.c[p->channel], sigma_a = p->medium.sigma_a.c[p->channel];
  ss_phase_init(&tr->phase, p->medium.phase, p->medium.g.c[p->channel], NULL);
  tr->sigma_t = sigma_s + sigma_a;
  tr->albedo = sigma_s / tr->sigma_t;
  tr->eta = p->eta;
  tr->has_flakes = p->medium.flakes.type != SS_FLAKE_NONE;
  if (tr->has_flakes) {
    /* Validated with the medium: the tables are built here. */
    ss_microflake_init_medium(&tr->flakes, &p->medium.flakes, tr->albedo, NULL);
    tr->density = 2.0 * tr->sigma_t;
  }
  /* Snell's law at entry; the beam travels toward +x. */
  double sin_i = sin(p->theta_i), cos_i = cos(p->theta_i);
  double sin_t = sin_i / p->eta, cos_t = sqrt(fmax(0.0, 1.0 - sin_t * sin_t));
  tr->entry_dir = ss_vec3_make(sin_t, 0.0, -cos_t);
  tr->entry_weight = 1.0 - ss_fresnel_dielectric(cos_i, p->eta);
  tr->log_rmin = log(p->rmin);
  tr->log_step = (log(p->rmax) - tr->log_rmin) / (p->rbins - 1);
  tr->off_radial = T_SCALARS;
  tr->off_dirs = tr->off_radial + (size_t)p->rbins;
  tr->off_map = tr->off_dirs + (size_t)p->n_theta_o * (size_t)p->xbins;
  tr->nbins = tr->off_map + (p->want_map ? (size_t)p->xbins * (size_t)p->ybins : 0);
  for (int k = 0; k < p->n_theta_o; ++k) {
    double st = sin(p->theta_o[k]) / p->eta;
    tr->dir_ok[k] = fabs(st) < 1.0;
    if (!tr->dir_ok[k]) {
      continue; /* no internal direction refracts into theta_o (eta < 1) */
    }
    double ct = sqrt(1.0 - st * st);
    tr->dir_sin_t[k] = st;
    tr->dir_cos_t[k] = ct;
    tr->dir_fr[k] = ss_fresnel_dielectric(-ct, p->eta);
    /* Power of intensity I leaving toward the exact direction: int L_o dA =
     * I (1 - Fr) / (eta^2 cos_t) (radiance / n^2 is conserved across a
     * smooth boundary; solid angles compress by cos_o / (eta^2 cos_t)). */
    tr->dir_factor[k] = (1.0 - tr->dir_fr[k]) / (p->eta * p->eta * ct);
    ss_vec3 up = walk_frame(tr, tr->has_flakes, ss_vec3_make(st, 0.0, ct));
    ss_vec3 down = walk_frame(tr, tr->has_flakes, ss_vec3_make(st, 0.0, -ct));
    tr->dir_rate_up[k] = extinction(tr, tr->has_flakes, up) / ct;
    tr->dir_rate_down[k] = extinction(tr, tr->has_flakes, down) / ct;
  }
}

static int radial_bin(const tracer *tr, double r) {
  if (r < tr->p->rmin) {
    return 0;
  }
  double b = (log(r) - tr->log_rmin) / tr->log_step;
  return b < tr->p->rbins - 1 ? 1 + ss_table_cell_clamped(b, tr->p->rbins - 1) : -1;
}

static int linear_bin(double x, double lo, double hi, int n) {
  if (!(x >= lo) || !(x < hi)) {
    return -1;
  }
  return ss_table_cell_clamped((x - lo) / (hi - lo) * n, n);
}

/* Next-event estimation toward each exact outgoing direction from a
 * scattering event at `pos` with incoming propagation direction `dir` and
 * scattered power `w`. In a slab, light may also reach the top after
 * specular bounces between the faces: those images are summed too. */
static void tally_directions(const tracer *tr, double *t, ss_vec3 pos, ss_vec3 dir, double w) {
  const ss_halfspace_params *p = tr->p;
  double depth = -pos.z, d = p->thickness;
  for (int k = 0; k < p->n_theta_o; ++k) {
    if (!tr->dir_ok[k]) {
      continue;
    }
    double st = tr->dir_sin_t[k], ct = tr->dir_cos_t[k], fr = tr->dir_fr[k];
    double tan_t = st / ct, rate_up = tr->dir_rate_up[k], rate_down = tr->dir_rate_down[k];
    double base = w * tr->dir_factor[k];
    double *row = t + tr->off_dirs + (size_t)k * (size_t)p->xbins;
    /* Up first: up depth + j d, down j d, with Fr^(2j). */
    double up = base * phase_toward(tr, dir, ss_vec3_make(st, 0.0, ct));
    double down = base * phase_toward(tr, dir, ss_vec3_make(st, 0.0, -ct));
    for (int j = 0;; ++j) {
      double travel = j == 0 ? depth : depth + 2.0 * j * d; /* d may be infinite */
      double v =
          up * exp(-(j == 0 ? rate_up * depth : rate_up * (depth + j * d) + rate_down * (j * d)));
      int b = linear_bin(pos.x + tan_t * travel, p->xmin, p->xmax, p->xbins);
      if (b >= 0) {
        row[b] += v;
      }
      if (!isfinite(d) || fr == 0.0) {
        break;
      }
      /* Down first: down (d - depth) + j d, then up d + j d. */
      double travel_down = (d - depth) + d + 2.0 * j * d;
      double vd = down * fr * exp(-(rate_down * (d - depth + j * d) + rate_up * (d + j * d)));
      b = linear_bin(pos.x + tan_t * travel_down, p->xmin, p->xmax, p->xbins);
      if (b >= 0) {
        row[b] += vd;
      }
      up *= fr * fr;
      down *= fr * fr;
      if (v + vd < 1e-14 * base) {
        break;
      }
    }
  }
}

/* A diffuse spot's entry (Jakob2010 sec. 7, the finite-element validation): a uniform point of the
 * disc, a cosine-distributed incident direction (Lambertian irradiance),
 * refracted by Snell's law; returns the transmitted weight 1 - Fr. */
static double spot_entry(const tracer *tr, ss_rng *rng, ss_vec3 *pos, ss_vec3 *dir) {
  double u = ss_rng_uniform(rng), v = ss_rng_uniform(rng);
  double r = tr->p->spot_radius * sqrt(u), phi = 2.0 * SS_PI * v;
  *pos = ss_vec3_make(r * cos(phi), r * sin(phi), 0.0);
  ss_vec3 in = ss_sample_cosine_hemisphere(ss_rng_uniform(rng), ss_rng_uniform(rng));
  double sin_i = sqrt(fmax(0.0, 1.0 - in.z * in.z)), sin_t = sin_i / tr->eta;
  double cos_t = sqrt(fmax(0.0, 1.0 - sin_t * sin_t)), k = sin_i > 0.0 ? sin_t / sin_i : 0.0;
  *dir = ss_vec3_make(in.x * k, in.y * k, -cos_t);
  return 1.0 - ss_fresnel_dielectric(in.z, tr->eta);
}

/* Traces one path into the batch tallies `t`; returns its scattering events.
 * Inlined once for each value of `flakes` (tr->has_flakes), so that neither
 * walk is compiled around the other's sampler. */
static inline __attribute__((always_inline)) uint64_t trace_path(const tracer *tr, int flakes,
                                                                 ss_rng *rng, double *t) {
  const ss_halfspace_params *p = tr->p;
  const double eta = tr->eta;
  const double bottom = -p->thickness, half = 0.5 * p->width;
  ss_vec3 pos = ss_vec3_make(0.0, 0.0, 0.0), dir = tr->entry_dir;
  double w = tr->entry_weight;
  if (p->spot_radius > 0.0) {
    w = spot_entry(tr, rng, &pos, &dir);
    t[T_SPECULAR] += 1.0 - w;
  }
  const double w_rr = RR_THRESHOLD * w;
  uint64_t events = 0;
  /* The direction also in walk_frame: from one event to the next, the
   * flakes' walk changes no frame on the way (dir follows from dl). */
  ss_vec3 dl = walk_frame(tr, flakes, dir);
  for (;;) {
    double s = ss_walk_free_flight(rng, extinction(tr, flakes, dl));
    int axis = 2; /* of the face reached first: 0, 1 sides, 2 top or bottom */
    double s_boundary =
        dir.z > 0.0 ? -pos.z / dir.z : (dir.z < 0.0 ? (bottom - pos.z) / dir.z : INFINITY);
    for (int a = 0; a < 2 && half < INFINITY; ++a) {
      double d = a ? dir.y : dir.x, x = a ? pos.y : pos.x;
      double sa = d > 0.0 ? (half - x) / d : (d < 0.0 ? (-half - x) / d : INFINITY);
      if (sa < s_boundary) {
        s_boundary = sa;
        axis = a;
      }
    }
    if (s >= s_boundary) {
      pos = ss_vec3_madd(pos, dir, s_boundary);
      double *dc = axis == 0 ? &dir.x : (axis == 1 ? &dir.y : &dir.z);
      double *pc = axis == 0 ? &pos.x : (axis == 1 ? &pos.y : &pos.z);
      int top = axis == 2 && dir.z > 0.0;
      *pc = axis == 2 ? (top ? 0.0 : bottom) : copysign(half, *dc);
      double fr = eta == 1.0 ? 0.0 : ss_fresnel_dielectric(-fabs(*dc), eta);
      if (fr > 0.0 && ss_rng_uniform(rng) < fr) {
        *dc = -*dc;
        dl = walk_frame(tr, flakes, dir);
        continue;
      }
      if (!top) {
        t[T_TRANSMIT] += w;
        return events;
      }
      t[T_REFLECT] += w;
      int rb = radial_bin(tr, hypot(pos.x, pos.y));
      if (rb >= 0) {
        t[tr->off_radial + (size_t)rb] += w;
      }
      if (p->want_map) {
        int bx = linear_bin(pos.x, p->xmin, p->xmax, p->xbins);
        int by = linear_bin(pos.y, p->ymin, p->ymax, p->ybins);
        if (bx >= 0 && by >= 0) {
          t[tr->off_map + (size_t)by * (size_t)p->xbins + (size_t)bx] += w;
        }
      }
      return events;
    }
    pos = ss_vec3_madd(pos, dir, s);
    if (events == p->max_depth) {
      t[T_TRUNCATE] += w; /* it would scatter a (max_depth + 1)-th time */
      return events;
    }
    ++events;
    double albedo = collision_albedo(tr, flakes, dl);
    t[T_ABSORB] += w * (1.0 - albedo);
    w *= albedo;
    if (p->n_theta_o > 0) {
      tally_directions(tr, t, pos, dir, w);
    }
    if (w < w_rr) {
      if (ss_rng_uniform(rng) * w_rr >= w) {
        return events;
      }
      w = w_rr;
    }
    if (flakes) {
      dl = ss_microflake_sample_phase_local(&tr->flakes, dl, rng);
      dir = ss_frame_to_world(tr->flakes.frame, dl);
    } else {
      dir = dl = ss_walk_scatter(&tr->phase, dir, rng);
    }
  }
}

/* Fixed batches (independent of the thread count): at most 1024 of them. */
static uint64_t batch_size_for(uint64_t paths) {
  uint64_t b = (paths + 1023) / 1024;
  return b < 16 ? 16 : b;
}

ss_status ss_halfspace_result_create(const ss_halfspace_params *p, ss_halfspace_result **out,
                                     ss_error *err) {
  ss_halfspace_result *r = calloc(1, sizeof *r);
  if (!r) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the half-space result");
  }
  r->rbins = p->rbins;
  r->xbins = p->xbins;
  r->ybins = p->ybins;
  r->n_theta_o = p->n_theta_o;
  memcpy(r->theta_o, p->theta_o, sizeof r->theta_o);
  r->r_lo = malloc((size_t)p->rbins * sizeof *r->r_lo);
  r->r_hi = malloc((size_t)p->rbins * sizeof *r->r_hi);
  r->radial = calloc((size_t)p->rbins, sizeof *r->radial);
  r->x_lo = malloc((size_t)p->xbins * sizeof *r->x_lo);
  r->x_hi = malloc((size_t)p->xbins * sizeof *r->x_hi);
  r->y_lo = malloc((size_t)p->ybins * sizeof *r->y_lo);
  r->y_hi = malloc((size_t)p->ybins * sizeof *r->y_hi);
  r->directions = calloc((size_t)p->n_theta_o * (size_t)p->xbins + 1, sizeof *r->directions);
  if (p->want_map) {
    r->map = calloc((size_t)p->xbins * (size_t)p->ybins, sizeof *r->map);
  }
  if (!r->r_lo || !r->r_hi || !r->radial || !r->x_lo || !r->x_hi || !r->y_lo || !r->y_hi ||
      !r->directions || (p->want_map && !r->map)) {
    ss_halfspace_result_destroy(r);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for the half-space result");
  }
  double step = (log(p->rmax) - log(p->rmin)) / (p->rbins - 1);
  for (int i = 0; i < p->rbins; ++i) {
    r->r_lo[i] = i == 0 ? 0.0 : p->rmin * exp(step * (i - 1));
    r->r_hi[i] = p->rmin * exp(step * i);
  }
  for (int i = 0; i < p->xbins; ++i) {
    r->x_lo[i] = p->xmin + (p->xmax - p->xmin) * i / p->xbins;
    r->x_hi[i] = p->xmin + (p->xmax - p->xmin) * (i + 1) / p->xbins;
  }
  for (int i = 0; i < p->ybins; ++i) {
    r->y_lo[i] = p->ymin + (p->ymax - p->ymin) * i / p->ybins;
    r->y_hi[i] = p->ymin + (p->ymax - p->ymin) * (i + 1) / p->ybins;
  }
  *out = r;
  return SS_OK;
}

static ss_estimate scaled(const ss_batch_tally *t, size_t bin, double k) {
  ss_estimate e = {ss_batch_tally_mean(t, bin) * k, ss_batch_tally_stderr(t, bin) * k};
  return e;
}

static void result_fill(const tracer *tr, const ss_batch_tally *t, ss_halfspace_result *r) {
  const ss_halfspace_params *p = tr->p;
  r->reflectance = scaled(t, T_REFLECT, 1.0);
  r->transmittance = scaled(t, T_TRANSMIT, 1.0);
  r->absorbed = scaled(t, T_ABSORB, 1.0);
  r->truncated = scaled(t, T_TRUNCATE, 1.0);
  if (p->spot_radius > 0.0) {
    r->specular = scaled(t, T_SPECULAR, 1.0);
  } else {
    r->specular.value = 1.0 - tr->entry_weight;
    r->specular.error = 0.0;
  }
  for (int i = 0; i < p->rbins; ++i) {
    double area = SS_PI * (r->r_hi[i] * r->r_hi[i] - r->r_lo[i] * r->r_lo[i]);
    r->radial[i] = scaled(t, tr->off_radial + (size_t)i, 1.0 / area);
  }
  double dx = (p->xmax - p->xmin) / p->xbins, dy = (p->ymax - p->ymin) / p->ybins;
  for (size_t i = 0; i < (size_t)p->n_theta_o * (size_t)p->xbins; ++i) {
    r->directions[i] = scaled(t, tr->off_dirs + i, 1.0 / dx);
  }
  if (p->want_map) {
    for (size_t i = 0; i < (size_t)p->xbins * (size_t)p->ybins; ++i) {
      r->map[i] = scaled(t, tr->off_map + i, 1.0 / (dx * dy));
    }
  }
}

typedef struct {
  const tracer *tr;
  uint64_t bsize;
  double t0;
  ss_batch_stop halt;
} run_state;

static uint64_t run_batch(void *ctx, int64_t batch, double *sums, uint64_t *events) {
  run_state *rs = ctx;
  const ss_halfspace_params *p = rs->tr->p;
  if (p->batch_stride > 1 && batch % p->batch_stride != p->batch_offset) {
    return p->batch_source ? p->batch_source(p->batch_ctx, batch, sums, rs->tr->nbins, events) : 0;
  }
  uint64_t first = (uint64_t)batch * rs->bsize;
  uint64_t count = p->paths - first < rs->bsize ? p->paths - first : rs->bsize;
  uint64_t traced = 0;
  for (; traced < count; ++traced) {
    if (traced % CHECK_INTERVAL == 0 &&
        ss_batch_stop_poll(&rs->halt, p->cancel,
                           p->time_limit > 0.0 && omp_get_wtime() - rs->t0 > p->time_limit)) {
      break;
    }
    ss_rng rng;
    ss_rng_seed_item(&rng, p->seed, first + traced);
    *events +=
        rs->tr->has_flakes ? trace_path(rs->tr, 1, &rng, sums) : trace_path(rs->tr, 0, &rng, sums);
  }
  if (p->batch_sink) {
    p->batch_sink(p->batch_ctx, batch, sums, rs->tr->nbins, traced, *events);
  }
  return traced;
}

static void on_merged(void *ctx, uint64_t done) {
  const run_state *rs = ctx;
  const ss_halfspace_params *p = rs->tr->p;
  if (p->progress) {
    p->progress(p->progress_ctx, done, p->paths);
  }
}

double ss_halfspace_bytes(const ss_halfspace_params *p) {
  tracer tr;
  tracer_init(&tr, p);
  /* Per bin: the merged tally's sum and sum of squares, and the result's
   * estimate (value and error). */
  return ss_batch_run_bytes(tr.nbins, p->threads) + 4.0 * sizeof(double) * (double)tr.nbins;
}

ss_status ss_halfspace_run(const ss_halfspace_params *p, ss_halfspace_result **out, ss_error *err) {
  *out = NULL;
  ss_status st = ss_halfspace_validate(p, err);
  if (st != SS_OK) {
    return st;
  }
  tracer tr;
  tracer_init(&tr, p);
  ss_halfspace_result *r = NULL;
  if ((st = ss_halfspace_result_create(p, &r, err)) != SS_OK) {
    return st;
  }
  ss_batch_tally tally;
  if (ss_batch_tally_init(&tally, tr.nbins) != 0) {
    ss_halfspace_result_destroy(r);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "out of memory for %zu tally bins", tr.nbins);
  }
  run_state rs;
  memset(&rs, 0, sizeof rs);
  rs.tr = &tr;
  rs.bsize = batch_size_for(p->paths);
  rs.t0 = omp_get_wtime();
  const int64_t nbatches = (int64_t)((p->paths + rs.bsize - 1) / rs.bsize);
  uint64_t events = 0;
  st = ss_batch_run(&tally, nbatches, p->threads, run_batch, on_merged, &rs, &events, err);
  if (st != SS_OK) {
    ss_batch_tally_free(&tally);
    ss_halfspace_result_destroy(r);
    return st;
  }
  uint64_t done = tally.paths;
  r->scatter_events = events;
  r->interrupted = rs.halt.interrupted;
  r->paths = done;
  r->seconds = omp_get_wtime() - rs.t0;
  r->partial = done < p->paths;
  result_fill(&tr, &tally, r);
  ss_batch_tally_free(&tally);
  *out = r;
  return SS_OK;
}

void ss_halfspace_result_destroy(ss_halfspace_result *r) {
  if (!r) {
    return;
  }
  free(r->r_lo);
  free(r->r_hi);
  free(r->radial);
  free(r->x_lo);
  free(r->x_hi);
  free(r->y_lo);
  free(r->y_hi);
  free(r->directions);
  free(r->map);
  free(r);
}
