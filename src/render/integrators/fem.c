/* `fem`: the diffusion term of every translucent object from a finite-
 * element solution of the (anisotropic, heterogeneous) diffusion equation
 * (Jakob2010 sec. 5-6.2; include/subsurf/fem.h; docs/fem.md).
 *
 * Prepare (once per render): each translucent shape's closed surface is
 * filled with tetrahedra by gmsh at a uniform element size (option
 * element_size, in the medium's shortest transport mean free path); the
 * Fresnel-transmitted irradiance E at each boundary face's point on the
 * surface (the renderer's direct and indirect light through the boundary as
 * in `hierarchical`'s pass 1, or with option indirect 0 the lights' direct
 * light only; irradiance_points.h) enters as the paper's
 * boundary source Gamma_s = E exp(-sigma_a/sigma_s) (eq. 37), or with option
 * volume_source 1 as the volume source of one ray per face along the
 * incident light's mean refracted direction, power E area alpha' and the
 * extinction of the first event (for flakes both reduced by the similarity
 * relation; fem_medium.h, fem_rays.c); per
 * colour channel the coefficients of every tetrahedron are the medium's at
 * its centroid (fem_medium.h: isotropic or micro-flakes, times a grid's
 * density, about a grid's axes) and the system of eq. 39-42 is solved
 * (CHOLMOD, or Jacobi-PCG with option pcg = 1). The exitance M_o at the
 * boundary vertices is kept.
 *
 * Render: path tracing as `hierarchical` (diffusion_path.h); the diffusion
 * term at x_o toward w_o is the paper's query (sec. 6.2.2)
 *     L(x_o, w_o) = Ft(w_o)/(4 pi) ((1 + 1/A) phi - 4 Gamma_s/(Fdt A))
 *                 = Ft(w_o) M_o / (pi Fdt),
 * divided by eta^2 for the radiance leaving into the outer medium (as the
 * single scattering term does), with M_o interpolated linearly on the
 * boundary triangle found below x_o along its normal. */
#include "render/integrators/fem.h"
#include "render/integrators/common.h"
#include "render/integrators/diffusion_path.h"
#include "render/integrators/fem_medium.h"

#include "subsurf/fem_cache.h"
#include "subsurf/fresnel.h"
#include "subsurf/irradiance_points.h"
#include "subsurf/progress.h"
#include "subsurf/sampling.h"
#include "subsurf/subsurface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FEM_DEFAULT_ELEMENT_SIZE 1.0
#define FEM_DEFAULT_IRRADIANCE_SAMPLES 16
#define FEM_DEFAULT_MAX_ELEMENTS 2e6
#define FEM_DEFAULT_MIN_DENSITY 0.01
/* Tetrahedra per h^3 of volume in gmsh's meshes of uniform size h (measured
 * on boxes and spheres: 7-9; the guard uses the upper end). */
#define FEM_TETS_PER_CUBE 9.0

typedef struct {
  double element_size, max_elements, min_density, medium_element_size;
  int irradiance_samples, pcg, volume_source, indirect;
  int cache_read_only; /* the cache file is read, never written */
} fem_options;

typedef struct {
  ss_fem_mesh *mesh;
  float *exitance;  /* 3 per vertex: M_o per channel */
  double eta, norm; /* norm = 1 / (pi eta^2 Fdt) */
  double reach;     /* how far below or above x_o the boundary is looked for */
  unsigned geom;    /* in the lookup accel */
  /* the keys of its mesh and solution (fem_cache.h), with a cache only */
  uint64_t mesh_key, solution_key;
} fem_object;

typedef struct {
  fem_options opt;
  size_t num_shapes;
  fem_object *obj; /* per scene shape; mesh NULL where not translucent */
  ss_mesh **bound; /* boundary meshes of the lookup accel */
  size_t num_bound;
  ss_accel *lookup; /* the boundary triangles of every solution */
  double mesh_seconds, irradiance_seconds, assemble_seconds, solve_seconds;
  size_t tets;
  const char *cache_path; /* the scene's integrator.cache; NULL: none */
  ss_fem_cache *cache;    /* its records during prepare (NULL: none valid) */
  int objects, meshes_cached, solutions_cached;
} fem_state;

