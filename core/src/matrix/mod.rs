//! The Delassus operator W in the three storages a host may hand us, and the block-row form the
//! Gauss-Seidel sweep works on.
//!
//! * [`DenseMatrix`]: column-major, borrowed from the host without a copy when it can be.
//! * [`BlockSparseMatrix`]: 3x3 blocks in block-CSR order (Siconos' sparse-block storage).
//! * [`CsrMatrix`]: general sparse; CSC and triplets are converted to it once (sorted, duplicates summed).
//!
//! Whatever the storage, [`Delassus::block_rows`] builds the [`BlockRows`] view once per solve:
//! per contact its diagonal block and the list of non-zero off-diagonal blocks. Zero blocks of a dense
//! W are dropped there, so a scene that couples few contacts costs what it couples.

mod block_rows;
mod block_sparse;
mod csr;
mod dense;
mod f32_coupling;
mod hform;
mod mass;
pub(crate) mod storage;

pub use block_rows::BlockRows;
pub use block_sparse::BlockSparseMatrix;
pub use csr::CsrMatrix;
pub use dense::DenseMatrix;
pub use f32_coupling::{F32Coupling, SweepRows};
pub(crate) use hform::sort_and_dedup_from;
pub use hform::{transpose, transpose_mul_add, HForm};
pub use mass::{MassFactor, DENSE_BLOCK_MAX};
pub use storage::{BlockValues, Shared};

use crate::alloc::try_push;
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::math::linalg::Mat3;

/// A dense W is solved through its [`Delassus::sparse_block_view`] when at most this fraction of
/// its 3x3 blocks hold a non-zero entry: a product then reads the non-zero blocks only (the
/// VI and projection families were 6-16x slower on the dense storage of such a W).
pub const SPARSE_VIEW_MAX_FILL: f64 = 0.5;

