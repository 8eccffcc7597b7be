//! `#[repr(C)]` mirrors of the Siconos Numerics 4.4 structs a host fills and reads (Debian build:
//! `SICONOS_INT64`, no MPI, no OpenSSL). Field order and types are ABI: do not reorder.
//!
//! Fields that C writes and that carry a choice (storage type, solver id, booleans) are plain
//! integers here; they are validated when converted, never transmuted into Rust enums or `bool`.

#![allow(non_snake_case, non_camel_case_types)]

use std::os::raw::{c_double, c_int, c_uint, c_void};

/// CSparse's integer (`CS_INT`, `long` on the 64-bit Debian build of Siconos).
pub type CS_INT = i64;

/// Siconos' data version counter.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct NumericsDataVersion {
    pub number: u64,
}

/// CSparse matrix: compressed column (`nz == -1`), triplet (`nz >= 0`, `p` holds column
/// indices) or, in Siconos' convention, compressed row (`nz == -2`, `n` rows, `m` columns,
/// `p` row pointers, `i` column indices).
#[repr(C)]
#[derive(Debug)]
pub struct cs_dl_sparse {
    pub nzmax: CS_INT,
    pub m: CS_INT,
    pub n: CS_INT,
    pub p: *mut CS_INT,
    pub i: *mut CS_INT,
    pub x: *mut c_double,
    pub nz: CS_INT,
}

/// Siconos' name for the CSparse matrix struct.
pub type CSparseMatrix = cs_dl_sparse;

/// Siconos' sparse storage: several CSparse forms of one matrix; `origin` says which is the
/// reference (0 unknown, 1 triplet, 2 CSC, 3 CSR, 4 half triplet).
#[repr(C)]
#[derive(Debug)]
pub struct NumericsSparseMatrix {
    pub triplet: *mut CSparseMatrix,
    pub half_triplet: *mut CSparseMatrix,
    pub csc: *mut CSparseMatrix,
    pub trans_csc: *mut CSparseMatrix,
    pub csr: *mut CSparseMatrix,
    pub diag_indx: *mut CS_INT,
    pub origin: c_int,
    pub linearSolverParams: *mut c_void,
    pub versions: [NumericsDataVersion; 5],
}

/// Siconos' sparse-block matrix. `blocksize0/1` are cumulative sizes; `index1_data` holds
/// `filled1 = blocknumber0 + 1` block-row pointers and `index2_data` the `filled2` block-column
/// indices; `block[k]` points to the column-major values of block k.
#[repr(C)]
#[derive(Debug)]
pub struct SparseBlockStructuredMatrix {
    pub nbblocks: c_uint,
    pub block: *mut *mut c_double,
    pub blocknumber0: c_uint,
    pub blocknumber1: c_uint,
    pub blocksize0: *mut c_uint,
    pub blocksize1: *mut c_uint,
    pub filled1: usize,
    pub filled2: usize,
    pub index1_data: *mut usize,
    pub index2_data: *mut usize,
    pub diagonal_blocks: *mut c_uint,
    pub version: NumericsDataVersion,
}

/// Siconos' coordinate block matrix (blocks at 1-based `row[k]`, `column[k]` as built by
/// `SBCM_new_3x3`).
#[repr(C)]
#[derive(Debug)]
pub struct SparseBlockCoordinateMatrix {
    pub nbblocks: c_uint,
    pub blocknumber0: c_uint,
    pub blocknumber1: c_uint,
    pub block: *mut *mut c_double,
    pub blocksize0: *mut c_uint,
    pub blocksize1: *mut c_uint,
    pub row: *mut c_uint,
    pub column: *mut c_uint,
}

/// Work memory Siconos attaches to a matrix (never read by fc3d; freed with the matrix).
#[repr(C)]
#[derive(Debug)]
pub struct NumericsMatrixInternalData {
    pub iWorkSize: usize,
    pub iWork: *mut c_void,
    pub sizeof_elt: usize,
    pub dWorkSize: usize,
    pub dWork: *mut c_double,
    pub isLUfactorized: u8,
    pub isCholeskyfactorized: u8,
    pub isLDLTfactorized: u8,
    pub isInversed: u8,
}

