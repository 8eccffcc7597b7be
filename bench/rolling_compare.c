/* One rolling solve timed: reads a rolling .dat problem, runs rolling_fc3d_driver (or
 * rolling_fc2d_driver for a 2D file) `reps` times from r = 0 with fresh options of `id` (local
 * solver `local` when non-zero, tolerance and iteration limit set) and prints one tab-separated
 * line: file, id, local, info, iterations, dparam[1], the error recomputed by the library's
 * rolling_fc*d_compute_error with norm = ||q||, the median time in seconds. Compiled twice by
 * scripts/compare-siconos-rolling.sh: against fc3d's compat headers (-lfc3d) and against the
 * installed Siconos 4.4 (-lsiconos_numerics).
 *
 *   rolling_compare FILE ID LOCAL TOL MAX_ITER REPS */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "RollingFrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "SolverOptions.h"
#include "rolling_fc3d_compute_error.h"
#include "rolling_fc2d_compute_error.h"

/* Siconos 4.4's rolling_fc2d_compute_error.h reuses the include guard of the 3D header, so its
 * declaration is skipped there: declared here (the same prototype). */
int rolling_fc2d_compute_error(RollingFrictionContactProblem* problem, double* z, double* w,
                               double tolerance, SolverOptions* options, double norm,
                               double* error);

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  if (argc != 7) {
    fprintf(stderr, "usage: %s FILE ID LOCAL TOL MAX_ITER REPS\n", argv[0]);
    return 2;
  }
  RollingFrictionContactProblem* p = rollingFrictionContact_new_from_filename(argv[1]);
  if (!p || (p->dimension != 5 && p->dimension != 3)) {
    fprintf(stderr, "%s: not a rolling problem\n", argv[1]);
    return 2;
  }
  int id = atoi(argv[2]), local = atoi(argv[3]), max_iter = atoi(argv[5]), reps = atoi(argv[6]);
  double tol = atof(argv[4]);
  if (reps < 1 || reps > 99) reps = 1;
  int n = p->dimension * p->numberOfContacts;
  double* r = calloc((size_t)n, sizeof(double));
  double* u = calloc((size_t)n, sizeof(double));
  double* w = calloc((size_t)n, sizeof(double));
  double times[99];
  int info = 0, iterations = 0;
  double error = 0, recomputed = 0, norm_q = 0;
  for (int i = 0; i < n; i++) norm_q += p->q[i] * p->q[i];
  norm_q = sqrt(norm_q);
  for (int k = 0; k < reps; k++) {
    SolverOptions* o = solver_options_create(id);
    if (local) solver_options_update_internal(o, 0, local);
    o->dparam[SICONOS_DPARAM_TOL] = tol;
    o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    memset(r, 0, sizeof(double) * (size_t)n);
    memset(u, 0, sizeof(double) * (size_t)n);
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    info = p->dimension == 5 ? rolling_fc3d_driver(p, r, u, o) : rolling_fc2d_driver(p, r, u, o);
    clock_gettime(CLOCK_MONOTONIC, &b);
    times[k] = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
    error = o->dparam[SICONOS_DPARAM_RESIDU];
    if (p->dimension == 5)
      rolling_fc3d_compute_error(p, r, w, tol, o, norm_q, &recomputed);
    else
      rolling_fc2d_compute_error(p, r, w, tol, o, norm_q, &recomputed);
    solver_options_delete(o);
    free(o);
  }
  qsort(times, (size_t)reps, sizeof(double), by_value);
  const char* name = strrchr(argv[1], '/');
  printf("%s\t%d\t%d\t%d\t%d\t%.3e\t%.3e\t%.6f\n", name ? name + 1 : argv[1], id, local, info,
         iterations, error, recomputed, times[reps / 2]);
  free(r);
  free(u);
  free(w);
  rollingFrictionContactProblem_free(p);
  return 0;
}