static int is_translucent(const ss_material *m) {
  return m && m->kind == SS_MATERIAL_INTERFACE && m->medium >= 0;
}

static ss_status read_option(const ss_scene *s, const char *name, double lo, double hi, int whole,
                             double def, double *out, ss_error *err) {
  double v = ss_scene_integrator_option(s, name, def);
  if (!(v >= lo && v <= hi) || (whole && v != floor(v))) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: option %s: expected a %s in [%g, %g], got %g", name,
                        whole ? "whole number" : "number", lo, hi, v);
  }
  *out = v;
  return SS_OK;
}

static ss_status read_options(const ss_scene *s, fem_options *o, ss_error *err) {
  double samples = 0, pcg = 0, volume = 0, indirect = 0, read_only = 0;
  ss_status st = read_option(s, "element_size", 0.01, 100.0, 0, FEM_DEFAULT_ELEMENT_SIZE,
                             &o->element_size, err);
  if (st == SS_OK)
    st = read_option(s, "irradiance_samples", 1, 1 << 16, 1, FEM_DEFAULT_IRRADIANCE_SAMPLES,
                     &samples, err);
  if (st == SS_OK)
    st = read_option(s, "pcg", 0, 1, 1, 0, &pcg, err);
  if (st == SS_OK)
    st = read_option(s, "max_elements", 100, 1e8, 1, FEM_DEFAULT_MAX_ELEMENTS, &o->max_elements,
                     err);
  if (st == SS_OK)
    st = read_option(s, "min_density", 1e-6, 1, 0, FEM_DEFAULT_MIN_DENSITY, &o->min_density, err);
  if (st == SS_OK)
    st = read_option(s, "volume_source", 0, 1, 1, 0, &volume, err);
  if (st == SS_OK)
    st = read_option(s, "medium_element_size", 0, 100.0, 0, 0, &o->medium_element_size, err);
  if (st == SS_OK)
    st = read_option(s, "indirect", 0, 1, 1, 1, &indirect, err);
  if (st == SS_OK)
    st = read_option(s, "cache_read_only", 0, 1, 1, 0, &read_only, err);
  o->irradiance_samples = (int)samples;
  o->pcg = (int)pcg;
  o->volume_source = (int)volume;
  o->indirect = (int)indirect;
  o->cache_read_only = (int)read_only;
  return st;
}

static double boundary_eta(const ss_material *m) {
  return m->boundary == SS_BOUNDARY_INDEX_MATCHED ? 1.0 : m->eta;
}

/* The tetrahedral mesh of shape i at the element size, and with
 * medium_element_size and a grid down to that where the medium varies (the
 * size field of `med` over the shape's bounds); the scene has checked that
 * translucent shapes are closed. Refuses a mesh over max_elements before
 * meshing (estimated from the sizes over the bounds, scaled by the shape's
 * share of their volume). */
