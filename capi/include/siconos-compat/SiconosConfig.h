/* fc3d compatibility header: stands in for Siconos Numerics 4.4's SiconosConfig.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_SICONOSCONFIG_H
#define FC3D_COMPAT_SICONOSCONFIG_H
#include <fc3d.h>
/* fc3d uses 64-bit CSparse indices, as the Debian build of Siconos (SICONOS_INT64). */
#ifndef SICONOS_INT64
#define SICONOS_INT64
#endif
#endif
