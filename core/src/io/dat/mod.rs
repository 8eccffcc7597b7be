//! The Siconos Numerics `.dat` text format of a `FrictionContactProblem` (reduced form).
//!
//! The file is a sequence of whitespace-separated tokens (0-based indices everywhere):
//!
//! ```text
//! dim nc
//! storageType size0 size1   matrix body (see below)
//! q[0] ... q[size0-1]
//! mu[0] ... mu[nc-1]
//! anything (ignored)
//! ```
//!
//! Matrix bodies, as written by Siconos 4.4 (`NM_write_in_file`) and read by `NM_new_from_file`:
//!
//! * dense (0): `size0 size1` again, then `size0 * size1` values, column-major;
//! * sparse-block (1): `nbblocks`, `blocknumber0 blocknumber1`, the cumulative row then column
//!   block sizes, `filled1 filled2`, `index1_data` (block-row pointers, `filled1` of them),
//!   `index2_data` (block columns, `filled2` of them), then for each block row and each of its
//!   blocks the block number and its values column-major. A lone `0` (no block) ends the body;
//! * sparse (2): an origin (`1` triplet, `2` CSC, `3` CSR), then the CSparse dump of
//!   `CSparseMatrix_print_in_file`: a banner line `CSparse Version ...`, then either
//!   `m-by-n, nzmax: Z nnz: N, 1-norm: X` followed by `col j : locations a to b` and `i : value`
//!   lines, or `triplet: m-by-n, nzmax: Z nnz: N` followed by `N` lines `row col : value`.
//!
//! Siconos prints sparse values with `%g` (6 significant digits), so its own sparse files are lossy;
//! [`write_dat`] prints every value in the shortest form that reads back to the same `f64`
//! (Rust's `{:e}`, which C's `strtod` reads too), so our files round-trip bit for bit in all three
//! storages.
//!
//! [`parse_dat`] and the other readers of a 3D problem reject dimension 2
//! ([`Fc3dError::UnsupportedDimension`]); the `_any` readers ([`parse_dat_any`],
//! [`read_dat_any`], [`read_dat_file_any`]) also read 2D problems ([`DatProblem::Planar`]), whose
//! sparse-block W (2x2 blocks) becomes a general sparse matrix. Otherwise sparse-block matrices
//! must be made of 3x3 blocks, and every error in the text is an [`Fc3dError::Parse`] naming the
//! token at fault (or `<end of file>`).
//!
//! # Reading bounded by the data
//!
//! Files and streams ([`read_dat_file`], [`read_dat`], [`read_matrix`], [`read_sbm`],
//! [`read_matrix_file`]) are read in chunks (of at most 64 KiB), only up to the end of what the
//! header declares: what follows a problem's mu (or a matrix) is not read, so a valid problem followed
//! by anything, even an endless stream, reads as Siconos reads it. Nothing is allocated for a
//! declared size before the data is there: a declared size the rest of the input cannot hold
//! (known for text in memory and regular files: `k` tokens take at least `2k - 1` bytes) is a
//! parse error naming the end of the input, found without storing anything; otherwise (a pipe)
//! values are stored as they arrive, in vectors grown fallibly, so that a stream going on with
//! valid numbers ends in [`Fc3dError::OutOfMemory`] under a memory limit, never an abort. A
//! stream that stops making tokens is rejected after a bounded read: a token longer than 64 KiB
//! (`/dev/zero` is one endless token), more than 16 MiB of whitespace between two tokens, or a
//! skipped CSparse banner line longer than 1 MiB is a parse error.
//!
//! The matrix part alone (`storageType size0 size1` and the body, any shape) is what Siconos'
//! `NM_write_in_file` writes and `NM_new_from_file` reads: [`parse_matrix`] and [`write_matrix`].
//! The sparse-block body without that header is what `SBM_write_in_file` writes and
//! `SBM_new_from_file` reads: [`parse_sbm`] and [`write_sbm`]. The `_prefix` variants also say
//! where the matrix text ends, for readers that continue after it.

mod csparse;
mod global;
mod parse;
mod scan;
mod storage;
mod store;
#[cfg(test)]
mod tests;
mod tokens;
mod write;

pub use global::{
    block_cut, block_start, block_values, csr_of_dense, parse_global_dat, read_global_dat,
    read_global_dat_file, read_global_rolling_dat, read_global_rolling_dat_file, write_global_dat,
    write_global_dat_file, write_global_rolling_dat, write_stored_matrix, BlockCut, GlobalDat,
    GlobalDatProblem, GlobalStorage, MatrixStorage,
};
pub use parse::{
    parse_dat, parse_dat_any, parse_matrix, parse_matrix_prefix, parse_sbm, parse_sbm_prefix,
    read_dat, read_dat_any, read_dat_file, read_dat_file_any, read_dat_file_into, read_dat_into,
    read_matrix, read_matrix_file, read_matrix_file_into, read_matrix_into, read_sbm,
    read_sbm_into, DatProblem,
};
pub use parse::{parse_rolling_dat, read_rolling_dat, read_rolling_dat_file, RollingDatProblem};
pub use store::{BlockArray, DatStore, OwnStore, ReadArray, ReadMatrix, ReadProblem};
pub use write::{write_dat, write_dat_file, write_matrix, write_rolling_dat, write_sbm};

#[cfg(doc)]
use crate::error::Fc3dError;

/// Siconos `NM_types` codes of the matrix storage.
const STORAGE_DENSE: usize = 0;
const STORAGE_SPARSE_BLOCK: usize = 1;
const STORAGE_SPARSE: usize = 2;

/// Siconos 4.4 `NumericsSparseOrigin` codes (`NSM_UNKNOWN, NSM_TRIPLET, NSM_CSC, NSM_CSR,
/// NSM_HALF_TRIPLET`).
const ORIGIN_TRIPLET: usize = 1;
const ORIGIN_CSC: usize = 2;
const ORIGIN_CSR: usize = 3;
const ORIGIN_HALF_TRIPLET: usize = 4;
