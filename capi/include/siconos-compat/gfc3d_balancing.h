/* fc3d compatibility header: stands in for Siconos Numerics 4.4's gfc3d_balancing.h
   Siconos' balancing of a global problem (gfc3d_rescaling, gfc3d_balancing_*) is the internal
   machinery of its NSN_AC and ADMM solvers (BalancingMatrices, problem->env); fc3d does not
   provide it (docs/siconos-functions.md): this header declares nothing beyond fc3d.h.
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GFC3D_BALANCING_H
#define FC3D_COMPAT_GFC3D_BALANCING_H
#include <fc3d.h>
#include "GlobalFrictionContactProblem.h"
#endif
