/* fc3d compatibility header: stands in for Siconos Numerics 4.4's gfc3d_Solvers.h (the solver
   entries of the global problem, which run gfc3d_driver for their id, gfc3d_checkTrivialCaseGlobal
   and gfc3d_set_internalsolver_tolerance). Siconos' ADMM and IPM work-space functions
   (gfc3d_ADMM_init/free, gfc3d_IPM_init/free) and the *_set_default functions are not provided
   (docs/siconos-functions.md): solver_options_create gives the defaults.
   Compile a Siconos host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_GFC3D_SOLVERS_H
#define FC3D_COMPAT_GFC3D_SOLVERS_H
#include <fc3d.h>
#include "GlobalFrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"
#include "gfc3d_nonsmooth_Newton_AlartCurnier.h"

/* Siconos' function-pointer types of its global solvers. */
typedef void (*SolverGlobalPtr)(int, int, double*, int*, double*);
typedef void (*PostSolverGlobalPtr)(int, double*);
typedef void (*FreeSolverGlobalPtr)(GlobalFrictionContactProblem*);
typedef void (*ComputeErrorGlobalPtr)(GlobalFrictionContactProblem*, double*, double*, double*, double,
                                      SolverOptions*, double, double, double*);
#endif
