/* Ray queries on Embree 3. Embree shares the meshes' vertex and index
 * arrays; they are read back to build hit records in double. */
#include "subsurf/accel.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

struct ss_accel {
  RTCDevice device;
  RTCScene scene;
  const ss_mesh **meshes;
  size_t count;
  double scale;           /* largest |coordinate| of the scene, for hit tolerances */
  ss_error embree;        /* first error reported by Embree's callback */
  _Atomic(RTCScene) fine; /* the high-quality BVH (ss_accel_refine), or NULL */
};

/* The scene queries traverse: the high-quality BVH once built. */
static RTCScene current(const ss_accel *a) {
  RTCScene fine = atomic_load_explicit((_Atomic(RTCScene) *)&a->fine, memory_order_acquire);
  return fine ? fine : a->scene;
}

static const char *rtc_error_name(enum RTCError code) {
  switch (code) {
  case RTC_ERROR_NONE:
    return "none";
  case RTC_ERROR_UNKNOWN:
    return "unknown error";
  case RTC_ERROR_INVALID_ARGUMENT:
    return "invalid argument";
  case RTC_ERROR_INVALID_OPERATION:
    return "invalid operation";
  case RTC_ERROR_OUT_OF_MEMORY:
    return "out of memory";
  case RTC_ERROR_UNSUPPORTED_CPU:
    return "unsupported CPU";
  case RTC_ERROR_CANCELLED:
    return "cancelled";
  }
  return "unrecognised error";
}

/* Embree reports errors through this callback; the first one is kept so that
 * ss_accel_create can return it with the context it happened in. */
static void on_embree_error(void *user, enum RTCError code, const char *str) {
  ss_accel *a = user;
  if (a->embree.status == SS_OK) {
    ss_error_set(&a->embree,
                 code == RTC_ERROR_OUT_OF_MEMORY ? SS_ERR_NO_MEMORY : SS_ERR_UNSUPPORTED,
                 "Embree %s (code %d): %s", rtc_error_name(code), (int)code, str ? str : "");
  }
}

static ss_status embree_failed(ss_accel *a, ss_error *err, const char *what) {
  ss_status st = a->embree.status != SS_OK ? a->embree.status : SS_ERR_UNSUPPORTED;
  if (a->embree.status == SS_OK) {
    ss_error_set(&a->embree, st, "Embree returned no result");
  }
  ss_error_set(err, st, "accel: %s: %s", what, a->embree.message);
  return st;
}

static ss_status attach_mesh(ss_accel *a, RTCScene scene, const ss_mesh *m, unsigned id,
                             enum RTCBuildQuality quality, ss_error *err) {
  RTCGeometry g = rtcNewGeometry(a->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!g) {
    return embree_failed(a, err, "creating a triangle geometry");
  }
  /* Vertices and indices are shared, as the meshes outlive the accelerator
   * (its queries read them); Embree reads 16 bytes at the last vertex, the
   * float of padding every ss_mesh's positions carry (mesh.h). */
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m->positions, 0,
                             3 * sizeof(float), m->num_vertices);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->indices, 0,
                             3 * sizeof(uint32_t), m->num_triangles);
  rtcSetGeometryMask(g, 0xFFFFFFFFu);
  rtcSetGeometryBuildQuality(g, quality);
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, id);
  rtcReleaseGeometry(g);
  if (a->embree.status != SS_OK) {
    return embree_failed(a, err, "attaching a mesh");
  }
  return SS_OK;
}

/* The Embree scene of the meshes with BVHs built at `quality` (the scene's
 * and its geometries': a geometry's own quality, MEDIUM by default, decides
 * its build); NULL on failure. */