static ss_status mesh_shape(const ss_scene *scene, fem_state *s, size_t i, double mfp,
                            ss_fem_scene_medium *med, ss_error *err) {
  const fem_options *o = &s->opt;
  fem_object *ob = &s->obj[i];
  const ss_shape *sh = &scene->shapes[i];
  double h = o->element_size * mfp, volume = fabs(ss_mesh_signed_volume(sh->mesh));
  double estimate = FEM_TETS_PER_CUBE * volume / (h * h * h);
  ss_fem_size_field *field = NULL;
  ss_status st = SS_OK;
  if (o->medium_element_size > 0.0) {
    ss_vec3 lo, hi;
    ss_mesh_bounds(sh->mesh, &lo, &hi);
    st = ss_fem_scene_medium_size_field(med, lo, hi, fmin(o->medium_element_size * mfp, h), h,
                                        &field, err);
    if (field) {
      ss_vec3 d = ss_vec3_sub(hi, lo);
      estimate = FEM_TETS_PER_CUBE * ss_fem_size_field_cells(field) * volume / (d.x * d.y * d.z);
    }
  }
  if (st == SS_OK && !(estimate <= o->max_elements)) {
    st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                      "fem: shape '%s': about %.3g tetrahedra at element_size %g, "
                      "medium_element_size %g (mean free path %g, volume %g) exceed "
                      "max_elements %g; raise the sizes",
                      sh->name, estimate, o->element_size, o->medium_element_size, mfp, volume,
                      o->max_elements);
  }
  ss_fem_mesh_options mo = {.size_max = h, .size_min = h, .medium_size = field};
  if (st == SS_OK && s->cache_path) {
    ob->mesh_key = ss_fem_cache_mesh_key(sh->mesh->positions, sh->mesh->num_vertices,
                                         sh->mesh->indices, sh->mesh->num_triangles, &mo);
    ss_error ignored; /* a record the checksum passed but ss_fem_mesh_create refuses: remeshed */
    if (ss_fem_cache_mesh(s->cache, ob->mesh_key, &ob->mesh, &ignored) == SS_OK && ob->mesh) {
      s->meshes_cached++;
    }
  }
  if (st == SS_OK && !ob->mesh) {
    st = ss_fem_mesh_surface(sh->mesh->positions, sh->mesh->num_vertices, sh->mesh->indices,
                             sh->mesh->num_triangles, &mo, &ob->mesh, err);
    if (st != SS_OK) {
      ss_error_prefix(err, "fem: shape '%s': ", sh->name);
    }
  }
  ss_fem_size_field_destroy(field);
  return st;
}

/* The irradiance point of each boundary face: its centroid moved to the
 * shape's surface along the face normal (gmsh's boundary lies on the
 * surface's triangles or on chords inside it), with the surface's normal. */
static void face_points(const ss_scene *scene, unsigned shape, const ss_fem_mesh *m, double reach,
                        ss_irradiance_point *pts) {
  for (size_t f = 0; f < m->num_faces; ++f) {
    ss_vec3 p[3];
    ss_fem_face_vertices(m, f, p);
    ss_vec3 c = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), p[2]), 1.0 / 3.0);
    ss_vec3 n = ss_vec3_cross(ss_vec3_sub(p[1], p[0]), ss_vec3_sub(p[2], p[0]));
    double area = 0.5 * ss_vec3_length(n);
    n = ss_vec3_normalize(n);
    pts[f] = (ss_irradiance_point){.p = c, .n = n, .area = area, .shape = shape};
    ss_ray ray = {ss_vec3_madd(c, n, reach), ss_vec3_neg(n), 0.0, 2.0 * reach};
    ss_hit hits[8];
    size_t nh = ss_accel_intersect_all(scene->accel, &ray, shape, hits, 8);
    double best = INFINITY;
    for (size_t k = 0; k < nh && k < 8; ++k) {
      if (fabs(hits[k].t - reach) < best && ss_vec3_dot(hits[k].ng, n) > 0.0) {
        best = fabs(hits[k].t - reach);
        pts[f].p = hits[k].p;
        pts[f].n = hits[k].ng;
      }
    }
  }
}

/* The volume source of boundary face f in channel c: one ray from its
 * centroid carrying the refracted power E area times the albedo of the first
 * event (the light absorbed there is lost, as in the dipole), along the
 * incident light's mean refracted direction m = F/E (irradiance_points.h),
 * with the medium's extinction along it divided by |m|. In an isotropic
 * medium the first events of light refracted along directions w_t lie on
 * average at E[w_t]/sigma = m/sigma from the entry point, and so do those of
 * this ray: exactly the light's along one direction (|m| = 1), and the depth
 * of several directions of one refraction angle (|m| = its cosine); under
 * diffuse light (m about -n cos) the single depth of the mean stands for a
 * spread of depths. Both reduced by the similarity relation for flakes
 * (fem_medium.h, fem_rays.c). */
static ss_fem_ray face_ray(const ss_fem_mesh *m, size_t f, const ss_fem_scene_medium *med,
                           const ss_irradiance_point *pt, const ss_irradiance_flux *flux, int c) {
  ss_vec3 p[3];
  ss_fem_face_vertices(m, f, p);
  ss_vec3 o = ss_vec3_scale(ss_vec3_add(ss_vec3_add(p[0], p[1]), p[2]), 1.0 / 3.0);
  ss_vec3 mean = ss_vec3_scale(flux->c[c], 1.0 / pt->E.c[c]);
  double len = ss_vec3_length(mean);
  ss_vec3 w = ss_vec3_scale(mean, 1.0 / len);
  ss_flake_first_event e = ss_fem_scene_medium_first_event(med, o, w);
  return (ss_fem_ray){
      .origin = o, .dir = w, .sigma = e.sigma / len, .power = pt->E.c[c] * pt->area * e.albedo};
}

