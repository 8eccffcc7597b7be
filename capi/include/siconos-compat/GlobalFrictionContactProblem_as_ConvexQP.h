/* fc3d compatibility header: stands in for Siconos Numerics 4.4's GlobalFrictionContactProblem_as_ConvexQP.h
   Siconos' callback of its ConvexQP framework for the global problem
   (Projection_ConvexQP_GFC3D_DualCone) takes Siconos-internal structs; fc3d does not provide it
   (docs/siconos-functions.md): this header declares nothing beyond fc3d.h.
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_AS_CONVEXQP_H
#define FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_AS_CONVEXQP_H
#include <fc3d.h>
#include "GlobalFrictionContactProblem.h"
#endif
