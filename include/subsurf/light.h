/* Light sources.
 *
 * Delta lights (point, spot, directional, beam) are reached only by light
 * sampling; area lights (emissive meshes, one-sided: they emit on the side
 * their outward normal points to) and the constant environment are also hit
 * by rays and then weighted by multiple importance sampling.
 *
 * `value` means, by type:
 *   point, spot   intensity (W/sr)
 *   directional   irradiance on a plane normal to the direction (W/m^2)
 *   area          radiance (W/m^2/sr)
 *   environment   radiance arriving from every direction (W/m^2/sr), or
 *                 the factor on the radiance of its map (envmap.h)
 *   beam          total power (W) of a collimated beam of circular
 *                 cross-section (radius, centre `position`, travelling
 *                 along `direction`), the papers' narrow-beam set-up. */
#ifndef SUBSURF_LIGHT_H
#define SUBSURF_LIGHT_H

#include "subsurf/accel.h"
#include "subsurf/envmap.h"
#include "subsurf/material.h"
#include "subsurf/rgb.h"
#include "subsurf/sampling.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

/* Largest `value` a light may have (any channel): it leaves 18 orders of
 * magnitude below the float range of the image for geometry terms and sample
 * weights, so that an image pixel does not overflow to Inf. */
#define SS_LIGHT_MAX_VALUE 1e20

typedef enum {
  SS_LIGHT_POINT,
  SS_LIGHT_SPOT,
  SS_LIGHT_DIRECTIONAL,
  SS_LIGHT_AREA,
  SS_LIGHT_ENVIRONMENT,
  SS_LIGHT_BEAM,
} ss_light_type;

typedef struct {
  ss_light_type type;
  char name[SS_NAME_SIZE];
  ss_rgb value;
  ss_vec3 position;     /* point, spot; beam: centre of the emitting disk */
  ss_vec3 direction;    /* spot axis; directional and beam: propagation direction */
  double cone_angle;    /* spot: total half-angle, degrees */
  double falloff_angle; /* spot: half-angle where the smooth falloff starts, degrees */
  int spot_smoothstep;  /* spot: pbrt-v4's smoothstep falloff instead of pbrt-v3's quartic */
  double radius;        /* beam radius */
  int shape;            /* area: index of the emissive shape */
  ss_envmap *map;       /* environment: its image, owned (NULL: uniform) */

  /* Derived by ss_light_init. */
  double cos_outer, cos_inner;
  ss_frame frame;         /* beam: frame.n = direction */
  ss_distribution1d tris; /* area: triangle areas */
  double area;            /* area: total area */
  const ss_mesh *mesh;    /* area: the emissive mesh */
  /* area: the mesh's bounding sphere, and whether directions are sampled in
   * the cone it subtends (a closed, round emitter: see ss_light_bind) */
  ss_vec3 bound_centre;
  double bound_radius;
  int round;
  const ss_accel *accel; /* set by ss_light_bind: the scene's, for the cone's hit on the mesh */
} ss_light;

/* A light sample as seen from a reference point. */
typedef struct {
  ss_vec3 wi;   /* unit direction from the reference point toward the light */
  double dist;  /* distance to the sampled point (INFINITY: directional/environment) */
  ss_vec3 p, n; /* sampled point and its geometric normal (n = 0 for non-surfaces) */
  ss_rgb li;    /* incident radiance, or irradiance for delta lights */
  double pdf;   /* solid-angle density; 1 for delta lights */
  int delta;    /* 1 for point, spot, directional and beam */
} ss_light_sample;

/* Validates the light and builds its sampling data; `mesh` is the emissive
 * shape's mesh for area lights (NULL otherwise). The message names the light. */
ss_status ss_light_init(ss_light *light, const ss_mesh *mesh, ss_error *err);
void ss_light_free(ss_light *light);

int ss_light_is_delta(const ss_light *light);

/* Binds an area light to the scene's accel, whose geometry `light->shape`
 * is its mesh. A round emitter (mesh area at least half its bounding
 * sphere's, 2 pi R^2: a sphere, a cube) is then sampled from a reference
 * point outside that sphere by a direction uniform in the cone the sphere
 * subtends, the emitting point being the first hit of that direction on the
 * mesh (pbrt-v3 sec. 14.2.2's sphere sampling, made exact for a tessellated
 * mesh by the ray query): uniform-by-area sampling wastes the half of the
 * points that face away and weights the rest by cos / d^2. Unbound lights
 * (and reference points inside the sphere) sample by area. */
void ss_light_bind(ss_light *light, const ss_accel *accel);

/* Samples incident light at `ref`; returns 0 when the light cannot reach it
 * (outside a spot's cone or a beam's cylinder, a back-facing area sample). */
int ss_light_sample_li(const ss_light *light, ss_vec3 ref, double u1, double u2,
                       ss_light_sample *s);
/* An area light's point p (unit geometric normal n) uniform by area, density
 * 1 / light->area, with the random numbers ss_light_sample_li would use when
 * it samples by area; whether it faces a reference point is left to the
 * caller. */
int ss_light_sample_point(const ss_light *light, double u1, double u2, ss_vec3 *p, ss_vec3 *n);
/* Solid-angle density with which ss_light_sample_li would pick direction wi
 * from `ref` when the ray hits the area light at `hit` (area lights: the
 * light's first point along wi, as a ray from ref finds it), or any
 * direction (environment). 0 for delta lights. */
double ss_light_pdf_li(const ss_light *light, ss_vec3 ref, ss_vec3 wi, const ss_hit *hit);
/* Radiance leaving an area light at a point with geometric normal ng toward
 * w (unit, pointing away from the light), or of the environment seen along
 * a ray that escapes with direction -w. Black for delta lights. */
ss_rgb ss_light_le(const ss_light *light, ss_vec3 ng, ss_vec3 w);

/* The environment's radiance arriving from unit direction w and, in
 * *pdf, the density ss_light_pdf_li gives w: the two lookups of an
 * escaped ray in one (a map is looked up once). */
ss_rgb ss_light_environment_li(const ss_light *env, ss_vec3 w, double *pdf);

/* Parses "point", "spot", "directional", "area", "environment", "beam". */
int ss_light_type_from_name(const char *name, ss_light_type *type);
const char *ss_light_type_name(ss_light_type type);

#endif
