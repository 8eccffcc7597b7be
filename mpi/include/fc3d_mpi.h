#ifndef FC3D_MPI_H
#define FC3D_MPI_H

/* fc3d's distributed solve over a host's MPI communicator (libfc3d_mpi, pkg-config fc3d-mpi,
 * CMake fc3d::mpi). Each rank gives the block rows of its own contacts, with global contact
 * ids; every call below is collective over its communicator unless marked otherwise. The
 * library also carries the native entry of <fc3d_native.h> (fc3d_settings_*, fc3d_last_error_*):
 * link -lfc3d_mpi alone. See docs/mpi.md. */

#include <mpi.h>
#include <stdint.h>

#include "fc3d_native.h"

/* An MPI call failed, or the communicator is unusable (MPI_COMM_NULL, MPI not initialised). */
#define FC3D_MPI_ERR_COMMUNICATION -20

/* Gauss-Seidel over the colours of the global contact graph (default): the same bits for any
 * number of ranks and any partition, equal to a one-process run. */
#define FC3D_MPI_REPRODUCIBLE 0

/* Gauss-Seidel inside each rank, Jacobi across ranks (one exchange per sweep): fewer messages,
 * results and sweep counts depend on the partition. */
#define FC3D_MPI_FAST 1

/* A distributed solver kept across time steps (opaque). */
typedef struct Fc3dMpiSolver Fc3dMpiSolver;

/* What fc3d_mpi_solver_stats reports, for the calling rank. */
typedef struct Fc3dMpiStats {
  int ranks;
  int mode;                   /* FC3D_MPI_REPRODUCIBLE or FC3D_MPI_FAST */
  int64_t colours;            /* colours of the global contact graph (1 in the fast mode) */
  int64_t colouring_rounds;   /* rounds the parallel colouring took */
  int64_t contacts;           /* this rank's contacts */
  int64_t total_contacts;     /* all ranks' */
  int64_t ghosts;             /* other ranks' contacts this rank reads (received each sweep) */
  int64_t boundary;           /* this rank's contacts other ranks read (sent each sweep) */
  int64_t neighbours;         /* ranks this one exchanges with */
  int64_t messages_per_sweep; /* messages this rank sends per sweep */
  int64_t bytes_per_sweep;    /* bytes this rank sends per sweep */
  int64_t setups;             /* set-ups built by this solver */
  int64_t solves;             /* solves done by this solver */
  int64_t sweeps;             /* sweeps of the last solve */
  double seconds_setup;       /* the last set-up */
  double seconds_compute;     /* the last solve's sweeps and error measures on this rank */
  double seconds_wait;        /* the last solve's waits in MPI (halo messages, reductions) */
  double cpu_seconds_compute; /* CPU seconds of that compute (less than its wall time when
                                 other processes share the core) */
} Fc3dMpiStats;

#ifdef __cplusplus
extern "C" {
#endif

/* Solves FC(W, q, mu) distributed over `comm` with NSGS (solver 500; other ids are refused with
 * FC3D_ERR_UNSUPPORTED_SOLVER) in the reproducible mode. Each rank gives:
 *   n_local, contact_ids   its contacts' global ids (any order, any non-negative values; a rank
 *                          may own none: n_local = 0, block_row_ptr = {0})
 *   n_blocks, block_row_ptr (n_local + 1), block_col_ids (n_blocks, the GLOBAL id of each
 *                          block's column), blocks (9 per block, column-major): its rows of W,
 *                          diagonal blocks included, as fc3d_solve_blocks takes them
 *   q (3 n_local), mu (n_local), r (3 n_local: the warm start, receives the result),
 *   u (3 n_local: receives W r + q)
 * `settings` (may be NULL: NSGS with Siconos' defaults) must be the same on every rank. The
 * result (info, sweeps, error of the whole problem, seconds: the slowest rank's) is the same on
 * every rank. Returns info (0 converged, 1 sweep limit, 2 time budget) or, on every rank alike,
 * a negative FC3D_ERR_* code with the same message (naming the rank that failed); nothing is
 * written on failure. */
int fc3d_mpi_solve_blocks(MPI_Comm comm, int64_t n_local, const int64_t *contact_ids,
                          int64_t n_blocks, const int64_t *block_row_ptr,
                          const int64_t *block_col_ids, const double *blocks, const double *q,
                          const double *mu, double *r, double *u,
                          const struct Fc3dSettings *settings, struct Fc3dResult *result);

/* fc3d_mpi_solve_blocks for Fortran hosts: the communicator's Fortran handle, by value. */
int fc3d_mpi_solve_blocks_f(MPI_Fint comm, int64_t n_local, const int64_t *contact_ids,
                            int64_t n_blocks, const int64_t *block_row_ptr,
                            const int64_t *block_col_ids, const double *blocks, const double *q,
                            const double *mu, double *r, double *u,
                            const struct Fc3dSettings *settings, struct Fc3dResult *result);

/* A solver for a sequence of solves (time stepping): its set-up (owners, ghosts, colouring,
 * message schedule) is kept while every rank's contact ids and block pattern stay the same.
 * `mode`: FC3D_MPI_REPRODUCIBLE or FC3D_MPI_FAST. NULL on every rank on failure. */
Fc3dMpiSolver *fc3d_mpi_solver_new(MPI_Comm comm, int mode);

/* fc3d_mpi_solver_new with the communicator's Fortran handle. */
Fc3dMpiSolver *fc3d_mpi_solver_new_f(MPI_Fint comm, int mode);

/* fc3d_mpi_solve_blocks with a solver's communicator, mode and kept set-up. */
int fc3d_mpi_solver_solve(Fc3dMpiSolver *solver, int64_t n_local, const int64_t *contact_ids,
                          int64_t n_blocks, const int64_t *block_row_ptr,
                          const int64_t *block_col_ids, const double *blocks, const double *q,
                          const double *mu, double *r, double *u,
                          const struct Fc3dSettings *settings, struct Fc3dResult *result);

/* The calling rank's statistics (not collective). Returns 0 or a negative code. */
int fc3d_mpi_solver_stats(const Fc3dMpiSolver *solver, Fc3dMpiStats *stats);

/* Releases a solver (collective: fc3d's duplicate of the communicator is freed). NULL is
 * accepted. */
void fc3d_mpi_solver_free(Fc3dMpiSolver *solver);

#ifdef __cplusplus
}
#endif

#endif /* FC3D_MPI_H */
