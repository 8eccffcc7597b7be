/* fc3d compatibility header: stands in for Siconos Numerics 4.4's SparseBlockMatrix.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_SPARSEBLOCKMATRIX_H
#define FC3D_COMPAT_SPARSEBLOCKMATRIX_H
#include <fc3d.h>
#define NUMERICS_SBM_FREE_BLOCK 4
#define NUMERICS_SBM_FREE_SBM 8
#endif
