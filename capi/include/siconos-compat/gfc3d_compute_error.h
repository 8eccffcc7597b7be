/* fc3d compatibility header: stands in for Siconos Numerics 4.4's gfc3d_compute_error.h
   (gfc3d_compute_error and gfc3d_compute_error_convex).
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GFC3D_COMPUTE_ERROR_H
#define FC3D_COMPAT_GFC3D_COMPUTE_ERROR_H
#include <fc3d.h>
#include "GlobalFrictionContactProblem.h"
#include "SolverOptions.h"
#endif
