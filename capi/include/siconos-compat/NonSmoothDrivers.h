/* fc3d compatibility header: stands in for Siconos Numerics 4.4's NonSmoothDrivers.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_NONSMOOTHDRIVERS_H
#define FC3D_COMPAT_NONSMOOTHDRIVERS_H
#include <fc3d.h>
#include "FrictionContactProblem.h"
#include "GlobalFrictionContactProblem.h"
#include "GlobalRollingFrictionContactProblem.h"
#include "SolverOptions.h"
#endif
