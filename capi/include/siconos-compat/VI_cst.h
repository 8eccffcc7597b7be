/* fc3d compatibility header: stands in for Siconos Numerics 4.4's VI_cst.h, which Debian does not
   install but Siconos' friction tests include: the ids and option indices of the variational-inequality solvers.
   Every enum, enumerator and solver-name variable it declares, with Siconos' values. fc3d
   creates the options of these solvers (solver_options_create, as internal solvers of the
   friction solvers); fc3d_driver does not run them as top-level solvers. */
#ifndef FC3D_COMPAT_VI_CST_H
#define FC3D_COMPAT_VI_CST_H
/* Siconos' include guard, defined too: code that tests it sees the header as included. */
#define VI_CST_H
#include <fc3d.h>

enum VI_SOLVER
{
  SICONOS_VI_EG = 1000,
  SICONOS_VI_FPP = 1001,
  SICONOS_VI_HP = 1002,
  SICONOS_VI_BOX_QI = 1020,
  SICONOS_VI_BOX_AVI_LSA = 1021,
  SICONOS_VI_BOX_PATH = 1022
};

enum SICONOS_VI_IPARAM
{
  SICONOS_VI_IPARAM_DECREASE_RHO = 3,
  SICONOS_VI_IPARAM_LINESEARCH_METHOD = 6,
  SICONOS_VI_IPARAM_ERROR_EVALUATION = 7,
  SICONOS_VI_IPARAM_ERROR_EVALUATION_FREQUENCY = 8,
  SICONOS_VI_IPARAM_LS_MAX_ITER = 9,
  SICONOS_VI_IPARAM_ACTIVATE_UPDATE = 10
};

enum SICONOS_VI_LINESEARCH_METHOD
{
  SICONOS_VI_LS_ARMIJO = 0,
  SICONOS_VI_LS_SOLODOV = 1,
  SICONOS_VI_LS_HANSUN = 2
};

enum SICONOS_VI_DPARAM
{
  SICONOS_VI_DPARAM_RHO = 3,
  SICONOS_VI_DPARAM_LS_TAU = 4,
  SICONOS_VI_DPARAM_LS_TAUINV = 5,
  SICONOS_VI_DPARAM_LS_L = 6,
  SICONOS_VI_DPARAM_LS_LMIN = 7,
  SICONOS_VI_DPARAM_SIGMA = 8
};

enum SICONOS_VI_ERROR_EVALUATION_ENUM
{
  SICONOS_VI_ERROR_EVALUATION_FULL = 0,
  SICONOS_VI_ERROR_EVALUATION_LIGHT_WITH_FULL_FINAL = 1,
  SICONOS_VI_ERROR_EVALUATION_LIGHT = 2,
  SICONOS_VI_ERROR_EVALUATION_ADAPTIVE = 3
};


#if defined(__cplusplus)
extern "C" {
#endif
extern const char* const SICONOS_VI_EG_STR;
extern const char* const SICONOS_VI_FPP_STR;
extern const char* const SICONOS_VI_HP_STR;
extern const char* const SICONOS_VI_BOX_QI_STR;
extern const char* const SICONOS_VI_BOX_AVI_LSA_STR;
extern const char* const SICONOS_VI_BOX_PATH_STR;
#if defined(__cplusplus)
}
#endif

#endif
