/* fc3d compatibility header: stands in for Siconos Numerics 4.4's SOCLCP_cst.h, which Debian does not
   install but Siconos' friction tests include: the ids and option indices of the second-order-cone LCP solvers.
   Every enum, enumerator and solver-name variable it declares, with Siconos' values. fc3d
   creates the options of these solvers (solver_options_create, as internal solvers of the
   friction solvers); fc3d_driver does not run them as top-level solvers. */
#ifndef FC3D_COMPAT_SOCLCP_CST_H
#define FC3D_COMPAT_SOCLCP_CST_H
/* Siconos' include guard, defined too: code that tests it sees the header as included. */
#define SOCLCP_CST_H
#include <fc3d.h>

enum SOCLCP_SOLVER
{
  SICONOS_SOCLCP_NSGS = 1100,
  SICONOS_SOCLCP_VI_FPP = 1106,
  SICONOS_SOCLCP_VI_EG = 1107,
  SICONOS_SOCLCP_ProjectionOnCone = 1150,
  SICONOS_SOCLCP_ProjectionOnConeWithLocalIteration = 1151,
  SICONOS_SOCLCP_ProjectionOnConeWithRegularization = 1152
};

enum SICONOS_DPARAM_SOCLCP
{
  SICONOS_DPARAM_SOCLCP_PROJECTION_RHO = 3,
  SICONOS_DPARAM_SOCLCP_NSGS_RELAXATION = 8
};

enum SICONOS_IPARAM_SOCLCP
{
  SICONOS_IPARAM_SOCLCP_NSGS_WITH_RELAXATION = 8,
  SICONOS_IPARAM_SOCLCP_PROJECTION_CONE_INDEX = 4
};


#if defined(__cplusplus)
extern "C" {
#endif
extern const char* const SICONOS_SOCLCP_NSGS_STR;
extern const char* const SICONOS_SOCLCP_NSGSV_STR;
extern const char* const SICONOS_SOCLCP_PROX_STR;
extern const char* const SICONOS_SOCLCP_TFP_STR;
extern const char* const SICONOS_SOCLCP_NSN_AC_STR;
extern const char* const SICONOS_SOCLCP_NSN_FB_STR;
extern const char* const SICONOS_SOCLCP_DSFP_STR;
extern const char* const SICONOS_SOCLCP_VI_EG_STR;
extern const char* const SICONOS_SOCLCP_VI_FPP_STR;
extern const char* const SICONOS_SOCLCP_EG_STR;
extern const char* const SICONOS_SOCLCP_FPP_STR;
extern const char* const SICONOS_SOCLCP_HP_STR;
extern const char* const SICONOS_SOCLCP_NCPGlockerFBFixedPoint_STR;
extern const char* const SICONOS_SOCLCP_AlartCurnierNewton_STR;
extern const char* const SICONOS_SOCLCP_DampedAlartCurnierNewton_STR;
extern const char* const SICONOS_SOCLCP_NCPGlockerFBNewton_STR;
extern const char* const SICONOS_SOCLCP_ProjectionOnConeWithDiagonalization_STR;
extern const char* const SICONOS_SOCLCP_ProjectionOnCone_STR;
extern const char* const SICONOS_SOCLCP_ProjectionOnConeWithLocalIteration_STR;
extern const char* const SICONOS_SOCLCP_ProjectionOnConeWithRegularization_STR;
extern const char* const SICONOS_SOCLCP_NCPGlockerFBPATH_STR;
extern const char* const SICONOS_SOCLCP_projectionOnCylinder_STR;
extern const char* const SICONOS_SOCLCP_ProjectionOnCone_velocity_STR;
extern const char* const SICONOS_SOCLCP_PGoC_STR;
extern const char* const SICONOS_SOCLCP_DeSaxceFixedPoint_STR;
extern const char* const SICONOS_SOCLCP_QUARTIC_STR;
extern const char* const SICONOS_SOCLCP_QUARTIC_NU_STR;
#if defined(__cplusplus)
}
#endif

#endif
