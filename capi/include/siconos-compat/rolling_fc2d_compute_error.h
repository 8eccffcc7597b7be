/* fc3d compatibility header: stands in for Siconos Numerics 4.4's rolling_fc2d_compute_error.h
   (rolling_fc2d_compute_error, rolling_fc2d_unitary_compute_and_add_error).
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_ROLLING_FC2D_COMPUTE_ERROR_H
#define FC3D_COMPAT_ROLLING_FC2D_COMPUTE_ERROR_H
#include <fc3d.h>
#endif
