//! A square sparse matrix on a fixed pattern with faer's sparse LU: the symbolic analysis
//! (fill-reducing column order, elimination structure) is done once when the pattern is set;
//! each [`SparseLu::factor`] refactors the current values numerically; solves allocate nothing.
//! What every factorizing piece of the global formulation builds on (M, `M + rho H H^T`, the
//! global Newton matrix).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par};

use crate::error::{try_vec, Fc3dError};
use crate::math::lu_cost::{
    checked_lu_cost, factor_ends_by_kept, LuCost, GLOBAL_LU_FLOPS_PER_SECOND,
};

/// A sparse `n x n` matrix in compressed columns, its values refillable in place, with its LU.
pub struct SparseLu {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    scratch: MemBuffer,
    factored: bool,
    /// The predicted cost of a numeric factorization, computed at the first
    /// [`SparseLu::factor_ends_by`] under a deadline.
    cost: Option<LuCost>,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLu")
            .field("n", &self.n)
            .field("nnz", &self.values.len())
            .field("factored", &self.factored)
            .finish()
    }
}

impl SparseLu {
    /// The pattern of a square matrix from its compressed columns (`col_ptr` of `n + 1`
    /// entries, row indices sorted and unique within each column), values zero. `what` names
    /// the matrix in errors.
    pub fn new(
        n: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
        what: &str,
    ) -> Result<Self, Fc3dError> {
        let nnz = row_idx.len();
        // The callers build sorted, in-range patterns; faer checks them again.
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = factorize_symbolic_lu(pattern.as_ref(), Default::default())
            .map_err(|e| Fc3dError::Unsupported(format!("{what}: sparse LU analysis: {e:?}")))?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let scratch = MemBuffer::try_new(req).map_err(|_| Fc3dError::OutOfMemory {
            what: format!("{what}: sparse LU work space"),
            bytes: req.unaligned_bytes_required(),
        })?;
        Ok(SparseLu {
            n,
            pattern,
            values: crate::error::try_vec(nnz, 0.0, what)?,
            symbolic,
            numeric: NumericLu::new(),
            scratch,
            factored: false,
            cost: None,
        })
    }

    /// The pattern of `(row, col)` positions given in any order (duplicates merged); returns
    /// the matrix and, for each position in the given order, its value slot.
    pub fn from_positions(
        n: usize,
        positions: &[(usize, usize)],
        what: &str,
    ) -> Result<(Self, Vec<usize>), Fc3dError> {
        let (col_ptr, row_idx, slots) = compressed_columns(n, positions, |p| p, what)?;
        Ok((SparseLu::new(n, col_ptr, row_idx, what)?, slots))
    }

    pub fn size(&self) -> usize {
        self.n
    }

    /// Stored entries of the pattern.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// The values, in the pattern's slot order; changing them invalidates the factorization.
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.factored = false;
        &mut self.values
    }

    /// Factors the current values. Fails (and leaves the matrix unfactored) on a non-finite
    /// value or a structurally or numerically singular matrix.
    pub fn factor(&mut self) -> Result<(), Fc3dError> {
        self.factored = false;
        if !self.values.iter().all(|v| v.is_finite()) {
            return Err(Fc3dError::Unsupported(
                "a sparse LU of a matrix with a non-finite entry".into(),
            ));
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                mat,
                Par::Seq,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|e| Fc3dError::Unsupported(format!("singular matrix (sparse LU: {e:?})")))?;
        self.factored = true;
        Ok(())
    }

    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Whether a numeric factorization started now is predicted to end by `deadline`
    /// ([`LuCost::ends_by_at`] [`GLOBAL_LU_FLOPS_PER_SECOND`] of [`checked_lu_cost`]'s
    /// prediction from this pattern's symbolic
    /// analysis, made at the first call under a deadline and kept: the pattern is fixed). Without
    /// a deadline: true, with no work. Fails when the prediction's work arrays cannot be
    /// allocated or the factors would not fit in memory (`what` names the matrix).
    pub fn factor_ends_by(
        &mut self,
        deadline: Option<std::time::Instant>,
        what: &str,
    ) -> Result<bool, Fc3dError> {
        factor_ends_by_kept(&mut self.cost, deadline, GLOBAL_LU_FLOPS_PER_SECOND, || {
            checked_lu_cost(self.pattern.as_ref(), self.symbolic.col_perm(), what)
        })
    }

    /// The prediction [`SparseLu::factor_ends_by`] made, if it made one.
    pub fn predicted_cost(&self) -> Option<LuCost> {
        self.cost
    }

    /// Solves `A x = rhs` in place with the last factorization (which must exist).
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        assert!(
            self.factored,
            "SparseLu::solve_in_place before a factorization"
        );
        debug_assert_eq!(rhs.len(), self.n);
        // The factors live in `numeric`; the view is rebuilt without allocating.
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.numeric);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, self.n, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }

    /// `y <- y + A x` with the stored values.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        let (col_ptr, row_idx) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for (j, &xj) in x.iter().enumerate().take(self.n) {
            for k in col_ptr[j]..col_ptr[j + 1] {
                y[row_idx[k]] += self.values[k] * xj;
            }
        }
    }
}

