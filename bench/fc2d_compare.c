/* One 2D solve timed: reads a .dat problem, runs fc2d_driver `reps` times from r = 0 with fresh
 * options of `id` (tolerance and iteration limit set) and prints one tab-separated line: file,
 * id, info, iterations, dparam[1], the median time in seconds. Compiled twice by
 * scripts/compare-siconos-2d.sh: against fc3d's compat headers (-lfc3d) and against the installed
 * Siconos 4.4 (-lsiconos_numerics).
 *
 *   fc2d_compare FILE ID TOL MAX_ITER REPS */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "SolverOptions.h"

static int by_value(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

int main(int argc, char** argv) {
  if (argc != 6) {
    fprintf(stderr, "usage: %s FILE ID TOL MAX_ITER REPS\n", argv[0]);
    return 2;
  }
  FrictionContactProblem* p = frictionContact_new_from_filename(argv[1]);
  if (!p || p->dimension != 2) {
    fprintf(stderr, "%s: not a 2D problem\n", argv[1]);
    return 2;
  }
  int id = atoi(argv[2]), max_iter = atoi(argv[4]), reps = atoi(argv[5]);
  double tol = atof(argv[3]);
  if (reps < 1 || reps > 99) reps = 1;
  int n = 2 * p->numberOfContacts;
  double* r = calloc((size_t)n, sizeof(double));
  double* u = calloc((size_t)n, sizeof(double));
  double times[99];
  int info = 0, iterations = 0;
  double error = 0;
  for (int k = 0; k < reps; k++) {
    SolverOptions* o = solver_options_create(id);
    o->dparam[SICONOS_DPARAM_TOL] = tol;
    o->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
    memset(r, 0, sizeof(double) * (size_t)n);
    memset(u, 0, sizeof(double) * (size_t)n);
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    info = fc2d_driver(p, r, u, o);
    clock_gettime(CLOCK_MONOTONIC, &b);
    times[k] = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    iterations = o->iparam[SICONOS_IPARAM_ITER_DONE];
    error = o->dparam[SICONOS_DPARAM_RESIDU];
    solver_options_delete(o);
    free(o);
  }
  qsort(times, (size_t)reps, sizeof(double), by_value);
  const char* name = strrchr(argv[1], '/');
  printf("%s\t%d\t%d\t%d\t%.3e\t%.6f\n", name ? name + 1 : argv[1], id, info, iterations, error, times[reps / 2]);
  free(r);
  free(u);
  frictionContactProblem_free(p);
  return 0;
}
