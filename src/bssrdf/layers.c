/* Layered materials: multipole profiles of each layer combined by
 * Kubelka-Munk adding in 2D frequency space (DonnerJensen2005
 * sec. 4, eq. 14-15), with FFTW.
 *
 * | option             | meaning                                            |
 * |--------------------|----------------------------------------------------|
 * | layers             | sigma_s, sigma_a, g, eta (to the outside), d per   |
 * |                    | layer (bssrdf_layers.h); the last layer may be     |
 * |                    | semi-infinite (d = inf); default "skin": the three |
 * |                    | skin layers of DonnerJensen2005 Table 3 (mm^-1)    |
 * | sigma_s, sigma_a,  | ignored: the layers carry their own                |
 * | g, eta             |                                                    |
 *
 * For two slabs 1 over 2: R12 = R1 + T1 R2 T1 / (1 - R1 R2) and
 * T12 = T1 T2 / (1 - R1 R2), where products are 2D convolutions: pointwise
 * products of the Fourier transforms. Each face uses the boundary term A of
 * the relative index across it. The profiles live on an N x N grid of cell
 * masses (the profile integrated over each cell, so that energy is kept even
 * where a thin layer's peak is narrower than a cell); the result is averaged
 * over the cells of annuli one cell wide into the radial table that eval,
 * exitance and sampling use. The grid spans 12 diffusion lengths of the
 * slowest layer in each direction, so the radial resolution is
 * h = 24 / (512 sigma_tr,min) per channel: profiles are exact in total power
 * but smoothed over h near the entry point. S = (1/pi) Ft(eta_top, w_i) R(r) Ft(eta_top, w_o). */
#include "subsurf/bssrdf_layers.h"

#include "bssrdf/multipole.h"
#include "bssrdf/radial_model.h"

#include "subsurf/table_index.h"

#include <fftw3.h>
/* after fftw3.h, which would otherwise make fftw_complex a C99 complex */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GRID 512           /* cells per side */
#define GRID_HALF_WIDTH 12 /* grid half-width in units of the slowest 1/sigma_tr */
#define MAX_PAIRS 2000

typedef struct {
  double h;     /* cell width */
  int bins;     /* annuli of width h */
  double *refl; /* [bins] annulus-averaged R(r) */
  double *mass; /* [bins] power per annulus */
  double max_radius;
  ss_distribution1d dist;
} channel_table;

/* The radial model's mixture samplers stay empty: entry points are drawn
 * from the tabulated annulus masses instead. */
typedef struct {
  ss_radial_model base; /* total, transmit: the stack's R and T */
  channel_table ch[SS_BSSRDF_CHANNELS];
} layered;

static void layered_destroy(void *state) {
  layered *L = state;
  if (!L) {
    return;
  }
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    free(L->ch[c].refl);
    free(L->ch[c].mass);
    if (L->ch[c].dist.cdf) {
      ss_distribution1d_free(&L->ch[c].dist);
    }
  }
  free(L);
}

/* Periodic coordinate of grid index i. */
static double grid_coord(int i, double h) { return (i < GRID / 2 ? i : i - GRID) * h; }

/* 2 pi int_0^rho r P(r) dr of a multipole profile P (closed form). */
typedef double (*disk_fn)(const ss_multipole *m, double rho);

/* Cell masses of a radial profile: midpoint values times the cell area,
 * supersampled near the origin; the origin cell takes whatever the analytic
 * total leaves, so the grid carries exactly the profile's power. The profile
 * is first tabulated as averages over annuli h/8 wide, from its closed-form
 * disk integrals (a multipole may sum thousands of pairs): a peak narrower
 * than that (a source next to a face, T ~ 1/z^2 at r = 0) keeps its mass in
 * the first annulus instead of being sampled at a point. */
