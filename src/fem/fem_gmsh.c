/* Tetrahedral meshing with gmsh's C API (libgmsh-dev): a box from the
 * OpenCASCADE kernel, or the inside of a closed triangle surface re-meshed
 * through classifySurfaces + createGeometry (gmsh's tutorial t13). Element
 * sizes come from one MathEval background field graded from size_min near
 * the source to size_max, optionally down to rim_size along the spot's
 * rim, and to the medium's size field (fem_size_field.c) through gmsh's size
 * callback. gmsh keeps global state: each call initialises and
 * finalises it, with its terminal output off (the library never prints). */
#include "fem/fem_internal.h"
#include "fem/gmsh_api.h"
#include "subsurf/sampling.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__SANITIZE_ADDRESS__)
#define SS_FEM_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SS_FEM_LSAN 1
#endif
#endif
#ifdef SS_FEM_LSAN
#include <sanitizer/lsan_interface.h>
#endif

/* The API, loaded by start() (gmsh's state is global anyway). */
static const ss_gmsh_api *g;

/* gmsh leaks its own model objects (classifyFaces, discrete entities, mesh
 * generation), also across gmshFinalize. Under LeakSanitizer, what is
 * allocated between gmsh_enter and gmsh_leave is never reported; they
 * bracket the stretches of gmsh calls only, so that a leak of our own
 * arrays or of the mesh returned is still reported. (A suppression by
 * library name would need the slow unwinder in every fem test: gmsh has no
 * frame pointers.) The calls nest. */
static void gmsh_enter(void) {
#ifdef SS_FEM_LSAN
  __lsan_disable();
#endif
}

static void gmsh_leave(void) {
#ifdef SS_FEM_LSAN
  __lsan_enable();
#endif
}

/* An error from gmsh: its last logged message, naming the step. */
static ss_status gmsh_error(ss_error *err, const char *step) {
  char *msg = NULL;
  int ierr = 0;
  gmsh_enter();
  g->gmshLoggerGetLastError(&msg, &ierr);
  gmsh_leave();
  /* TetGen's "PLC Error: A segment and a facet intersect", "two facets
   * intersect", ...: the surface crosses itself. */
  const char *why = msg && strstr(msg, "intersect") ? "the surface intersects itself: " : "";
  ss_status st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "fem mesh: %sgmsh %s failed: %s", why,
                              step, msg && *msg ? msg : "no message");
  g->gmshFree(msg);
  return st;
}

static ss_status check_options(const ss_fem_mesh_options *o, ss_error *err) {
  if (!(o->size_max > 0.0) || !isfinite(o->size_max) || !(o->size_min > 0.0) ||
      o->size_min > o->size_max) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: element sizes min %g, max %g (need 0 < min <= max)", o->size_min,
                        o->size_max);
  }
  if (!isfinite(o->refine_radius) || !isfinite(o->refine_grade) || o->refine_grade < 0.0 ||
      !isfinite(ss_vec3_length(o->refine_center))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: refinement radius %g, grade %g must be finite, grade >= 0",
                        o->refine_radius, o->refine_grade);
  }
  if (!(o->rim_size >= 0.0) || !isfinite(o->rim_size) || !(o->rim_radius >= 0.0) ||
      !isfinite(o->rim_radius) || (o->rim_size > 0.0 && !(o->rim_radius > 0.0))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: rim size %g, radius %g must be finite and >= 0 (a radius "
                        "> 0 with a rim size)",
                        o->rim_size, o->rim_radius);
  }
  return SS_OK;
}

