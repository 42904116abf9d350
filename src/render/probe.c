/* Entry-point sampling by probe rays and its MIS density (see probe.h). */
#include "subsurf/probe.h"

#include "subsurf/sampling.h"

#include <math.h>

void ss_probe_init(ss_probe *p, const ss_accel *accel, unsigned geom_id, const ss_bssrdf *b,
                   ss_vec3 x_o, ss_frame frame, ss_vec3 w_o) {
  p->accel = accel;
  p->geom_id = geom_id;
  p->bssrdf = b;
  p->x_o = x_o;
  p->frame = frame;
  p->w_o = w_o;
  p->radius = 0.0;
  for (int c = 0; c < SS_BSSRDF_CHANNELS; ++c) {
    p->radius = fmax(p->radius, ss_bssrdf_max_radius(b, c));
  }
}

ss_frame ss_probe_axis_frame(const ss_probe *p, int axis) {
  ss_frame f = p->frame, g;
  if (axis == 0) {
    return f;
  }
  if (axis == 1) {
    g.s = f.t;
    g.t = f.n;
    g.n = f.s;
  } else {
    g.s = f.n;
    g.t = f.s;
    g.n = f.t;
  }
  return g;
}

double ss_probe_axis_probability(int axis) { return axis == 0 ? 0.5 : 0.25; }

static ss_bssrdf_sample_ctx axis_ctx(const ss_probe *p, int axis) {
  ss_bssrdf_sample_ctx ctx = {.x = p->x_o, .frame = ss_probe_axis_frame(p, axis), .w = p->w_o};
  return ctx;
}

/* The chord of the probe sphere through the point at (a, b) of the plane
 * normal to f.n (coordinates in f.s, f.t), travelling along -f.n. */
static int chord(const ss_probe *p, ss_frame f, double a, double b, ss_ray *ray) {
  double rr = a * a + b * b, R = p->radius;
  if (!(rr < R * R)) {
    return 0;
  }
  double half = sqrt(R * R - rr);
  ss_vec3 base = ss_vec3_madd(ss_vec3_madd(p->x_o, f.s, a), f.t, b);
  ray->o = ss_vec3_madd(base, f.n, half);
  ray->d = ss_vec3_neg(f.n);
  ray->tmin = 0.0;
  ray->tmax = 2.0 * half;
  return 1;
}

/* The technique (axis, channel) and the chord through the sampled point,
 * from u[0..3]; 0 when the point falls outside the probe sphere. */
static int sample_chord(const ss_probe *p, const double u[4], int *axis, int *channel,
                        ss_ray *ray) {
  *axis = u[0] < 0.5 ? 0 : u[0] < 0.75 ? 1 : 2;
  int c = (int)(u[1] * SS_BSSRDF_CHANNELS);
  *channel = c < SS_BSSRDF_CHANNELS ? c : SS_BSSRDF_CHANNELS - 1;
  ss_bssrdf_sample_ctx ctx = axis_ctx(p, *axis);
  ss_bssrdf_entry e;
  return ss_bssrdf_sample_entry(p->bssrdf, &ctx, *channel, u[2], u[3], &e) &&
         chord(p, ctx.frame, e.r * cos(e.phi), e.r * sin(e.phi), ray);
}

int ss_probe_sample_entry(const ss_probe *p, const double u[5], ss_probe_sample *out,
                          unsigned long long *queries) {
  int axis, channel;
  ss_ray ray;
  if (!sample_chord(p, u, &axis, &channel, &ray)) {
    return 0;
  }
  ++*queries;
  size_t count = ss_accel_intersect_sample(p->accel, &ray, p->geom_id, u[4], &out->hit);
  if (count == 0) {
    return 0;
  }
  out->axis = axis;
  out->channel = channel;
  out->hits = count;
  out->pdf = ss_probe_pdf(p, &out->hit, axis, count, queries);
  return out->pdf > 0.0 && isfinite(out->pdf);
}

