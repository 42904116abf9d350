/* Ray queries against triangle meshes, backed by Embree 3.
 *
 * An ss_accel is an opaque handle built once from an array of meshes; mesh k
 * gets geometry id k. The vertex and index buffers are shared with Embree
 * and the meshes are read during queries (shading normals, uvs), so they
 * must outlive the accel and must not change. Every query is thread-safe
 * (call from OpenMP threads).
 *
 * Conventions: a ray is o + t d for t in (tmin, tmax); d need not be unit
 * and t is measured in units of |d|. The geometric normal ng follows the
 * winding (mesh.h: outward for closed shapes), so dot(d, ng) < 0 means the
 * ray arrives from the outside. */
#ifndef SUBSURF_ACCEL_H
#define SUBSURF_ACCEL_H

#include "subsurf/mesh.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <math.h>
#include <stddef.h>

/* Every position of a scene (vertices, camera, lights) must lie within
 * |x|, |y|, |z| <= SS_WORLD_LIMIT (scenes are validated against it). Embree
 * works in float and asserts on rays whose origin exceeds 1.8e18; at 1e8 a
 * float still resolves 8 units, which is as far as a scene can sensibly go. */
#define SS_WORLD_LIMIT 1e8

/* 1 when every coordinate of p is within the world limit (NaN is not). */
static inline int ss_in_world(ss_vec3 p) {
  return fabs(p.x) <= SS_WORLD_LIMIT && fabs(p.y) <= SS_WORLD_LIMIT && fabs(p.z) <= SS_WORLD_LIMIT;
}

typedef struct {
  ss_vec3 o, d;
  double tmin, tmax;
} ss_ray;

typedef struct {
  double t;
  unsigned geom_id, prim_id;
  double b1, b2; /* barycentrics: p = (1 - b1 - b2) p0 + b1 p1 + b2 p2 */
  ss_vec3 p;     /* position from the barycentrics (more accurate than o + t d) */
  ss_vec3 ng;    /* unit geometric normal, from the winding */
  ss_vec3 ns;    /* unit shading normal: interpolated vertex normals turned
                    into ng's hemisphere, or ng when the mesh has none */
  double st[2];  /* texture coordinates, 0 when the mesh has none */
} ss_hit;

typedef struct ss_accel ss_accel;

/* Builds the Embree scene. `meshes[k]` becomes geometry k. Embree errors are
 * recorded in err (via the device's error callback) with their code. */
ss_status ss_accel_create(const ss_mesh *const *meshes, size_t count, ss_accel **out,
                          ss_error *err);
void ss_accel_destroy(ss_accel *accel);
/* ss_accel_create builds a BVH of low quality (fast to build, slower to
 * traverse); this builds a high-quality one (spatial splits) that later
 * queries use, once: worth it when the queries to come outnumber the
 * triangles. Thread-safe, also while queries run (they see either BVH: the
 * same hits, but for a tie where a ray meets an edge exactly). On failure
 * the first BVH stays in use. */
ss_status ss_accel_refine(ss_accel *accel, ss_error *err);
size_t ss_accel_triangle_count(const ss_accel *accel);

size_t ss_accel_mesh_count(const ss_accel *accel);
const ss_mesh *ss_accel_mesh(const ss_accel *accel, unsigned geom_id);
/* World bounds of all meshes. */
void ss_accel_bounds(const ss_accel *accel, ss_vec3 *lo, ss_vec3 *hi);

/* Closest hit in (tmin, tmax); returns 1 and fills *hit, or 0 on a miss. */
int ss_accel_intersect(const ss_accel *accel, const ss_ray *ray, ss_hit *hit);
/* Lazy hit records: the same closest hit with only what Embree
 * knows, so the mesh's vertices are not read: t, the ids, the barycentrics,
 * ng = Embree's geometric normal made unit (float precision, same side as
 * ss_accel_intersect's), p = o + t d, ns = ng and st = 0.
 * ss_accel_hit_complete then fills the record as ss_accel_intersect would. */
int ss_accel_intersect_distance(const ss_accel *accel, const ss_ray *ray, ss_hit *hit);
void ss_accel_hit_complete(const ss_accel *accel, ss_hit *hit);
/* Returns 1 when anything lies in (tmin, tmax) (shadow rays). */
int ss_accel_occluded(const ss_accel *accel, const ss_ray *ray);
/* Occlusion by the geometries k with pass[k] == 0 only (pass has one entry
 * per mesh): the others are seen through, and *passed is set to 1 when the
 * ray crossed one of them (left unchanged otherwise; meaningful only when
 * the ray is not occluded). One traversal, stopping at the first blocker:
 * a shadow ray through index-matched boundaries (Embree filter callback). */
int ss_accel_occluded_passing(const ss_accel *accel, const ss_ray *ray, const unsigned char *pass,
                              int *passed);

/* All hits of ONE object (geom_id) along the segment (tmin, tmax), ignoring
 * every other object: the BSSRDF probe query (Cycles' local intersection).
 * Hits arrive unordered from Embree and the same crossing can be reported
 * more than once (a triangle referenced twice by the BVH, or the triangles
 * sharing an edge or vertex the ray passes through); they are deduplicated
 * by (geom_id, prim_id) and by (same side of the surface, distance along
 * the ray within 1e-6 of the magnitude of the segment's end points and
 * length), so each surface crossing counts once.
 *
 * Every distinct hit is kept (a fixed buffer of SS_ACCEL_LOCAL_HITS, then a
 * heap array), so the deduplication is exact for any number of crossings and
 * results do not depend on Embree's traversal order; Cycles' reservoir over a
 * fixed buffer could not recognise duplicates of hits it had evicted.
 *
 * ss_accel_intersect_all stores the min(count, max_hits) closest hits sorted
 * by t and returns the number of distinct hits along the segment. */
#define SS_ACCEL_LOCAL_HITS 64
size_t ss_accel_intersect_all(const ss_accel *accel, const ss_ray *ray, unsigned geom_id,
                              ss_hit *hits, size_t max_hits);
/* Picks one of the distinct hits uniformly: the hit of rank floor(u * count)
 * in order of t, u in [0, 1). Returns their number (0: no hit, *hit
 * untouched); the sample's probability is 1 / count. */
size_t ss_accel_intersect_sample(const ss_accel *accel, const ss_ray *ray, unsigned geom_id,
                                 double u, ss_hit *hit);

/* ---- Robust ray spawning (Waechter & Binder 2019, "A Fast and Robust
 * Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6): the point
 * is moved along +ng or -ng, towards the side `w` points into, by a few
 * float ulps scaled to the magnitude of its coordinates (a fixed tiny offset
 * near the origin). A ray leaving from the offset point with tmin = 0 does
 * not hit the surface it starts on, on either side, so a path cannot leak
 * out of (or into) a closed mesh. */
ss_vec3 ss_offset_ray_origin(ss_vec3 p, ss_vec3 ng, ss_vec3 w);
/* Ray from a surface point p (geometric normal ng) in direction d: offset
 * origin, tmin = 0, tmax = INFINITY. */
ss_ray ss_ray_spawn(ss_vec3 p, ss_vec3 ng, ss_vec3 d);
/* Shadow ray between two surface points, both ends offset towards each other;
 * t in (0, 1 - 1e-4) covers the open segment. Pass a zero normal for a point
 * that is not on a surface (a point light, a medium vertex). */
ss_ray ss_ray_spawn_to(ss_vec3 p0, ss_vec3 n0, ss_vec3 p1, ss_vec3 n1);

#endif
