/* fc3d compatibility header: stands in for Siconos Numerics 4.4's gfc3d_nonsmooth_Newton_AlartCurnier.h
   (gfc3d_sparseGlobalAlartCurnierInit, empty in Siconos 4.4 as in fc3d;
   gfc3d_nonsmooth_Newton_AlartCurnier_setDefaultSolverOptions is declared by Siconos but
   defined nowhere, so neither library has it).
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GFC3D_NONSMOOTH_NEWTON_ALARTCURNIER_H
#define FC3D_COMPAT_GFC3D_NONSMOOTH_NEWTON_ALARTCURNIER_H
#include <fc3d.h>
#include "SolverOptions.h"
#endif
