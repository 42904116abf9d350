/* The MPI calls of the CLI on MPI_COMM_WORLD, in plain C types: the plugin
 * libsubsurf_mpi.so (mpi_plugin.h). */
#include "cli/mpi_plugin.h"

#include <mpi.h>

_Static_assert(sizeof(MPI_Request) <= sizeof(ss_mpi_request),
               "ss_mpi_request holds an MPI_Request");

static MPI_Datatype datatype(int type) {
  return type == SS_MPI_INT ? MPI_INT : type == SS_MPI_UINT64 ? MPI_UINT64_T : MPI_BYTE;
}

static MPI_Op operation(int op) {
  return op == SS_MPI_MIN ? MPI_MIN : op == SS_MPI_MAX ? MPI_MAX : MPI_SUM;
}

static int code(int rc) { return rc == MPI_SUCCESS ? 0 : -1; }

static MPI_Request *request(ss_mpi_request *r) { return (MPI_Request *)(void *)r->opaque; }

static int init(int *rank, int *size) {
  int provided;
  if (MPI_Init_thread(NULL, NULL, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS ||
      provided < MPI_THREAD_SERIALIZED) {
    return -1;
  }
  /* Errors come back as codes, so that a lost rank ends the job with a
   * message instead of a hang. */
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return 0;
}

static void finalize(void) { MPI_Finalize(); }

static void abort_job(int rc) { MPI_Abort(MPI_COMM_WORLD, rc); }

static int allreduce(const void *in, void *out, int count, int type, int op) {
  return code(MPI_Allreduce(in, out, count, datatype(type), operation(op), MPI_COMM_WORLD));
}

static int iallreduce(const void *in, void *out, int count, int type, int op, ss_mpi_request *req) {
  return code(
      MPI_Iallreduce(in, out, count, datatype(type), operation(op), MPI_COMM_WORLD, request(req)));
}

static int reduce(const void *in, void *out, int count, int type, int op, int root) {
  return code(MPI_Reduce(in, out, count, datatype(type), operation(op), root, MPI_COMM_WORLD));
}

static int isend(const void *buf, int count, int type, int to, int tag, ss_mpi_request *req) {
  return code(MPI_Isend(buf, count, datatype(type), to, tag, MPI_COMM_WORLD, request(req)));
}

static int irecv(void *buf, int count, int type, int from, int tag, ss_mpi_request *req) {
  return code(MPI_Irecv(buf, count, datatype(type), from, tag, MPI_COMM_WORLD, request(req)));
}

static int test(ss_mpi_request *req) {
  int done = 0;
  int rc = MPI_Test(request(req), &done, MPI_STATUS_IGNORE);
  return rc != MPI_SUCCESS ? -1 : done != 0;
}

const ss_mpi_plugin_api ss_mpi_plugin = {init,   finalize, abort_job, allreduce, iallreduce,
                                         reduce, isend,    irecv,     test};
