/* fc3d compatibility header: stands in for Siconos Numerics 4.4's NumericsMatrix.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_NUMERICSMATRIX_H
#define FC3D_COMPAT_NUMERICSMATRIX_H
#include <fc3d.h>
#include "NumericsDataVersion.h"
#include "NumericsSparseMatrix.h"
#include "SparseBlockMatrix.h"
/* Storage types of NumericsMatrix.storageType. */
typedef enum NumericsMatrix_types { NM_DENSE = 0, NM_SPARSE_BLOCK = 1, NM_SPARSE = 2, NM_UNKNOWN = 3 } NM_types;
typedef NumericsMatrix RawNumericsMatrix;
#endif