static ss_status start_gmsh(const ss_fem_mesh_options *o, ss_error *err) {
  ss_status st = ss_gmsh_api_get(&g, err);
  if (st != SS_OK) {
    return st;
  }
  int ierr = 0;
  g->gmshInitialize(0, NULL, 0, &ierr);
  if (ierr) {
    return ss_error_set(err, SS_ERR_UNSUPPORTED, "fem mesh: gmsh did not initialise");
  }
  g->gmshOptionSetNumber("General.Terminal", 0, &ierr);
  g->gmshOptionSetNumber("General.NumThreads", 1, &ierr);
  g->gmshOptionSetNumber("Mesh.MeshSizeExtendFromBoundary", 0, &ierr);
  g->gmshOptionSetNumber("Mesh.MeshSizeFromPoints", 0, &ierr);
  g->gmshOptionSetNumber("Mesh.MeshSizeFromCurvature", 0, &ierr);
  g->gmshOptionSetNumber("Mesh.MeshSizeMax", o->size_max, &ierr);
  double smallest = o->rim_size > 0.0 ? fmin(o->size_min, o->rim_size) : o->size_min;
  smallest = o->medium_size ? fmin(smallest, ss_fem_size_field_min(o->medium_size)) : smallest;
  g->gmshOptionSetNumber("Mesh.MeshSizeMin", smallest, &ierr);
  g->gmshModelAdd("subsurf", &ierr);
  return ierr ? gmsh_error(err, "model set-up") : SS_OK;
}

/* Loads gmsh (its libraries' initialisers allocate too) and starts a model. */
static ss_status start(const ss_fem_mesh_options *o, ss_error *err) {
  gmsh_enter();
  ss_status st = start_gmsh(o, err);
  gmsh_leave();
  return st;
}

/* gmsh's size callback: the medium's size field (gmsh takes the smaller of
 * it and the background field). */
static double medium_size_at(int dim, int tag, double x, double y, double z, void *data) {
  (void)dim;
  (void)tag;
  return ss_fem_size_field_at(data, ss_vec3_make(x, y, z));
}

/* The size field: size_min within refine_radius of the centre, growing
 * linearly to size_max over refine_grade beyond it; with a rim, at most
 * rim_size + the distance from the sphere of radius rim_radius about the
 * centre (zero along the spot's rim on the surface: gmsh's Distance +
 * Threshold fields would need the rim as a curve of the model, which a
 * re-meshed surface does not have). */
static ss_status size_field(const ss_fem_mesh_options *o, ss_error *err) {
  int ierr = 0;
  if (o->medium_size) {
    gmsh_enter();
    g->gmshModelMeshSetSizeCallback(medium_size_at, (void *)o->medium_size, &ierr);
    gmsh_leave();
    if (ierr) {
      return gmsh_error(err, "size callback");
    }
  }
  int graded = o->refine_radius > 0.0 && o->size_min < o->size_max;
  if (!graded && !(o->rim_size > 0.0)) {
    return SS_OK;
  }
  double grade = o->refine_grade > 0.0 ? o->refine_grade : o->refine_radius;
  double slope = graded ? (o->size_max - o->size_min) / grade : 0.0;
  ss_vec3 c = o->refine_center;
  char dist[256], base[512], expr[1024];
  snprintf(dist, sizeof dist, "sqrt((x-(%.17g))^2+(y-(%.17g))^2+(z-(%.17g))^2)", c.x, c.y, c.z);
  snprintf(base, sizeof base, "min(%.17g, %.17g + max(0, %s - %.17g) * %.17g)", o->size_max,
           graded ? o->size_min : o->size_max, dist, o->refine_radius, slope);
  if (o->rim_size > 0.0) {
    snprintf(expr, sizeof expr, "min(%s, %.17g + abs(%s - %.17g))", base, o->rim_size, dist,
             o->rim_radius);
  } else {
    snprintf(expr, sizeof expr, "%s", base);
  }
  gmsh_enter();
  int f = g->gmshModelMeshFieldAdd("MathEval", -1, &ierr);
  if (!ierr) {
    g->gmshModelMeshFieldSetString(f, "F", expr, &ierr);
  }
  if (!ierr) {
    g->gmshModelMeshFieldSetAsBackgroundMesh(f, &ierr);
  }
  gmsh_leave();
  return ierr ? gmsh_error(err, "size field") : SS_OK;
}