static RTCScene build_scene(ss_accel *a, enum RTCBuildQuality quality, ss_error *err) {
  RTCScene scene = rtcNewScene(a->device);
  if (!scene) {
    embree_failed(a, err, "creating the scene");
    return NULL;
  }
  /* ROBUST: watertight traversal, so that no ray slips between two triangles
   * sharing an edge (a path must not leak out of a closed medium).
   * CONTEXT_FILTER_FUNCTION: the per-query filter of the all-hits query. */
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene, quality);
  for (size_t k = 0; k < a->count; ++k) {
    if (attach_mesh(a, scene, a->meshes[k], (unsigned)k, quality, err) != SS_OK) {
      ss_error_prefix(err, "mesh %zu: ", k);
      rtcReleaseScene(scene);
      return NULL;
    }
  }
  rtcCommitScene(scene);
  if (a->embree.status != SS_OK) {
    embree_failed(a, err, "building the BVH");
    rtcReleaseScene(scene);
    return NULL;
  }
  return scene;
}

ss_status ss_accel_create(const ss_mesh *const *meshes, size_t count, ss_accel **out,
                          ss_error *err) {
  *out = NULL;
  if (count == 0 || count >= RTC_INVALID_GEOMETRY_ID) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "accel: %zu meshes (expected at least 1)",
                        count);
  }
  for (size_t k = 0; k < count; ++k) {
    if (!meshes[k] || meshes[k]->num_triangles == 0) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "accel: mesh %zu has no triangles", k);
    }
    ss_status st = ss_mesh_validate(meshes[k], NULL, err);
    if (st != SS_OK) {
      ss_error_prefix(err, "accel: mesh %zu: ", k);
      return st;
    }
  }
  ss_accel *a = calloc(1, sizeof *a);
  if (!a || !(a->meshes = malloc(count * sizeof *a->meshes))) {
    free(a);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "accel: out of memory");
  }
  ss_error_clear(&a->embree);
  memcpy(a->meshes, meshes, count * sizeof *a->meshes);
  a->count = count;
  atomic_init(&a->fine, NULL);
  ss_status st = SS_OK;
  a->device = rtcNewDevice("verbose=0");
  if (!a->device) {
    enum RTCError code = rtcGetDeviceError(NULL);
    st = ss_error_set(err, SS_ERR_UNSUPPORTED, "accel: cannot create an Embree device: %s",
                      rtc_error_name(code));
    goto fail;
  }
  rtcSetDeviceErrorFunction(a->device, on_embree_error, a);
  /* A first BVH of low quality (Morton codes: about 1/3 of the CPU time of
   * the default build), so that short renders start at once;
   * ss_accel_refine builds the high-quality one for long renders
   * (bench/RESULTS.md). */
  if (!(a->scene = build_scene(a, RTC_BUILD_QUALITY_LOW, err))) {
    st = a->embree.status != SS_OK ? a->embree.status : SS_ERR_UNSUPPORTED;
    goto fail;
  }
  ss_vec3 lo, hi;
  ss_accel_bounds(a, &lo, &hi);
  a->scale = fmax(fmax(fabs(lo.x), fabs(hi.x)),
                  fmax(fmax(fabs(lo.y), fabs(hi.y)), fmax(fabs(lo.z), fabs(hi.z))));
  *out = a;
  return SS_OK;
fail:
  ss_accel_destroy(a);
  return st;
}

ss_status ss_accel_refine(ss_accel *a, ss_error *err) {
  ss_status st = SS_OK;
#pragma omp critical(ss_accel_refine)
  if (!atomic_load_explicit(&a->fine, memory_order_acquire)) {
    RTCScene fine = build_scene(a, RTC_BUILD_QUALITY_HIGH, err);
    if (fine) {
      atomic_store_explicit(&a->fine, fine, memory_order_release);
    } else {
      st = a->embree.status != SS_OK ? a->embree.status : SS_ERR_UNSUPPORTED;
    }
  }
  return st;
}

size_t ss_accel_triangle_count(const ss_accel *a) {
  size_t n = 0;
  for (size_t k = 0; k < a->count; ++k) {
    n += a->meshes[k]->num_triangles;
  }
  return n;
}