/* One channel's medium and load: the paper's boundary flux Gamma_s =
 * E exp(-sigma_a/sigma_s) per face (Jakob2010 eq. 37), or the rays' volume
 * source (option volume_source). */
typedef struct {
  ss_fem_scene_medium ctx;
  double *gamma;
  ss_fem_ray *rays;
  ss_fem_problem pb;
} fem_channel;

static ss_status channel_init(const fem_state *s, const fem_object *ob, const ss_medium *med, int c,
                              const ss_irradiance_point *pts, const ss_irradiance_flux *flux,
                              fem_channel *ch, ss_error *err) {
  ss_status st = ss_fem_scene_medium_init(&ch->ctx, med, c, s->opt.min_density, err);
  size_t nf = ob->mesh->num_faces;
  ch->gamma = s->opt.volume_source ? NULL : calloc(nf + 1, sizeof *ch->gamma);
  ch->rays = s->opt.volume_source ? malloc((nf + 1) * sizeof *ch->rays) : NULL;
  if (st == SS_OK && !ch->gamma && !ch->rays) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory");
  }
  if (st == SS_OK) {
    ch->pb = (ss_fem_problem){.eta = ob->eta, .face_gamma = ch->gamma, .rays = ch->rays};
    double att = ss_fem_scene_medium_attenuation(&ch->ctx);
    for (size_t f = 0; f < nf; ++f) {
      if (!ch->rays) {
        ch->gamma[f] = pts[f].E.c[c] * att;
      } else if (pts[f].E.c[c] > 0.0) {
        ch->rays[ch->pb.num_rays++] = face_ray(ob->mesh, f, &ch->ctx, &pts[f], &flux[f], c);
      }
    }
  }
  return st;
}

static void channel_release(fem_channel *ch) {
  free(ch->gamma);
  free(ch->rays);
  ss_fem_scene_medium_release(&ch->ctx);
}

static ss_fem_solve_options solve_options(const fem_state *s) {
  return (ss_fem_solve_options){.solver = s->opt.pcg ? SS_FEM_PCG : SS_FEM_CHOLMOD,
                                .tolerance = 1e-10,
                                .max_iterations = 100000};
}

/* One channel's solution: M_o at every vertex into exitance[3 v + c]. */
static ss_status solve_channel(fem_state *s, fem_object *ob, int c, fem_channel *ch,
                               ss_error *err) {
  ss_fem_solve_options so = solve_options(s);
  ss_fem_solution *sol = NULL;
  ss_status st = ss_fem_solve(ob->mesh, ss_fem_scene_medium_at, &ch->ctx, &ch->pb, &so, &sol, err);
  if (st == SS_OK) {
    for (size_t v = 0; v < ob->mesh->num_vertices; ++v) {
      ob->exitance[3 * v + (size_t)c] = (float)sol->exitance[v];
    }
    s->assemble_seconds += sol->assemble_seconds;
    s->solve_seconds += sol->solve_seconds;
  }
  ss_fem_solution_destroy(sol);
  return st;
}

/* The three channels' solutions, read from the cache when it holds the
 * solution of this mesh, these coefficients and this load (fem_cache.h). */
