use std::sync::Arc;

use super::storage::{with_blocks, BlockAt, BlockValues, Shared};
use crate::alloc::reserve;
use crate::error::{check_finite, Fc3dError};
use crate::math::linalg::{mat3_from_col_major, Mat3};

/// Square 3x3-block sparse matrix in block-CSR order, blocks stored column-major as in Siconos'
/// `SparseBlockStructuredMatrix` (restricted to the uniform 3x3 blocks of fc3d).
///
/// The arrays are fc3d's own, reference-counted (the [`super::BlockRows`] view of a sweep shares
/// them instead of copying W; a clone is cheap too; [`BlockSparseMatrix::scaled`] copies), or a
/// host's, borrowed for `'a` ([`BlockSparseMatrix::from_block_table`]: zero copy).
#[derive(Debug, Clone)]
pub struct BlockSparseMatrix<'a> {
    n_block_rows: usize,
    n_block_cols: usize,
    row_ptr: Shared<'a, usize>,
    col_idx: Shared<'a, usize>,
    /// 9 values per block, column-major, blocks in storage order.
    values: BlockValues<'a>,
    /// Where each block row's diagonal block is stored ([`NO_DIAGONAL`] when it has none),
    /// found in the pass that checks the structure.
    diagonal_at: Arc<Vec<usize>>,
    /// Whether some block row stores its diagonal block more than once.
    repeated_diagonal: bool,
}

/// [`BlockSparseMatrix::diagonal_positions`] of a block row without a diagonal block.
pub const NO_DIAGONAL: usize = usize::MAX;

impl PartialEq for BlockSparseMatrix<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.n_block_rows == other.n_block_rows
            && self.n_block_cols == other.n_block_cols
            && *self.row_ptr == *other.row_ptr
            && *self.col_idx == *other.col_idx
            && self.blocks().eq(other.blocks())
    }
}

impl BlockSparseMatrix<'static> {
    /// `row_ptr` has `n_block_rows + 1` entries; block `k` sits at block row `i` for
    /// `row_ptr[i] <= k < row_ptr[i+1]`, block column `col_idx[k]`.
    pub fn new(
        n_block_rows: usize,
        n_block_cols: usize,
        row_ptr: Vec<usize>,
        col_idx: Vec<usize>,
        blocks: Vec<[f64; 9]>,
    ) -> Result<Self, Fc3dError> {
        let (diagonal_at, repeated_diagonal) =
            check_structure(n_block_rows, n_block_cols, &row_ptr, &col_idx)?;
        let nb = col_idx.len();
        if blocks.len() != nb {
            return Err(Fc3dError::dims("blocks", nb, blocks.len()));
        }
        for (k, b) in blocks.iter().enumerate() {
            check_block(k, b)?;
        }
        Ok(BlockSparseMatrix {
            n_block_rows,
            n_block_cols,
            row_ptr: row_ptr.into(),
            col_idx: col_idx.into(),
            // Same memory, seen as 9 n_blocks values: no copy.
            values: BlockValues::Packed(Arc::new(blocks.into_flattened())),
            diagonal_at,
            repeated_diagonal,
        })
    }

    /// The matrix whose block `k` (storage order, column-major) is `block(k)`, built in one
    /// streaming pass: each block is checked finite as it is copied into storage allocated once,
    /// fallibly (no zero-filled buffer first, no second pass). `storage` is where the values go
    /// (cleared first): a caller may hand a buffer it prepared (reserved, or advised to the
    /// kernel), else `Vec::new()`.
    pub fn from_block_fn<E: From<Fc3dError>>(
        n_block_rows: usize,
        n_block_cols: usize,
        row_ptr: Vec<usize>,
        col_idx: Vec<usize>,
        storage: Vec<f64>,
        mut block: impl FnMut(usize) -> Result<[f64; 9], E>,
    ) -> Result<Self, E> {
        let (diagonal_at, repeated_diagonal) =
            check_structure(n_block_rows, n_block_cols, &row_ptr, &col_idx)?;
        let nb = col_idx.len();
        let mut values = storage;
        values.clear();
        values
            .try_reserve_exact(9 * nb)
            .map_err(|_| Fc3dError::OutOfMemory {
                what: "W blocks".into(),
                bytes: nb.saturating_mul(72),
            })?;
        for k in 0..nb {
            let b = block(k)?;
            check_block(k, &b)?;
            values.extend_from_slice(&b);
        }
        Ok(BlockSparseMatrix {
            n_block_rows,
            n_block_cols,
            row_ptr: row_ptr.into(),
            col_idx: col_idx.into(),
            values: BlockValues::Packed(Arc::new(values)),
            diagonal_at,
            repeated_diagonal,
        })
    }
}

