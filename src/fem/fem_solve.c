/* Solving the finite-element system (Jakob2010 eq. 39) with SuiteSparse
 * CHOLMOD: a supernodal Cholesky factorisation (fill-reducing ordering by
 * AMD/METIS as CHOLMOD chooses), or conjugate gradients preconditioned by
 * the diagonal (Jacobi) with CHOLMOD's sparse product, for meshes whose
 * factor would not fit in memory. Then the exitance and the energy balance. */
#include "fem/cholmod_api.h"
#include "fem/fem_internal.h"

#include <cholmod.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double norm2(const double *x, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    s += x[i] * x[i];
  }
  return sqrt(s);
}

/* y = K x */
static void apply(cholmod_sparse *K, cholmod_dense *x, cholmod_dense *y, cholmod_common *cm) {
  double one[2] = {1, 0}, zero[2] = {0, 0};
  cholmod_sdmult(K, 0, one, zero, x, y, cm);
}

static ss_status solve_cholmod(cholmod_sparse *K, cholmod_dense *b, cholmod_dense **x,
                               cholmod_common *cm, ss_error *err) {
  cholmod_factor *L = cholmod_analyze(K, cm);
  if (L) {
    cholmod_factorize(K, L, cm);
  }
  if (!L || cm->status == CHOLMOD_OUT_OF_MEMORY) {
    cholmod_free_factor(&L, cm);
    return ss_error_set(err, SS_ERR_NO_MEMORY,
                        "fem: out of memory for the Cholesky factor of %zu unknowns (try the "
                        "iterative solver)",
                        K->nrow);
  }
  if (cm->status == CHOLMOD_NOT_POSDEF || L->minor < L->n) {
    size_t col = L->minor;
    cholmod_free_factor(&L, cm);
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: singular system (not positive definite at unknown %zu): a part of "
                        "the mesh with neither absorption nor boundary?",
                        col);
  }
  *x = cholmod_solve(CHOLMOD_A, L, b, cm);
  cholmod_free_factor(&L, cm);
  return *x ? SS_OK : ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory in the solve");
}

/* Conjugate gradients with the Jacobi preconditioner (Saad 2003, alg. 9.1). */
static ss_status solve_pcg(cholmod_sparse *K, cholmod_dense *b, const ss_fem_solve_options *o,
                           cholmod_dense **out, int *iterations, cholmod_common *cm,
                           ss_error *err) {
  size_t n = K->nrow;
  cholmod_dense *x = cholmod_zeros(n, 1, CHOLMOD_REAL, cm), *r = cholmod_copy_dense(b, cm),
                *p = cholmod_zeros(n, 1, CHOLMOD_REAL, cm),
                *q = cholmod_zeros(n, 1, CHOLMOD_REAL, cm);
  double *inv_diag = malloc(n * sizeof *inv_diag), *z = malloc(n * sizeof *z);
  ss_status st = SS_OK;
  if (!x || !r || !p || !q || !inv_diag || !z) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for CG on %zu unknowns", n);
  }
  const int *Kp = K->p, *Ki = K->i;
  const double *Kx = K->x;
  for (size_t j = 0; j < n && st == SS_OK; ++j) {
    double d = 0.0;
    for (int k = Kp[j]; k < Kp[j + 1]; ++k) {
      if ((size_t)Ki[k] == j) {
        d = Kx[k];
      }
    }
    if (!(d > 0.0)) {
      st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: singular system (diagonal %g at unknown %zu)", d, j);
    }
    inv_diag[j] = st == SS_OK ? 1.0 / d : 0.0;
  }
  double bnorm = st == SS_OK ? norm2(b->x, n) : 0.0, rz = 0.0;
  int it = 0;
  if (st == SS_OK && bnorm > 0.0) {
    double *xv = x->x, *rv = r->x, *pv = p->x, *qv = q->x;
    for (size_t i = 0; i < n; ++i) {
      z[i] = inv_diag[i] * rv[i];
      pv[i] = z[i];
      rz += rv[i] * z[i];
    }
    while (norm2(rv, n) > o->tolerance * bnorm) {
      if (it >= o->max_iterations) {
        st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem: conjugate gradients did not reach %g in %d iterations "
                          "(residual %g)",
                          o->tolerance, o->max_iterations, norm2(rv, n) / bnorm);
        break;
      }
      apply(K, p, q, cm);
      double pq = 0.0;
      for (size_t i = 0; i < n; ++i) {
        pq += pv[i] * qv[i];
      }
      if (!(pq > 0.0)) {
        st = ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                          "fem: singular or indefinite system (p.Kp = %g at CG iteration %d)", pq,
                          it);
        break;
      }
      double alpha = rz / pq, rz_new = 0.0;
      for (size_t i = 0; i < n; ++i) {
        xv[i] += alpha * pv[i];
        rv[i] -= alpha * qv[i];
        z[i] = inv_diag[i] * rv[i];
        rz_new += rv[i] * z[i];
      }
      for (size_t i = 0; i < n; ++i) {
        pv[i] = z[i] + rz_new / rz * pv[i];
      }
      rz = rz_new;
      ++it;
    }
  }
  *iterations = it;
  free(inv_diag);
  free(z);
  cholmod_free_dense(&r, cm);
  cholmod_free_dense(&p, cm);
  cholmod_free_dense(&q, cm);
  if (st != SS_OK) {
    cholmod_free_dense(&x, cm);
  }
  *out = x;
  return st;
}