/// The Delassus operator W of a problem, in the storage the host gave.
#[derive(Debug, Clone, PartialEq)]
pub enum Delassus<'a> {
    Dense(DenseMatrix<'a>),
    SparseBlock(BlockSparseMatrix<'a>),
    Sparse(CsrMatrix),
}

impl<'a> Delassus<'a> {
    pub fn nrows(&self) -> usize {
        match self {
            Delassus::Dense(m) => m.nrows(),
            Delassus::SparseBlock(m) => m.nrows(),
            Delassus::Sparse(m) => m.nrows(),
        }
    }

    pub fn ncols(&self) -> usize {
        match self {
            Delassus::Dense(m) => m.ncols(),
            Delassus::SparseBlock(m) => m.ncols(),
            Delassus::Sparse(m) => m.ncols(),
        }
    }

    /// `y <- y + W x`.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        match self {
            Delassus::Dense(m) => m.mul_add(x, y),
            Delassus::SparseBlock(m) => m.mul_add(x, y),
            Delassus::Sparse(m) => m.mul_add(x, y),
        }
    }

    /// `u <- W r + q`.
    pub fn velocity(&self, r: &[f64], q: &[f64], u: &mut [f64]) {
        u.copy_from_slice(q);
        self.mul_add(r, u);
    }

    /// `alpha W` in the same storage (owned), allocated fallibly.
    pub fn scaled(&self, alpha: f64) -> Result<Delassus<'static>, Fc3dError> {
        Ok(match self {
            Delassus::Dense(m) => Delassus::Dense(m.scaled(alpha)?),
            Delassus::SparseBlock(m) => Delassus::SparseBlock(m.scaled(alpha)?),
            Delassus::Sparse(m) => Delassus::Sparse(m.scaled(alpha)?),
        })
    }

    /// `W + shift I` in W's own storage (owned): the proximal method's regularized W.
    pub fn shifted(&self, shift: f64) -> Result<Delassus<'static>, Fc3dError> {
        let n = self.nrows();
        Ok(match self {
            Delassus::Dense(d) => {
                let mut data = d.values().to_vec();
                for i in 0..n {
                    data[i + i * n] += shift;
                }
                Delassus::Dense(DenseMatrix::new(n, n, data)?)
            }
            Delassus::SparseBlock(s) => {
                let mut blocks: Vec<[f64; 9]> = s.blocks().copied().collect();
                for bi in 0..s.n_block_rows() {
                    let (start, end) = (s.row_ptr()[bi], s.row_ptr()[bi + 1]);
                    // Column-major 3x3: the diagonal is entries 0, 4, 8. Added to the first
                    // diagonal block only, should a host store it twice.
                    if let Some(k) = (start..end).find(|&k| s.col_idx()[k] == bi) {
                        for e in [0, 4, 8] {
                            blocks[k][e] += shift;
                        }
                    }
                }
                Delassus::SparseBlock(BlockSparseMatrix::new(
                    s.n_block_rows(),
                    s.n_block_cols(),
                    s.row_ptr().to_vec(),
                    s.col_idx().to_vec(),
                    blocks,
                )?)
            }
            Delassus::Sparse(s) => {
                let mut triplets = Vec::with_capacity(s.nnz() + n);
                s.for_each_entry(|i, j, v| triplets.push((i, j, v)));
                triplets.extend((0..n).map(|i| (i, i, shift)));
                Delassus::Sparse(CsrMatrix::from_triplets(n, n, &triplets)?)
            }
        })
    }

    /// Entry (i, j), zero where nothing is stored.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        match self {
            Delassus::Dense(m) => m.get(i, j),
            Delassus::SparseBlock(m) => m.get(i, j),
            Delassus::Sparse(m) => m.get(i, j),
        }
    }

    /// Calls `f(i, j, value)` for every stored entry (structural zeros of sparse storages skipped,
    /// every entry of a dense one visited).
    pub fn for_each_entry(&self, f: impl FnMut(usize, usize, f64)) {
        match self {
            Delassus::Dense(m) => m.for_each_entry(f),
            Delassus::SparseBlock(m) => m.for_each_entry(f),
            Delassus::Sparse(m) => m.for_each_entry(f),
        }
    }

    /// The 3x3 diagonal block of contact `c` (row-major), `None` if a sparse-block W lacks it.
    pub fn diagonal_block(&self, c: usize) -> Option<Mat3> {
        match self {
            Delassus::SparseBlock(m) => m.diagonal_block(c),
            _ => {
                let mut b = [[0.0; 3]; 3];
                for (i, row) in b.iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = self.get(3 * c + i, 3 * c + j);
                    }
                }
                Some(b)
            }
        }
    }

    /// The block-row form used by Gauss-Seidel sweeps (built once per solve).
    pub fn block_rows(&self) -> Result<BlockRows<'a>, Fc3dError> {
        BlockRows::from_delassus(self)
    }

    /// A dense, owned copy (column-major).
    pub fn to_dense(&self) -> DenseMatrix<'static> {
        let (m, n) = (self.nrows(), self.ncols());
        let mut data = vec![0.0; m * n];
        self.for_each_entry(|i, j, v| data[i + j * m] += v);
        DenseMatrix::new(m, n, data).expect("sizes agree by construction")
    }

    /// A CSR copy (sorted, no duplicates; exact zeros are not stored). Panics when it cannot be
    /// allocated: see [`Delassus::try_to_csr`].
    pub fn to_csr(&self) -> CsrMatrix {
        self.try_to_csr().expect("room for a CSR copy of W")
    }

    /// A CSR copy (sorted, no duplicates; exact zeros are not stored), allocated fallibly.
    pub fn try_to_csr(&self) -> Result<CsrMatrix, Fc3dError> {
        // A view of a host's blocks has not been read yet: a NaN is named by its block.
        self.check_finite()?;
        let mut triplets = Vec::new();
        let mut failed = Ok(());
        self.for_each_entry(|i, j, v| {
            if v != 0.0 && failed.is_ok() {
                failed = try_push(&mut triplets, (i, j, v), "the entries of W");
            }
        });
        failed?;
        CsrMatrix::from_triplets(self.nrows(), self.ncols(), &triplets)
    }

    /// A sparse-block copy (3x3 blocks) holding every block with a non-zero entry and every
    /// diagonal block. W must be square with a size divisible by 3. Built in two passes over
    /// W's rows (count, then fill), every array allocated fallibly.
    pub fn to_block_sparse(&self) -> Result<BlockSparseMatrix<'static>, Fc3dError> {
        let n = self.nrows();
        if n != self.ncols() || n % 3 != 0 {
            return Err(Fc3dError::InvalidStructure(format!(
                "a 3x3-block copy needs a square W with a size divisible by 3, got {}x{}",
                self.nrows(),
                self.ncols()
            )));
        }
        let copy;
        let csr = match self {
            Delassus::Sparse(s) => s,
            _ => {
                copy = self.try_to_csr()?;
                &copy
            }
        };
        let nc = n / 3;
        let (rp, ci, vals) = (csr.row_ptr(), csr.col_idx(), csr.values());
        let mut cols = Vec::new();
        let mut row_ptr = try_vec(nc + 1, 0usize, "the block rows of W")?;
        for bi in 0..nc {
            csr.block_columns(3, bi, &mut cols)?;
            row_ptr[bi + 1] = row_ptr[bi] + cols.len();
        }
        let nb = row_ptr[nc];
        let mut col_idx = try_vec(nb, 0usize, "the block columns of W")?;
        let mut blocks = try_vec(nb, [0.0; 9], "the blocks of W")?;
        for bi in 0..nc {
            let start = row_ptr[bi];
            csr.block_columns(3, bi, &mut cols)?;
            col_idx[start..start + cols.len()].copy_from_slice(&cols);
            for i in 0..3 {
                for k in rp[3 * bi + i]..rp[3 * bi + i + 1] {
                    if vals[k] != 0.0 {
                        let (bj, j) = (ci[k] / 3, ci[k] % 3);
                        let slot = cols.binary_search(&bj).expect("gathered above");
                        blocks[start + slot][i + 3 * j] += vals[k];
                    }
                }
            }
        }
        BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)
    }

    /// Calls `f(a, b)` for each pair of distinct contacts (3x3 blocks) that a non-zero entry of
    /// W couples: once per stored block holding one (per entry on a CSR W; a pair may repeat).
    /// The contact graph at the cost of reading W once, without a call per entry (a dense W's
    /// scratch, two arrays of its size, allocated fallibly).
    pub fn for_each_coupling(&self, mut f: impl FnMut(usize, usize)) -> Result<(), Fc3dError> {
        match self {
            Delassus::Dense(d) => {
                let n = d.nrows();
                if n != d.ncols() || n % 3 != 0 {
                    return Ok(());
                }
                let mut flags = try_vec(n / 3, false, "a block column of W")?;
                let mut rows = try_vec(n, 0u64, "a block column of W")?;
                for bj in 0..n / 3 {
                    dense_block_column_pattern(d.values(), n, bj, &mut flags, &mut rows);
                    for (bi, _) in flags.iter().enumerate().filter(|&(bi, f)| *f && bi != bj) {
                        f(bi, bj);
                    }
                }
            }
            Delassus::SparseBlock(m) => {
                for (bi, bj, b) in m.iter_blocks() {
                    if bi != bj && b.iter().any(|v| *v != 0.0) {
                        f(bi, bj);
                    }
                }
            }
            Delassus::Sparse(m) => m.for_each_entry(|i, j, v| {
                if v != 0.0 && i / 3 != j / 3 {
                    f(i / 3, j / 3);
                }
            }),
        }
        Ok(())
    }

    /// For a dense W of 3x3 blocks whose blocks are mostly zero (at most
    /// [`SPARSE_VIEW_MAX_FILL`] of them hold a non-zero entry), the same matrix in sparse-block
    /// storage: every block with a non-zero entry and every diagonal block, values unchanged.
    /// `None` for other storages, for dense matrices that are not mostly zero, and when the view
    /// cannot be allocated. One pass over the dense values, column by column; memory in
    /// proportion to the non-zero blocks.
    pub fn sparse_block_view(&self) -> Option<BlockSparseMatrix<'static>> {
        let Delassus::Dense(d) = self else {
            return None;
        };
        let n = d.nrows();
        if n != d.ncols() || n % 3 != 0 || n < 6 {
            return None;
        }
        let nc = n / 3;
        let values = d.values();
        // The block rows of block column bj holding a non-zero entry, and the diagonal.
        // Memory in proportion to the blocks kept, allocated fallibly: without it, no view (the
        // solve runs on the dense W).
        let mut rows = try_vec(n, 0u64, "a block column of W").ok()?;
        let mut mark = |bj: usize, flags: &mut [bool]| {
            dense_block_column_pattern(values, n, bj, flags, &mut rows);
            flags[bj] = true;
        };
        let mut flags = try_vec(nc, false, "a block column of W").ok()?;
        let mut row_count = try_vec(nc + 1, 0usize, "the block rows of W").ok()?;
        let limit = (SPARSE_VIEW_MAX_FILL * (nc * nc) as f64) as usize;
        // The blocks kept, column by column: W's values are read once for the pattern.
        let mut found: Vec<(usize, usize)> = Vec::new();
        for bj in 0..nc {
            mark(bj, &mut flags);
            for (bi, _) in flags.iter().enumerate().filter(|(_, f)| **f) {
                row_count[bi + 1] += 1;
                try_push(&mut found, (bi, bj), "the blocks of W").ok()?;
            }
            if found.len() > limit {
                return None;
            }
        }
        for i in 0..nc {
            row_count[i + 1] += row_count[i];
        }
        let row_ptr = try_copy(&row_count, "the block rows of W").ok()?;
        let mut next = row_count;
        let mut col_idx = try_vec(found.len(), 0usize, "the block columns of W").ok()?;
        let mut blocks = try_vec(found.len(), [0.0; 9], "the blocks of W").ok()?;
        for (bi, bj) in found {
            let k = next[bi];
            next[bi] += 1;
            col_idx[k] = bj;
            for c in 0..3 {
                for r in 0..3 {
                    blocks[k][r + 3 * c] = values[(3 * bi + r) + (3 * bj + c) * n];
                }
            }
        }
        BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks).ok()
    }

    /// Fails with [`Fc3dError::NonFinite`] when W holds a NaN or an infinity. Only a view over a
    /// host's blocks ([`BlockSparseMatrix::from_block_table`]) can: every other storage is
    /// checked when it is built, so this returns at once for them.
    pub fn check_finite(&self) -> Result<(), Fc3dError> {
        self.check_finite_part(0, 1)
    }

    /// [`Delassus::check_finite`] over part `part` of `parts` equal ranges of the stored blocks:
    /// the parts together check what it checks, and the first failing part names the block it
    /// names.
    pub fn check_finite_part(&self, part: usize, parts: usize) -> Result<(), Fc3dError> {
        match self {
            Delassus::SparseBlock(m) if m.is_borrowed() => {
                m.check_finite_blocks(part_of(m.n_blocks(), part, parts))
            }
            _ => Ok(()),
        }
    }

    /// Whether W's values were not read when it was built (a view over a host's blocks: see
    /// [`Delassus::check_finite`]).
    pub fn is_borrowed_view(&self) -> bool {
        matches!(self, Delassus::SparseBlock(m) if m.is_borrowed())
    }

    /// max |W - W^T| / max |W| (0 for a zero matrix): how far W is from symmetric.
    pub fn relative_asymmetry(&self) -> f64 {
        let mut amax = 0.0_f64;
        let mut dmax = 0.0_f64;
        self.for_each_entry(|i, j, v| {
            amax = amax.max(v.abs());
            if i < j {
                dmax = dmax.max((v - self.get(j, i)).abs());
            } else if i > j && self.get(j, i) == 0.0 {
                dmax = dmax.max(v.abs());
            }
        });
        if amax == 0.0 {
            0.0
        } else {
            dmax / amax
        }
    }

    /// The entries W stores: every entry of a dense W, 9 per block of a sparse-block W, the
    /// stored entries of a CSR W. What a sparse factorization's analysis reads.
    pub fn stored_entries(&self) -> usize {
        match self {
            Delassus::Dense(m) => m.nrows() * m.ncols(),
            Delassus::SparseBlock(m) => 9 * m.n_blocks(),
            Delassus::Sparse(m) => m.nnz(),
        }
    }

    /// Short storage name for tables and messages.
    pub fn storage_name(&self) -> &'static str {
        match self {
            Delassus::Dense(_) => "dense",
            Delassus::SparseBlock(_) => "sparse-block",
            Delassus::Sparse(_) => "csr",
        }
    }
}