static ss_status solve_channels(fem_state *s, fem_object *ob, const ss_medium *med,
                                const ss_irradiance_point *pts, const ss_irradiance_flux *flux,
                                ss_error *err) {
  fem_channel ch[3];
  memset(ch, 0, sizeof ch);
  ss_fem_solve_options so = solve_options(s);
  uint64_t key = ob->mesh_key;
  ss_status st = SS_OK;
  for (int c = 0; c < 3 && st == SS_OK; ++c) {
    st = channel_init(s, ob, med, c, pts, flux, &ch[c], err);
    if (st == SS_OK && s->cache_path) {
      st = ss_fem_cache_hash_solve(&key, ob->mesh, ss_fem_scene_medium_at, &ch[c].ctx, &ch[c].pb,
                                   &so, err);
    }
  }
  ob->solution_key = key;
  if (st == SS_OK && s->cache_path &&
      ss_fem_cache_solution(s->cache, key, ob->mesh->num_vertices, ob->exitance)) {
    s->solutions_cached++;
  } else {
    for (int c = 0; c < 3 && st == SS_OK; ++c) {
      st = solve_channel(s, ob, c, &ch[c], err);
    }
  }
  for (int c = 0; c < 3; ++c) {
    channel_release(&ch[c]);
  }
  return st;
}

/* The lookup mesh of an object: its vertices and boundary faces. */
static ss_status boundary_mesh(const ss_fem_mesh *m, ss_mesh **out, ss_error *err) {
  ss_status st = ss_mesh_create(m->num_vertices, m->num_faces, 0, out, err);
  if (st != SS_OK) {
    return st;
  }
  for (size_t i = 0; i < 3 * m->num_vertices; ++i) {
    (*out)->positions[i] = (float)m->positions[i];
  }
  memcpy((*out)->indices, m->faces, 3 * m->num_faces * sizeof *m->faces);
  return SS_OK;
}

/* Meshes, lights and solves translucent shape i. */
static ss_status solve_shape(const ss_scene *scene, fem_state *s, size_t i, const double *etas,
                             ss_error *err) {
  const ss_material *mat = &scene->materials[scene->shapes[i].material];
  const ss_medium *med = &scene->media[mat->medium];
  fem_object *ob = &s->obj[i];
  ob->eta = boundary_eta(mat);
  /* the shortest mean free path's channel sizes the elements */
  double mfp = INFINITY;
  int shortest = 0;
  for (int c = 0; c < 3; ++c) {
    ss_fem_scene_medium ctx;
    ss_status st = ss_fem_scene_medium_init(&ctx, med, c, s->opt.min_density, err);
    if (st == SS_OK && ss_fem_scene_medium_mfp(&ctx) < mfp) {
      mfp = ss_fem_scene_medium_mfp(&ctx);
      shortest = c;
    }
    ss_fem_scene_medium_release(&ctx);
    if (st != SS_OK) {
      return st;
    }
  }
  double t0 = ss_seconds();
  ss_fem_scene_medium ctx;
  ss_status st = ss_fem_scene_medium_init(&ctx, med, shortest, s->opt.min_density, err);
  if (st == SS_OK) {
    st = mesh_shape(scene, s, i, mfp, &ctx, err);
  }
  ss_fem_scene_medium_release(&ctx);
  s->mesh_seconds += ss_seconds() - t0;
  if (st != SS_OK) {
    return st;
  }
  s->tets += ob->mesh->num_tets;
  ob->reach = 2.0 * ss_fem_mesh_max_edge(ob->mesh);
  ob->exitance = calloc(3 * ob->mesh->num_vertices, sizeof *ob->exitance);
  ss_irradiance_point *pts = calloc(ob->mesh->num_faces + 1, sizeof *pts);
  ss_irradiance_flux *flux =
      s->opt.volume_source ? calloc(ob->mesh->num_faces + 1, sizeof *flux) : NULL;
  if (!ob->exitance || !pts || (s->opt.volume_source && !flux)) {
    free(pts);
    free(flux);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory");
  }
  t0 = ss_seconds();
  face_points(scene, (unsigned)i, ob->mesh, ob->reach, pts);
  if (s->opt.indirect) {
    ss_irradiance_points_compute(scene, pts, ob->mesh->num_faces, etas, s->opt.irradiance_samples,
                                 scene->render.seed, 0, flux, NULL);
  } else {
    ss_irradiance_points_direct(scene, pts, ob->mesh->num_faces, etas, s->opt.irradiance_samples,
                                scene->render.seed, 0, flux, NULL);
  }
  s->irradiance_seconds += ss_seconds() - t0;
  st = solve_channels(s, ob, med, pts, flux, err);
  free(pts);
  free(flux);
  /* Jensen2001 / Jakob2010 sec. 6.2.2 with eta^2 on leaving */
  double Fdt = 1.0 - ss_fresnel_diffuse_reflectance(ob->eta);
  ob->norm = 1.0 / (SS_PI * ob->eta * ob->eta * Fdt);
  if (st == SS_OK) {
    ob->geom = (unsigned)s->num_bound;
    st = boundary_mesh(ob->mesh, &s->bound[s->num_bound], err);
    s->num_bound += st == SS_OK;
  }
  return st;
}