/* Generates the volume mesh and copies the vertices used by tetrahedra. */
static ss_status generate(ss_fem_mesh **out, ss_error *err) {
  int ierr = 0;
  gmsh_enter();
  g->gmshModelMeshGenerate(3, &ierr);
  gmsh_leave();
  if (ierr) {
    return gmsh_error(err, "3D meshing");
  }
  size_t *ntags = NULL, nn = 0, nc = 0, np = 0;
  double *coord = NULL, *param = NULL;
  gmsh_enter();
  g->gmshModelMeshGetNodes(&ntags, &nn, &coord, &nc, &param, &np, -1, -1, 0, 0, &ierr);
  size_t *etags = NULL, ne = 0, *enodes = NULL, nen = 0;
  if (!ierr) {
    g->gmshModelMeshGetElementsByType(4, &etags, &ne, &enodes, &nen, -1, 0, 1, &ierr);
  }
  gmsh_leave();
  ss_status st = SS_OK;
  size_t max_tag = 0;
  for (size_t i = 0; i < nn; ++i) {
    max_tag = ntags[i] > max_tag ? ntags[i] : max_tag;
  }
  uint32_t *index = NULL;
  double *pos = NULL;
  uint32_t *tets = NULL;
  size_t nt = nen / 4, nv = 0;
  if (ierr) {
    st = gmsh_error(err, "mesh query");
  } else if (nt == 0) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "fem mesh: gmsh produced no tetrahedra (is the surface closed?)");
  } else {
    index = malloc((max_tag + 1) * sizeof *index);
    size_t *where = malloc((max_tag + 1) * sizeof *where);
    pos = malloc(3 * nn * sizeof *pos);
    tets = malloc(4 * nt * sizeof *tets);
    if (!index || !where || !pos || !tets) {
      st = ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory for %zu tetrahedra", nt);
    } else {
      for (size_t i = 0; i <= max_tag; ++i) {
        index[i] = UINT32_MAX;
        where[i] = SIZE_MAX;
      }
      for (size_t i = 0; i < nn; ++i) {
        where[ntags[i]] = i;
      }
      for (size_t i = 0; i < nen && st == SS_OK; ++i) {
        size_t tag = enodes[i];
        if (tag > max_tag || where[tag] == SIZE_MAX) {
          st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                            "fem mesh: gmsh returned an element with unknown node %zu", tag);
        } else {
          if (index[tag] == UINT32_MAX) {
            index[tag] = (uint32_t)nv;
            for (int k = 0; k < 3; ++k) {
              pos[3 * nv + (size_t)k] = coord[3 * where[tag] + (size_t)k];
            }
            ++nv;
          }
          tets[i] = index[tag];
        }
      }
    }
    free(where);
  }
  if (st == SS_OK) {
    st = ss_fem_mesh_create(pos, nv, tets, nt, out, err);
  }
  free(index);
  free(pos);
  free(tets);
  g->gmshFree(ntags);
  g->gmshFree(coord);
  g->gmshFree(param);
  g->gmshFree(etags);
  g->gmshFree(enodes);
  return st;
}

static ss_status finish(ss_status st, ss_fem_mesh **out, ss_error *err) {
  if (st == SS_OK) {
    st = generate(out, err);
  }
  int ierr = 0;
  gmsh_enter();
  g->gmshFinalize(&ierr);
  gmsh_leave();
  return st;
}

ss_status ss_fem_mesh_box(ss_vec3 lo, ss_vec3 hi, const ss_fem_mesh_options *opt, ss_fem_mesh **out,
                          ss_error *err) {
  *out = NULL;
  ss_status st = check_options(opt, err);
  if (st != SS_OK) {
    return st;
  }
  ss_vec3 d = ss_vec3_sub(hi, lo);
  if (!(d.x > 0.0 && d.y > 0.0 && d.z > 0.0) || !isfinite(d.x + d.y + d.z)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: box sides %g x %g x %g must be positive and finite", d.x, d.y,
                        d.z);
  }
  st = start(opt, err);
  if (st != SS_OK) {
    return st;
  }
  int ierr = 0;
  gmsh_enter();
  g->gmshModelOccAddBox(lo.x, lo.y, lo.z, d.x, d.y, d.z, -1, &ierr);
  if (!ierr) {
    g->gmshModelOccSynchronize(&ierr);
  }
  gmsh_leave();
  st = ierr ? gmsh_error(err, "box") : size_field(opt, err);
  return finish(st, out, err);
}

/* The surface as one discrete entity, classified into patches with curves
 * at sharp edges (40 degrees) and given a parametrisation so that gmsh can
 * re-mesh it at the requested sizes. */