/// Compressed columns `(col_ptr, row_idx)` of an `n x n` pattern given as positions in any
/// order, each mapped by `entry` to the stored `(row, col)` (the identity, or a symmetric
/// matrix's lower triangle), duplicates merged, and for each position in the given order its
/// slot. Fails on a position outside the matrix or when the arrays cannot be allocated.
pub(crate) fn compressed_columns(
    n: usize,
    positions: &[(usize, usize)],
    entry: impl Fn((usize, usize)) -> (usize, usize),
    what: &str,
) -> Result<(Vec<usize>, Vec<usize>, Vec<usize>), Fc3dError> {
    if let Some(&(i, j)) = positions.iter().find(|&&(i, j)| i >= n || j >= n) {
        return Err(Fc3dError::InvalidStructure(format!(
            "{what}: entry ({i}, {j}) outside a {n}x{n} matrix"
        )));
    }
    let mut order = try_vec(positions.len(), 0usize, what)?;
    order.iter_mut().enumerate().for_each(|(k, o)| *o = k);
    order.sort_unstable_by_key(|&k| {
        let (i, j) = entry(positions[k]);
        (j, i)
    });
    let mut col_ptr = try_vec(n + 1, 0usize, what)?;
    let mut row_idx = Vec::new();
    row_idx
        .try_reserve_exact(positions.len())
        .map_err(|_| Fc3dError::OutOfMemory {
            what: what.to_string(),
            bytes: positions.len() * 8,
        })?;
    let mut slots = try_vec(positions.len(), 0usize, what)?;
    let mut last = None;
    for k in order {
        let (i, j) = entry(positions[k]);
        if last != Some((i, j)) {
            row_idx.push(i);
            col_ptr[j + 1] += 1;
            last = Some((i, j));
        }
        slots[k] = row_idx.len() - 1;
    }
    for j in 0..n {
        col_ptr[j + 1] += col_ptr[j];
    }
    Ok((col_ptr, row_idx, slots))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_and_solves_a_non_symmetric_matrix_refilled_in_place() {
        // [[4, 1, 0], [2, 5, 1], [0, 3, 6]]
        let positions = [(0, 0), (0, 1), (1, 0), (1, 1), (1, 2), (2, 1), (2, 2)];
        let values = [4.0, 1.0, 2.0, 5.0, 1.0, 3.0, 6.0];
        let (mut lu, slots) = SparseLu::from_positions(3, &positions, "test").unwrap();
        for (s, v) in slots.iter().zip(values) {
            lu.values_mut()[*s] = v;
        }
        lu.factor().unwrap();
        let mut x = [1.0, 2.0, 3.0];
        lu.solve_in_place(&mut x);
        let mut check = [0.0; 3];
        lu.mul_add(&x, &mut check);
        for (c, b) in check.iter().zip([1.0, 2.0, 3.0]) {
            assert!((c - b).abs() < 1e-14, "{check:?}");
        }
        // Refilled with twice the values: the solution halves.
        lu.values_mut().iter_mut().for_each(|v| *v *= 2.0);
        lu.factor().unwrap();
        let mut y = [1.0, 2.0, 3.0];
        lu.solve_in_place(&mut y);
        for (a, b) in x.iter().zip(y) {
            assert!((a / 2.0 - b).abs() < 1e-14);
        }
    }

    #[test]
    fn a_singular_matrix_is_refused() {
        let (mut lu, slots) = SparseLu::from_positions(2, &[(0, 0), (1, 0)], "test").unwrap();
        lu.values_mut()[slots[0]] = 1.0;
        lu.values_mut()[slots[1]] = 1.0;
        assert!(lu.factor().is_err());
        assert!(!lu.is_factored());
    }

    #[test]
    fn a_factorization_is_predicted_only_under_a_deadline() {
        use std::time::{Duration, Instant};
        // A dense 60x60 pattern: 2 * 60^3 / 3 flops, microseconds at any rate measured.
        let n = 60;
        let positions: Vec<(usize, usize)> =
            (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
        let (mut lu, _) = SparseLu::from_positions(n, &positions, "test").unwrap();
        // Without a deadline: no prediction made.
        assert!(lu.factor_ends_by(None, "test").unwrap());
        assert_eq!(lu.predicted_cost(), None);
        let far = Instant::now() + Duration::from_secs(3600);
        assert!(lu.factor_ends_by(Some(far), "test").unwrap());
        let cost = lu.predicted_cost().unwrap();
        // sum_j 2 c_j^2 with c_j = n - j: about 2 n^3 / 3.
        let dense: f64 = (1..=n).map(|c| 2.0 * (c * c) as f64).sum();
        assert_eq!(cost.flops, dense);
        // A deadline already reached: refused.
        assert!(!lu.factor_ends_by(Some(Instant::now()), "test").unwrap());
    }
}