impl<'a> BlockSparseMatrix<'a> {
    /// A view of blocks that live elsewhere (a host's, for the length of a call): block `k` is
    /// `*blocks[k]`, nothing is copied. The structure is checked here (the index arrays only);
    /// the values are not read: [`BlockSparseMatrix::check_finite`] does that when asked (a
    /// solve asks when its error comes out non-finite, which a non-finite entry of W always
    /// causes, since `NaN * 0` and `inf * 0` are NaN).
    pub fn from_block_table(
        n_block_rows: usize,
        n_block_cols: usize,
        row_ptr: Shared<'a, usize>,
        col_idx: Shared<'a, usize>,
        blocks: Shared<'a, &'a [f64; 9]>,
    ) -> Result<Self, Fc3dError> {
        let (diagonal_at, repeated_diagonal) =
            check_structure(n_block_rows, n_block_cols, &row_ptr, &col_idx)?;
        let nb = col_idx.len();
        if blocks.len() != nb {
            return Err(Fc3dError::dims("blocks", nb, blocks.len()));
        }
        Ok(BlockSparseMatrix {
            n_block_rows,
            n_block_cols,
            row_ptr,
            col_idx,
            values: BlockValues::Table(blocks),
            diagonal_at,
            repeated_diagonal,
        })
    }

    /// Whether the blocks are borrowed (a view over a host's blocks).
    pub fn is_borrowed(&self) -> bool {
        self.values.is_borrowed()
    }

    /// Fails with [`Fc3dError::NonFinite`] naming the first block holding a NaN or an infinity.
    /// One pass at the pace of memory ([`crate::error::all_finite`] over a chunk of blocks);
    /// only a chunk that fails is searched block by block. (A test per block chains nine
    /// additions: 0.3 sweep at 5·10^5 contacts, against 0.1 for the memory.)
    pub fn check_finite(&self) -> Result<(), Fc3dError> {
        self.check_finite_blocks(0..self.n_blocks())
    }

    /// [`BlockSparseMatrix::check_finite`] over the blocks `blocks` (in storage order): threads
    /// that share the blocks out in ranges find the same first block.
    pub fn check_finite_blocks(&self, blocks: std::ops::Range<usize>) -> Result<(), Fc3dError> {
        const CHUNK: usize = 256;
        let lanes = |range: std::ops::Range<usize>| match &self.values {
            BlockValues::Packed(v) => crate::error::all_finite(&v[9 * range.start..9 * range.end]),
            // Blocks apart in memory: a block's nine values as the lanes.
            BlockValues::Table(t) => crate::error::all_finite_lanes(t[range].iter().copied()),
        };
        for start in blocks.clone().step_by(CHUNK) {
            let end = (start + CHUNK).min(blocks.end);
            if !lanes(start..end) {
                for k in start..end {
                    check_block(k, self.block(k))?;
                }
            }
        }
        Ok(())
    }

