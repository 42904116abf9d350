/* Geometry of a BSSRDF query for the models that see the incidence angle
 * (pbd, table-gwc): private to src/bssrdf. */
#ifndef SUBSURF_BSSRDF_ENTRY_GEOMETRY_H
#define SUBSURF_BSSRDF_ENTRY_GEOMETRY_H

#include "subsurf/bssrdf.h"

#include <math.h>

/* Incidence angle at the entry point and the exit point's polar coordinates
 * about it, the azimuth measured from the refracted beam's forward
 * horizontal direction (-w_i projected on the tangent plane), in [0, pi]. */
static inline void ss_entry_geometry(const ss_bssrdf_query *q, double *theta, double *r,
                                     double *phi) {
  double cos_i = fmin(1.0, fmax(-1.0, ss_vec3_dot(q->w_i, q->n_i)));
  *theta = acos(fabs(cos_i));
  ss_vec3 d = ss_vec3_sub(q->x_o, q->x_i);
  *r = ss_vec3_length(d);
  ss_vec3 d_t = ss_vec3_madd(d, q->n_i, -ss_vec3_dot(d, q->n_i));
  ss_vec3 fwd = ss_vec3_madd(ss_vec3_neg(q->w_i), q->n_i, cos_i);
  double lf = ss_vec3_length(fwd), ld = ss_vec3_length(d_t);
  *phi = (lf > 1e-12 && ld > 0.0) ? acos(fmin(1.0, fmax(-1.0, ss_vec3_dot(d_t, fwd) / (lf * ld))))
                                  : 0.0;
}

#endif