static ss_status check_solve_options(const ss_fem_solve_options *o, ss_error *err) {
  if (o->solver != SS_FEM_CHOLMOD && o->solver != SS_FEM_PCG) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT, "fem: unknown solver %d", (int)o->solver);
  }
  if (o->solver == SS_FEM_PCG &&
      (!(o->tolerance > 0.0 && o->tolerance < 1.0) || o->max_iterations < 1)) {
    return ss_error_set(err, SS_ERR_INVALID_ARGUMENT,
                        "fem: CG tolerance %g must be in (0, 1) and iterations %d >= 1",
                        o->tolerance, o->max_iterations);
  }
  return SS_OK;
}

/* Exitance at the vertices and the energy balance from the solution. */
static void finish_solution(const ss_fem_mesh *m, const ss_fem_system *sys, ss_fem_solution *s) {
  double Fdt = 2.0 / (sys->A + 1.0); /* A = (1 + Fdr)/(1 - Fdr) => 1 - Fdr = 2/(A + 1) */
  double absorbed = 0.0, boundary = 0.0;
  for (size_t i = 0; i < sys->n; ++i) {
    absorbed += sys->absorb_weight[i] * s->fluence[i];
    boundary += sys->face_weight[i] * s->fluence[i];
  }
  for (size_t f = 0; f < 3 * m->num_faces; ++f) {
    uint32_t v = m->faces[f];
    /* Jakob2010 sec. 6.2.2: L = Ft/(4 pi) [(1 + 1/A) phi - 4 Gamma_s/(Fdt A)],
     * integrated over the outgoing hemisphere (int Ft cos = pi Fdt) */
    s->exitance[v] =
        Fdt * (1.0 + 1.0 / sys->A) * s->fluence[v] / 4.0 - sys->gamma_vertex[v] / sys->A;
  }
  s->absorbed = absorbed;
  s->escaped = Fdt * (1.0 + 1.0 / sys->A) * boundary / 4.0 - sys->spot_injected / sys->A;
  s->injected = sys->spot_injected + sys->volume_injected;
}

ss_status ss_fem_solve(const ss_fem_mesh *mesh, ss_fem_medium_fn medium, void *medium_ctx,
                       const ss_fem_problem *problem, const ss_fem_solve_options *opt,
                       ss_fem_solution **out, ss_error *err) {
  *out = NULL;
  ss_status st = check_solve_options(opt, err);
  if (st != SS_OK) {
    return st;
  }
  if ((st = ss_cholmod_load(err)) != SS_OK) {
    return st;
  }
  cholmod_common cm;
  cholmod_start(&cm);
  cm.print = 0; /* the library never prints */
  double t0 = cpu_seconds();
  ss_fem_system sys;
  st = ss_fem_assemble(mesh, medium, medium_ctx, problem, &cm, &sys, err);
  if (st != SS_OK) {
    cholmod_finish(&cm);
    return st;
  }
  ss_fem_solution *s = calloc(1, sizeof *s);
  double *fluence = calloc(sys.n, sizeof *fluence), *exitance = calloc(sys.n, sizeof *exitance);
  cholmod_dense *b = cholmod_zeros(sys.n, 1, CHOLMOD_REAL, &cm), *x = NULL;
  if (!s || !fluence || !exitance || !b) {
    st = ss_error_set(err, SS_ERR_NO_MEMORY, "fem: out of memory for %zu unknowns", sys.n);
  }
  double t1 = cpu_seconds();
  if (st == SS_OK) {
    memcpy(b->x, sys.b, sys.n * sizeof *sys.b);
    s->unknowns = sys.n;
    s->nonzeros = cholmod_nnz(sys.K, &cm);
    s->assemble_seconds = t1 - t0;
    st = opt->solver == SS_FEM_CHOLMOD ? solve_cholmod(sys.K, b, &x, &cm, err)
                                       : solve_pcg(sys.K, b, opt, &x, &s->iterations, &cm, err);
  }
  if (st == SS_OK) {
    s->solve_seconds = cpu_seconds() - t1;
    s->factor_nonzeros = opt->solver == SS_FEM_CHOLMOD ? cm.lnz : 0.0;
    s->peak_bytes = (double)cm.memory_usage;
    memcpy(fluence, x->x, sys.n * sizeof *fluence);
    /* the achieved relative residual |b - K x| / |b| */
    cholmod_dense *r = cholmod_copy_dense(b, &cm);
    double minus_one[2] = {-1, 0}, one[2] = {1, 0};
    if (r) {
      cholmod_sdmult(sys.K, 0, minus_one, one, x, r, &cm);
      double bn = norm2(b->x, sys.n);
      s->residual = bn > 0.0 ? norm2(r->x, sys.n) / bn : 0.0;
    }
    cholmod_free_dense(&r, &cm);
    s->fluence = fluence;
    s->exitance = exitance;
    finish_solution(mesh, &sys, s);
    *out = s;
  } else {
    free(fluence);
    free(exitance);
    free(s);
  }
  cholmod_free_dense(&x, &cm);
  cholmod_free_dense(&b, &cm);
  ss_fem_system_free(&sys, &cm);
  cholmod_finish(&cm);
  return st;
}

void ss_fem_solution_destroy(ss_fem_solution *sol) {
  if (!sol) {
    return;
  }
  free(sol->fluence);
  free(sol->exitance);
  free(sol);
}
