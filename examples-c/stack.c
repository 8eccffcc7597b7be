/* A simulator's use of fc3d, as a host author would copy it.
 *
 * Scene: two unit cubes stacked on the ground, one contact point under each (a deliberately
 * small model: 2 contacts). The Delassus operator W = H M^-1 H^T of the two contacts couples them
 * (the upper contact acts on both cubes), so W has two diagonal and two off-diagonal 3x3 blocks.
 * We hand W to fc3d in sparse-block storage, built from 1-based block coordinates, solve with
 * NSGS and print r, u, iterations and the error fc3d measured on the answer.
 *
 * Build (from the repository root, as the README's in-tree example does):
 *   bash scripts/install.sh --prefix local
 *   export PKG_CONFIG_PATH=$PWD/local/lib/pkgconfig
 *   cc -std=c99 examples-c/stack.c -I"$(pkg-config --variable=siconos_includedir fc3d)" \
 *      $(pkg-config --cflags --libs fc3d) -lm -Wl,-rpath,"$PWD/local/lib" -o local/stack
 *   local/stack
 */
#include <stdio.h>
#include <stdlib.h>

#include "SiconosNumerics.h"

int main(void) {
  const double m = 1.0, g = 9.81, dt = 0.01; /* unit masses, one time step */
  const double mu_ground = 0.6, mu_cube = 0.4;

  /* Contact 0: ground under cube A (normal +z).  Contact 1: cube A under cube B.
   * With point masses and frames (n, t1, t2) = (z, x, y), the impulse r_1 pushes B up and A down:
   *   W_00 = I/m,  W_11 = 2 I/m,  W_01 = W_10 = -I/m  (column-major 3x3 blocks). */
  double blocks[4 * 9] = {
      1 / m, 0, 0, 0, 1 / m, 0, 0, 0, 1 / m,    /* (1,1) */
      -1 / m, 0, 0, 0, -1 / m, 0, 0, 0, -1 / m, /* (1,2) */
      -1 / m, 0, 0, 0, -1 / m, 0, 0, 0, -1 / m, /* (2,1) */
      2 / m, 0, 0, 0, 2 / m, 0, 0, 0, 2 / m,    /* (2,2) */
  };
  unsigned row[4] = {1, 1, 2, 2}, col[4] = {1, 2, 1, 2};

  /* Local free velocities after one step of gravity: cube A falls onto the ground at g dt; A and
   * B fall together (no relative normal velocity) while B slides on A at 0.5 m/s along x. */
  double q[6] = {-g * dt, 0.0, 0.0, 0.0, 0.5, 0.0};
  double mu[2] = {mu_ground, mu_cube};

  SparseBlockCoordinateMatrix* coo = SBCM_new_3x3(2, 2, 4, row, col, blocks);
  SparseBlockStructuredMatrix* sbm = SBCM_to_SBM(coo);
  NumericsMatrix* W = NM_new_SBM(6, 6, sbm);
  FrictionContactProblem problem = {3, 2, W, q, mu}; /* on the stack: q, mu, W stay ours */

  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  options->dparam[SICONOS_DPARAM_TOL] = 1e-10;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = 1000;

  double r[6] = {0}, u[6] = {0};
  int info = fc3d_driver(&problem, r, u, options);
  if (info < 0) {
    fprintf(stderr, "fc3d rejected the problem: %s\n", fc3d_last_error_message());
    return 1;
  }
  printf("info %d (%s), %d iterations, error %.3e\n", info, info == 0 ? "converged" : "not converged",
         options->iparam[SICONOS_IPARAM_ITER_DONE], options->dparam[SICONOS_DPARAM_RESIDU]);
  for (int c = 0; c < 2; c++)
    printf("contact %d: r = (% .6f, % .6f, % .6f)  u = (% .6f, % .6f, % .6f)\n", c, r[3 * c], r[3 * c + 1],
           r[3 * c + 2], u[3 * c], u[3 * c + 1], u[3 * c + 2]);

  solver_options_delete(options);
  free(options);
  SBM_free_from_SBCM(sbm); /* the blocks are the array above: detach before NM_free */
  W->matrix1 = NULL;
  NM_free(W);
  SBCM_free_3x3(coo);
  return info;
}
