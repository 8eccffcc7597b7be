// A Siconos-style C++ host: Siconos' headers and calls, compiled against fc3d's Siconos-named
// headers (fc3d_SICONOS_INCLUDE_DIR) and linked with fc3d::fc3d.
#include "SiconosNumerics.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

int main() {
  double W[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double q[3] = {-1, 2, 0}, mu[1] = {0.5}, r[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  NumericsMatrix* M = NM_create_from_data(NM_DENSE, 3, 3, W);
  FrictionContactProblem problem = {3, 1, M, q, mu};
  SolverOptions* options = solver_options_create(SICONOS_FRICTION_3D_NSGS);
  options->dparam[SICONOS_DPARAM_TOL] = 1e-12;
  int info = fc3d_driver(&problem, r, u, options);
  std::printf("Siconos-style host: info %d, error %.2e, r = (%g, %g, %g)\n", info,
              options->dparam[SICONOS_DPARAM_RESIDU], r[0], r[1], r[2]);
  solver_options_delete(options);
  std::free(options);
  M->matrix0 = NULL;  // the data is the host's: NM_free must not free it
  M = NM_free(M);
  return info == 0 && std::fabs(r[1] + 0.5) < 1e-10 ? 0 : 1;
}
