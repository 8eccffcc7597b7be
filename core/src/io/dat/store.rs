//! Where the readers put what they read: fc3d's own vectors ([`OwnStore`]), or storage a caller
//! provides through [`DatStore`] (the C layer allocates q, mu, a dense W's values, a sparse-block
//! W's index arrays and each of its blocks as the host will release them, so that reading a
//! file into a host's structures holds one copy of W, never a second one to convert from).

use std::ops::Deref;

use crate::alloc::{reserve, try_push};
use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, Delassus, DenseMatrix};

/// A growable array of plain values that a reader fills in order, allocated fallibly.
pub trait ReadArray<T: Copy>: Deref<Target = [T]> + Sized {
    /// An empty array with room for `capacity` values (the reader bounds it by what the input
    /// can hold). `what` names the array in an out-of-memory error.
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, Fc3dError>;
    /// Appends `value`, growing the array fallibly when it is full.
    fn push(&mut self, value: T, what: &str) -> Result<(), Fc3dError>;
}

/// The blocks of a sparse-block matrix (3x3, column-major), appended in storage order.
pub trait BlockArray: Sized {
    /// An empty array with room for `capacity` blocks.
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, Fc3dError>;
    /// Appends a block.
    fn push(&mut self, block: &[f64; 9], what: &str) -> Result<(), Fc3dError>;
}

/// The storage a reader fills for the parts of a problem or matrix it does not build as fc3d's
/// own matrix types: reals (q, mu, the values of a dense matrix, column-major), indices (the
/// block-row pointers and block columns of a sparse-block matrix) and 3x3 blocks.
pub trait DatStore {
    type Reals: ReadArray<f64>;
    type Indices: ReadArray<usize>;
    type Blocks: BlockArray;
}

/// fc3d's own storage: vectors, which [`ReadMatrix::into_delassus`] turns into a [`Delassus`].
#[derive(Debug, Clone, Copy, Default)]
pub struct OwnStore;

impl DatStore for OwnStore {
    type Reals = Vec<f64>;
    type Indices = Vec<usize>;
    type Blocks = Vec<[f64; 9]>;
}

impl<T: Copy> ReadArray<T> for Vec<T> {
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, Fc3dError> {
        let mut v = Vec::new();
        reserve(&mut v, capacity, what)?;
        Ok(v)
    }

    fn push(&mut self, value: T, what: &str) -> Result<(), Fc3dError> {
        try_push(self, value, what)
    }
}

impl BlockArray for Vec<[f64; 9]> {
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, Fc3dError> {
        <Self as ReadArray<[f64; 9]>>::with_capacity(capacity, what)
    }

    fn push(&mut self, block: &[f64; 9], what: &str) -> Result<(), Fc3dError> {
        try_push(self, *block, what)
    }
}

/// A matrix as a reader stored it. Every value has been checked finite and the structure
/// checked token by token (block columns in range, row pointers non-decreasing up to the number
/// of blocks, block numbers in order, the diagonal blocks of a problem's W present).
pub enum ReadMatrix<S: DatStore> {
    /// `rows x cols` values, column-major.
    Dense {
        rows: usize,
        cols: usize,
        values: S::Reals,
    },
    /// 3x3 blocks in block-CSR order: `row_ptr` has `block_rows + 1` entries, `col_idx` and
    /// `blocks` one per block.
    SparseBlock {
        block_rows: usize,
        block_cols: usize,
        row_ptr: S::Indices,
        col_idx: S::Indices,
        blocks: S::Blocks,
    },
    /// What the readers build as fc3d's own matrix whatever the store: a sparse (CSparse)
    /// matrix, a 2D problem's sparse-block W (2x2 blocks, held as a general sparse matrix).
    Built(Delassus<'static>),
}

impl ReadMatrix<OwnStore> {
    /// The matrix as fc3d's own storage (no copy).
    pub fn into_delassus(self) -> Result<Delassus<'static>, Fc3dError> {
        Ok(match self {
            ReadMatrix::Dense { rows, cols, values } => {
                Delassus::Dense(DenseMatrix::new(rows, cols, values)?)
            }
            ReadMatrix::SparseBlock {
                block_rows,
                block_cols,
                row_ptr,
                col_idx,
                blocks,
            } => Delassus::SparseBlock(BlockSparseMatrix::new(
                block_rows, block_cols, row_ptr, col_idx, blocks,
            )?),
            ReadMatrix::Built(w) => w,
        })
    }
}

/// A problem as a reader stored it (see [`super::read_dat_into`]): its contact dimension (2 or
/// 3), W (`dimension * mu.len()` square), q and mu (checked `>= 0`).
pub struct ReadProblem<S: DatStore> {
    pub dimension: usize,
    pub w: ReadMatrix<S>,
    pub q: S::Reals,
    pub mu: S::Reals,
}
