/* One process linking Siconos Numerics 4.4 and fc3d's native-only library side by side: the
 * Siconos calls reach Siconos, the fc3d_* calls reach fc3d, and each library scores the other's
 * answer. Built by the test suite:
 *
 *   cc -I/usr/include/siconos/numerics -I/usr/include/siconos -I<prefix>/include side_by_side.c \
 *      -L<prefix>/lib -lfc3d_native -lsiconos_numerics -lm -o side_by_side
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "FrictionContactProblem.h"
#include "Friction_cst.h"
#include "NonSmoothDrivers.h"
#include "SolverOptions.h"
#include "fc3d_compute_error.h"
#include <fc3d_native.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: side_by_side problem.dat\n");
    return 2;
  }
  FrictionContactProblem* problem = frictionContact_new_from_filename(argv[1]);
  Fc3dProblem* mine = fc3d_problem_read(argv[1]);
  if (!problem || !mine) {
    fprintf(stderr, "cannot read %s\n", argv[1]);
    return 2;
  }
  int n = 3 * problem->numberOfContacts;
  double *r_s = calloc(n, sizeof(double)), *u_s = calloc(n, sizeof(double));
  double *r_f = calloc(n, sizeof(double)), *u_f = calloc(n, sizeof(double));

  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  options->dparam[SICONOS_DPARAM_TOL] = 1e-8;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = 10000;
  int info_s = fc3d_driver(problem, r_s, u_s, options);

  Fc3dSettings* settings = fc3d_settings_new(500);
  fc3d_settings_set_tolerance(settings, 1e-8);
  fc3d_settings_set_max_iter(settings, 10000);
  Fc3dResult result;
  int info_f = fc3d_problem_solve(mine, r_f, u_f, settings, &result);

  /* Each library scores the other's reaction. */
  double siconos_on_fc3d = 0, q_norm = 0;
  for (int i = 0; i < n; i++) q_norm += problem->q[i] * problem->q[i];
  q_norm = sqrt(q_norm);
  fc3d_compute_error(problem, r_f, u_s, 1e-8, options, q_norm, &siconos_on_fc3d);
  printf("%s: Siconos info %d, %d sweeps, error %.3e; fc3d info %d, %lld sweeps, error %.3e; Siconos' error of "
         "fc3d's reaction %.3e\n",
         argv[1], info_s, options->iparam[SICONOS_IPARAM_ITER_DONE], options->dparam[SICONOS_DPARAM_RESIDU],
         info_f, (long long)result.iterations, result.error, siconos_on_fc3d);
  /* fc3d names its one-contact id 570; Siconos does not know it: the Siconos call reached
     Siconos, not a namesake in fc3d. */
  int reached_siconos = strcmp(solver_options_id_to_name(570), "FC3D_ONECONTACT_FP_VI_UPK") != 0;
  if (!reached_siconos) fprintf(stderr, "a Siconos call reached fc3d\n");
  int ok = reached_siconos && info_s == 0 && info_f == 0 && siconos_on_fc3d <= 1e-7 && result.iterations > 0;

  solver_options_delete(options);
  free(options);
  fc3d_settings_free(settings);
  fc3d_problem_free(mine);
  frictionContactProblem_free(problem);
  free(r_s); free(u_s); free(r_f); free(u_f);
  return ok ? 0 : 1;
}
