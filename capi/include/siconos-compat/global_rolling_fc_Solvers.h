/* fc3d compatibility header: stands in for Siconos Numerics 4.4's global_rolling_fc_Solvers.h
   (grfc3d_nsgs_wr and grfc3d_checkTrivialCaseGlobal; the driver is in NonSmoothDrivers.h).
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GLOBAL_ROLLING_FC_SOLVERS_H
#define FC3D_COMPAT_GLOBAL_ROLLING_FC_SOLVERS_H
#include <fc3d.h>
#include "GlobalRollingFrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#endif
