/* fc3d compatibility header: stands in for Siconos Numerics 4.4's rolling_fc_Solvers.h
   (rolling_fc3d_nsgs, rolling_fc2d_nsgs and the trivial-case tests; the drivers are in NonSmoothDrivers.h).
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_ROLLING_FC_SOLVERS_H
#define FC3D_COMPAT_ROLLING_FC_SOLVERS_H
#include <fc3d.h>
#include "RollingFrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#endif