void ss_accel_destroy(ss_accel *a) {
  if (!a) {
    return;
  }
  if (a->scene) {
    rtcReleaseScene(a->scene);
  }
  RTCScene fine = atomic_load(&a->fine);
  if (fine) {
    rtcReleaseScene(fine);
  }
  if (a->device) {
    rtcReleaseDevice(a->device);
  }
  free(a->meshes);
  free(a);
}

size_t ss_accel_mesh_count(const ss_accel *a) { return a->count; }

const ss_mesh *ss_accel_mesh(const ss_accel *a, unsigned geom_id) {
  return geom_id < a->count ? a->meshes[geom_id] : NULL;
}

void ss_accel_bounds(const ss_accel *a, ss_vec3 *lo, ss_vec3 *hi) {
  struct RTCBounds b;
  rtcGetSceneBounds(a->scene, &b);
  *lo = ss_vec3_make(b.lower_x, b.lower_y, b.lower_z);
  *hi = ss_vec3_make(b.upper_x, b.upper_y, b.upper_z);
}

static void set_ray(struct RTCRay *r, const ss_ray *ray) {
  r->org_x = (float)ray->o.x;
  r->org_y = (float)ray->o.y;
  r->org_z = (float)ray->o.z;
  r->dir_x = (float)ray->d.x;
  r->dir_y = (float)ray->d.y;
  r->dir_z = (float)ray->d.z;
  r->tnear = (float)fmax(ray->tmin, 0.0);
  r->tfar = (float)ray->tmax;
  r->time = 0.0f;
  r->mask = 0xFFFFFFFFu;
  r->id = 0;
  r->flags = 0;
}

/* Hit record in double from the mesh data (Embree's float Ng and t are only
 * used to find the triangle). */
static void fill_hit(const ss_accel *a, unsigned geom, unsigned prim, double t, double b1,
                     double b2, ss_hit *h) {
  const ss_mesh *m = a->meshes[geom];
  const uint32_t *idx = m->indices + 3 * (size_t)prim;
  ss_vec3 p[3];
  ss_mesh_triangle(m, prim, p);
  double b0 = 1.0 - b1 - b2;
  h->t = t;
  h->geom_id = geom;
  h->prim_id = prim;
  h->b1 = b1;
  h->b2 = b2;
  h->p = ss_vec3_add(ss_vec3_scale(p[0], b0),
                     ss_vec3_add(ss_vec3_scale(p[1], b1), ss_vec3_scale(p[2], b2)));
  ss_vec3 ng = ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0]));
  double len = ss_vec3_length(ng);
  h->ng = len > 0.0 ? ss_vec3_scale(ng, 1.0 / len) : ss_vec3_make(0.0, 0.0, 1.0);
  h->ns = h->ng;
  if (m->normals) {
    ss_vec3 n = ss_vec3_make(0.0, 0.0, 0.0);
    const double w[3] = {b0, b1, b2};
    for (int k = 0; k < 3; ++k) {
      const float *nk = m->normals + 3 * (size_t)idx[k];
      n = ss_vec3_madd(n, ss_vec3_make(nk[0], nk[1], nk[2]), w[k]);
    }
    double nl = ss_vec3_length(n);
    if (nl > 0.0) {
      n = ss_vec3_scale(n, 1.0 / nl);
      h->ns = ss_vec3_dot(n, h->ng) < 0.0 ? ss_vec3_neg(n) : n;
    }
  }
  h->st[0] = h->st[1] = 0.0;
  if (m->uvs) {
    const float *t0 = m->uvs + 2 * (size_t)idx[0], *t1 = m->uvs + 2 * (size_t)idx[1];
    const float *t2 = m->uvs + 2 * (size_t)idx[2];
    h->st[0] = b0 * t0[0] + b1 * t1[0] + b2 * t2[0];
    h->st[1] = b0 * t0[1] + b1 * t1[1] + b2 * t2[1];
  }
}

