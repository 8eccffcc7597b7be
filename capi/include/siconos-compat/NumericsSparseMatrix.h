/* fc3d compatibility header: stands in for Siconos Numerics 4.4's NumericsSparseMatrix.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_NUMERICSSPARSEMATRIX_H
#define FC3D_COMPAT_NUMERICSSPARSEMATRIX_H
#include <fc3d.h>
#include "CSparseMatrix.h"
/* Which CSparse form of a NumericsSparseMatrix is the reference. */
typedef enum { NSM_UNKNOWN = 0, NSM_TRIPLET = 1, NSM_CSC = 2, NSM_CSR = 3, NSM_HALF_TRIPLET = 4 } NumericsSparseOrigin;
typedef NumericsSparseOrigin NSM_t;
typedef enum { NSM_CS_CSC = -1, NSM_CS_CSR = -2 } NumericsSparseTypesNZ;
#endif
