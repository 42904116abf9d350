/* Manifold next-event estimation for volpath (Hanika, Droske & Fascione
 * 2015): a scattering vertex inside a smooth dielectric boundary connects to
 * a light outside through one refraction, or in nested media through a
 * chain of two (a medium in a smooth glass shell), found by Newton's method
 * on the meshes (render/manifold.h). Delta lights (point, spot,
 * directional, beam) light such media only this way; area lights are also
 * reached by phase-sampled paths that refract out and hit them, and the two
 * strategies are combined by the balance heuristic (with volpath's
 * spectral MIS over the colour channels). Environment lights are left to
 * phase sampling: MNEE picks among the other lights only. Toward an area
 * light that subtends a solid angle Omega at the vertex (its bounding
 * sphere's) a sample is taken with probability min(1, Omega_0 / Omega),
 * Omega_0 the option mnee_solid_angle, its MIS density scaled by it: the
 * larger the light, the more often phase sampling hits it and the less an
 * MNEE sample adds for the cost of its rays (on the bundled scenes a
 * sample at every vertex cost more than it saved; bench/RESULTS.md).
 * Smaller lights, which phase sampling rarely hits, and delta lights,
 * which it never does, are sampled at every vertex. */
#ifndef SUBSURF_RENDER_INTEGRATORS_MNEE_H
#define SUBSURF_RENDER_INTEGRATORS_MNEE_H

#include "render/integrators/common.h"
#include "render/manifold.h"

/* volpath's options (scene file `integrator` keys). */
typedef struct {
  int enabled;        /* "mnee": 0 or 1 */
  int max_iterations; /* "mnee_iterations": Newton steps, 1..1000 */
  double tolerance;   /* "mnee_tolerance": |h x n| at convergence, (0, 0.1] */
  double solid_angle; /* "mnee_solid_angle": Omega_0 of the rate toward area lights, sr, > 0 */
} ss_mnee_options;

#define SS_MNEE_DEFAULT_ENABLED 1
/* 50, not 20: since a failed solve leaves the phase-sampled path its full MIS
 * weight (unbiased), solves stopped at 20 steps made fireflies on
 * skin_sphere_thick.json (relMSE 0.51-0.97 at 32 spp against 0.046-0.049
 * with 50, at the same CPU time; bench/RESULTS.md). */
#define SS_MNEE_DEFAULT_ITERATIONS 50
#define SS_MNEE_DEFAULT_TOLERANCE 1e-6
#define SS_MNEE_MAX_ITERATIONS 1000
#define SS_MNEE_MAX_TOLERANCE 0.1
/* 0.03 sr, a cone of half-angle 5.6 deg: the bundled scenes' lamps (about
 * 0.3 sr at their media) are sampled at a tenth of the vertices, where the
 * efficiency of liquid_glass.json's central view is 1.1-1.5x that of phase
 * sampling alone per channel (0.3-0.4x at every vertex) and that of the
 * skin spheres' images 1.2-1.6x that at every vertex (bench/RESULTS.md). */
#define SS_MNEE_DEFAULT_SOLID_ANGLE 0.03

/* The option names, NULL-terminated (volpath's option table). */
extern const char *const ss_mnee_option_names[];
/* The defaults (a volpath without prepared state uses them). */
extern const ss_mnee_options ss_mnee_defaults;

/* Reads and checks the options; the message names the bad one. */
ss_status ss_mnee_options_read(const ss_scene *scene, ss_mnee_options *o, ss_error *err);

/* The number of the scene's lights MNEE samples (all but the environment):
 * without one a vertex has nothing to solve for. */
size_t ss_mnee_light_count(const ss_scene *scene);

/* 1 when medium vertices behind material m connect through it: a smooth
 * refracting (eta != 1) interface. */
int ss_mnee_interface(const ss_material *m);

/* The throughput and spectral-MIS state of the path at a medium vertex. */
typedef struct {
  ss_rgb beta, r_u;
  ss_vec3 x0, d; /* the vertex and the unit direction the path arrived along */
  const ss_medium *medium;
  /* Nested media (medium_stack.h): the regions the vertex is in; NULL
   * when the scene's media are apart. */
  const ss_medium_stack *media;
} ss_mnee_vertex;

/* One light sample from medium vertex v through the refracting boundary:
 * its MIS-weighted contribution. Apart media: through the boundary the
 * straight line toward the light leaves by (an ss_mnee_interface). Nested
 * media: through the true interfaces (medium_stack.h) that line crosses
 * when they are one or two, all smooth. Black when the Newton solve fails,
 * the light is occluded or the line crosses no such chain. */
ss_rgb ss_mnee_next_event(const ss_scene *scene, const ss_mnee_options *o, const ss_mnee_vertex *v,
                          ss_rng *rng, ss_path_stats *stats);

/* A phase-sampled path from medium vertex x0 so far: the smooth
 * refractions z[0 .. k-1] it took since x0, each from a side of index n to
 * one of n': eta = n / n', enters: into the hit shape. */
typedef struct {
  ss_vec3 x0;
  ss_medium_stack media; /* the regions at x0 (nested media) */
  int k;
  ss_hit z[SS_MANIFOLD_MAX_CHAIN];
  double eta[SS_MANIFOLD_MAX_CHAIN];
  int enters[SS_MANIFOLD_MAX_CHAIN];
} ss_mnee_refractions;

/* For such a path hitting y on area light l: the solid-angle density at x0
 * with which ss_mnee_next_event (options o) samples it, the rate included:
 * 0 when it would not, because the straight line x0 -> y does not cross
 * the same interfaces (nested media) or Newton's method from it fails for
 * this y, or at a caustic point of the manifold. */
double ss_mnee_light_pdf(const ss_scene *scene, const ss_mnee_options *o, const ss_light *l,
                         const ss_mnee_refractions *r, int nested, const ss_hit *y,
                         ss_path_stats *stats);

#endif
