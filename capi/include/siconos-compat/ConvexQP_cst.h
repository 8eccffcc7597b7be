/* fc3d compatibility header: stands in for Siconos Numerics 4.4's ConvexQP_cst.h, which Debian does not
   install but Siconos' friction tests include: the ids and option indices of the convex QP solvers.
   Every enum, enumerator and solver-name variable it declares, with Siconos' values. fc3d
   creates the options of these solvers (solver_options_create, as internal solvers of the
   friction solvers); fc3d_driver does not run them as top-level solvers. */
#ifndef FC3D_COMPAT_CONVEXQP_CST_H
#define FC3D_COMPAT_CONVEXQP_CST_H
/* Siconos' include guard, defined too: code that tests it sees the header as included. */
#define CONVEXQP_CST_H
#include <fc3d.h>

enum CONVEXQP_SOLVER
{
  SICONOS_CONVEXQP_PG = 1200,
  SICONOS_CONVEXQP_VI_FPP = 1201,
  SICONOS_CONVEXQP_VI_EG = 1202,
  SICONOS_CONVEXQP_ADMM = 1203
};

enum SICONOS_CONVEXQP_PGOC_IPARAM_ENUM
{
  SICONOS_CONVEXQP_PGOC_LINESEARCH_MAX_ITER = 10
};

enum SICONOS_CONVEXQP_PGOC_DPARAM_ENUM
{
  SICONOS_CONVEXQP_PGOC_RHO = 3,
  SICONOS_CONVEXQP_PGOC_RHOMIN = 4,
  SICONOS_CONVEXQP_PGOC_LINESEARCH_MU = 5,
  SICONOS_CONVEXQP_PGOC_LINESEARCH_TAU = 6
};

enum SICONOS_CONVEXQP_ADMM_IPARAM_ENUM
{
  SICONOS_CONVEXQP_ADMM_IPARAM_RHO_STRATEGY = 9,
  SICONOS_CONVEXQP_ADMM_IPARAM_ACCELERATION = 10
};

enum SICONOS_CONVEXQP_ADMM_DPARAM_ENUM
{
  SICONOS_CONVEXQP_ADMM_RHO = 3,
  SICONOS_CONVEXQP_ADMM_RESTART_ETA = 4,
  SICONOS_CONVEXQP_ADMM_BALANCING_RESIDUAL_TAU = 5,
  SICONOS_CONVEXQP_ADMM_BALANCING_RESIDUAL_PHI = 6
};

enum SICONOS_CONVEXQP_ADMM_ACCELERATION_ENUM
{
  SICONOS_CONVEXQP_ADMM_NO_ACCELERATION = 0,
  SICONOS_CONVEXQP_ADMM_ACCELERATION = 1,
  SICONOS_CONVEXQP_ADMM_ACCELERATION_AND_RESTART = 2
};

enum SICONOS_CONVEXQP_RHO_STRATEGY_ENUM
{
  SICONOS_CONVEXQP_RHO_STRATEGY_CONSTANT = 0,
  SICONOS_CONVEXQP_ADMM_RHO_STRATEGY_NORM_INF = 1,
  SICONOS_CONVEXQP_ADMM_RHO_STRATEGY_RESIDUAL_BALANCING = 2,
  SICONOS_CONVEXQP_ADMM_RHO_STRATEGY_SCALED_RESIDUAL_BALANCING = 3
};


#if defined(__cplusplus)
extern "C" {
#endif
extern const char* const SICONOS_CONVEXQP_PG_STR;
extern const char* const SICONOS_CONVEXQP_VI_FPP_STR;
extern const char* const SICONOS_CONVEXQP_VI_EG_STR;
extern const char* const SICONOS_CONVEXQP_ADMM_STR;
#if defined(__cplusplus)
}
#endif

#endif
