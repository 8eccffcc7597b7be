/* fc3d compatibility header: stands in for Siconos Numerics 4.4's SolverOptions.h.
   Compile a Siconos fc3d host with -I<this directory> -I<the directory of fc3d.h> (pkg-config
   fc3d: its variable siconos_includedir and its --cflags) and link with -lfc3d. */
#ifndef FC3D_COMPAT_SOLVEROPTIONS_H
#define FC3D_COMPAT_SOLVEROPTIONS_H
/* Siconos' include guard, defined too: code that tests it sees the header as included. */
#define SolverOptions_H
#include <fc3d.h>
/* Generic option indices (iparam / dparam). */
enum SICONOS_IPARAM
{
  SICONOS_IPARAM_MAX_ITER = 0,
  SICONOS_IPARAM_ITER_DONE = 1,
  SICONOS_IPARAM_PREALLOC = 2,
  SICONOS_IPARAM_NSGS_SHUFFLE = 5,
  SICONOS_IPARAM_ERROR_EVALUATION = 3,
  SICONOS_IPARAM_PATHSEARCH_STACKSIZE = 19
};
enum SICONOS_IPARAM_ERROR_EVALUATION_ENUM
{
  SICONOS_ERROR_FULL_EVALUATION = 0,
  SICONOS_ERROR_LIGHT_EVALUATION = 1,
  SICONOS_ERROR_LIGHT_EVALUATION_NO_UPDATE = 2
};
enum SICONOS_DPARAM
{
  SICONOS_DPARAM_TOL = 0,
  SICONOS_DPARAM_RESIDU = 1
};
#endif
