/* Entry points of a BSSRDF sampled by probe rays (bssrdf_vertex.h). */
#include "render/integrators/bssrdf_vertex.h"

#include "subsurf/fwddip_entry.h"

/* The 5 uniforms of a probe sample (probe.h). */
static void uniforms(ss_rng *rng, double u[5]) {
  for (int k = 0; k < 5; ++k) {
    u[k] = ss_rng_uniform(rng);
  }
}

/* Moves v (an ENTRY or SOURCE vertex) to hit. */
static void entry_at(ss_vertex *v, const ss_hit *hit) {
  v->p = hit->p;
  v->ng = hit->ng;
  v->frame = ss_frame_from_normal(hit->ng);
  v->query.x_i = hit->p;
  v->query.n_i = hit->ng;
}

double ss_vertex_sample_entry(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                              ss_rng *rng, ss_vertex *v, ss_path_stats *stats) {
  double u[5];
  uniforms(rng, u);
  ss_probe_sample ps;
  unsigned long long queries = 0;
  int ok = ss_fwddip_entry_sample(probe, u, &ps, &queries);
  stats->probe_rays += queries;
  if (!ok) {
    return 0.0;
  }
  v->kind = SS_VERTEX_ENTRY;
  entry_at(v, &ps.hit);
  v->query.thickness =
      ss_bssrdf_uses_thickness(probe->bssrdf) ? ss_local_thickness(scene, surface, stats) : 0.0;
  return ps.pdf;
}

int ss_vertex_sample_entries(const ss_scene *scene, const ss_probe *probe, const ss_hit *surface,
                             ss_rgb beta, ss_rng *rng, ss_vertex *v, ss_rgb *L,
                             ss_path_stats *stats) {
  double u[5];
  uniforms(rng, u);
  ss_probe_hits ph;
  unsigned long long queries = 0;
  size_t n = ss_probe_sample_hits(probe, u, &ph, &queries);
  stats->probe_rays += queries;
  if (n == 0) {
    return 0;
  }
  v->query.thickness =
      ss_bssrdf_uses_thickness(probe->bssrdf) ? ss_local_thickness(scene, surface, stats) : 0.0;
  double scale = v->scale;
  for (size_t j = 0; j < n; ++j) {
    entry_at(v, &ph.hit[j]);
    v->scale = scale / ph.pdf[j];
    *L = ss_rgb_add(*L, ss_rgb_mul(beta, ss_vertex_direct(scene, v, rng, stats)));
  }
  size_t j = (size_t)(ss_rng_uniform(rng) * (double)n);
  j = j < n ? j : n - 1;
  entry_at(v, &ph.hit[j]);
  v->scale = scale * (double)n / ph.pdf[j];
  v->lit = 1;
  return 1;
}

double ss_local_thickness(const ss_scene *scene, const ss_hit *hit, ss_path_stats *stats) {
  ss_vec3 in = ss_vec3_neg(hit->ng);
  ss_ray ray = {ss_offset_ray_origin(hit->p, hit->ng, in), in, 0.0, INFINITY};
  ss_hit far;
  stats->probe_rays++;
  if (!ss_accel_intersect(scene->accel, &ray, &far) || far.geom_id != hit->geom_id) {
    return 0.0;
  }
  return far.t * ss_vec3_length(ray.d);
}