static void fem_release(void *state) {
  fem_state *s = state;
  if (!s) {
    return;
  }
  ss_accel_destroy(s->lookup);
  ss_fem_cache_destroy(s->cache);
  for (size_t i = 0; s->obj && i < s->num_shapes; ++i) {
    ss_fem_mesh_destroy(s->obj[i].mesh);
    free(s->obj[i].exitance);
  }
  for (size_t i = 0; s->bound && i < s->num_bound; ++i) {
    ss_mesh_destroy(s->bound[i]);
  }
  free(s->bound);
  free(s->obj);
  free(s);
}

static ss_status fem_check(const ss_scene *scene, ss_error *err) {
  fem_options o;
  ss_status st = ss_refuse_nested_media(scene, "fem", err);
  if (st == SS_OK) {
    st = read_options(scene, &o, err);
  }
  return st == SS_OK ? ss_refuse_varying_media(scene, "fem", "give the medium a grid instead", err)
                     : st;
}

/* Rewrites the cache unless every record came from it (and it was valid). */
static ss_status write_cache(const fem_state *s, ss_error *err) {
  if (s->cache && s->meshes_cached == s->objects && s->solutions_cached == s->objects) {
    return SS_OK;
  }
  ss_fem_cache_entry *e = calloc((size_t)s->objects + 1, sizeof *e);
  if (!e) {
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory");
  }
  size_t n = 0;
  for (size_t i = 0; i < s->num_shapes; ++i) {
    const fem_object *ob = &s->obj[i];
    if (ob->mesh) {
      e[n++] = (ss_fem_cache_entry){ob->mesh_key, ob->solution_key, ob->mesh, ob->exitance};
    }
  }
  ss_status st = ss_fem_cache_write(s->cache_path, e, n, err);
  free(e);
  return st;
}

static ss_status fem_prepare(const ss_scene *scene, void **state, ss_error *err) {
  *state = NULL;
  fem_options o;
  ss_status st = fem_check(scene, err);
  if (st != SS_OK || (st = read_options(scene, &o, err)) != SS_OK) {
    return st;
  }
  /* The indirect light's continuation rays see translucent objects through
   * their BSSRDF models, as in `hierarchical`'s pass 1 (irradiance_points.h):
   * the flake and grid media's models are built only on demand. */
  if (o.indirect && (st = ss_subsurface_build(scene->subsurface, err)) != SS_OK) {
    ss_error_prefix(err, "fem: indirect light: ");
    return st;
  }
  size_t n = scene->num_shapes;
  fem_state *s = calloc(1, sizeof *s);
  double *etas = calloc(n + 1, sizeof *etas);
  if (s) {
    s->opt = o;
    s->num_shapes = n;
    s->obj = calloc(n + 1, sizeof *s->obj);
    s->bound = calloc(n + 1, sizeof *s->bound);
  }
  if (!s || !etas || !s->obj || !s->bound) {
    free(etas);
    fem_release(s);
    return ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory");
  }
  for (size_t i = 0; i < n; ++i) {
    int m = scene->shapes[i].material;
    etas[i] = m >= 0 ? boundary_eta(&scene->materials[m]) : 1.0;
  }
  if (scene->integrator.cache[0]) {
    /* a file that cannot be used is recomputed and rewritten (the CLI names
     * it first, ss_fem_cache_read) */
    ss_error ignored;
    s->cache_path = scene->integrator.cache;
    ss_fem_cache_read(s->cache_path, &s->cache, &ignored);
  }
  for (size_t i = 0; st == SS_OK && i < n; ++i) {
    int m = scene->shapes[i].material;
    if (m >= 0 && is_translucent(&scene->materials[m])) {
      st = solve_shape(scene, s, i, etas, err);
      s->objects++;
    }
  }
  free(etas);
  if (st == SS_OK && s->cache_path && !s->opt.cache_read_only) {
    st = write_cache(s, err);
  }
  ss_fem_cache_destroy(s->cache);
  s->cache = NULL;
  if (st == SS_OK && s->num_bound) {
    st = ss_accel_create((const ss_mesh *const *)s->bound, s->num_bound, &s->lookup, err);
  }
  if (st != SS_OK) {
    fem_release(s);
    return st;
  }
  *state = s;
  return SS_OK;
}

