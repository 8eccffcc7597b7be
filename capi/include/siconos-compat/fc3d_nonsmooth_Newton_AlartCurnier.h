/* fc3d compatibility header: stands in for Siconos Numerics 4.4's fc3d_nonsmooth_Newton_AlartCurnier.h (the functions fc3d
   provides; see docs/siconos-functions.md for the ones it leaves out).
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_FC3D_NONSMOOTH_NEWTON_ALARTCURNIER_H
#define FC3D_COMPAT_FC3D_NONSMOOTH_NEWTON_ALARTCURNIER_H
#include <fc3d.h>
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#endif
