use std::sync::Arc;

use super::block_sparse::NO_DIAGONAL;
use super::storage::{with_blocks, BlockAt, BlockValues, Shared};
use super::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::alloc::{reserve, try_collect, try_extend, try_push};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{block_vec_add, contact_of, Block};

/// Block-row view of a square W with `D x D` blocks (`D` the contact dimension, 3 by default),
/// built once per solve for Gauss-Seidel sweeps: for each contact, its diagonal block and the
/// coupling blocks of its row.
///
/// On a sparse-block W the blocks are W's own arrays, shared (reference-counted) or, when W is a
/// view of a host's blocks, borrowed for `'a`: not copied. Preparing the view reads the indices
/// only (where each contact's diagonal block is), so it costs a small fraction of one sweep and
/// no second copy of W. Rows then hold their diagonal block among the others: the sweeps skip it
/// there and read it through [`BlockRows::diagonal`]. From a dense or CSR W, the
/// view is built in one pass, row by row, keeping only the blocks with a non-zero entry, so a
/// scene that couples few contacts costs what it couples.
#[derive(Debug, Clone)]
pub struct BlockRows<'a, const D: usize = 3> {
    n_contacts: usize,
    /// Each contact's diagonal block, row-major, when W's storage does not hold exactly one
    /// per contact (a dense or CSR W, or a sparse-block W storing one twice); empty otherwise.
    diagonal: Vec<Block<D>>,
    /// Where each contact's diagonal block is among `values`, when W stores exactly one per
    /// contact (a sparse-block W): read from there, nothing gathered or copied.
    diagonal_at: Arc<Vec<usize>>,
    n_off_diagonal: usize,
    row_ptr: Shared<'a, usize>,
    cols: Shared<'a, usize>,
    /// `D * D` values per block, column-major, in row order.
    values: BlockValues<'a>,
}

impl<'a, const D: usize> BlockRows<'a, D> {
    pub fn from_delassus(w: &Delassus<'a>) -> Result<Self, Fc3dError> {
        let n = w.nrows();
        if n != w.ncols() || n % D != 0 {
            return Err(Fc3dError::InvalidStructure(format!(
                "W must be square with {D}x{D} blocks, got {}x{}",
                w.nrows(),
                w.ncols()
            )));
        }
        match w {
            Delassus::SparseBlock(s) => Self::from_block_sparse(s),
            Delassus::Dense(d) => Self::from_dense(d),
            Delassus::Sparse(s) => Self::from_csr(s),
        }
    }

    /// The view of a sparse-block W, sharing its arrays (no copy of the blocks): one pass over
    /// the block indices and the diagonal blocks. Duplicate blocks at one place are summed, as
    /// every other reader of W sums them.
    pub fn from_block_sparse(s: &BlockSparseMatrix<'a>) -> Result<Self, Fc3dError> {
        if D != 3 {
            return Err(Fc3dError::InvalidStructure(format!(
                "a 3x3 sparse-block W cannot be cut into {D}x{D} contact blocks"
            )));
        }
        let nc = s.n_block_rows();
        let (row_ptr, cols, values) = s.shared_parts();
        // Where each diagonal block is was found when W's structure was checked: nothing is
        // read here; the blocks are read where they are, by the sweeps.
        let (positions, repeated) = s.diagonal_positions();
        if let Some(c) = positions.iter().position(|&k| k == NO_DIAGONAL) {
            return Err(Fc3dError::MissingDiagonalBlock { contact: c });
        }
        let mut diagonal_at = Arc::clone(positions);
        let mut n_off_diagonal = s.n_blocks() - nc;
        let mut diagonal = Vec::new();
        if repeated {
            // A diagonal block stored twice: each contact's sum, copied once.
            diagonal_at = Arc::new(Vec::new());
            diagonal = crate::error::try_vec(nc, [[0.0; D]; D], "diagonal blocks")?;
            sum_diagonals(s, &mut diagonal);
            n_off_diagonal = (0..nc)
                .map(|c| {
                    (row_ptr[c]..row_ptr[c + 1])
                        .filter(|&k| cols[k] != c)
                        .count()
                })
                .sum();
        }
        Ok(BlockRows {
            n_contacts: nc,
            diagonal,
            diagonal_at,
            n_off_diagonal,
            row_ptr,
            cols,
            values,
        })
    }

