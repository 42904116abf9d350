/* Entry points for BSSRDF transport by probe rays (King2013; pbrt-v3
 * sec. 15.4; Cycles).
 *
 * Given the exit point x_o on an object, one sample picks a projection axis
 * (the normal with probability 1/2, each tangent 1/4), a colour channel
 * (1/3 each), a radius and azimuth from the model's sample_entry on the
 * plane normal to that axis, casts the chord of the probe sphere (radius R =
 * the largest max_radius over the channels, centred at x_o) through the
 * sampled point along the axis, and picks one of the object's hits on it
 * uniformly (accel.h's all-hits query of one object).
 *
 * The density of the entry point x_i per unit surface area is the one-sample
 * MIS (balance heuristic) combination of the 9 techniques (axis a, channel c):
 *     p(x_i) = sum_a P_a |n_i . a| / N_a(x_i) (1/3) sum_c p_c(r_a, phi_a),
 * with p_c the model's pdf_entry on the plane normal to a, (r_a, phi_a) the
 * projection of x_i - x_o onto that plane, n_i the geometric normal at x_i
 * and N_a(x_i) the number of the object's hits on the chord through x_i
 * parallel to a (every technique's own hit count, not just the sampled one:
 * this needs one all-hits query per other axis). */
/*
 * All hits of a chord (ss_probe_sample_hits): every hit x_j of the sampled
 * chord is an entry point, so a technique's samples form a point process of
 * intensity P_a |n_i . a| (1/3) p_c(r_a, phi_a) per unit area, without the
 * 1 / N_a of choosing one hit; the balance heuristic over the 9 techniques
 * then weighs each x_j by the sum of the intensities,
 *     D(x_j) = sum_a P_a |n_j . a| (1/3) sum_c p_c(r_a, phi_a),
 * and sum_j f(x_j) / D(x_j) is an unbiased estimate of the integral of f
 * over the object's surface inside the probe sphere: one all-hits query per
 * sample and no counting queries on the other axes. */
#ifndef SUBSURF_PROBE_H
#define SUBSURF_PROBE_H

#include "subsurf/accel.h"
#include "subsurf/bssrdf.h"

#define SS_PROBE_AXES 3

/* The exit point and what sampling needs from it. */
typedef struct {
  const ss_accel *accel;
  unsigned geom_id; /* the object probes are restricted to */
  const ss_bssrdf *bssrdf;
  ss_vec3 x_o;
  ss_frame frame; /* frame.n: geometric normal at x_o, outward */
  ss_vec3 w_o;    /* direction toward the viewer, outside (0 when unknown) */
  double radius;  /* R: set by ss_probe_init */
} ss_probe;

typedef struct {
  ss_hit hit;        /* the entry point */
  double pdf;        /* area density, MIS over axes x channels x hits */
  int axis, channel; /* the technique that produced it */
  size_t hits;       /* number of hits on the sampled chord */
} ss_probe_sample;

/* Fills the probe for exit point x_o (frame.n = its outward geometric
 * normal); radius from the model's max_radius. */
void ss_probe_init(ss_probe *p, const ss_accel *accel, unsigned geom_id, const ss_bssrdf *b,
                   ss_vec3 x_o, ss_frame frame, ss_vec3 w_o);

/* Samples an entry point with 5 uniforms (axis, channel, radius, azimuth,
 * hit). Returns 0 when the sample misses (radius beyond R, no hit on the
 * chord); *queries counts the all-hits queries made. */
int ss_probe_sample_entry(const ss_probe *p, const double u[5], ss_probe_sample *out,
                          unsigned long long *queries);

/* The hits of one chord kept by ss_probe_sample_hits. */
#define SS_PROBE_MAX_HITS 8

typedef struct {
  ss_hit hit[SS_PROBE_MAX_HITS];
  double pdf[SS_PROBE_MAX_HITS]; /* D(x_j) times the probability that x_j is kept */
  size_t n;                      /* hits kept */
  int axis, channel;             /* the technique that produced them */
} ss_probe_hits;

/* Samples a chord with 5 uniforms as ss_probe_sample_entry does and keeps
 * every hit on it, each with its density D(x_j) above; a chord crossing
 * the object more than SS_PROBE_MAX_HITS times keeps one hit chosen
 * uniformly with u[4] (kept with probability 1 / count). Returns the number
 * of hits kept (0: a miss); *queries counts the all-hits queries made. */
size_t ss_probe_sample_hits(const ss_probe *p, const double u[5], ss_probe_hits *out,
                            unsigned long long *queries);
/* D(x_i) above: the sum of the techniques' intensities at entry point hit. */
double ss_probe_hits_density(const ss_probe *p, const ss_hit *hit);

/* The axis frames: the frame whose normal is axis a (0: the normal, 1 and
 * 2: the tangents s and t) and its selection probability. */
ss_frame ss_probe_axis_frame(const ss_probe *p, int axis);
double ss_probe_axis_probability(int axis);

/* The density of technique (axis, channel) alone at entry point `hit`
 * (area measure, including 1 / N_a), with the chord's hit count `count`
 * (0: query it). */
double ss_probe_technique_pdf(const ss_probe *p, int axis, int channel, const ss_hit *hit,
                              size_t count, unsigned long long *queries);
/* The MIS density p(x_i) above; `axis` and `count` give the sampled chord's
 * hit count, which is not queried again (axis -1: query every axis). */
double ss_probe_pdf(const ss_probe *p, const ss_hit *hit, int axis, size_t count,
                    unsigned long long *queries);

#endif
