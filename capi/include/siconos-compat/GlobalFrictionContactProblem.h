/* fc3d compatibility header: stands in for Siconos Numerics 4.4's GlobalFrictionContactProblem.h
   (the GlobalFrictionContactProblem struct, its life cycle, .dat files, display, copy, global
   velocity and reduction to the local problem).
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_H
#define FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_H
#include <fc3d.h>
#include "NumericsFwd.h"
#include "NumericsMatrix.h"
#endif
