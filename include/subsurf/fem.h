/* Heterogeneous anisotropic diffusion by finite elements (Jakob2010
 * sec. 5-6.2).
 *
 * The medium is the anisotropic diffusion equation (Jakob2010 eq. 35)
 *   div(M^-1 grad phi) = mu0/(4 pi) phi - Q0
 * with the paper's matrix M (eq. 34; M = 3 sigma_t' I for an isotropic
 * medium, so M^-1 is the classical diffusion constant) and absorption
 * mu0 = mu0[sigma_a] (eq. 28; 4 pi sigma_a when isotropic), one (M, mu0) per
 * tetrahedron, and the anisotropic diffusive source boundary condition
 * (eq. 37-38)
 *   phi/4 + (A/2) n^T M^-1 grad phi = Gamma_s / Fdt,
 * A = (1 + Fdr)/(1 - Fdr), Fdt = 1 - Fdr, which reduces to the classical
 * Robin condition when isotropic. Linear tetrahedral elements give the
 * system (R + S + T) a = q + g of eq. 39-42.
 *
 * Meshes are made by gmsh (libgmsh-dev, its C API), systems are solved by
 * SuiteSparse CHOLMOD (libsuitesparse-dev): a supernodal Cholesky
 * factorisation, or conjugate gradients preconditioned by the diagonal with
 * CHOLMOD's sparse products. See docs/fem.md. */
#ifndef SUBSURF_FEM_H
#define SUBSURF_FEM_H

#include "subsurf/microflake.h"
#include "subsurf/status.h"
#include "subsurf/vec3.h"

#include <stddef.h>
#include <stdint.h>

/* A tetrahedral mesh: vertices, tetrahedra (positively oriented) and the
 * boundary triangles (faces of exactly one tetrahedron, wound so that
 * (p1 - p0) x (p2 - p0) points outward). */
typedef struct {
  size_t num_vertices, num_tets, num_faces;
  double *positions; /* 3 * num_vertices */
  uint32_t *tets;    /* 4 * num_tets */
  uint32_t *faces;   /* 3 * num_faces */
} ss_fem_mesh;

/* A field of element sizes from the medium's variation (fem_size_field.c):
 * where the coefficients (M, mu0) change fast between neighbouring samples
 * the elements are small, so that a density step or a turn of the flakes'
 * axis is not smeared over large tetrahedra (each takes its medium at its
 * centroid). See ss_fem_size_field_from_medium. */
typedef struct ss_fem_size_field ss_fem_size_field;

/* Element sizes: size_max everywhere, graded down to size_min within
 * refine_radius of refine_center (the size growing linearly to size_max over
 * a further refine_grade). With refine_radius <= 0 the size is size_max
 * everywhere. With rim_size > 0, also rim_size along the rim of a spot of
 * radius rim_radius about refine_center (where the sphere of that radius
 * meets the surface: the edge of the projected source image, Jakob2010
 * sec. 7), growing by its distance from that sphere. */
typedef struct {
  double size_max, size_min;
  ss_vec3 refine_center;
  double refine_radius, refine_grade;
  double rim_radius, rim_size;
  /* With a field (or NULL), also at most its size at every point. */
  const ss_fem_size_field *medium_size;
} ss_fem_mesh_options;

/* Meshes the box [lo, hi] (gmsh's OpenCASCADE kernel). */
ss_status ss_fem_mesh_box(ss_vec3 lo, ss_vec3 hi, const ss_fem_mesh_options *opt, ss_fem_mesh **out,
                          ss_error *err);

/* Meshes the inside of a closed, outward-wound triangle surface (positions:
 * 3 * num_vertices floats, indices: 3 * num_triangles). The caller checks
 * closedness (ss_mesh_check_closed); the surface is re-meshed to the sizes of
 * `opt` (gmsh's classifySurfaces + createGeometry) and the volume filled.
 * A surface gmsh cannot fill (self-intersecting, open) is an error naming
 * gmsh's message. */
ss_status ss_fem_mesh_surface(const float *positions, size_t num_vertices, const uint32_t *indices,
                              size_t num_triangles, const ss_fem_mesh_options *opt,
                              ss_fem_mesh **out, ss_error *err);

/* Builds a mesh from vertices and tetrahedra given by the caller (copied);
 * finds the boundary faces. Tetrahedra of zero volume or indices out of
 * range are errors naming the tetrahedron. */