    /// Takes the blocks of `w` when `w` has exactly the block pattern these rows were built
    /// with (same contacts, same coupling blocks in the same order), and returns `true`; returns
    /// `false`, leaving the rows unspecified, otherwise (the caller rebuilds them with
    /// [`BlockRows::from_delassus`]). A time stepper whose contact set did not change between
    /// steps keeps its prepared rows this way. On a sparse-block W nothing is allocated: the
    /// diagonal blocks are refilled in place and W's arrays shared; a dense or CSR W is cut into
    /// rows again (one pass) and its pattern compared.
    pub fn refill_from(&mut self, w: &Delassus<'a>) -> bool {
        let nc = self.n_contacts;
        if w.nrows() != D * nc || w.ncols() != D * nc {
            return false;
        }
        match w {
            Delassus::SparseBlock(s) => {
                if D != 3 || s.row_ptr() != &*self.row_ptr || s.col_idx() != &*self.cols {
                    return false;
                }
                // Same pattern: the diagonal positions hold; summed diagonals are summed again.
                if self.diagonal_at.is_empty() {
                    sum_diagonals(s, &mut self.diagonal);
                }
                // The host's index arrays when W borrows them (equal to ours, checked above).
                let (row_ptr, cols, values) = s.shared_parts();
                if row_ptr.is_borrowed() {
                    self.row_ptr = row_ptr;
                    self.cols = cols;
                }
                self.values = values;
                true
            }
            Delassus::Dense(_) | Delassus::Sparse(_) => match Self::from_delassus(w) {
                Ok(fresh) if *fresh.row_ptr == *self.row_ptr && *fresh.cols == *self.cols => {
                    *self = fresh;
                    true
                }
                _ => false,
            },
        }
    }

