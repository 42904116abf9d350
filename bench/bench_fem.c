/* bench_fem: meshing, assembly and solve of the finite-element
 * diffusion against the number of tetrahedra, Cholesky (CHOLMOD) against
 * conjugate gradients (Jacobi), on a 20 x 20 x 10 block of an isotropic
 * medium (sigma_s' = 1, sigma_a = 0.01, eta = 1.3) lit by a spot, uniform
 * element size h. Meshing is gmsh's wall time and the process's CPU time
 * over it (gmsh runs one thread here); assembly and solves are CPU time; memory is CHOLMOD's peak
 * and the process's peak resident set (ru_maxrss, cumulative). The spot is the
 * paper's boundary flux (Jakob2010 eq. 37) for both solvers; a third (CG)
 * solve takes it as the rays' volume source of `subsurf fem` (fem_rays.c:
 * 6 rings x 12 sectors of the disc x 72 cosine-distributed directions, 16
 * depth strata each), whose assembly time includes depositing the rays
 * (the point-location grid and 83 k located points). An argument H/N is a
 * graded mesh as `subsurf fem`'s defaults make: size N within 1.5 of the
 * spot's centre, growing linearly to H over a further 6.
 * usage: bench_fem [h | H/N ...]   (default 2 1.4 1 0.7 0.5 2/0.25) */
#include "subsurf/fem.h"
#include "subsurf/progress.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static ss_status iso(void *ctx, ss_vec3 x, ss_fem_coeffs *out, ss_error *err) {
  *out = ss_fem_coeffs_isotropic(1.0, 0.01);
  return SS_OK;
}

static double sigma_t(void *ctx, ss_vec3 w) { return 1.01; }

static double cpu_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double rss_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

int main(int argc, char **argv) {
  const char *def[] = {"2", "1.4", "1", "0.7", "0.5", "2/0.25"};
  int n = argc > 1 ? argc - 1 : (int)(sizeof def / sizeof def[0]);
  printf("| h | vertices | tetrahedra | mesh s (wall) | mesh s (CPU) | assemble s | nnz(K) | "
         "cholmod s | nnz(L) | cholmod MB | pcg s | pcg its | pcg MB | assemble s, rays | "
         "max RSS MB |\n");
  printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < n; ++i) {
    const char *arg = argc > 1 ? argv[i + 1] : def[i], *near = strchr(arg, '/');
    double h = atof(arg);
    ss_error err = {0};
    ss_fem_mesh_options mo = {.size_max = h, .size_min = near ? atof(near + 1) : h};
    if (near) {
      mo.refine_radius = 1.5;
      mo.refine_grade = 6.0;
    }
    ss_fem_mesh *m = NULL;
    double t0 = ss_seconds(), c0 = cpu_seconds();
    if (ss_fem_mesh_box(ss_vec3_make(-10, -10, -10), ss_vec3_make(10, 10, 0), &mo, &m, &err)) {
      fprintf(stderr, "bench_fem: %s\n", err.message);
      return 1;
    }
    double mesh_s = ss_seconds() - t0, mesh_cpu = cpu_seconds() - c0;
    ss_fem_problem pb = {.eta = 1.3, .spot_radius = 1.0, .spot_power = 1.0};
    ss_fem_ray *spot_rays = NULL;
    ss_fem_problem rays = {.eta = 1.3};
    if (ss_fem_spot_rays(ss_vec3_make(0, 0, 0), ss_vec3_make(0, 0, 1), 1.0, 1.0, 1, 6, 6, sigma_t,
                         NULL, &spot_rays, &rays.num_rays, &err)) {
      fprintf(stderr, "bench_fem: %s\n", err.message);
      return 1;
    }
    rays.rays = spot_rays;
    ss_fem_solution *s[3] = {NULL, NULL, NULL};
    for (int k = 0; k < 3; ++k) {
      ss_fem_solve_options so = {
          .solver = k ? SS_FEM_PCG : SS_FEM_CHOLMOD, .tolerance = 1e-8, .max_iterations = 100000};
      if (ss_fem_solve(m, iso, NULL, k == 2 ? &rays : &pb, &so, &s[k], &err)) {
        fprintf(stderr, "bench_fem: %s\n", err.message);
        return 1;
      }
    }
    printf("| %s | %zu | %zu | %.2f | %.2f | %.3f | %zu | %.3f | %.3g | %.1f | %.3f | %d | %.1f | "
           "%.3f | %.0f |\n",
           arg, m->num_vertices, m->num_tets, mesh_s, mesh_cpu, s[0]->assemble_seconds,
           s[0]->nonzeros, s[0]->solve_seconds, s[0]->factor_nonzeros, s[0]->peak_bytes / 1048576.0,
           s[1]->solve_seconds, s[1]->iterations, s[1]->peak_bytes / 1048576.0,
           s[2]->assemble_seconds, rss_mb());
    fflush(stdout);
    ss_fem_solution_destroy(s[0]);
    ss_fem_solution_destroy(s[1]);
    ss_fem_solution_destroy(s[2]);
    free(spot_rays);
    ss_fem_mesh_destroy(m);
  }
  return 0;
}