    /// An owned copy (owned storage is shared, borrowed blocks are copied).
    pub fn into_owned(self) -> BlockSparseMatrix<'static> {
        let values = match self.values {
            BlockValues::Packed(v) => v,
            BlockValues::Table(t) => Arc::new(t.iter().flat_map(|b| b.iter().copied()).collect()),
        };
        BlockSparseMatrix {
            n_block_rows: self.n_block_rows,
            n_block_cols: self.n_block_cols,
            row_ptr: self.row_ptr.into_owned(),
            col_idx: self.col_idx.into_owned(),
            values: BlockValues::Packed(values),
            diagonal_at: self.diagonal_at,
            repeated_diagonal: self.repeated_diagonal,
        }
    }

    /// `alpha * self`, same block structure (owned; index arrays shared when owned), allocated
    /// fallibly.
    pub fn scaled(&self, alpha: f64) -> Result<BlockSparseMatrix<'static>, Fc3dError> {
        let nb = self.n_blocks();
        let mut values = Vec::new();
        reserve(&mut values, 9 * nb, "the blocks of a rescaled W")?;
        for k in 0..nb {
            values.extend(self.block(k).iter().map(|v| v * alpha));
        }
        Ok(BlockSparseMatrix {
            n_block_rows: self.n_block_rows,
            n_block_cols: self.n_block_cols,
            row_ptr: self.row_ptr.clone().try_into_owned("the block rows of W")?,
            col_idx: self
                .col_idx
                .clone()
                .try_into_owned("the block columns of W")?,
            values: BlockValues::Packed(Arc::new(values)),
            diagonal_at: Arc::clone(&self.diagonal_at),
            repeated_diagonal: self.repeated_diagonal,
        })
    }

    /// `(n_block_rows, n_block_cols, row_ptr, col_idx, values)` (9 column-major values per
    /// block), without a copy unless the arrays are shared with a view still alive or borrowed.
    #[allow(clippy::type_complexity)]
    pub fn into_parts(self) -> (usize, usize, Vec<usize>, Vec<usize>, Vec<f64>) {
        let owned = self.into_owned();
        let BlockValues::Packed(values) = owned.values else {
            unreachable!("into_owned packs the values")
        };
        let values = Arc::try_unwrap(values).unwrap_or_else(|a| (*a).clone());
        (
            owned.n_block_rows,
            owned.n_block_cols,
            owned.row_ptr.into_vec(),
            owned.col_idx.into_vec(),
            values,
        )
    }

    /// The shared arrays `(row_ptr, col_idx, values)`, for views that must not copy W.
    pub(crate) fn shared_parts(&self) -> (Shared<'a, usize>, Shared<'a, usize>, BlockValues<'a>) {
        (
            self.row_ptr.clone(),
            self.col_idx.clone(),
            self.values.clone(),
        )
    }

    pub fn nrows(&self) -> usize {
        3 * self.n_block_rows
    }
    pub fn ncols(&self) -> usize {
        3 * self.n_block_cols
    }
    pub fn n_block_rows(&self) -> usize {
        self.n_block_rows
    }
    pub fn n_block_cols(&self) -> usize {
        self.n_block_cols
    }
    pub fn n_blocks(&self) -> usize {
        self.col_idx.len()
    }
    pub fn row_ptr(&self) -> &[usize] {
        &self.row_ptr
    }
    pub fn col_idx(&self) -> &[usize] {
        &self.col_idx
    }

    /// Block `k` of the storage order, column-major.
    #[inline]
    pub fn block(&self, k: usize) -> &[f64; 9] {
        match &self.values {
            BlockValues::Packed(v) => v[9 * k..9 * (k + 1)]
                .try_into()
                .expect("9 values per block"),
            BlockValues::Table(t) => t[k],
        }
    }

    /// Column-major 3x3 blocks in storage order.
    pub fn blocks(&self) -> impl ExactSizeIterator<Item = &[f64; 9]> + '_ {
        (0..self.n_blocks()).map(move |k| self.block(k))
    }

    /// Iterates `(block_row, block_col, column-major block)`.
    pub fn iter_blocks(&self) -> impl Iterator<Item = (usize, usize, &[f64; 9])> + '_ {
        (0..self.n_block_rows).flat_map(move |i| {
            (self.row_ptr[i]..self.row_ptr[i + 1]).map(move |k| (i, self.col_idx[k], self.block(k)))
        })
    }

    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (bi, bj) = (i / 3, j / 3);
        (self.row_ptr[bi]..self.row_ptr[bi + 1])
            .filter(|&k| self.col_idx[k] == bj)
            .map(|k| self.block(k)[(i % 3) + 3 * (j % 3)])
            .sum()
    }

    /// Sum of the stored blocks at (c, c) as a row-major matrix, `None` if there is none.
    pub fn diagonal_block(&self, c: usize) -> Option<Mat3> {
        let mut found = None::<Mat3>;
        for k in self.row_ptr[c]..self.row_ptr[c + 1] {
            if self.col_idx[k] == c {
                let b = mat3_from_col_major(self.block(k));
                found = Some(match found {
                    None => b,
                    Some(a) => {
                        let mut s = a;
                        for i in 0..3 {
                            for j in 0..3 {
                                s[i][j] += b[i][j];
                            }
                        }
                        s
                    }
                });
            }
        }
        found
    }

    /// `y <- y + W x`.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        self.mul_add_block_rows(x, y, 0..self.n_block_rows);
    }

    /// [`BlockSparseMatrix::mul_add`] for the block rows `rows` only: `y` holds their 3
    /// entries each. Every entry gets the same terms in the same order as in the whole product,
    /// so threads that share the rows out compute the same bits.
    pub fn mul_add_block_rows(&self, x: &[f64], y: &mut [f64], rows: std::ops::Range<usize>) {
        let (row_ptr, col_idx) = (&*self.row_ptr, &*self.col_idx);
        with_blocks!(&self.values, 9, |blocks| mul_add_in(
            &blocks,
            rows.clone(),
            row_ptr,
            col_idx,
            x,
            y
        ))
    }

    /// Whether block row `c` stores its diagonal block (indices only: no value is read).
    pub fn has_diagonal_block(&self, c: usize) -> bool {
        self.diagonal_at[c] != NO_DIAGONAL
    }

    /// Per block row, where its diagonal block is stored ([`NO_DIAGONAL`] when it has none; the
    /// last one when it has several), and whether some row has several.
    pub fn diagonal_positions(&self) -> (&Arc<Vec<usize>>, bool) {
        (&self.diagonal_at, self.repeated_diagonal)
    }

    pub fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        for (bi, bj, b) in self.iter_blocks() {
            for c in 0..3 {
                for r in 0..3 {
                    f(3 * bi + r, 3 * bj + c, b[r + 3 * c]);
                }
            }
        }
    }
}

