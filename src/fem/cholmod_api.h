/* SuiteSparse CHOLMOD loaded on first use (dlopen) instead of linked, like
 * gmsh (gmsh_api.h): libcholmod pulls in ten more shared objects (AMD,
 * COLAMD, CAMD, CCOLAMD, METIS, LAPACK, BLAS, gfortran, quadmath,
 * SuiteSparse_config), which cost every subsurf process ~6 ms of dynamic
 * loading (bench/RESULTS.md) though only the fem solver uses
 * them. cholmod_api.c defines the CHOLMOD functions the fem module calls,
 * under their own names and hidden (libsubsurf.so does not export them), as
 * calls through the loaded library; ss_cholmod_load must have returned
 * SS_OK before any of them is called. */
#ifndef SUBSURF_FEM_CHOLMOD_API_H
#define SUBSURF_FEM_CHOLMOD_API_H

#include "subsurf/status.h"

/* The functions called: X(return type, name, parameters, arguments). */
#define SS_CHOLMOD_FUNCTIONS(X)                                                                    \
  X(int, cholmod_start, (cholmod_common * c), (c))                                                 \
  X(int, cholmod_finish, (cholmod_common * c), (c))                                                \
  X(cholmod_triplet *, cholmod_allocate_triplet,                                                   \
    (size_t nrow, size_t ncol, size_t nzmax, int stype, int xtype, cholmod_common *c),             \
    (nrow, ncol, nzmax, stype, xtype, c))                                                          \
  X(int, cholmod_free_triplet, (cholmod_triplet * *t, cholmod_common * c), (t, c))                 \
  X(cholmod_sparse *, cholmod_triplet_to_sparse,                                                   \
    (cholmod_triplet * t, size_t nzmax, cholmod_common * c), (t, nzmax, c))                        \
  X(int, cholmod_free_sparse, (cholmod_sparse * *a, cholmod_common * c), (a, c))                   \
  X(long, cholmod_nnz, (cholmod_sparse * a, cholmod_common * c), (a, c))                           \
  X(cholmod_dense *, cholmod_zeros, (size_t nrow, size_t ncol, int xtype, cholmod_common *c),      \
    (nrow, ncol, xtype, c))                                                                        \
  X(cholmod_dense *, cholmod_copy_dense, (cholmod_dense * x, cholmod_common * c), (x, c))          \
  X(int, cholmod_free_dense, (cholmod_dense * *x, cholmod_common * c), (x, c))                     \
  X(int, cholmod_sdmult,                                                                           \
    (cholmod_sparse * a, int transpose, double alpha[2], double beta[2], cholmod_dense *x,         \
     cholmod_dense *y, cholmod_common *c),                                                         \
    (a, transpose, alpha, beta, x, y, c))                                                          \
  X(cholmod_factor *, cholmod_analyze, (cholmod_sparse * a, cholmod_common * c), (a, c))           \
  X(int, cholmod_factorize, (cholmod_sparse * a, cholmod_factor * l, cholmod_common * c),          \
    (a, l, c))                                                                                     \
  X(int, cholmod_free_factor, (cholmod_factor * *l, cholmod_common * c), (l, c))                   \
  X(cholmod_dense *, cholmod_solve,                                                                \
    (int sys, cholmod_factor *l, cholmod_dense *b, cholmod_common *c), (sys, l, b, c))

/* Opens CHOLMOD once per process (thread-safe): SS_OK, or
 * SS_ERR_UNSUPPORTED naming the library and what is missing. */
ss_status ss_cholmod_load(ss_error *err);

#endif
