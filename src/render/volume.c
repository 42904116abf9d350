/* Micro-flake and gridded media: coefficients at a point and along a
 * direction, and the flakes' phase function (volume.h). Free flights and
 * transmittance: volume_tracking.c. */
#include "subsurf/volume.h"

#include "subsurf/grid.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_medium_prepare_volume(ss_medium *m, ss_error *err) {
  const ss_medium_flakes *f = &m->optics.flakes;
  m->axis = ss_frame_from_normal(ss_vec3_make(0.0, 0.0, 1.0));
  double k = 1.0;
  if (f->type != SS_FLAKE_NONE) {
    m->axis = ss_frame_from_normal(ss_vec3_normalize(f->axis));
    if (!m->flakes) {
      /* The tables about +z: a direction enters them in the frame of the
       * axis at its point (the medium's, or a voxel's). */
      ss_medium_flakes about_z = *f;
      about_z.axis = ss_vec3_make(0.0, 0.0, 1.0);
      m->flakes = malloc(sizeof *m->flakes);
      if (!m->flakes) {
        return ss_error_set(err, SS_ERR_NO_MEMORY, "medium '%s': out of memory", m->name);
      }
      ss_status st = ss_microflake_init_medium(m->flakes, &about_z, 1.0, err);
      if (st != SS_OK) {
        free(m->flakes);
        m->flakes = NULL;
        ss_error_prefix(err, "medium '%s': ", m->name);
        return st;
      }
    }
    /* sigma_t(w) = 2 sigma_t sigma(w), bounded by the table's largest entry. */
    k = 2.0 * ss_microflake_sigma_max(m->flakes);
  }
  /* Trilinear densities never exceed the largest voxel's. */
  m->majorant = k * (m->grid ? m->grid->max_density : 1.0);
  if (m->grid && !m->majorant_exceeded) {
    m->majorant_exceeded = calloc(1, sizeof *m->majorant_exceeded);
    if (!m->majorant_exceeded) {
      return ss_error_set(err, SS_ERR_NO_MEMORY, "medium '%s': out of memory", m->name);
    }
  }
  return SS_OK;
}

void ss_medium_release_volume(ss_medium *m) {
  free(m->flakes);
  m->flakes = NULL;
  free(m->majorant_exceeded);
  m->majorant_exceeded = NULL;
  ss_grid_destroy(m->grid);
  m->grid = NULL;
}

ss_volume_point ss_volume_at(const ss_medium *m, ss_vec3 p) {
  ss_volume_point q = {1.0, m->axis};
  if (m->grid) {
    q.density = ss_grid_density(m->grid, p);
    if (m->flakes && m->grid->axis && q.density > 0.0) {
      q.axis = ss_frame_from_normal(ss_grid_axis(m->grid, p));
    }
  }
  return q;
}

ss_rgb ss_volume_sigma_t(const ss_medium *m, const ss_volume_point *q, ss_vec3 w) {
  double k = q->density;
  if (m->flakes) {
    /* Jakob2010 eq. 11 with a rho = 2 (sigma_s + sigma_a) (microflake.h). */
    k *= 2.0 * ss_microflake_sigma_t(m->flakes, ss_frame_to_local(q->axis, w));
  }
  return ss_rgb_scale(m->sigma_t, k);
}

ss_rgb ss_volume_sigma_s(const ss_medium *m, const ss_volume_point *q, ss_vec3 w) {
  double k = q->density;
  if (m->flakes) {
    /* Jakob2010 eq. 12: a rho alpha1 = 2 sigma_s times int (alpha / alpha1) |w.m| D. */
    k *= 2.0 * ss_microflake_sigma_s(m->flakes, ss_frame_to_local(q->axis, w));
  }
  return ss_rgb_scale(m->optics.sigma_s, k);
}

double ss_volume_phase_eval(const ss_medium *m, const ss_volume_point *q, ss_vec3 w_in,
                            ss_vec3 w_out) {
  if (m->flakes) {
    /* Jakob2010 eq. 13: alpha1 cancels between the flakes and sigma_s. */
    return ss_microflake_phase_eval(m->flakes, ss_frame_to_local(q->axis, w_in),
                                    ss_frame_to_local(q->axis, w_out));
  }
  return ss_phase_eval(&m->phase, ss_vec3_dot(w_in, w_out));
}

ss_vec3 ss_volume_phase_sample(const ss_medium *m, const ss_volume_point *q, ss_vec3 w_in,
                               ss_rng *rng) {
  if (m->flakes) {
    ss_vec3 w = ss_microflake_sample_phase(m->flakes, ss_frame_to_local(q->axis, w_in), rng);
    return ss_frame_to_world(q->axis, w);
  }
  double u1 = ss_rng_uniform(rng), u2 = ss_rng_uniform(rng);
  return ss_phase_sample(&m->phase, w_in, u1, u2);
}