/* Embree's closest hit of `ray` in *rh; 0 when the ray hits nothing. */
static int closest_hit(const ss_accel *a, const ss_ray *ray, struct RTCRayHit *rh) {
  set_ray(&rh->ray, ray);
  rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  struct RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(current(a), &ctx, rh);
  return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

int ss_accel_intersect(const ss_accel *a, const ss_ray *ray, ss_hit *hit) {
  struct RTCRayHit rh;
  if (!closest_hit(a, ray, &rh)) {
    return 0;
  }
  fill_hit(a, rh.hit.geomID, rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v, hit);
  return 1;
}

int ss_accel_intersect_distance(const ss_accel *a, const ss_ray *ray, ss_hit *hit) {
  struct RTCRayHit rh;
  if (!closest_hit(a, ray, &rh)) {
    return 0;
  }
  hit->t = rh.ray.tfar;
  hit->geom_id = rh.hit.geomID;
  hit->prim_id = rh.hit.primID;
  hit->b1 = rh.hit.u;
  hit->b2 = rh.hit.v;
  hit->p = ss_vec3_madd(ray->o, ray->d, hit->t);
  ss_vec3 ng = ss_vec3_make(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  double len = ss_vec3_length(ng);
  hit->ng = len > 0.0 ? ss_vec3_scale(ng, 1.0 / len) : ss_vec3_make(0.0, 0.0, 1.0);
  hit->ns = hit->ng;
  hit->st[0] = hit->st[1] = 0.0;
  return 1;
}

void ss_accel_hit_complete(const ss_accel *a, ss_hit *hit) {
  fill_hit(a, hit->geom_id, hit->prim_id, hit->t, hit->b1, hit->b2, hit);
}

int ss_accel_occluded(const ss_accel *a, const ss_ray *ray) {
  struct RTCRay r;
  set_ray(&r, ray);
  struct RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded1(current(a), &ctx, &r);
  return r.tfar == -INFINITY;
}

/* ---- Occlusion through pass-through geometries. The context comes first so
 * that the filter can recover the rest. */
typedef struct {
  struct RTCIntersectContext ctx;
  const unsigned char *pass;
  size_t count;
  int passed;
} pass_query;

/* Rejects (sees through) candidates of pass-through geometries, noting that
 * one was crossed; any other candidate stands and ends the occlusion query. */
static void pass_filter(const struct RTCFilterFunctionNArguments *args) {
  pass_query *q = (pass_query *)args->context;
  const unsigned *hu = (const unsigned *)args->hit;
  for (unsigned i = 0; i < args->N; ++i) {
    unsigned geom = hu[6 * args->N + i];
    if (args->valid[i] && geom < q->count && q->pass[geom]) {
      args->valid[i] = 0;
      q->passed = 1;
    }
  }
}

int ss_accel_occluded_passing(const ss_accel *a, const ss_ray *ray, const unsigned char *pass,
                              int *passed) {
  pass_query q;
  rtcInitIntersectContext(&q.ctx);
  q.ctx.filter = pass_filter;
  q.pass = pass;
  q.count = a->count;
  q.passed = 0;
  struct RTCRay r;
  set_ray(&r, ray);
  rtcOccluded1(current(a), &q.ctx, &r);
  if (r.tfar == -INFINITY) {
    return 1;
  }
  if (q.passed) {
    *passed = 1;
  }
  return 0;
}

/* ---- All hits of one object along a segment. */

typedef struct {
  float t, u, v;
  unsigned prim;
  int front; /* 1 when the ray arrives from the side the winding faces */
} local_hit;

/* The Embree context comes first so that the filter can recover the rest.
 * Hits go to a fixed buffer and, past it, to a growing heap array: keeping
 * every distinct hit makes the deduplication exact for any number of
 * crossings (a reservoir that evicts hits cannot recognise their duplicates
 * later) and the choice independent of Embree's traversal order. */
typedef struct {
  struct RTCIntersectContext ctx;
  unsigned geom;
  float tol; /* two hits of the same facing closer than this in t are one crossing */
  size_t count, capacity;
  local_hit *hits; /* = buf, or a heap array once buf is full */
  int oom;         /* a heap allocation failed: later hits are dropped */
  local_hit buf[SS_ACCEL_LOCAL_HITS];
} local_query;

static int same_crossing(const local_hit *a, const local_hit *b, float tol) {
  return a->prim == b->prim || (a->front == b->front && fabsf(a->t - b->t) <= tol);
}

static void local_push(local_query *q, const local_hit *h) {
  if (q->count == q->capacity) {
    size_t cap = 4 * q->capacity;
    local_hit *grown = malloc(cap * sizeof *grown);
    if (!grown) {
      q->oom = 1;
      return;
    }
    memcpy(grown, q->hits, q->count * sizeof *grown);
    if (q->hits != q->buf) {
      free(q->hits);
    }
    q->hits = grown;
    q->capacity = cap;
  }
  q->hits[q->count++] = *h;
}

/* Rejects every candidate, so that traversal continues to tfar, after
 * recording the distinct ones of the target object (Cycles' local
 * intersection). Embree may report one crossing several times: a triangle
 * referenced by two BVH leaves (same prim), or the triangles around an edge
 * or vertex the ray passes through (same t, same facing). */
static void local_filter(const struct RTCFilterFunctionNArguments *args) {
  local_query *q = (local_query *)args->context;
  unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) {
      continue;
    }
    args->valid[i] = 0;
    const float *hf = (const float *)args->hit;
    const unsigned *hu = (const unsigned *)args->hit;
    const float *rf = (const float *)args->ray;
    if (hu[6 * N + i] != q->geom) {
      continue;
    }
    double dn = (double)rf[4 * N + i] * hf[0 * N + i] + (double)rf[5 * N + i] * hf[1 * N + i] +
                (double)rf[6 * N + i] * hf[2 * N + i];
    local_hit h = {rf[8 * N + i], hf[3 * N + i], hf[4 * N + i], hu[5 * N + i], dn < 0.0};
    int dup = 0;
    for (size_t k = 0; k < q->count && !dup; ++k) {
      dup = same_crossing(&q->hits[k], &h, q->tol);
    }
    if (!dup) {
      local_push(q, &h);
    }
  }
}