/// Part `part` of `0..n` cut in `parts` contiguous ranges of equal length (the last shorter or
/// empty): how threads share out blocks or block rows in a fixed order.
pub(crate) fn part_of(n: usize, part: usize, parts: usize) -> std::ops::Range<usize> {
    let per_part = n.div_ceil(parts.max(1));
    (part * per_part).min(n)..((part + 1) * per_part).min(n)
}

/// Marks in `flags` the block rows of block column `bj` of a dense column-major `n x n` W (3x3
/// blocks) that hold a non-zero entry; the others are cleared. `rows` (at least `n` long) is
/// work space. No branch per entry: on a small dense W this pass is most of a one-sweep call.
fn dense_block_column_pattern(
    values: &[f64],
    n: usize,
    bj: usize,
    flags: &mut [bool],
    rows: &mut [u64],
) {
    // Row by row over the three columns, then by block row. `v != 0.0` is "the bits of v
    // without the sign are not 0" (-0 is 0, a NaN is not): integer ORs, which vectorize.
    let rows = &mut rows[..n];
    rows.iter_mut().for_each(|f| *f = 0);
    for col in values[3 * bj * n..3 * (bj + 1) * n].chunks_exact(n) {
        rows.iter_mut()
            .zip(col)
            .for_each(|(f, v)| *f |= v.to_bits() << 1);
    }
    for (f, r) in flags.iter_mut().zip(rows.chunks_exact(3)) {
        *f = (r[0] | r[1] | r[2]) != 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From every storage, the sparse-block copy holds each diagonal block and each block with
    /// a non-zero entry (duplicates summed; a block holding only an explicit zero is left out),
    /// with W's values.
    #[test]
    fn block_sparse_copies_keep_the_values_and_the_non_zero_blocks() {
        let triplets = [
            (0, 0, 1.0),
            (1, 1, 2.0),
            (2, 2, 3.0),
            (0, 4, 1.5),
            (0, 4, 0.5),
            (7, 1, 0.0),
            (4, 4, 1.0),
            (6, 6, 1.0),
            (8, 3, -2.0),
        ];
        let csr = Delassus::Sparse(CsrMatrix::from_triplets(9, 9, &triplets).unwrap());
        let dense = Delassus::Dense(csr.to_dense());
        let blocks = Delassus::SparseBlock(csr.to_block_sparse().unwrap());
        for w in [&csr, &dense, &blocks] {
            let b = w.to_block_sparse().unwrap();
            assert_eq!(b.row_ptr(), &[0, 2, 3, 5]);
            assert_eq!(b.col_idx(), &[0, 1, 1, 1, 2]);
            for i in 0..9 {
                for j in 0..9 {
                    assert_eq!(b.get(i, j), csr.get(i, j), "({i}, {j})");
                }
            }
        }
        assert_eq!(csr.get(0, 4), 2.0);
    }

    #[test]
    fn shifted_keeps_the_storage_and_adds_to_the_diagonal() {
        let d = DenseMatrix::new(3, 3, vec![1.0, 2.0, 0.0, 0.0, 3.0, 0.0, 0.5, 0.0, 4.0]).unwrap();
        let w = Delassus::Dense(d);
        let csr = Delassus::Sparse(w.to_csr());
        let sbm = Delassus::SparseBlock(w.to_block_sparse().unwrap());
        for m in [&w, &csr, &sbm] {
            let s = m.shifted(0.25).unwrap();
            assert_eq!(s.storage_name(), m.storage_name());
            for i in 0..3 {
                for j in 0..3 {
                    let extra = if i == j { 0.25 } else { 0.0 };
                    assert_eq!(s.get(i, j), w.get(i, j) + extra);
                }
            }
        }
    }
}
