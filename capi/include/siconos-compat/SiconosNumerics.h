/* fc3d compatibility header: stands in for Siconos Numerics 4.4's SiconosNumerics.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_SICONOSNUMERICS_H
#define FC3D_COMPAT_SICONOSNUMERICS_H
#include <fc3d.h>
#include "SiconosConfig.h"
#include "NumericsFwd.h"
#include "NumericsMatrix.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "fc3d_Solvers.h"
#include "fc3d_compute_error.h"
#include "NonSmoothDrivers.h"
#include "NumericsVerbose.h"
#endif