/// `y <- y + W x` over blocks of any storage (the one product of a sparse-block W).
fn mul_add_in(
    blocks: &impl BlockAt,
    rows: std::ops::Range<usize>,
    row_ptr: &[usize],
    col_idx: &[usize],
    x: &[f64],
    y: &mut [f64],
) {
    for (bi, ys) in rows.zip(y.chunks_exact_mut(3)) {
        // The row's sums kept in registers; each entry gets its terms in the same order as
        // block by block into y.
        let mut acc = [ys[0], ys[1], ys[2]];
        for k in row_ptr[bi]..row_ptr[bi + 1] {
            // A fixed-size view: no bounds check on the 9 values below.
            let b: &[f64; 9] = blocks.at(k).first_chunk().expect("9 values per block");
            let bj = col_idx[k];
            let xs = &x[3 * bj..3 * bj + 3];
            for (c, &xc) in xs.iter().enumerate() {
                acc[0] += b[3 * c] * xc;
                acc[1] += b[3 * c + 1] * xc;
                acc[2] += b[3 * c + 2] * xc;
            }
        }
        ys.copy_from_slice(&acc);
    }
}

/// Checks the block structure and finds each block row's diagonal block in the same pass over
/// the column indices: returns the positions ([`NO_DIAGONAL`] where none) and whether a row
/// stores its diagonal block more than once.
fn check_structure(
    n_block_rows: usize,
    n_block_cols: usize,
    row_ptr: &[usize],
    col_idx: &[usize],
) -> Result<(Arc<Vec<usize>>, bool), Fc3dError> {
    if row_ptr.len() != n_block_rows + 1 {
        return Err(Fc3dError::dims(
            "block row pointers",
            n_block_rows + 1,
            row_ptr.len(),
        ));
    }
    if row_ptr[0] != 0 || row_ptr.windows(2).any(|w| w[0] > w[1]) {
        return Err(Fc3dError::InvalidStructure(
            "block row pointers must start at 0 and be non-decreasing".into(),
        ));
    }
    let nb = row_ptr[n_block_rows];
    if col_idx.len() != nb {
        return Err(Fc3dError::dims("block column indices", nb, col_idx.len()));
    }
    let mut diagonal_at = crate::error::try_vec(n_block_rows, NO_DIAGONAL, "diagonal positions")?;
    let mut repeated = false;
    for (i, at) in diagonal_at.iter_mut().enumerate() {
        for k in row_ptr[i]..row_ptr[i + 1] {
            let c = col_idx[k];
            if c >= n_block_cols {
                return Err(Fc3dError::InvalidStructure(format!(
                    "block {k} has column {c} >= {n_block_cols}"
                )));
            }
            if c == i {
                repeated |= *at != NO_DIAGONAL;
                *at = k;
            }
        }
    }
    Ok((Arc::new(diagonal_at), repeated))
}

#[inline]
fn check_block(k: usize, b: &[f64; 9]) -> Result<(), Fc3dError> {
    // One branch per block, not one per value; the value is named only on failure.
    if crate::error::all_finite(b) {
        return Ok(());
    }
    check_finite("W", b).map_err(|_| Fc3dError::NonFinite {
        what: format!("W (block {k})"),
        index: b.iter().position(|v| !v.is_finite()).unwrap_or(0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chunked pass finds a NaN or an infinity in any block of a borrowed table (first
    /// block, last of a chunk, first of the next, last of a partial chunk) and names it; finite
    /// values, -0 and the largest doubles included, pass.
    #[test]
    fn check_finite_names_the_block_anywhere_in_a_borrowed_table() {
        let n = 600;
        let mut values = vec![[1.0_f64; 9]; n];
        values[7] = [
            -0.0,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            0.0,
            1e-320,
            1.0,
            2.0,
            3.0,
        ];
        let (row_ptr, col_idx): (Vec<usize>, Vec<usize>) = ((0..=n).collect(), (0..n).collect());
        let check = |values: &[[f64; 9]]| {
            let table: Vec<&[f64; 9]> = values.iter().collect();
            BlockSparseMatrix::from_block_table(
                n,
                n,
                row_ptr.clone().into(),
                col_idx.clone().into(),
                Shared::Borrowed(&table),
            )
            .unwrap()
            .check_finite()
        };
        assert!(check(&values).is_ok());
        for (k, j, bad) in [
            (0, 0, f64::NAN),
            (255, 8, f64::INFINITY),
            (256, 4, f64::NEG_INFINITY),
            (599, 3, f64::NAN),
        ] {
            let kept = values[k][j];
            values[k][j] = bad;
            match check(&values) {
                Err(Fc3dError::NonFinite { what, index }) => {
                    assert_eq!((what, index), (format!("W (block {k})"), j))
                }
                other => panic!("block {k}: {other:?}"),
            }
            values[k][j] = kept;
        }
    }
}