static ss_status add_surface(const float *positions, size_t nv, const uint32_t *indices, size_t nt,
                             ss_error *err) {
  size_t *ntags = malloc(nv * sizeof *ntags), *etags = malloc(nt * sizeof *etags),
         *enodes = malloc(3 * nt * sizeof *enodes);
  double *coord = malloc(3 * nv * sizeof *coord);
  if (!ntags || !etags || !enodes || !coord) {
    free(ntags);
    free(etags);
    free(enodes);
    free(coord);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory for the surface");
  }
  for (size_t i = 0; i < nv; ++i) {
    ntags[i] = i + 1;
    for (int k = 0; k < 3; ++k) {
      coord[3 * i + (size_t)k] = positions[3 * i + (size_t)k];
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    etags[t] = t + 1;
    for (int k = 0; k < 3; ++k) {
      enodes[3 * t + (size_t)k] = (size_t)indices[3 * t + (size_t)k] + 1;
    }
  }
  int ierr = 0;
  gmsh_enter();
  int s = g->gmshModelAddDiscreteEntity(2, -1, NULL, 0, &ierr);
  if (!ierr) {
    g->gmshModelMeshAddNodes(2, s, ntags, nv, coord, 3 * nv, NULL, 0, &ierr);
  }
  if (!ierr) {
    g->gmshModelMeshAddElementsByType(s, 2, etags, nt, enodes, 3 * nt, &ierr);
  }
  gmsh_leave();
  free(ntags);
  free(etags);
  free(enodes);
  free(coord);
  gmsh_enter();
  if (!ierr) {
    g->gmshModelMeshRemoveDuplicateNodes(&ierr);
  }
  if (!ierr) {
    g->gmshModelMeshClassifySurfaces(40.0 * SS_PI / 180.0, 1, 1, SS_PI, 1, &ierr);
  }
  if (!ierr) {
    g->gmshModelMeshCreateGeometry(NULL, 0, &ierr);
  }
  gmsh_leave();
  if (ierr) {
    return gmsh_error(err, "surface classification");
  }
  int *dimtags = NULL;
  size_t n = 0;
  gmsh_enter();
  g->gmshModelGetEntities(&dimtags, &n, 2, &ierr);
  gmsh_leave();
  int *surfaces = malloc((n / 2 + 1) * sizeof *surfaces);
  if (!surfaces) {
    g->gmshFree(dimtags);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem mesh: out of memory");
  }
  for (size_t i = 0; i < n / 2; ++i) {
    surfaces[i] = dimtags[2 * i + 1];
  }
  g->gmshFree(dimtags);
  gmsh_enter();
  int loop = ierr ? 0 : g->gmshModelGeoAddSurfaceLoop(surfaces, n / 2, -1, &ierr);
  if (!ierr) {
    g->gmshModelGeoAddVolume(&loop, 1, -1, &ierr);
  }
  if (!ierr) {
    g->gmshModelGeoSynchronize(&ierr);
  }
  gmsh_leave();
  free(surfaces);
  return ierr ? gmsh_error(err, "volume from the surface") : SS_OK;
}

ss_status ss_fem_mesh_surface(const float *positions, size_t num_vertices, const uint32_t *indices,
                              size_t num_triangles, const ss_fem_mesh_options *opt,
                              ss_fem_mesh **out, ss_error *err) {
  *out = NULL;
  ss_status st = check_options(opt, err);
  if (st != SS_OK) {
    return st;
  }
  if (num_triangles < 4 || num_vertices < 4) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem mesh: a closed surface needs at least 4 triangles (got %zu)",
                        num_triangles);
  }
  for (size_t i = 0; i < 3 * num_triangles; ++i) {
    if (indices[i] >= num_vertices) {
      return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem mesh: triangle %zu has vertex %u (of %zu)", i / 3, indices[i],
                          num_vertices);
    }
  }
  st = start(opt, err);
  if (st != SS_OK) {
    return st;
  }
  st = add_surface(positions, num_vertices, indices, num_triangles, err);
  if (st == SS_OK) {
    st = size_field(opt, err);
  }
  return finish(st, out, err);
}