static ss_status fill_grid(double *g, const ss_multipole *m, disk_fn disk, double h, double cutoff,
                           ss_error *err) {
  const double dr = h / 8.0;
  double reach = fmin(cutoff, GRID * h);
  int n = (int)ceil(reach / dr) + 2;
  double *table = malloc((size_t)n * sizeof *table);
  if (!table) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "layers: out of memory");
  }
  double inner = 0.0;
  for (int j = 0; j < n; ++j) {
    double outer = disk(m, (j + 1) * dr);
    table[j] = (outer - inner) / (SS_PI * (2 * j + 1) * dr * dr);
    inner = outer;
  }
  const double total = disk(m, INFINITY);
  double sum = 0.0;
  for (int i = 0; i < GRID; ++i) {
    double x = grid_coord(i, h);
    for (int j = 0; j < GRID; ++j) {
      double y = grid_coord(j, h), v = 0.0;
      if (hypot(x, y) > reach) {
        g[i * GRID + j] = 0.0;
        continue;
      }
      const int s =
          abs(i < GRID / 2 ? i : i - GRID) <= 3 && abs(j < GRID / 2 ? j : j - GRID) <= 3 ? 8 : 1;
      for (int a = 0; a < s; ++a) {
        for (int b = 0; b < s; ++b) {
          double sx = x + ((a + 0.5) / s - 0.5) * h, sy = y + ((b + 0.5) / s - 0.5) * h;
          /* linear between annulus centres (k + 1/2) dr */
          double u = fmax(hypot(sx, sy) / dr - 0.5, 0.0);
          int k = ss_table_cell(u, n - 1);
          double val = k >= 0 ? table[k] + (u - k) * (table[k + 1] - table[k]) : 0.0;
          v += val * h * h / (s * s);
        }
      }
      g[i * GRID + j] = v;
      sum += v;
    }
  }
  free(table);
  sum -= g[0];
  g[0] = total - sum;
  return SS_OK;
}

typedef struct {
  double *grid;
  fftw_complex *R, *T, *Rk, *Tk;
  fftw_plan forward, backward;
  double *fwd_in, *bwd_out;
  fftw_complex *fwd_out, *bwd_in;
} workspace;

static void transform(workspace *w, fftw_complex *dst) {
  fftw_execute_dft_r2c(w->forward, w->grid, dst);
}

/* Combines the layers of one channel and tabulates the result. */
static ss_status build_channel(const ss_bssrdf_layer_stack *p, int c, workspace *w, layered *L,
                               ss_error *err) {
  channel_table *t = &L->ch[c];
  const int nc = GRID * (GRID / 2 + 1);
  double slowest = INFINITY;
  ss_multipole mp[SS_BSSRDF_MAX_LAYERS];
  double cutoff[SS_BSSRDF_MAX_LAYERS];
  for (int k = 0; k < p->layer_count; ++k) {
    const ss_bssrdf_layer *ly = &p->layers[k];
    ss_bssrdf_coeffs co = ss_bssrdf_coeffs_make(ly->sigma_s[c], ly->sigma_a[c], ly->g[c]);
    if (ly->thickness < 1.0 / co.sigma_t_prime) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "layers: layer %d thickness %g is below its source depth "
                          "1/sigma_t' = %g (channel %c)",
                          k, ly->thickness, 1.0 / co.sigma_t_prime, "RGB"[c]);
    }
    double eta_above = k == 0 ? 1.0 : p->layers[k - 1].eta;
    double eta_below = k + 1 < p->layer_count ? p->layers[k + 1].eta : 1.0;
    double A_top = ss_fresnel_A(ly->eta / eta_above), A_bot = ss_fresnel_A(ly->eta / eta_below);
    ss_multipole_setup(&mp[k], co, ly->thickness, A_top, A_bot, MAX_PAIRS);
    double rate = fmax(co.sigma_tr, 1e-3 * co.sigma_t_prime);
    slowest = fmin(slowest, rate);
    cutoff[k] = 40.0 / rate + 4.0 * ly->thickness * isfinite(ly->thickness);
  }
  double h = 2.0 * GRID_HALF_WIDTH / slowest / GRID;
  /* Bottom-up adding: (R, T) holds the stack below the current layer. */
  for (int k = p->layer_count - 1; k >= 0; --k) {
    ss_status st = fill_grid(w->grid, &mp[k], ss_multipole_reflectance_disk, h, cutoff[k], err);
    if (st != SS_OK) {
      return st;
    }
    transform(w, k == p->layer_count - 1 ? w->R : w->Rk);
    st = fill_grid(w->grid, &mp[k], ss_multipole_transmittance_disk, h, cutoff[k], err);
    if (st != SS_OK) {
      return st;
    }
    transform(w, k == p->layer_count - 1 ? w->T : w->Tk);
    if (k == p->layer_count - 1) {
      continue;
    }
    for (int i = 0; i < nc; ++i) {
      /* Donner & Jensen 2005, eq. 14-15 in the frequency domain. */
      double _Complex r1 = w->Rk[i][0] + I * w->Rk[i][1], t1 = w->Tk[i][0] + I * w->Tk[i][1];
      double _Complex r2 = w->R[i][0] + I * w->R[i][1], t2 = w->T[i][0] + I * w->T[i][1];
      double _Complex inv = 1.0 / (1.0 - r1 * r2);
      double _Complex rr = r1 + t1 * r2 * t1 * inv, tt = t1 * t2 * inv;
      w->R[i][0] = creal(rr);
      w->R[i][1] = cimag(rr);
      w->T[i][0] = creal(tt);
      w->T[i][1] = cimag(tt);
    }
  }
  L->base.total[c] = w->R[0][0];
  L->base.transmit[c] = w->T[0][0];
  fftw_execute_dft_c2r(w->backward, w->R, w->grid);
  t->h = h;
  t->bins = GRID / 2;
  t->refl = calloc((size_t)t->bins, sizeof *t->refl);
  t->mass = calloc((size_t)t->bins, sizeof *t->mass);
  if (!t->refl || !t->mass) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "layers: out of memory");
  }
  const double norm = 1.0 / ((double)GRID * GRID);
  int *cells = calloc((size_t)t->bins, sizeof *cells);
  if (!cells) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "layers: out of memory");
  }
  for (int i = 0; i < GRID; ++i) {
    for (int j = 0; j < GRID; ++j) {
      int bin = (int)(hypot(grid_coord(i, 1.0), grid_coord(j, 1.0)) + 0.5);
      if (bin < t->bins) {
        t->mass[bin] += fmax(0.0, w->grid[i * GRID + j] * norm);
        cells[bin]++;
      }
    }
  }
  /* Annulus k holds the cells whose centres lie in [k - 1/2, k + 1/2) h. */
  double acc = 0.0, total = 0.0;
  for (int b = 0; b < t->bins; ++b) {
    total += t->mass[b];
  }
  t->max_radius = t->bins * h;
  for (int b = 0; b < t->bins; ++b) {
    double hi = (b + 0.5) * h;
    /* the average over the cells of the bin, not over the ideal annulus */
    t->refl[b] = cells[b] ? t->mass[b] / (cells[b] * h * h) : 0.0;
    acc += t->mass[b];
    if (acc >= (1.0 - 1e-4) * total && t->max_radius == t->bins * h) {
      t->max_radius = hi;
    }
  }
  free(cells);
  if (ss_distribution1d_init(&t->dist, t->mass, (size_t)t->bins) != 0) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "layers: channel %c reflects no light",
                        "RGB"[c]);
  }
  return SS_OK;
}