ss_status ss_fem_mesh_create(const double *positions, size_t num_vertices, const uint32_t *tets,
                             size_t num_tets, ss_fem_mesh **out, ss_error *err);
void ss_fem_mesh_destroy(ss_fem_mesh *mesh);

/* The three vertices of boundary face f. */
void ss_fem_face_vertices(const ss_fem_mesh *mesh, size_t f, ss_vec3 p[3]);

/* The largest edge length of the mesh (its h). */
double ss_fem_mesh_max_edge(const ss_fem_mesh *mesh);

/* One element's coefficients: the paper's M (Jakob2010 eq. 34; row-major,
 * symmetric positive definite) and mu0[sigma_a] (eq. 28). */
typedef struct {
  double M[9];
  double mu0;
} ss_fem_coeffs;

/* The isotropic medium: M = 3 sigma_t' I, mu0 = 4 pi sigma_a (Jakob2010
 * sec. 5: M^-1 = I/(3 sigma_t') is the diffusion constant). */
ss_fem_coeffs ss_fem_coeffs_isotropic(double sigma_s_prime, double sigma_a);
/* A micro-flake medium of flakes `mf` with density a rho (flake_diffusion.h:
 * M of eq. 31/34, mu0 of eq. 28). */
ss_fem_coeffs ss_fem_coeffs_flakes(const ss_microflake *mf, double density);

/* The medium at a point (the tetrahedron's centroid). */
typedef ss_status (*ss_fem_medium_fn)(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err);

/* How ss_fem_size_field_from_medium samples the medium and sizes elements:
 * the medium is sampled on a lattice of `spacing` (e.g. a grid's voxel size;
 * coarsened so that the lattice has at most 2^22 samples) over [lo, hi];
 * between two neighbouring samples the relative change of the coefficients
 * r = max(|M_i - M_j|_F / max(|M_i|_F, |M_j|_F), |mu0_i - mu0_j| /
 * max(mu0_i, mu0_j)) over their distance d is the medium's relative
 * gradient g = r/d, and both samples get the size tolerance/g (the length
 * over which the medium changes by the fraction `tolerance`), kept in
 * [size_min, size_max]; the size then grows by at most `grade` per unit
 * distance from where it is small. */
typedef struct {
  ss_vec3 lo, hi;
  double spacing, tolerance, size_min, size_max, grade;
} ss_fem_size_options;

/* Samples the medium on the lattice and builds the size field. Errors: bad
 * options (naming the value), the medium's own error. */
ss_status ss_fem_size_field_from_medium(ss_fem_medium_fn medium, void *ctx,
                                        const ss_fem_size_options *opt, ss_fem_size_field **out,
                                        ss_error *err);
/* The element size at x: the lattice's trilinear interpolation (its nearest
 * sample outside its box). */
double ss_fem_size_field_at(const ss_fem_size_field *f, ss_vec3 x);
/* The integral of size^-3 over the field's box (the mean over its samples
 * times its volume): tetrahedra per unit of it estimate a mesh's count. */
double ss_fem_size_field_cells(const ss_fem_size_field *f);
/* The smallest size in the field. */
double ss_fem_size_field_min(const ss_fem_size_field *f);
/* The lattice behind ss_fem_size_field_at: its first sample, spacing and
 * counts, and the sizes (n[0] n[1] n[2] floats, x fastest). */
const float *ss_fem_size_field_lattice(const ss_fem_size_field *f, ss_vec3 *lo, double step[3],
                                       int n[3]);
void ss_fem_size_field_destroy(ss_fem_size_field *f);

/* A ray of refracted light inside the medium whose first scattering events
 * are an exponentially attenuated volume source: power * sigma exp(-sigma s)
 * per unit length at distance s from `origin` along the unit `dir` (the
 * reduced-intensity source that Jakob2010 eq. 37 approximates by a boundary
 * flux; its mean depth 1/sigma is the dipole's source depth, eq. 44). */
typedef struct {
  ss_vec3 origin, dir;
  double sigma, power;
} ss_fem_ray;

/* Extinction coefficient of the medium along the unit direction w. */
typedef double (*ss_fem_sigma_fn)(void *ctx, ss_vec3 w);

