/* Prints size and field offsets of every struct hosts fill. Compiled once against fc3d's
 * compat headers and once against Siconos 4.4's real headers; the two outputs must be equal. */
#include <stddef.h>
#include <stdio.h>

#include "SiconosNumerics.h"
#include "NumericsMatrix.h"
#include "NumericsSparseMatrix.h"
#include "SparseBlockMatrix.h"
#include "FrictionContactProblem.h"
#include "SolverOptions.h"
#include "Friction_cst.h"

#define S(T) printf("sizeof " #T " %zu\n", sizeof(T))
#define F(T, f) printf(#T "." #f " %zu\n", offsetof(T, f))

int main(void) {
  S(FrictionContactProblem);
  F(FrictionContactProblem, dimension); F(FrictionContactProblem, numberOfContacts);
  F(FrictionContactProblem, M); F(FrictionContactProblem, q); F(FrictionContactProblem, mu);
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
  return 0;
}
