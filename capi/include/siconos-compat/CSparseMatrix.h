/* fc3d compatibility header: stands in for Siconos Numerics 4.4's CSparseMatrix.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_CSPARSEMATRIX_H
#define FC3D_COMPAT_CSPARSEMATRIX_H
#include <fc3d.h>
/* CS_INT is a typedef (int64_t) in fc3d.h; cs_dl_sparse is defined there in full so that hosts
   can fill it without SuiteSparse's cs.h (do not include both). */
#endif