/* The rays of a diffuse spot of `radius` about `center` on a surface of
 * outward unit `normal`: stratified points of the disc in its tangent plane
 * (n_disc = rings x 2 rings sectors), each with refracted directions that are
 * cosine-distributed about -normal when `diffuse` (n_dirs x 2 n_dirs
 * strata), or -normal alone; `power` is shared equally, the extinction along
 * each direction is sigma(ctx, dir). *out (num_rays) is allocated. */
ss_status ss_fem_spot_rays(ss_vec3 center, ss_vec3 normal, double radius, double power, int diffuse,
                           int rings, int n_dirs, ss_fem_sigma_fn sigma, void *ctx,
                           ss_fem_ray **out, size_t *num_rays, ss_error *err);

/* Sources: a diffuse spot on the boundary (Jakob2010 eq. 37: Gamma_s is the
 * refracted irradiance attenuated by exp(-sigma_a/sigma_s), uniform over the
 * boundary within spot_radius of spot_center, spot_power in total; the
 * caller applies the transmission and attenuation), an isotropic point source
 * inside (Q0 = point_power delta(x - point)) and a uniform volume source
 * (Q0 = volume_source everywhere). Any may be zero. */
typedef struct {
  double eta;
  ss_vec3 spot_center;
  double spot_radius, spot_power;
  ss_vec3 point;
  double point_power;
  double volume_source;
  /* Gamma_s per boundary face (mesh->num_faces values, constant over each
   * face: e.g. the refracted irradiance of a scene's lights at its centroid,
   * attenuated as for the spot), or NULL; adds to the spot. */
  const double *face_gamma;
  /* Exponentially attenuated rays (num_rays, or NULL): each deposits its
   * power as a volume source Q0 at depth strata of the exponential, spread
   * over the containing tetrahedron's vertices by the linear shape functions
   * (q_i = int Q0 beta_i); strata outside the mesh are lost (not injected). */
  const ss_fem_ray *rays;
  size_t num_rays;
} ss_fem_problem;

typedef enum {
  SS_FEM_CHOLMOD, /* supernodal Cholesky (CHOLMOD) */
  SS_FEM_PCG,     /* conjugate gradients, Jacobi preconditioner */
} ss_fem_solver;

typedef struct {
  ss_fem_solver solver;
  double tolerance; /* PCG: relative residual |b - K a| / |b| */
  int max_iterations;
} ss_fem_solve_options;

typedef struct {
  double *fluence;  /* phi at each vertex */
  double *exitance; /* radiant exitance M_o at each boundary vertex, 0 inside:
                       Fdt (1 + 1/A) phi/4 - Gamma_s/A (Jakob2010 sec. 6.2.2's
                       query integrated over the outgoing hemisphere) */
  /* Energy per unit time: injected = int Gamma_s + int Q0; absorbed =
   * int mu0/(4 pi) phi; escaped = int M_o over the boundary. */
  double injected, absorbed, escaped;
  size_t unknowns, nonzeros;              /* of the upper triangle of K */
  double factor_nonzeros;                 /* of the Cholesky factor L; 0 for PCG */
  double peak_bytes;                      /* CHOLMOD's peak memory (matrix, factor, vectors) */
  int iterations;                         /* PCG; 0 for CHOLMOD */
  double residual;                        /* |b - K a| / |b| */
  double assemble_seconds, solve_seconds; /* CPU time */
} ss_fem_solution;

/* Assembles and solves. Errors: a medium whose M is not symmetric positive
 * definite or mu0 < 0 (naming the element), a point source outside the mesh,
 * a singular or indefinite system, PCG not converging. */
ss_status ss_fem_solve(const ss_fem_mesh *mesh, ss_fem_medium_fn medium, void *medium_ctx,
                       const ss_fem_problem *problem, const ss_fem_solve_options *opt,
                       ss_fem_solution **out, ss_error *err);
void ss_fem_solution_destroy(ss_fem_solution *sol);

/* The gmsh and CHOLMOD the module loads at run time: their versions and
 * library files, e.g. "gmsh 4.8.0 (/usr/lib/.../libgmsh.so.4.8.4), CHOLMOD
 * 3.0.14 (/usr/lib/.../libcholmod.so.3.0.14)" (the fem integrator's cache
 * keys hash it, fem_cache.h). */
const char *ss_fem_libraries(void);

/* Linear interpolation of the vertex values `f` at x: 0 when x is in no
 * tetrahedron (returns 0 then, 1 when found). */
int ss_fem_interpolate(const ss_fem_mesh *mesh, const double *f, ss_vec3 x, double *value);

#endif
