/* fc3d compatibility header: stands in for Siconos Numerics 4.4's AlartCurnierGenerated.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_ALARTCURNIERGENERATED_H
#define FC3D_COMPAT_ALARTCURNIERGENERATED_H
#include <fc3d.h>
#endif
