/* fc3d compatibility header: stands in for Siconos Numerics 4.4's gfc3d_Gams.h
   Siconos' GAMS data of the global problem: fc3d does not link GAMS (608 and 609 are refused);
   this header declares nothing beyond fc3d.h.
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GFC3D_GAMS_H
#define FC3D_COMPAT_GFC3D_GAMS_H
#include <fc3d.h>
#include "NumericsMatrix.h"
#endif
