/* Spherical texture coordinates for a mesh around the origin (the
 * icosphere), with the seam and the poles made seamless by duplicating
 * vertices (see mesh.h). */
#include "subsurf/mesh.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* u = phi / 2pi in [0, 1), v = theta / pi (theta from +z), as
 * ss_shape_sphere_uv. */
static void spherical(const float *p, double *u, double *v, int *pole) {
  double r = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
  double rho = hypot(p[0], p[1]);
  *pole = !(rho > 1e-9 * r);
  double phi = *pole ? 0.0 : atan2(p[1], p[0]);
  *u = phi < 0.0 ? phi / (2.0 * SS_PI) + 1.0 : phi / (2.0 * SS_PI);
  *v = r > 0.0 ? acos(fmax(-1.0, fmin(1.0, p[2] / r))) / SS_PI : 0.0;
}

typedef struct {
  float *pos, *nrm, *uv;
  size_t n, cap;
} vertex_list;

static int push(vertex_list *l, const ss_mesh *m, uint32_t src, double u, double v) {
  if (l->n == l->cap) {
    size_t cap = 2 * l->cap;
    float *p = realloc(l->pos, 3 * cap * sizeof *p);
    if (p)
      l->pos = p;
    float *n = realloc(l->nrm, 3 * cap * sizeof *n);
    if (n)
      l->nrm = n;
    float *t = realloc(l->uv, 2 * cap * sizeof *t);
    if (t)
      l->uv = t;
    if (!p || !n || !t) {
      return 0;
    }
    l->cap = cap;
  }
  memcpy(l->pos + 3 * l->n, m->positions + 3 * (size_t)src, 3 * sizeof(float));
  memcpy(l->nrm + 3 * l->n, m->normals + 3 * (size_t)src, 3 * sizeof(float));
  l->uv[2 * l->n] = (float)u;
  l->uv[2 * l->n + 1] = (float)v;
  l->n++;
  return 1;
}

/* Per triangle: when its corners' u span more than 1/2, the triangle lies
 * across the seam and the corners with u < 1/2 take u + 1 (a copy of the vertex past u = 1); a pole
 * corner takes the mean u of the other two (a copy per triangle), so that
 * no triangle's u spans the whole circle. */
ss_status ss_mesh_add_spherical_uvs(const ss_mesh *m, ss_mesh **out, ss_error *err) {
  *out = NULL;
  size_t nv = m->num_vertices;
  /* Room for the seam and pole copies (a few per thousand vertices on an
   * icosphere), so that push rarely has to grow the arrays. */
  size_t cap = nv + nv / 16 + 64;
  vertex_list l = {malloc(3 * cap * sizeof(float)), malloc(3 * cap * sizeof(float)),
                   malloc(2 * cap * sizeof(float)), 0, cap};
  uint32_t *seam = malloc((nv + 1) * sizeof *seam); /* the u + 1 copy, or UINT32_MAX */
  int *pole = malloc((nv + 1) * sizeof *pole);
  uint32_t *idx = malloc((3 * m->num_triangles + 1) * sizeof *idx);
  ss_status st = SS_OK;
  if (!l.pos || !l.nrm || !l.uv || !seam || !pole || !idx || !m->normals) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "sphere uvs: out of memory");
    goto done;
  }
  for (size_t k = 0; k < nv; ++k) {
    double u, v;
    spherical(m->positions + 3 * k, &u, &v, &pole[k]);
    push(&l, m, (uint32_t)k, u, v);
    seam[k] = UINT32_MAX;
  }
  for (size_t t = 0; t < m->num_triangles; ++t) {
    const uint32_t *c = m->indices + 3 * t;
    double u[3], umin = 2.0, umax = -1.0, usum = 0.0;
    int poles = 0;
    for (int k = 0; k < 3; ++k) {
      u[k] = l.uv[2 * (size_t)c[k]];
      poles += pole[c[k]];
      umin = pole[c[k]] ? umin : fmin(umin, u[k]);
      umax = pole[c[k]] ? umax : fmax(umax, u[k]);
    }
    int across = umax - umin > 0.5;
    for (int k = 0; k < 3; ++k) {
      idx[3 * t + (size_t)k] = c[k];
      if (pole[c[k]]) {
        continue;
      }
      if (across && u[k] < 0.5) {
        if (seam[c[k]] == UINT32_MAX) {
          seam[c[k]] = (uint32_t)l.n;
          if (!push(&l, m, c[k], u[k] + 1.0, l.uv[2 * (size_t)c[k] + 1])) {
            goto oom;
          }
        }
        idx[3 * t + (size_t)k] = seam[c[k]];
        u[k] += 1.0;
      }
      usum += u[k];
    }
    for (int k = 0; k < 3 && poles < 3; ++k) {
      if (pole[c[k]]) {
        idx[3 * t + (size_t)k] = (uint32_t)l.n;
        if (!push(&l, m, c[k], usum / (3 - poles), l.uv[2 * (size_t)c[k] + 1])) {
          goto oom;
        }
      }
    }
  }
  st = ss_mesh_create(l.n, m->num_triangles, SS_MESH_NORMALS | SS_MESH_UVS, out, err);
  if (st == SS_OK) {
    memcpy((*out)->positions, l.pos, 3 * l.n * sizeof(float));
    memcpy((*out)->normals, l.nrm, 3 * l.n * sizeof(float));
    memcpy((*out)->uvs, l.uv, 2 * l.n * sizeof(float));
    memcpy((*out)->indices, idx, 3 * m->num_triangles * sizeof *idx);
  }
  goto done;
oom:
  st = ss_error_set(err, SS_ERR_NO_MEMORY, "sphere uvs: out of memory");
done:
  free(l.pos);
  free(l.nrm);
  free(l.uv);
  free(seam);
  free(pole);
  free(idx);
  return st;
}
