/* fc3d compatibility header: stands in for Siconos Numerics 4.4's RollingFrictionContactProblem.h
   (the RollingFrictionContactProblem struct, its constructors, free, display and .dat files).
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_ROLLINGFRICTIONCONTACTPROBLEM_H
#define FC3D_COMPAT_ROLLINGFRICTIONCONTACTPROBLEM_H
#include <fc3d.h>
#endif
