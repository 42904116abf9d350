/* The scattering vertex of the path integrators: a surface BSDF (or only a
 * dielectric boundary's reflection lobe), a BSSRDF's entry point, an
 * effective BRDF or a medium's phase function, with what is evaluated
 * toward a light sample, sampled to continue the path, and the step from
 * one vertex to the next (light sampling, direction sampling, refraction's
 * radiance scaling, roulette). Private to src/render. */
#ifndef SUBSURF_RENDER_INTEGRATORS_SURFACE_VERTEX_H
#define SUBSURF_RENDER_INTEGRATORS_SURFACE_VERTEX_H

#include "render/integrators/common.h"
#include "render/integrators/path_state.h"
#include "subsurf/bssrdf.h"

typedef enum {
  SS_VERTEX_BSDF,       /* a surface BSDF, both lobes */
  SS_VERTEX_REFLECTION, /* a dielectric boundary's reflection lobe only */
  SS_VERTEX_ENTRY,      /* a BSSRDF entry point x_i: S(x_i, w_i; x_o, w_o) |cos| */
  SS_VERTEX_SOURCE,     /* a surface point x_i lit through the model's point source at
                           query.x_o, source_depth deep (the hybrid's hand-over at a
                           scattering event): L_o(z, r_i; w_i) |cos|
                           (ss_bssrdf_point_source_radiance) */
  SS_VERTEX_BRDF,       /* an effective BRDF (a model flagged SS_BSSRDF_BRDF) at x_o */
  SS_VERTEX_PHASE,      /* a scattering event in a medium traced volumetrically */
} ss_vertex_kind;

typedef struct {
  ss_vertex_kind kind;
  ss_vec3 p, ng;           /* the vertex and its geometric normal */
  ss_frame frame;          /* shading frame (BSDF kinds) or frame of ng */
  const ss_bsdf *bsdf;     /* BSDF kinds: the material's, or `local` */
  ss_bsdf local;           /* a textured material's BSDF at p */
  ss_vec3 wo_local;        /* BSDF and BRDF kinds: toward the previous vertex */
  ss_vec3 d;               /* direction the path arrived along (world) */
  const ss_bssrdf *bssrdf; /* ENTRY and BRDF: the material's, or `owned` */
  ss_bssrdf *owned;        /* built for the exit point's own coefficients */
  ss_bssrdf_query query;   /* ENTRY: x_i, n_i set, w_i filled per direction */
  double scale;            /* factor on the value (branch probabilities, 1 / area pdf) */
  double source_depth;     /* SOURCE: the point source's depth z below the entry plane */
  const ss_phase *phase;   /* PHASE: the medium's phase function ... */
  int medium;              /* ... and its index (light is attenuated through it) */
  int lit;                 /* its direct light is estimated already */
} ss_vertex;

/* Destroys the BSSRDF a vertex owns (a spatially varying material's). */
static inline void ss_vertex_release(ss_vertex *v) {
  ss_bssrdf_destroy(v->owned);
  v->owned = NULL;
}

/* The value f(w_i) |cos| (times scale) toward the world direction wi and
 * the solid-angle density the vertex samples wi with. */
ss_rgb ss_vertex_f(const ss_vertex *v, ss_vec3 wi, double *pdf);
/* Samples a direction: fills *wi, the weight f |cos| / pdf (times scale),
 * the density, whether it was a delta lobe and the refraction's eta
 * (n(wi side) / n(wo side) of a transmission, else 1); 0 when the path
 * ends. */
int ss_vertex_sample(const ss_vertex *v, ss_rng *rng, ss_vec3 *wi, ss_rgb *weight, double *pdf,
                     int *delta, double *eta);
/* Next-event estimation from a non-delta vertex, MIS-weighted against the
 * vertex's own sampling by the power heuristic (without the path throughput). */
ss_rgb ss_vertex_direct(const ss_scene *scene, const ss_vertex *v, ss_rng *rng,
                        ss_path_stats *stats);

/* A BSDF vertex at `hit` of material m, reached along d (unit), with the
 * material's BSDF at the hit (its textures looked up). */
void ss_vertex_at_bsdf(ss_vertex *v, const ss_material *m, const ss_hit *hit, ss_vec3 d);

/* Samples the BSDF at a surface vertex of geometric normal ng, reached
 * along d, with three uniforms (lobe, then direction). Returns 0 when the
 * path ends there: no sample, zero density, or a direction on the wrong
 * side of the actual surface (possible with shading normals), which would
 * leak through it. Otherwise fills bs and the world direction *wi. */
int ss_sample_surface(const ss_bsdf *bsdf, ss_frame frame, ss_vec3 wo_local, ss_vec3 d, ss_vec3 ng,
                      ss_rng *rng, ss_bsdf_sample *bs, ss_vec3 *wi);

/* The step from vertex v (reached by the path s, `depth` events so far):
 * its direct light by light sampling unless it is a delta vertex or lit
 * already, the next direction sampled, the throughput, MIS state and
 * refraction's radiance scaling updated, *ray spawned and roulette played
 * on the throughput without that scaling. Releases v. Returns 0 when the
 * path ends. */
int ss_path_advance(const ss_scene *scene, ss_path_state *s, ss_vertex *v, int depth, ss_ray *ray,
                    ss_rgb *L, ss_rng *rng, ss_path_stats *stats);

#endif
