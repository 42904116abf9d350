/* Pass 1 of the hierarchical BSSRDF evaluation (Jensen & Buhler 2002, seed
 * 001, sec. 3): points spread uniformly, as blue noise, over the surface of
 * every translucent object, each carrying its share of the area, and the
 * irradiance at each point from the renderer's own direct and indirect
 * lighting through the boundary:
 *     E(x) = int Ft(eta, w . n) L_i(x, w) (w . n) dw,
 * the cosine-weighted incident radiance times the Fresnel transmission into
 * the object (Jensen & Buhler 2002, eq. 3's E). The incident radiance is the
 * `bssrdf` integrator's (other translucent objects seen through their own
 * BSSRDFs), with light sampling at the point combined with cosine sampling
 * by the power heuristic. The pass runs in parallel; point i draws from its
 * own stream hash(seed, i), so the result does not depend on the number of
 * threads. */
#ifndef SUBSURF_IRRADIANCE_POINTS_H
#define SUBSURF_IRRADIANCE_POINTS_H

#include "subsurf/integrator.h"
#include "subsurf/mesh.h"
#include "subsurf/rgb.h"
#include "subsurf/scene.h"
#include "subsurf/status.h"

#include <stddef.h>
#include <stdint.h>

typedef struct {
  ss_vec3 p, n;   /* position and outward geometric normal */
  double area;    /* the share of the object's area the point stands for */
  ss_rgb E;       /* Fresnel-transmitted irradiance */
  ss_rgb power;   /* E area: what the point feeds into the diffusion kernel */
  uint32_t shape; /* the scene shape it lies on */
} ss_irradiance_point;

/* `count` points on the mesh, uniformly distributed by area with a minimum
 * distance between them (dart throwing, Cook 1986, on a pool of 6 count
 * uniform candidates tried tile by tile, with the disk radius shrunk by 10 %
 * per pass over the pool until `count` points are accepted; the first radius
 * sqrt(0.75 A / count) is about that of a maximal Poisson-disk set of this
 * size). Points get
 * area A / count, shape `shape`, zero irradiance. Deterministic in `seed`.
 * SS_ERR_INVALID_ARGUMENT for count 0 or a mesh of zero area. */
ss_status ss_poisson_disk_points(const ss_mesh *mesh, uint32_t shape, size_t count, uint64_t seed,
                                 ss_irradiance_point *out, ss_error *err);

/* The Fresnel transmission weight of the irradiance: 1 - Fr(cos, eta). */
double ss_irradiance_fresnel_weight(double cos_theta, double eta);

/* The net flux vector of the transmitted light per channel,
 *     F(x) = int Ft(eta, w . n) L_i(x, w) (w . n) w_t(w) dw,
 * w_t(w) the direction into the object of the light arriving from w (Snell's
 * law): F / E is the transmitted-flux-weighted mean refracted direction, of
 * length 1 when the light arrives from one direction, shorter the more the
 * directions spread (under a uniform sky 2/3 index-matched, 0.84 at eta 1.3), its
 * component along -n the mean cosine of the refracted directions. */
typedef struct {
  ss_vec3 c[3];
} ss_irradiance_flux;

/* Fills E and power of points [0, n) (their p, n, area and shape set) with
 * `samples` samples each, eta the relative index of each point's boundary
 * (eta_of_shape[shape]), on `threads` threads (0: OpenMP's default), and
 * flux[0, n) with F from the same samples when `flux` is not NULL (E is the
 * same either way). Returns the rays traced in *stats (may be NULL). */
void ss_irradiance_points_compute(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                                  const double *eta_of_shape, int samples, uint64_t seed,
                                  int threads, ss_irradiance_flux *flux, ss_path_stats *stats);
/* The same with the direct light only: the lights sampled from each point
 * (no MIS, no continuation), for the `fem` integrator's boundary source. */
void ss_irradiance_points_direct(const ss_scene *scene, ss_irradiance_point *points, size_t n,
                                 const double *eta_of_shape, int samples, uint64_t seed,
                                 int threads, ss_irradiance_flux *flux, ss_path_stats *stats);

#endif
