/* The few MPI calls libfc3d_mpi makes, compiled with the MPI compiler wrapper's flags so that
 * they follow this MPI's mpi.h (MPI_Comm is a pointer in Open MPI, an int in MPICH). The Rust side
 * holds communicators and requests as opaque pointers allocated here. Every function returns an
 * MPI error code (0 = MPI_SUCCESS): the communicator fc3d works on returns errors instead of
 * aborting (MPI_ERRORS_RETURN). Counts are in 8-byte words (int64 or the bits of doubles). */
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The host's communicator `*host` duplicated into a communicator of fc3d's own (its messages
 * never match the host's); -1 for MPI_COMM_NULL, -2 when MPI is not initialised. */
int fc3d_mpi_shim_dup(const MPI_Comm *host, void **out) {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (!initialised || finalised) return -2;
  if (*host == MPI_COMM_NULL) return -1;
  MPI_Comm *comm = malloc(sizeof(MPI_Comm));
  if (!comm) return MPI_ERR_NO_MEM;
  int e = MPI_Comm_dup(*host, comm);
  if (e != MPI_SUCCESS) {
    free(comm);
    return e;
  }
  MPI_Comm_set_errhandler(*comm, MPI_ERRORS_RETURN);
  *out = comm;
  return MPI_SUCCESS;
}

/* Collective: releases a communicator made by fc3d_mpi_shim_dup. */
void fc3d_mpi_shim_free(void *comm) {
  MPI_Comm *c = comm;
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Comm_free(c);
  free(c);
}

int fc3d_mpi_shim_rank_size(void *comm, int *rank, int *size) {
  int e = MPI_Comm_rank(*(MPI_Comm *)comm, rank);
  return e ? e : MPI_Comm_size(*(MPI_Comm *)comm, size);
}

/* In place: op 0 sum, 1 max, 2 min. */
int fc3d_mpi_shim_allreduce_i64(void *comm, int64_t *values, int n, int op) {
  MPI_Op o = op == 0 ? MPI_SUM : op == 1 ? MPI_MAX : MPI_MIN;
  return MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_INT64_T, o, *(MPI_Comm *)comm);
}

int fc3d_mpi_shim_bcast(void *comm, void *buffer, int bytes, int root) {
  return MPI_Bcast(buffer, bytes, MPI_BYTE, root, *(MPI_Comm *)comm);
}

int fc3d_mpi_shim_alltoall_i64(void *comm, const int64_t *send, int64_t *recv) {
  return MPI_Alltoall(send, 1, MPI_INT64_T, recv, 1, MPI_INT64_T, *(MPI_Comm *)comm);
}

int fc3d_mpi_shim_alltoallv_i64(void *comm, const int64_t *send, const int *send_counts,
                                const int *send_displs, int64_t *recv, const int *recv_counts,
                                const int *recv_displs) {
  return MPI_Alltoallv(send, send_counts, send_displs, MPI_INT64_T, recv, recv_counts,
                       recv_displs, MPI_INT64_T, *(MPI_Comm *)comm);
}

/* n requests, all MPI_REQUEST_NULL; NULL when out of memory. */
void *fc3d_mpi_shim_requests(int n) {
  MPI_Request *r = malloc(sizeof(MPI_Request) * (size_t)(n > 0 ? n : 1));
  if (r)
    for (int k = 0; k < n; ++k) r[k] = MPI_REQUEST_NULL;
  return r;
}

void fc3d_mpi_shim_requests_free(void *requests) { free(requests); }

int fc3d_mpi_shim_irecv(void *comm, int64_t *buffer, int n, int source, int tag, void *requests,
                        int k) {
  return MPI_Irecv(buffer, n, MPI_INT64_T, source, tag, *(MPI_Comm *)comm,
                   (MPI_Request *)requests + k);
}

int fc3d_mpi_shim_isend(void *comm, const int64_t *buffer, int n, int dest, int tag,
                        void *requests, int k) {
  return MPI_Isend(buffer, n, MPI_INT64_T, dest, tag, *(MPI_Comm *)comm,
                   (MPI_Request *)requests + k);
}

/* Waits for requests first .. first + n. */
int fc3d_mpi_shim_waitall(void *requests, int first, int n) {
  return MPI_Waitall(n, (MPI_Request *)requests + first, MPI_STATUSES_IGNORE);
}

/* The C communicator of a Fortran one. */
void fc3d_mpi_shim_f2c(MPI_Fint fortran, MPI_Comm *out) { *out = MPI_Comm_f2c(fortran); }

void fc3d_mpi_shim_error_string(int code, char *text, int capacity) {
  char buffer[MPI_MAX_ERROR_STRING];
  int len = 0;
  if (code < 0 || MPI_Error_string(code, buffer, &len) != MPI_SUCCESS) len = 0;
  if (capacity <= 0) return;
  if (len >= capacity) len = capacity - 1;
  memcpy(text, buffer, (size_t)len);
  text[len] = 0;
}

/* For fc3d's own MPI programs (the check program, benchmarks): MPI_Init, MPI_COMM_WORLD,
 * MPI_Finalize. */
int fc3d_mpi_shim_init(void) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  return initialised ? MPI_SUCCESS : MPI_Init(NULL, NULL);
}

void fc3d_mpi_shim_world(MPI_Comm *out) { *out = MPI_COMM_WORLD; }

int fc3d_mpi_shim_finalize(void) { return MPI_Finalize(); }

double fc3d_mpi_shim_wtime(void) { return MPI_Wtime(); }

/* CPU seconds of the calling thread: the work a rank did, whatever else shares its core. */
double fc3d_mpi_shim_thread_cpu_seconds(void) {
  struct timespec t;
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) != 0) return 0.0;
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
