/* Prints size and field offsets of every struct hosts fill. Compiled once against fc3d's
 * compat headers and once against Siconos 4.4's real headers; the two outputs must be equal
 * (local, rolling and global problem structs included). */
#include <stddef.h>
#include <stdio.h>

#include "SiconosNumerics.h"
#include "NumericsMatrix.h"
#include "NumericsSparseMatrix.h"
#include "SparseBlockMatrix.h"
#include "FrictionContactProblem.h"
#include "RollingFrictionContactProblem.h"
#include "GlobalFrictionContactProblem.h"
#include "GlobalRollingFrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"

#define S(T) printf("sizeof " #T " %zu\n", sizeof(T))
#define F(T, f) printf(#T "." #f " %zu\n", offsetof(T, f))

int main(void) {
  S(FrictionContactProblem);
  F(FrictionContactProblem, dimension); F(FrictionContactProblem, numberOfContacts);
  F(FrictionContactProblem, M); F(FrictionContactProblem, q); F(FrictionContactProblem, mu);
  S(RollingFrictionContactProblem);
  F(RollingFrictionContactProblem, dimension); F(RollingFrictionContactProblem, numberOfContacts);
  F(RollingFrictionContactProblem, M); F(RollingFrictionContactProblem, q);
  F(RollingFrictionContactProblem, mu); F(RollingFrictionContactProblem, mu_r);
  S(GlobalFrictionContactProblem);
  F(GlobalFrictionContactProblem, dimension); F(GlobalFrictionContactProblem, numberOfContacts);
  F(GlobalFrictionContactProblem, M); F(GlobalFrictionContactProblem, H); F(GlobalFrictionContactProblem, q);
  F(GlobalFrictionContactProblem, norm_q); F(GlobalFrictionContactProblem, b);
  F(GlobalFrictionContactProblem, norm_b); F(GlobalFrictionContactProblem, mu); F(GlobalFrictionContactProblem, env);
  S(GlobalRollingFrictionContactProblem);
  F(GlobalRollingFrictionContactProblem, dimension); F(GlobalRollingFrictionContactProblem, numberOfContacts);
  F(GlobalRollingFrictionContactProblem, M); F(GlobalRollingFrictionContactProblem, H);
  F(GlobalRollingFrictionContactProblem, q); F(GlobalRollingFrictionContactProblem, b);
  F(GlobalRollingFrictionContactProblem, mu); F(GlobalRollingFrictionContactProblem, mu_r);
  S(NumericsMatrix);
  F(NumericsMatrix, storageType); F(NumericsMatrix, size0); F(NumericsMatrix, size1);
  F(NumericsMatrix, matrix0); F(NumericsMatrix, matrix1); F(NumericsMatrix, matrix2);
  F(NumericsMatrix, internalData); F(NumericsMatrix, version); F(NumericsMatrix, destructible);
  S(NumericsMatrixInternalData);
  F(NumericsMatrixInternalData, iWork); F(NumericsMatrixInternalData, dWork);
  F(NumericsMatrixInternalData, isLUfactorized); F(NumericsMatrixInternalData, isInversed);
  S(SparseBlockStructuredMatrix);
  F(SparseBlockStructuredMatrix, nbblocks); F(SparseBlockStructuredMatrix, block);
  F(SparseBlockStructuredMatrix, blocknumber0); F(SparseBlockStructuredMatrix, blocknumber1);
  F(SparseBlockStructuredMatrix, blocksize0); F(SparseBlockStructuredMatrix, blocksize1);
  F(SparseBlockStructuredMatrix, filled1); F(SparseBlockStructuredMatrix, filled2);
  F(SparseBlockStructuredMatrix, index1_data); F(SparseBlockStructuredMatrix, index2_data);
  F(SparseBlockStructuredMatrix, diagonal_blocks); F(SparseBlockStructuredMatrix, version);
  S(SparseBlockCoordinateMatrix);
  F(SparseBlockCoordinateMatrix, nbblocks); F(SparseBlockCoordinateMatrix, blocknumber0);
  F(SparseBlockCoordinateMatrix, block); F(SparseBlockCoordinateMatrix, blocksize0);
  F(SparseBlockCoordinateMatrix, row); F(SparseBlockCoordinateMatrix, column);
  S(NumericsSparseMatrix);
  F(NumericsSparseMatrix, triplet); F(NumericsSparseMatrix, half_triplet); F(NumericsSparseMatrix, csc);
  F(NumericsSparseMatrix, trans_csc); F(NumericsSparseMatrix, csr); F(NumericsSparseMatrix, diag_indx);
  F(NumericsSparseMatrix, origin); F(NumericsSparseMatrix, linearSolverParams); F(NumericsSparseMatrix, versions);
  S(SolverOptions);
  F(SolverOptions, solverId); F(SolverOptions, isSet); F(SolverOptions, iSize); F(SolverOptions, iparam);
  F(SolverOptions, dSize); F(SolverOptions, dparam); F(SolverOptions, filterOn); F(SolverOptions, dWorkSize);
  F(SolverOptions, dWork); F(SolverOptions, iWorkSize); F(SolverOptions, iWork);
  F(SolverOptions, numberOfInternalSolvers); F(SolverOptions, internalSolvers); F(SolverOptions, callback);
  F(SolverOptions, solverParameters); F(SolverOptions, solverData);
  S(Callback);
  F(Callback, env); F(Callback, collectStatsIteration);
  printf("NM_DENSE %d NM_SPARSE_BLOCK %d NM_SPARSE %d\n", NM_DENSE, NM_SPARSE_BLOCK, NM_SPARSE);
  printf("NSM_TRIPLET %d NSM_CSC %d NSM_CSR %d\n", NSM_TRIPLET, NSM_CSC, NSM_CSR);
  printf("NSGS %d HYBRID %d ITER_DONE %d RESIDU %d ERR_EVAL %d\n", SICONOS_FRICTION_3D_NSGS,
         SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID, SICONOS_IPARAM_ITER_DONE, SICONOS_DPARAM_RESIDU,
         SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION);
  /* Every solver id and the fc3d option indices hosts use. */
  int ids[] = {SICONOS_FRICTION_2D_NSGS, SICONOS_FRICTION_2D_CPG, SICONOS_FRICTION_2D_LEMKE, SICONOS_FRICTION_2D_ENUM,
               SICONOS_FRICTION_3D_NSGS, SICONOS_FRICTION_3D_NSGSV, SICONOS_FRICTION_3D_PROX, SICONOS_FRICTION_3D_TFP,
               SICONOS_FRICTION_3D_NSN_AC, SICONOS_FRICTION_3D_DSFP, SICONOS_FRICTION_3D_VI_FPP, SICONOS_FRICTION_3D_VI_EG,
               SICONOS_FRICTION_3D_HP, SICONOS_FRICTION_3D_NCPGlockerFBFixedPoint, SICONOS_FRICTION_3D_FPP,
               SICONOS_FRICTION_3D_EG, SICONOS_FRICTION_3D_NSN_FB, SICONOS_FRICTION_3D_GAMS_PATH,
               SICONOS_FRICTION_3D_GAMS_PATHVI, SICONOS_FRICTION_3D_ACLMFP, SICONOS_FRICTION_3D_SOCLCP,
               SICONOS_FRICTION_3D_GAMS_LCP_PATH, SICONOS_FRICTION_3D_GAMS_LCP_PATHVI, SICONOS_FRICTION_3D_NSN_NM,
               SICONOS_FRICTION_3D_NSN_AC_TEST, SICONOS_FRICTION_3D_PFP, SICONOS_FRICTION_3D_ADMM,
               SICONOS_FRICTION_3D_ONECONTACT_NSN, SICONOS_FRICTION_3D_ONECONTACT_NSN_GP,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithRegularization,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithDiagonalization,
               SICONOS_FRICTION_3D_NCPGlockerFBPATH, SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinder,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone_velocity, SICONOS_FRICTION_3D_NCPGlockerFBNewton,
               SICONOS_FRICTION_3D_ONECONTACT_QUARTIC, SICONOS_FRICTION_3D_ONECONTACT_QUARTIC_NU,
               SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCylinderWithLocalIteration,
               SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID, SICONOS_FRICTION_3D_VI_FPP_Cylinder,
               SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER,
               SICONOS_GLOBAL_FRICTION_3D_NSGS_WR, SICONOS_GLOBAL_FRICTION_3D_NSGSV_WR,
               SICONOS_GLOBAL_FRICTION_3D_PROX_WR, SICONOS_GLOBAL_FRICTION_3D_DSFP_WR,
               SICONOS_GLOBAL_FRICTION_3D_TFP_WR, SICONOS_GLOBAL_FRICTION_3D_NSGS,
               SICONOS_GLOBAL_FRICTION_3D_NSN_AC_WR, SICONOS_GLOBAL_FRICTION_3D_NSN_AC,
               SICONOS_GLOBAL_FRICTION_3D_GAMS_PATH, SICONOS_GLOBAL_FRICTION_3D_GAMS_PATHVI,
               SICONOS_GLOBAL_FRICTION_3D_VI_FPP, SICONOS_GLOBAL_FRICTION_3D_VI_EG,
               SICONOS_GLOBAL_FRICTION_3D_ACLMFP, SICONOS_GLOBAL_FRICTION_3D_ADMM,
               SICONOS_GLOBAL_FRICTION_3D_ADMM_WR, SICONOS_GLOBAL_FRICTION_3D_IPM,
               SICONOS_GLOBAL_ROLLING_FRICTION_3D_NSGS_WR,
               SICONOS_FRICTION_3D_IPARAM_INTERNAL_ERROR_STRATEGY, SICONOS_FRICTION_3D_IPARAM_RESCALING,
               SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION_FREQUENCY, SICONOS_FRICTION_3D_NSGS_RELAXATION,
               SICONOS_FRICTION_3D_NSGS_SHUFFLE, SICONOS_FRICTION_3D_NSGS_SHUFFLE_SEED,
               SICONOS_FRICTION_3D_NSGS_FREEZING_CONTACT, SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE,
               SICONOS_FRICTION_3D_NSGS_RELAXATION_TRUE, SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE_EACH_LOOP,
               SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE_N_CONTACT,
               SICONOS_FRICTION_3D_DPARAM_INTERNAL_ERROR_RATIO, SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION,
               SICONOS_FRICTION_3D_NSN_RHO_STRATEGY, SICONOS_FRICTION_3D_NSN_FORMULATION,
               SICONOS_FRICTION_3D_NSN_LINESEARCH, SICONOS_FRICTION_3D_NSN_LINESEARCH_MAX_ITER,
               SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY, SICONOS_FRICTION_3D_NSN_HYBRID_MAX_LOOP,
               SICONOS_FRICTION_3D_NSN_HYBRID_MAX_ITER, SICONOS_FRICTION_3D_NSN_RHO,
               SICONOS_FRICTION_3D_NSN_LINESEARCH_NO, SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY_NSN_AND_PLI_NSN_LOOP,
               SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_SPLIT_SPECTRAL_NORM, OPTIONS_PARAM_SIZE};
  for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) printf("enum value %zu: %d\n", k, ids[k]);
  return 0;
}