/// Siconos' matrix: `storageType` 0 dense (column-major `matrix0`), 1 sparse-block (`matrix1`),
/// 2 sparse (`matrix2`).
#[repr(C)]
#[derive(Debug)]
pub struct NumericsMatrix {
    pub storageType: c_int,
    pub size0: c_int,
    pub size1: c_int,
    pub matrix0: *mut c_double,
    pub matrix1: *mut SparseBlockStructuredMatrix,
    pub matrix2: *mut NumericsSparseMatrix,
    pub internalData: *mut NumericsMatrixInternalData,
    pub version: NumericsDataVersion,
    pub destructible: *mut NumericsMatrix,
}

/// FC(W, q, mu) as Siconos hosts fill it (often on the stack).
#[repr(C)]
#[derive(Debug)]
pub struct FrictionContactProblem {
    pub dimension: c_int,
    pub numberOfContacts: c_int,
    pub M: *mut NumericsMatrix,
    pub q: *mut c_double,
    pub mu: *mut c_double,
}

/// Siconos' rolling-friction problem: FC(W, q, mu) with a rolling coefficient `mu_r` per
/// contact, `dimension` 5 (`rolling_fc3d`) or 3 (`rolling_fc2d`).
#[repr(C)]
#[derive(Debug)]
pub struct RollingFrictionContactProblem {
    pub dimension: c_int,
    pub numberOfContacts: c_int,
    pub M: *mut NumericsMatrix,
    pub q: *mut c_double,
    pub mu: *mut c_double,
    pub mu_r: *mut c_double,
}

/// Siconos 4.4's global problem: `M v = q + H r`, `u = H^T v + b`, Coulomb's law between u and
/// r per contact (`dimension` 3; 2 for a problem Siconos 4.5 writes). `norm_q`, `norm_b` and
/// `env` are Siconos' solver scratch: fc3d neither reads nor writes them.
#[repr(C)]
#[derive(Debug)]
pub struct GlobalFrictionContactProblem {
    pub dimension: c_int,
    pub numberOfContacts: c_int,
    pub M: *mut NumericsMatrix,
    pub H: *mut NumericsMatrix,
    pub q: *mut c_double,
    pub norm_q: c_double,
    pub b: *mut c_double,
    pub norm_b: c_double,
    pub mu: *mut c_double,
    pub env: *mut c_void,
}

/// Siconos 4.4's global rolling problem: a global problem of contacts of dimension 5 with a
/// rolling coefficient `mu_r` per contact.
#[repr(C)]
#[derive(Debug)]
pub struct GlobalRollingFrictionContactProblem {
    pub dimension: c_int,
    pub numberOfContacts: c_int,
    pub M: *mut NumericsMatrix,
    pub H: *mut NumericsMatrix,
    pub q: *mut c_double,
    pub b: *mut c_double,
    pub mu: *mut c_double,
    pub mu_r: *mut c_double,
}

/// Per-iteration callback: `collectStatsIteration(env, size, reaction, velocity, error, NULL)`.
#[repr(C)]
#[derive(Debug)]
pub struct Callback {
    pub env: *mut c_void,
    pub collectStatsIteration: Option<
        unsafe extern "C" fn(
            env: *mut c_void,
            size: c_int,
            reaction: *mut c_double,
            velocity: *mut c_double,
            error: c_double,
            extra_data: *mut c_void,
        ),
    >,
}

/// Siconos' solver options: `iparam`/`dparam` of `iSize`/`dSize` entries (20 by default).
#[repr(C)]
#[derive(Debug)]
pub struct SolverOptions {
    pub solverId: c_int,
    pub isSet: u8,
    pub iSize: c_int,
    pub iparam: *mut c_int,
    pub dSize: c_int,
    pub dparam: *mut c_double,
    pub filterOn: u8,
    pub dWorkSize: usize,
    pub dWork: *mut c_double,
    pub iWorkSize: usize,
    pub iWork: *mut c_int,
    pub numberOfInternalSolvers: usize,
    pub internalSolvers: *mut *mut SolverOptions,
    pub callback: *mut Callback,
    pub solverParameters: *mut c_void,
    pub solverData: *mut c_void,
}