    /// Appends the coupling blocks of block row `bi` gathered in `scratch` (`D * D` column-major
    /// values per column of `scratch_cols`), dropping all-zero ones, and takes its diagonal out.
    fn push_row(
        &mut self,
        bi: usize,
        scratch_cols: &[usize],
        scratch: &[f64],
        row_ptr: &mut Vec<usize>,
        cols: &mut Vec<usize>,
        values: &mut Vec<f64>,
    ) -> Result<(), Fc3dError> {
        for (slot, &bj) in scratch_cols.iter().enumerate() {
            let b = &scratch[D * D * slot..D * D * (slot + 1)];
            if bj == bi {
                for (i, row) in self.diagonal[bi].iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        *v = b[i + D * j];
                    }
                }
            } else if b.iter().any(|&v| v != 0.0) {
                try_push(cols, bj, "the coupling blocks of W")?;
                try_extend(values, b, "the coupling blocks of W")?;
            }
        }
        row_ptr.push(cols.len());
        Ok(())
    }

    /// Rows for `nc` contacts, their diagonal blocks zero, and room for the row pointers.
    fn owned(nc: usize) -> Result<(Self, Vec<usize>), Fc3dError> {
        let rows = BlockRows {
            n_contacts: nc,
            diagonal: try_vec(nc, [[0.0; D]; D], "the diagonal blocks of W")?,
            diagonal_at: Arc::new(Vec::new()),
            n_off_diagonal: 0,
            row_ptr: Shared::Owned(Arc::new(Vec::new())),
            cols: Shared::Owned(Arc::new(Vec::new())),
            values: BlockValues::Packed(Arc::new(Vec::new())),
        };
        let mut row_ptr = Vec::new();
        reserve(&mut row_ptr, nc + 1, "the block rows of W")?;
        row_ptr.push(0);
        Ok((rows, row_ptr))
    }

    fn finish(mut self, row_ptr: Vec<usize>, cols: Vec<usize>, values: Vec<f64>) -> Self {
        self.n_off_diagonal = cols.len();
        self.row_ptr = row_ptr.into();
        self.cols = cols.into();
        self.values = BlockValues::Packed(Arc::new(values));
        self
    }

    fn from_dense(d: &DenseMatrix<'_>) -> Result<Self, Fc3dError> {
        let nc = d.nrows() / D;
        let (mut out, mut row_ptr) = Self::owned(nc)?;
        let (mut cols, mut values) = (Vec::new(), Vec::new());
        let all_cols = try_collect(0..nc, "the block columns of W")?;
        let mut scratch = try_vec(D * D * nc, 0.0, "a block row of W")?;
        for bi in 0..nc {
            for (bj, b) in scratch.chunks_exact_mut(D * D).enumerate() {
                for j in 0..D {
                    for i in 0..D {
                        b[i + D * j] = d.get(D * bi + i, D * bj + j);
                    }
                }
            }
            out.push_row(
                bi,
                &all_cols,
                &scratch,
                &mut row_ptr,
                &mut cols,
                &mut values,
            )?;
        }
        Ok(out.finish(row_ptr, cols, values))
    }

    fn from_csr(s: &CsrMatrix) -> Result<Self, Fc3dError> {
        let nc = s.nrows() / D;
        let (mut out, mut row_ptr) = Self::owned(nc)?;
        let (mut cols, mut values) = (Vec::new(), Vec::new());
        let (rp, ci, vals) = (s.row_ptr(), s.col_idx(), s.values());
        let mut scratch_cols: Vec<usize> = Vec::new();
        let mut scratch: Vec<f64> = Vec::new();
        for bi in 0..nc {
            s.block_columns(D, bi, &mut scratch_cols)?;
            scratch.clear();
            reserve(&mut scratch, D * D * scratch_cols.len(), "a block row of W")?;
            scratch.resize(D * D * scratch_cols.len(), 0.0);
            for i in 0..D {
                for k in rp[D * bi + i]..rp[D * bi + i + 1] {
                    if vals[k] == 0.0 {
                        continue;
                    }
                    let (bj, j) = (ci[k] / D, ci[k] % D);
                    let slot = scratch_cols.binary_search(&bj).expect("gathered above");
                    scratch[D * D * slot + i + D * j] += vals[k];
                }
            }
            out.push_row(
                bi,
                &scratch_cols,
                &scratch,
                &mut row_ptr,
                &mut cols,
                &mut values,
            )?;
        }
        Ok(out.finish(row_ptr, cols, values))
    }

    pub fn n_contacts(&self) -> usize {
        self.n_contacts
    }

    /// Number of stored off-diagonal blocks.
    pub fn n_off_diagonal(&self) -> usize {
        self.n_off_diagonal
    }

    #[inline]
    pub fn diagonal(&self, c: usize) -> Block<D> {
        if self.diagonal_at.is_empty() {
            return self.diagonal[c];
        }
        let k = self.diagonal_at[c];
        with_blocks!(&self.values, D * D, |blocks| {
            let m = &blocks.at(k)[..D * D];
            let mut b = [[0.0; D]; D];
            for (i, row) in b.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = m[i + D * j];
                }
            }
            b
        })
    }

    /// `u <- W r + q` through the stored blocks (zero blocks skipped, so a dense W costs what
    /// its coupling costs).
    pub fn velocity(&self, q: &[f64], r: &[f64], u: &mut [f64]) {
        for c in 0..self.n_contacts {
            let uc = block_vec_add(&self.diagonal(c), &contact_of(r, c), &self.local_q(c, q, r));
            u[D * c..D * c + D].copy_from_slice(&uc);
        }
    }

    /// The contacts coupled to contact `c` through a stored block of its row (increasing, the
    /// contact graph of parallel and island sweeps; a repeated block repeats its contact).
    #[inline]
    pub fn coupled(&self, c: usize) -> impl Iterator<Item = usize> + '_ {
        self.cols[self.row_ptr[c]..self.row_ptr[c + 1]]
            .iter()
            .copied()
            .filter(move |&b| b != c)
    }

    /// Calls `f(b, block)` for each stored coupling block of contact `c`'s row (`b != c`, in
    /// storage order; `block` holds `D * D` values, column-major): what the f32 copy of the
    /// coupling reads.
    pub(crate) fn for_each_coupling_block(&self, c: usize, mut f: impl FnMut(usize, &[f64])) {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        let cols = &self.cols[range.clone()];
        with_blocks!(&self.values, D * D, |blocks| {
            for (m, &b) in blocks.blocks(range.clone()).zip(cols) {
                if b != c {
                    f(b, &m[..D * D]);
                }
            }
        })
    }

    /// The normal component of [`BlockRows::local_q`]: all a frictionless contact needs (one
    /// row of each coupled block instead of `D`).
    #[inline]
    pub fn local_q_normal(&self, c: usize, q: &[f64], r: &[f64]) -> f64 {
        self.local_q_normal_by(c, q, |i| r[i])
    }

    /// [`BlockRows::local_q_normal`] with the reaction read entry by entry through `r_at`
    /// (reactions shared between sweeping threads).
    #[inline]
    pub fn local_q_normal_by(&self, c: usize, q: &[f64], r_at: impl Fn(usize) -> f64) -> f64 {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        let cols = &self.cols[range.clone()];
        with_blocks!(&self.values, D * D, |blocks| {
            let mut acc = q[D * c];
            for (k, &b) in range.clone().zip(cols) {
                if b == c {
                    continue;
                }
                // Row 0 of the column-major block (cut to its length: no bounds checks below).
                let m = &blocks.at(k)[..D * D];
                let mut s = m[0] * r_at(D * b);
                for j in 1..D {
                    s += m[D * j] * r_at(D * b + j);
                }
                acc += s;
            }
            acc
        })
    }

    /// `q_c + sum_{b != c} W_cb r_b`: the local q of contact c for the current r.
    #[inline]
    pub fn local_q(&self, c: usize, q: &[f64], r: &[f64]) -> [f64; D] {
        // As D-arrays: one bounds check a coupled contact.
        let contacts = r.as_chunks::<D>().0;
        self.local_q_by(c, q, |b| contacts[b])
    }

    /// [`BlockRows::local_q`] with each contact's reaction read through `r_of` (reactions
    /// shared between sweeping threads).
    #[inline]
    pub fn local_q_by(&self, c: usize, q: &[f64], r_of: impl Fn(usize) -> [f64; D]) -> [f64; D] {
        let range = self.row_ptr[c]..self.row_ptr[c + 1];
        let cols = &self.cols[range.clone()];
        with_blocks!(&self.values, D * D, |blocks| {
            let mut acc = contact_of(q, c);
            for (m, &b) in blocks.blocks(range.clone()).zip(cols) {
                if b == c {
                    continue;
                }
                let rb: [f64; D] = r_of(b);
                let m = &m[..D * D];
                // Each component summed in the order of `block_vec_add` (same bits as a
                // row-major block).
                for (i, a) in acc.iter_mut().enumerate() {
                    for (j, x) in rb.iter().enumerate() {
                        *a += m[i + D * j] * x;
                    }
                }
            }
            acc
        })
    }

    /// The same rows with nothing borrowed, to be kept past the borrow (a workspace's, between
    /// calls): borrowed index arrays are copied (once: a workspace then compares the next W's
    /// pattern with its own copies), borrowed blocks dropped ([`BlockRows::refill_from`] takes
    /// the next W's). `None` when the copy cannot be allocated.
    pub fn into_detached(self) -> Option<BlockRows<'static, D>> {
        let copy = |a: Shared<'a, usize>| -> Option<Shared<'static, usize>> {
            Some(match a {
                Shared::Owned(v) => Shared::Owned(v),
                Shared::Borrowed(s) => {
                    Shared::Owned(Arc::new(crate::error::try_copy(s, "block rows").ok()?))
                }
            })
        };
        let values = match self.values {
            BlockValues::Packed(v) => BlockValues::Packed(v),
            BlockValues::Table(_) => BlockValues::Packed(Arc::new(Vec::new())),
        };
        Some(BlockRows {
            n_contacts: self.n_contacts,
            diagonal: self.diagonal,
            diagonal_at: self.diagonal_at,
            n_off_diagonal: self.n_off_diagonal,
            row_ptr: copy(self.row_ptr)?,
            cols: copy(self.cols)?,
            values,
        })
    }
}

