/* Overlapping boxes (box_overlaps.h) by Embree's BVH-against-BVH traversal
 * (rtcCollide) on one user geometry whose primitives are the boxes. Embree
 * reports candidate pairs from its worker threads, in no fixed order and
 * with pairs whose float bounds only nearly meet: each is tested in double,
 * appended under a lock, and the list is sorted and made unique after. */
#include "render/box_overlaps.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

typedef struct {
  const ss_vec3 *lo, *hi;
  pthread_mutex_t lock;
  ss_box_pair *pairs;
  size_t n, cap;
  int failed; /* out of memory while appending */
} collect;

/* Float bounds that contain the double box (rounded outwards). */
static void box_bounds(const struct RTCBoundsFunctionArguments *args) {
  const collect *c = args->geometryUserPtr;
  ss_vec3 lo = c->lo[args->primID], hi = c->hi[args->primID];
  struct RTCBounds *b = args->bounds_o;
  b->lower_x = nextafterf((float)lo.x, -INFINITY);
  b->lower_y = nextafterf((float)lo.y, -INFINITY);
  b->lower_z = nextafterf((float)lo.z, -INFINITY);
  b->upper_x = nextafterf((float)hi.x, INFINITY);
  b->upper_y = nextafterf((float)hi.y, INFINITY);
  b->upper_z = nextafterf((float)hi.z, INFINITY);
}

static int boxes_meet(const collect *c, size_t i, size_t j) {
  ss_vec3 a0 = c->lo[i], a1 = c->hi[i], b0 = c->lo[j], b1 = c->hi[j];
  return a0.x <= b1.x && b0.x <= a1.x && a0.y <= b1.y && b0.y <= a1.y && a0.z <= b1.z &&
         b0.z <= a1.z;
}

static void on_collisions(void *user, struct RTCCollision *col, unsigned int count) {
  collect *c = user;
  pthread_mutex_lock(&c->lock);
  for (unsigned k = 0; k < count && !c->failed; ++k) {
    size_t i = col[k].primID0, j = col[k].primID1;
    if (i == j || !boxes_meet(c, i, j)) {
      continue;
    }
    if (c->n == c->cap) {
      size_t cap = c->cap ? 2 * c->cap : 1024;
      ss_box_pair *grown = realloc(c->pairs, cap * sizeof *grown);
      if (!grown) {
        c->failed = 1;
        break;
      }
      c->pairs = grown;
      c->cap = cap;
    }
    c->pairs[c->n++] = i < j ? (ss_box_pair){i, j} : (ss_box_pair){j, i};
  }
  pthread_mutex_unlock(&c->lock);
}

static int compare_pairs(const void *pa, const void *pb) {
  const ss_box_pair *a = pa, *b = pb;
  if (a->i != b->i) {
    return a->i < b->i ? -1 : 1;
  }
  return a->j < b->j ? -1 : (a->j > b->j);
}

/* Sorts and drops repeats (a self-collision reports (i, j) and (j, i)). */
static size_t sort_unique(ss_box_pair *p, size_t n) {
  if (n == 0) {
    return 0;
  }
  qsort(p, n, sizeof *p, compare_pairs);
  size_t m = 1;
  for (size_t k = 1; k < n; ++k) {
    if (compare_pairs(&p[k], &p[m - 1]) != 0) {
      p[m++] = p[k];
    }
  }
  return m;
}

ss_status ss_box_overlaps(const ss_vec3 *lo, const ss_vec3 *hi, size_t n, ss_box_pair **pairs,
                          size_t *num_pairs, ss_error *err) {
  *pairs = NULL;
  *num_pairs = 0;
  if (n < 2) {
    return SS_OK;
  }
  if (n > 0xffffffffu) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "scene: more than 2^32 - 1 shapes");
  }
  collect c = {lo, hi, PTHREAD_MUTEX_INITIALIZER, NULL, 0, 0, 0};
  RTCDevice device = rtcNewDevice("verbose=0");
  RTCScene scene = device ? rtcNewScene(device) : NULL;
  RTCGeometry g = scene ? rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER) : NULL;
  ss_status st = SS_OK;
  if (!g) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "scene: cannot create an Embree scene (code %d)",
                      device ? (int)rtcGetDeviceError(device) : 0);
  } else {
    rtcSetGeometryUserPrimitiveCount(g, (unsigned)n);
    rtcSetGeometryUserData(g, &c);
    rtcSetGeometryBoundsFunction(g, box_bounds, NULL);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    rtcCollide(scene, scene, on_collisions, &c);
    enum RTCError code = rtcGetDeviceError(device);
    if (c.failed || code != RTC_ERROR_NONE) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY,
                        "scene: out of memory while relating %zu shapes (Embree code %d)", n,
                        (int)code);
    }
  }
  if (scene) {
    rtcReleaseScene(scene);
  }
  if (device) {
    rtcReleaseDevice(device);
  }
  pthread_mutex_destroy(&c.lock);
  if (st != SS_OK) {
    free(c.pairs);
    return st;
  }
  *pairs = c.pairs;
  *num_pairs = sort_unique(c.pairs, c.n);
  return SS_OK;
}
