/* fc3d compatibility header: stands in for Siconos Numerics 4.4's GlobalFrictionContactProblem_as_VI.h
   Siconos' callbacks of its VI framework for the global problem (Function_VI_GFC3D,
   Projection_VI_GFC3D) take Siconos-internal structs; fc3d does not provide them
   (docs/siconos-functions.md): this header declares nothing beyond fc3d.h.
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_AS_VI_H
#define FC3D_COMPAT_GLOBALFRICTIONCONTACTPROBLEM_AS_VI_H
#include <fc3d.h>
#include "GlobalFrictionContactProblem.h"
#endif