static int compare_local(const void *a, const void *b) {
  const local_hit *x = a, *y = b;
  if (x->t != y->t) {
    return x->t < y->t ? -1 : 1;
  }
  return (x->prim > y->prim) - (x->prim < y->prim);
}

static void local_run(const ss_accel *a, const ss_ray *ray, unsigned geom, local_query *q) {
  rtcInitIntersectContext(&q->ctx);
  q->ctx.filter = local_filter;
  q->geom = geom;
  q->count = 0;
  q->capacity = SS_ACCEL_LOCAL_HITS;
  q->hits = q->buf;
  q->oom = 0;
  /* Float hit distances are accurate to a few ulps of the coordinates along
   * the segment: scale the tolerance to its ends (or to the scene for an
   * unbounded ray), not to the whole scene, so small objects in large
   * scenes keep distinct crossings apart. */
  double dl = ss_vec3_length(ray->d), mag = a->scale;
  if (isfinite(ray->tmax)) {
    ss_vec3 e = ss_vec3_madd(ray->o, ray->d, ray->tmax);
    mag = fmax(fmax(fabs(e.x), fabs(e.y)), fabs(e.z));
  }
  mag = fmax(mag, fmax(fmax(fabs(ray->o.x), fabs(ray->o.y)), fabs(ray->o.z)));
  q->tol = (float)(1e-6 * (mag + dl * (isfinite(ray->tmax) ? ray->tmax : 0.0)) / dl);
  struct RTCRayHit rh;
  set_ray(&rh.ray, ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  if (geom < a->count) {
    rtcIntersect1(current(a), &q->ctx, &rh);
  }
  qsort(q->hits, q->count, sizeof q->hits[0], compare_local);
}

static void local_free(local_query *q) {
  if (q->hits != q->buf) {
    free(q->hits);
  }
}

size_t ss_accel_intersect_all(const ss_accel *a, const ss_ray *ray, unsigned geom_id, ss_hit *hits,
                              size_t max_hits) {
  local_query q;
  local_run(a, ray, geom_id, &q);
  size_t n = q.count < max_hits ? q.count : max_hits;
  for (size_t k = 0; k < n; ++k) {
    const local_hit *h = &q.hits[k];
    fill_hit(a, geom_id, h->prim, h->t, h->u, h->v, &hits[k]);
  }
  size_t total = q.count;
  local_free(&q);
  return total;
}

size_t ss_accel_intersect_sample(const ss_accel *a, const ss_ray *ray, unsigned geom_id, double u,
                                 ss_hit *hit) {
  local_query q;
  local_run(a, ray, geom_id, &q);
  size_t total = q.count;
  if (total > 0) {
    size_t k = (size_t)(u * (double)total);
    if (k >= total) {
      k = total - 1;
    }
    const local_hit *h = &q.hits[k];
    fill_hit(a, geom_id, h->prim, h->t, h->u, h->v, hit);
  }
  local_free(&q);
  return total;
}

/* ---- Robust spawning: Waechter & Binder 2019, listing 6-1. Offsets are
 * applied to the float coordinates Embree will see, in units of ulps (by
 * adding to the integer representation) far from the origin and as a fixed
 * distance near it, where ulps become tiny. */
static float offset_component(float p, float n) {
  const float origin = 1.0f / 32.0f, float_scale = 1.0f / 65536.0f, int_scale = 256.0f;
  if (fabsf(p) < origin) {
    return p + float_scale * n;
  }
  int32_t of = (int32_t)(int_scale * n), bits;
  memcpy(&bits, &p, sizeof bits);
  bits += (p < 0.0f) ? -of : of;
  float r;
  memcpy(&r, &bits, sizeof r);
  return r;
}

ss_vec3 ss_offset_ray_origin(ss_vec3 p, ss_vec3 ng, ss_vec3 w) {
  double len = ss_vec3_length(ng);
  if (!(len > 0.0)) {
    return ss_vec3_make((float)p.x, (float)p.y, (float)p.z);
  }
  ss_vec3 n = ss_vec3_scale(ng, (ss_vec3_dot(w, ng) < 0.0 ? -1.0 : 1.0) / len);
  return ss_vec3_make(offset_component((float)p.x, (float)n.x),
                      offset_component((float)p.y, (float)n.y),
                      offset_component((float)p.z, (float)n.z));
}

ss_ray ss_ray_spawn(ss_vec3 p, ss_vec3 ng, ss_vec3 d) {
  ss_ray r = {ss_offset_ray_origin(p, ng, d), d, 0.0, INFINITY};
  return r;
}

/* pbrt's ShadowEpsilon: stop short of the far end so that rounding of the
 * float ray cannot reach the surface the target point lies on. */
#define SS_SHADOW_EPSILON 1e-4

ss_ray ss_ray_spawn_to(ss_vec3 p0, ss_vec3 n0, ss_vec3 p1, ss_vec3 n1) {
  ss_vec3 o = ss_offset_ray_origin(p0, n0, ss_vec3_sub(p1, p0));
  ss_vec3 e = ss_offset_ray_origin(p1, n1, ss_vec3_sub(p0, p1));
  ss_ray r = {o, ss_vec3_sub(e, o), 0.0, 1.0 - SS_SHADOW_EPSILON};
  return r;
}
