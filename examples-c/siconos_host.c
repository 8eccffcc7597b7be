/* A host program written for Siconos Numerics 4.4's fc3d API, unmodified: it builds against
 * Siconos' own headers and -lsiconos_numerics, or against fc3d's compat headers and -lfc3d.
 *
 *   cc -I$(pkg-config --variable=siconos_includedir fc3d) $(pkg-config --cflags fc3d) \
 *      examples-c/siconos_host.c $(pkg-config --libs fc3d) -lm -o host_fc3d    (fc3d installed: README)
 *   cc -I/usr/include/siconos/numerics -I/usr/include/siconos examples-c/siconos_host.c \
 *      -lsiconos_numerics -o host_siconos
 *   ./host_fc3d problem.dat [tolerance] [max_iter] [local_solver_id]
 *
 * Prints one line: info, iterations, reported error, error recomputed by fc3d_compute_error. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "SiconosNumerics.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "fc3d_Solvers.h"
#include "fc3d_compute_error.h"
#include "NonSmoothDrivers.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s problem.dat [tolerance] [max_iter] [local_solver_id]\n", argv[0]);
    return 2;
  }
  double tol = argc > 2 ? atof(argv[2]) : 1e-8;
  int max_iter = argc > 3 ? atoi(argv[3]) : 100000;
  int local = argc > 4 ? atoi(argv[4]) : 0;

  FrictionContactProblem* problem = frictionContact_new_from_filename(argv[1]);
  if (!problem) {
    fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  int n = problem->dimension * problem->numberOfContacts;
  double* reaction = calloc((size_t)n + 1, sizeof(double));
  double* velocity = calloc((size_t)n + 1, sizeof(double));
  double* w = calloc((size_t)n + 1, sizeof(double));

  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  if (local) solver_options_update_internal(options, 0, local);
  options->dparam[SICONOS_DPARAM_TOL] = tol;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;

  int info = fc3d_driver(problem, reaction, velocity, options);

  double norm_q = 0.0;
  for (int i = 0; i < n; i++) norm_q += problem->q[i] * problem->q[i];
  double error = -1.0;
  fc3d_compute_error(problem, reaction, w, tol, options, sqrt(norm_q), &error);
  printf("info %d iterations %d error %.6e recomputed %.6e\n", info, options->iparam[SICONOS_IPARAM_ITER_DONE],
         options->dparam[SICONOS_DPARAM_RESIDU], error);

  solver_options_delete(options);
  free(options);
  frictionContactProblem_free(problem);
  free(reaction);
  free(velocity);
  free(w);
  return info < 0 ? 2 : 0;
}
