/* fc3d compatibility header: stands in for Siconos Numerics 4.4's fc3d_solvers_wr.h
   (fc3d_reformulation_global_problem: a global problem whose reduction is the given local
   problem exactly).
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_FC3D_SOLVERS_WR_H
#define FC3D_COMPAT_FC3D_SOLVERS_WR_H
#include <fc3d.h>
#include "FrictionContactProblem.h"
#include "GlobalFrictionContactProblem.h"
#endif