/* Linear interpolation between annulus centres (the first annulus is a disk). */
static double table_eval(const channel_table *t, double r) {
  double x = fabs(r) / t->h;
  int b = ss_table_cell(x, t->bins - 1);
  if (b < 0) {
    return 0.0;
  }
  double f = x - b;
  return (1.0 - f) * t->refl[b] + f * t->refl[b + 1];
}

static void layered_profile(const void *state, double r, double scale,
                            double out[SS_BSSRDF_CHANNELS]) {
  const layered *L = state;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    out[c] = scale * table_eval(&L->ch[c], r);
  }
}

static const ss_option layered_options[] = {
    {.name = "layers",
     .type = SS_OPTION_STRING,
     .def = "skin",
     .help = "'sigma_s=R,G,B sigma_a=R,G,B g=X eta=X d=X; ...' top first, or skin",
     .meta = "STACK"},
    {0},
};

static ss_status layered_create(const ss_bssrdf_params *p_in, void **state, ss_error *err) {
  ss_bssrdf_layer_stack p;
  const char *text = ss_bssrdf_params_string(p_in, &layered_options[0]);
  ss_status parsed = ss_bssrdf_layer_stack_parse(text, &p, err);
  if (parsed != SS_OK) {
    ss_error_prefix(err, "layers: option layers: ");
    return parsed;
  }
  for (int k = 0; k < p.layer_count; ++k) {
    ss_bssrdf_params lp = *p_in;
    ss_bssrdf_params_clear_options(&lp);
    memcpy(lp.medium.sigma_s.c, p.layers[k].sigma_s, sizeof lp.medium.sigma_s.c);
    memcpy(lp.medium.sigma_a.c, p.layers[k].sigma_a, sizeof lp.medium.sigma_a.c);
    memcpy(lp.medium.g.c, p.layers[k].g, sizeof lp.medium.g.c);
    lp.medium.phase = SS_PHASE_HG;
    lp.eta = p.layers[k].eta;
    char name[32];
    snprintf(name, sizeof name, "layers: layer %d", k);
    ss_status st = ss_bssrdf_params_check(&lp, name, err);
    if (st != SS_OK) {
      return st;
    }
    if (!(p.layers[k].thickness > 0.0) ||
        (!isfinite(p.layers[k].thickness) && k + 1 < p.layer_count)) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "layers: layer %d thickness must be > 0 (INFINITY only for the last)", k);
    }
  }
  layered *L = calloc(1, sizeof *L);
  workspace w = {0};
  const int nc = GRID * (GRID / 2 + 1);
  w.grid = fftw_alloc_real((size_t)GRID * GRID);
  w.R = fftw_alloc_complex((size_t)nc);
  w.T = fftw_alloc_complex((size_t)nc);
  w.Rk = fftw_alloc_complex((size_t)nc);
  w.Tk = fftw_alloc_complex((size_t)nc);
  ss_status st = SS_OK;
  if (!L || !w.grid || !w.R || !w.T || !w.Rk || !w.Tk) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "layers: out of memory");
  } else {
    w.forward = fftw_plan_dft_r2c_2d(GRID, GRID, w.grid, w.R, FFTW_ESTIMATE);
    w.backward = fftw_plan_dft_c2r_2d(GRID, GRID, w.R, w.grid, FFTW_ESTIMATE);
    ss_radial_model_init(&L->base, p.layers[0].eta, SS_RADIAL_EXIT_FRESNEL, layered_profile);
    for (int c = 0; c < SS_BSSRDF_CHANNELS && st == SS_OK; ++c) {
      st = build_channel(&p, c, &w, L, err);
    }
    fftw_destroy_plan(w.forward);
    fftw_destroy_plan(w.backward);
  }
  fftw_free(w.grid);
  fftw_free(w.R);
  fftw_free(w.T);
  fftw_free(w.Rk);
  fftw_free(w.Tk);
  if (st != SS_OK) {
    layered_destroy(L);
    return st;
  }
  *state = L;
  return SS_OK;
}