size_t ss_probe_sample_hits(const ss_probe *p, const double u[5], ss_probe_hits *out,
                            unsigned long long *queries) {
  ss_ray ray;
  out->n = 0;
  if (!sample_chord(p, u, &out->axis, &out->channel, &ray)) {
    return 0;
  }
  ++*queries;
  size_t count = ss_accel_intersect_all(p->accel, &ray, p->geom_id, out->hit, SS_PROBE_MAX_HITS);
  double keep = 1.0;
  if (count > SS_PROBE_MAX_HITS) {
    ++*queries;
    ss_accel_intersect_sample(p->accel, &ray, p->geom_id, u[4], &out->hit[0]);
    keep = 1.0 / (double)count;
    count = 1;
  }
  for (size_t j = 0; j < count; ++j) {
    double d = keep * ss_probe_hits_density(p, &out->hit[j]);
    if (d > 0.0 && isfinite(d)) {
      out->hit[out->n] = out->hit[j];
      out->pdf[out->n++] = d;
    }
  }
  return out->n;
}

/* The projection of x_i - x_o on the plane of axis frame f, and the number
 * of hits on the chord through it (queried when count is 0). */
static size_t project(const ss_probe *p, ss_frame f, const ss_hit *hit, size_t count, double *r,
                      double *phi, unsigned long long *queries) {
  ss_vec3 d = ss_vec3_sub(hit->p, p->x_o);
  double a = ss_vec3_dot(d, f.s), b = ss_vec3_dot(d, f.t);
  *r = sqrt(a * a + b * b);
  *phi = atan2(b, a);
  if (*phi < 0.0) {
    *phi += 2.0 * SS_PI;
  }
  ss_ray ray;
  if (!chord(p, f, a, b, &ray)) {
    return 0;
  }
  if (count == 0) {
    ++*queries;
    count = ss_accel_intersect_all(p->accel, &ray, p->geom_id, NULL, 0);
  }
  return count;
}

/* The density of axis a's techniques at x_i: of channel `channel` alone, or
 * summed over the channels when channel < 0. */
static double axis_pdf(const ss_probe *p, int axis, int channel, const ss_hit *hit, size_t count,
                       unsigned long long *queries) {
  ss_bssrdf_sample_ctx ctx = axis_ctx(p, axis);
  double r, phi;
  size_t n = project(p, ctx.frame, hit, count, &r, &phi, queries);
  if (n == 0) {
    return 0.0;
  }
  double plane = channel < 0
                     ? ss_bssrdf_pdf_entry_channels(p->bssrdf, &ctx, r, phi)
                     : ss_bssrdf_pdf_entry(p->bssrdf, &ctx, channel, r, phi) / SS_BSSRDF_CHANNELS;
  double cos_a = fabs(ss_vec3_dot(hit->ng, ctx.frame.n));
  return ss_probe_axis_probability(axis) * plane * cos_a / (double)n;
}

double ss_probe_technique_pdf(const ss_probe *p, int axis, int channel, const ss_hit *hit,
                              size_t count, unsigned long long *queries) {
  return axis_pdf(p, axis, channel, hit, count, queries);
}

double ss_probe_pdf(const ss_probe *p, const ss_hit *hit, int axis, size_t count,
                    unsigned long long *queries) {
  double pdf = 0.0;
  for (int a = 0; a < SS_PROBE_AXES; ++a) {
    pdf += axis_pdf(p, a, -1, hit, a == axis ? count : 0, queries);
  }
  return pdf;
}

double ss_probe_hits_density(const ss_probe *p, const ss_hit *hit) {
  double pdf = 0.0;
  for (int a = 0; a < SS_PROBE_AXES; ++a) {
    ss_bssrdf_sample_ctx ctx = axis_ctx(p, a);
    ss_vec3 d = ss_vec3_sub(hit->p, p->x_o);
    double x = ss_vec3_dot(d, ctx.frame.s), y = ss_vec3_dot(d, ctx.frame.t);
    double r = sqrt(x * x + y * y), phi = atan2(y, x);
    if (!(r < p->radius)) {
      continue;
    }
    phi = phi < 0.0 ? phi + 2.0 * SS_PI : phi;
    double plane = ss_bssrdf_pdf_entry_channels(p->bssrdf, &ctx, r, phi);
    pdf += ss_probe_axis_probability(a) * plane * fabs(ss_vec3_dot(hit->ng, ctx.frame.n));
  }
  return pdf;
}
