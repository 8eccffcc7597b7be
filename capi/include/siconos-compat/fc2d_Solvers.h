/* fc3d compatibility header: stands in for Siconos Numerics 4.4's fc2d_Solvers.h (2D friction:
   fc2d_nsgs_dense, fc2d_nsgs_sbm, fc2d_cpg, fc2d_lexicolemke, fc2d_enum, fc2d_nsgs_set_default,
   fc2d_projc, fc2d_projf; fc2d_tolcp is not provided: fc3d has no LinearComplementarityProblem).
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_FC2D_SOLVERS_H
#define FC3D_COMPAT_FC2D_SOLVERS_H
#include <fc3d.h>
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#endif