/* Annulus b, [lo, hi), and the density per unit area with which the table's
 * sampler places points inside it. */
static double annulus_pdf(const channel_table *t, int b, double *lo, double *hi) {
  *lo = b == 0 ? 0.0 : (b - 0.5) * t->h;
  *hi = (b + 0.5) * t->h;
  return t->dist.func[b] / (t->dist.integral * t->bins) / (SS_PI * (*hi * *hi - *lo * *lo));
}

static int layered_sample(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel,
                          double u1, double u2, ss_bssrdf_entry *e) {
  const channel_table *t = &((const layered *)state)->ch[channel];
  double x = ss_distribution1d_sample_continuous(&t->dist, u1, NULL) * t->bins;
  int b = ss_table_cell_clamped(x, t->bins);
  double lo, hi, u = x - b;
  e->pdf = annulus_pdf(t, b, &lo, &hi);
  e->r = sqrt(lo * lo + u * (hi * hi - lo * lo));
  e->phi = 2.0 * SS_PI * u2;
  return 1;
}

static double layered_pdf(const void *state, const ss_bssrdf_sample_ctx *ctx, int channel, double r,
                          double phi) {
  const channel_table *t = &((const layered *)state)->ch[channel];
  int b = ss_table_cell(r / t->h + 0.5, t->bins);
  if (r < 0.0 || b < 0) {
    return 0.0;
  }
  double lo, hi;
  return annulus_pdf(t, b, &lo, &hi);
}

static double layered_max_radius(const void *state, int channel) {
  return ((const layered *)state)->ch[channel].max_radius;
}

static double layered_entry_eta(const void *state) { return ((const layered *)state)->base.eta; }

const ss_bssrdf_ops ss_bssrdf_model_layers = {
    .name = "layers",
    .summary = "layered slabs by Kubelka-Munk adding of multipole profiles in 2D Fourier space "
               "(Donner & Jensen 2005); default: three-layer skin",
    .flags = SS_BSSRDF_RADIAL | SS_BSSRDF_SLAB | SS_BSSRDF_TABULATED,
    .options = layered_options,
    .create = layered_create,
    .destroy = layered_destroy,
    .eval = ss_radial_model_eval,
    .sample_entry = layered_sample,
    .pdf_entry = layered_pdf,
    .max_radius = layered_max_radius,
    .total_reflectance = ss_radial_model_total_reflectance,
    .rd = ss_radial_model_rd,
    .profile = ss_radial_model_profile,
    .exitance = ss_radial_model_exitance,
    .brdf = ss_radial_model_brdf,
    .total_transmittance = ss_radial_model_total_transmittance,
    .entry_eta = layered_entry_eta,
};
