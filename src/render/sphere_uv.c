/* Spherical texture coordinates for a mesh around the origin (the
 * icosphere), with the seam and the poles made seamless by duplicating
 * vertices (see mesh.h). */
#include "render/sphere_uv.h"
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

size_t ss_spherical_uvs_room(size_t num_vertices) {
  /* The seam and pole copies are a few per thousand vertices on an icosphere. */
  return num_vertices + num_vertices / 16 + 64;
}

/* Resizes the vertex arrays of m to `cap` vertices, with ss_mesh_create's
 * one float of padding (which Embree's shared vertex buffers also need). */
static int resize_vertices(ss_mesh *m, size_t cap) {
  float *p = realloc(m->positions, (3 * cap + 1) * sizeof *p);
  if (p) {
    m->positions = p;
  }
  float *n = realloc(m->normals, (3 * cap + 1) * sizeof *n);
  if (n) {
    m->normals = n;
  }
  float *t = realloc(m->uvs, (2 * cap + 1) * sizeof *t);
  if (t) {
    m->uvs = t;
  }
  return p && n && t;
}

/* Appends a copy of vertex src with texture coordinates (u, v); returns its
 * index, or UINT32_MAX when out of memory. */
static uint32_t push_copy(ss_mesh *m, size_t *cap, uint32_t src, double u, double v) {
  if (m->num_vertices == *cap) {
    if (!resize_vertices(m, 2 * *cap)) {
      return UINT32_MAX;
    }
    *cap *= 2;
  }
  size_t k = m->num_vertices++;
  memcpy(m->positions + 3 * k, m->positions + 3 * (size_t)src, 3 * sizeof(float));
  memcpy(m->normals + 3 * k, m->normals + 3 * (size_t)src, 3 * sizeof(float));
  m->uvs[2 * k] = (float)u;
  m->uvs[2 * k + 1] = (float)v;
  return (uint32_t)k;
}

/* Per triangle: when its corners' u span more than 1/2, the triangle lies
 * across the seam and the corners with u < 1/2 take u + 1 (a copy of the
 * vertex past u = 1); a pole corner takes the mean u of the other two (a
 * copy per triangle), so that no triangle's u spans the whole circle. */
ss_status ss_mesh_spherical_uvs_in_place(ss_mesh *m, size_t room, ss_error *err) {
  if (!m->normals) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "sphere uvs: the mesh has no normals");
  }
  size_t nv = m->num_vertices;
  size_t cap = room ? room : ss_spherical_uvs_room(nv);
  uint32_t *seam = malloc((nv + 1) * sizeof *seam); /* the u + 1 copy, or UINT32_MAX */
  unsigned char *pole = malloc(nv + 1);
  ss_status st = SS_OK;
  if (!seam || !pole || (!room && !resize_vertices(m, cap))) {
    goto oom;
  }
  for (size_t k = 0; k < nv; ++k) {
    double u, v;
    int at_pole;
    spherical(m->positions + 3 * k, &u, &v, &at_pole);
    pole[k] = (unsigned char)at_pole;
    m->uvs[2 * k] = (float)u;
    m->uvs[2 * k + 1] = (float)v;
    seam[k] = UINT32_MAX;
  }
  for (size_t t = 0; t < m->num_triangles; ++t) {
    uint32_t *idx = m->indices + 3 * t;
    const uint32_t c[3] = {idx[0], idx[1], idx[2]};
    double u[3], umin = 2.0, umax = -1.0, usum = 0.0;
    int poles = 0;
    for (int k = 0; k < 3; ++k) {
      u[k] = m->uvs[2 * (size_t)c[k]];
      poles += pole[c[k]];
      umin = pole[c[k]] ? umin : fmin(umin, u[k]);
      umax = pole[c[k]] ? umax : fmax(umax, u[k]);
    }
    int across = umax - umin > 0.5;
    for (int k = 0; k < 3; ++k) {
      if (pole[c[k]]) {
        continue;
      }
      if (across && u[k] < 0.5) {
        if (seam[c[k]] == UINT32_MAX &&
            (seam[c[k]] = push_copy(m, &cap, c[k], u[k] + 1.0, m->uvs[2 * (size_t)c[k] + 1])) ==
                UINT32_MAX) {
          goto oom;
        }
        idx[k] = seam[c[k]];
        u[k] += 1.0;
      }
      usum += u[k];
    }
    for (int k = 0; k < 3 && poles < 3; ++k) {
      if (pole[c[k]] && (idx[k] = push_copy(m, &cap, c[k], usum / (3 - poles),
                                            m->uvs[2 * (size_t)c[k] + 1])) == UINT32_MAX) {
        goto oom;
      }
    }
  }
  if (!room) {
    resize_vertices(m, m->num_vertices); /* gives back the unused room */
  }
  goto done;
oom:
  st = ss_error_set(err, SS_ERR_NO_MEMORY, "sphere uvs: out of memory");
done:
  free(seam);
  free(pole);
  return st;
}

ss_status ss_mesh_add_spherical_uvs(const ss_mesh *m, ss_mesh **out, ss_error *err) {
  *out = NULL;
  ss_mesh *copy;
  ss_status st = ss_mesh_clone(m, &copy, err);
  if (st == SS_OK && (st = ss_mesh_spherical_uvs_in_place(copy, 0, err)) != SS_OK) {
    ss_mesh_destroy(copy);
  }
  if (st == SS_OK) {
    *out = copy;
  }
  return st;
}
