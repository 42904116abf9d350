/* Open MPI behind a plugin, libsubsurf_mpi.so (plugins/mpi_plugin.c),
 * opened by mpi_job.c only when the process was started by mpirun
 * (io/plugin.h): linking libmpi (with libopen-rte, libopen-pal, hwloc,
 * libevent, libudev) cost every subsurf process ~9 ms of dynamic loading
 * (bench/RESULTS.md). The plugin wraps the few MPI calls the CLI
 * makes on MPI_COMM_WORLD in plain C types; everything else, and all
 * decisions, stay in mpi_job.c and mpi_halfspace.c. */
#ifndef SUBSURF_CLI_MPI_PLUGIN_H
#define SUBSURF_CLI_MPI_PLUGIN_H

#define SS_MPI_PLUGIN_FILE "libsubsurf_mpi.so"

/* Room for one MPI_Request (the plugin checks that it fits). */
typedef struct {
  _Alignas(8) unsigned char opaque[32];
} ss_mpi_request;

/* Element types and reductions of the calls below. */
enum { SS_MPI_INT, SS_MPI_UINT64, SS_MPI_BYTE };
enum { SS_MPI_MIN, SS_MPI_MAX, SS_MPI_SUM };

/* Each call returns 0, or -1 when MPI reported an error (errors come back
 * as codes, MPI_ERRORS_RETURN), except test: 1 done, 0 not yet, -1 failed. */
typedef struct {
  /* MPI_Init_thread with threads calling MPI in turn (MPI_THREAD_SERIALIZED). */
  int (*init)(int *rank, int *size);
  void (*finalize)(void);
  void (*abort)(int code);
  int (*allreduce)(const void *in, void *out, int count, int type, int op);
  int (*iallreduce)(const void *in, void *out, int count, int type, int op, ss_mpi_request *req);
  int (*reduce)(const void *in, void *out, int count, int type, int op, int root);
  int (*isend)(const void *buf, int count, int type, int to, int tag, ss_mpi_request *req);
  int (*irecv)(void *buf, int count, int type, int from, int tag, ss_mpi_request *req);
  int (*test)(ss_mpi_request *req);
} ss_mpi_plugin_api;

extern const ss_mpi_plugin_api ss_mpi_plugin;

#endif