/// Each contact's diagonal block of `s`, the sum of those stored (row-major).
fn sum_diagonals<const D: usize>(s: &BlockSparseMatrix<'_>, diagonal: &mut [Block<D>]) {
    let (row_ptr, cols) = (s.row_ptr(), s.col_idx());
    for (c, diag) in diagonal.iter_mut().enumerate() {
        *diag = [[0.0; D]; D];
        for k in row_ptr[c]..row_ptr[c + 1] {
            if cols[k] == c {
                add_block(diag, s.block(k));
            }
        }
    }
}

/// `diag += b` for a column-major block `b`.
#[inline]
fn add_block<const D: usize>(diag: &mut Block<D>, b: &[f64]) {
    for (i, row) in diag.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v += b[i + D * j];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 3 contacts, a chain: 0-1 coupled, 1-2 coupled, 0-2 not; block (0, 1) stored twice.
    fn chain() -> BlockSparseMatrix<'static> {
        let b = |s: f64| -> [f64; 9] { std::array::from_fn(|k| s + k as f64) };
        BlockSparseMatrix::new(
            3,
            3,
            vec![0, 3, 6, 8],
            vec![0, 1, 1, 0, 1, 2, 1, 2],
            vec![
                b(10.0),
                b(1.0),
                b(0.5),
                b(2.0),
                b(20.0),
                b(3.0),
                b(4.0),
                b(30.0),
            ],
        )
        .unwrap()
    }

    #[test]
    fn sparse_block_rows_share_w_and_agree_with_dense_and_csr() {
        let s = chain();
        let rows = BlockRows::<3>::from_block_sparse(&s).unwrap();
        // The coupling blocks are W's own arrays, not a copy.
        let (BlockValues::Packed(a), BlockValues::Packed(b)) = (&rows.values, &s.shared_parts().2)
        else {
            panic!("packed storage expected")
        };
        assert!(Arc::ptr_eq(a, b));
        assert_eq!(rows.n_off_diagonal(), 5);
        let sparse = Delassus::SparseBlock(s);
        let dense = Delassus::Dense(sparse.to_dense());
        let csr = Delassus::Sparse(sparse.to_csr());
        let q: Vec<f64> = (0..9).map(|k| 0.1 * k as f64 - 0.3).collect();
        let r: Vec<f64> = (0..9).map(|k| 1.0 + 0.25 * k as f64).collect();
        for w in [&dense, &csr] {
            let other = BlockRows::<3>::from_delassus(w).unwrap();
            assert_eq!(other.n_off_diagonal(), 4, "{}", w.storage_name());
            for c in 0..3 {
                assert_eq!(rows.diagonal(c), other.diagonal(c));
                let (a, b) = (rows.local_q(c, &q, &r), other.local_q(c, &q, &r));
                for i in 0..3 {
                    approx::assert_relative_eq!(a[i], b[i], max_relative = 1e-15);
                }
                approx::assert_relative_eq!(
                    rows.local_q_normal(c, &q, &r),
                    other.local_q_normal(c, &q, &r),
                    max_relative = 1e-15
                );
            }
        }
        // u = W r + q through the view equals the product of W.
        let mut u = vec![0.0; 9];
        rows.velocity(&q, &r, &mut u);
        let mut expected = vec![0.0; 9];
        sparse.velocity(&r, &q, &mut expected);
        for i in 0..9 {
            approx::assert_relative_eq!(u[i], expected[i], max_relative = 1e-15);
        }
    }

    #[test]
    fn a_missing_diagonal_block_is_refused() {
        let s = BlockSparseMatrix::new(2, 2, vec![0, 1, 2], vec![0, 0], vec![[1.0; 9]; 2]).unwrap();
        assert!(matches!(
            BlockRows::<3>::from_block_sparse(&s),
            Err(Fc3dError::MissingDiagonalBlock { contact: 1 })
        ));
    }
}