/* M_o at the boundary point nearest x_o along its normal; 0 when no
 * boundary triangle lies within the object's reach. */
static int exitance_at(const fem_state *s, const fem_object *ob, const ss_hit *hit, double m[3]) {
  ss_ray ray = {ss_vec3_madd(hit->p, hit->ng, ob->reach), ss_vec3_neg(hit->ng), 0.0,
                2.0 * ob->reach};
  ss_hit hits[8];
  size_t nh = ss_accel_intersect_all(s->lookup, &ray, ob->geom, hits, 8);
  const ss_hit *best = NULL;
  for (size_t k = 0; k < nh && k < 8; ++k) {
    if (!best || fabs(hits[k].t - ob->reach) < fabs(best->t - ob->reach)) {
      best = &hits[k];
    }
  }
  if (!best) {
    return 0;
  }
  const uint32_t *f = ob->mesh->faces + 3 * (size_t)best->prim_id;
  double w[3] = {1.0 - best->b1 - best->b2, best->b1, best->b2};
  for (int c = 0; c < 3; ++c) {
    m[c] = 0.0;
    for (int k = 0; k < 3; ++k) {
      m[c] += w[k] * ob->exitance[3 * (size_t)f[k] + (size_t)c];
    }
  }
  return 1;
}

static ss_rgb diffusion(const void *state, const ss_hit *hit, ss_vec3 d, ss_path_stats *stats) {
  const fem_state *s = state;
  ss_rgb zero = ss_rgb_gray(0.0);
  if (hit->geom_id >= s->num_shapes || !s->obj[hit->geom_id].mesh) {
    return zero;
  }
  const fem_object *ob = &s->obj[hit->geom_id];
  double cos_o = -ss_vec3_dot(ss_vec3_normalize(d), hit->ng), m[3];
  stats->probe_rays++;
  if (!(cos_o > 0.0) || !exitance_at(s, ob, hit, m)) {
    return zero;
  }
  double k = ss_irradiance_fresnel_weight(cos_o, ob->eta) * ob->norm;
  return ss_rgb_make(k * fmax(m[0], 0.0), k * fmax(m[1], 0.0), k * fmax(m[2], 0.0));
}

void ss_fem_render_timings_of(const void *state, ss_fem_render_timings *t) {
  const fem_state *s = state;
  *t = (ss_fem_render_timings){
      s->mesh_seconds, s->irradiance_seconds, s->assemble_seconds, s->solve_seconds, s->tets,
      s->objects,      s->meshes_cached,      s->solutions_cached};
}

static ss_rgb fem_li(const ss_scene *scene, const void *state, ss_ray ray, ss_rng *rng,
                     ss_path_stats *stats) {
  return ss_diffusion_path_li(scene, diffusion, state, ray, rng, stats);
}

static const char *const fem_options_names[] = {"element_size",
                                                "irradiance_samples",
                                                "pcg",
                                                "max_elements",
                                                "min_density",
                                                "volume_source",
                                                "medium_element_size",
                                                "indirect",
                                                "cache",
                                                "cache_read_only",
                                                NULL};

const ss_integrator_ops ss_integrator_fem = {
    .name = "fem",
    .summary = "diffusion term from a finite-element solution of the (anisotropic, "
               "heterogeneous) diffusion equation in each translucent object, lit by the "
               "scene's direct and indirect light (Jakob et al. 2010)",
    .options = fem_options_names,
    .check = fem_check,
    .prepare = fem_prepare,
    .release = fem_release,
    .li = fem_li,
};
