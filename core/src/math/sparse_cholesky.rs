//! A symmetric positive definite sparse matrix on a fixed pattern with faer's sparse Cholesky
//! `L L^T`: the fill-reducing order (AMD) and the symbolic factorization (simplicial or
//! supernodal, faer's choice) are computed once when the pattern is set; each
//! [`SparseCholesky::factor`] refactors the current values; solves allocate nothing. For the
//! body-space matrices `M + rho H D H^T` of the global formulation, where it costs a fraction
//! of a sparse LU of the same matrix (no pivoting, half the entries, a symmetric order).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};

use crate::error::{try_vec, Fc3dError};
use crate::math::lu_cost::{
    checked_cholesky_cost, factor_ends_by_kept, LuCost, CHOLESKY_FLOPS_PER_SECOND,
};
use crate::math::sparse_lu::compressed_columns;

/// A symmetric `n x n` matrix stored by its lower triangle in compressed columns, values
/// refillable in place, with its Cholesky factor.
pub struct SparseCholesky {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
    symbolic: SymbolicCholesky<usize>,
    factor: Vec<f64>,
    scratch: MemBuffer,
    factored: bool,
    /// The predicted cost of a numeric factorization, computed at the first
    /// [`SparseCholesky::factor_ends_by`] under a deadline.
    cost: Option<LuCost>,
}

impl std::fmt::Debug for SparseCholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseCholesky")
            .field("n", &self.n)
            .field("nnz", &self.values.len())
            .field("factor_nnz", &self.factor.len())
            .field("factored", &self.factored)
            .finish()
    }
}

impl SparseCholesky {
    /// The lower-triangle pattern of the symmetric matrix with entries at `positions` (any
    /// order, either triangle: `(i, j)` and `(j, i)` are one entry; duplicates merged);
    /// returns the matrix and, for each position in the given order, its value slot. `what`
    /// names the matrix in errors.
    pub fn from_positions(
        n: usize,
        positions: &[(usize, usize)],
        what: &str,
    ) -> Result<(Self, Vec<usize>), Fc3dError> {
        let (col_ptr, row_idx, slots) =
            compressed_columns(n, positions, |(i, j)| (i.max(j), i.min(j)), what)?;
        let nnz = row_idx.len();
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = factorize_symbolic_cholesky(
            pattern.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| Fc3dError::Unsupported(format!("{what}: sparse Cholesky analysis: {e:?}")))?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let scratch = MemBuffer::try_new(req).map_err(|_| Fc3dError::OutOfMemory {
            what: format!("{what}: sparse Cholesky work space"),
            bytes: req.unaligned_bytes_required(),
        })?;
        let factor = try_vec(symbolic.len_val(), 0.0, what)?;
        Ok((
            SparseCholesky {
                n,
                pattern,
                values: try_vec(nnz, 0.0, what)?,
                symbolic,
                factor,
                scratch,
                factored: false,
                cost: None,
            },
            slots,
        ))
    }

    pub fn size(&self) -> usize {
        self.n
    }

    /// Stored entries of the lower triangle.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Stored entries of the factor L.
    pub fn factor_nnz(&self) -> usize {
        self.factor.len()
    }

    /// The values of the lower triangle, in the pattern's slot order; changing them
    /// invalidates the factorization.
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.factored = false;
        &mut self.values
    }

    /// Factors the current values. Fails (and leaves the matrix unfactored) on a non-finite
    /// value or a matrix that is not numerically positive definite.
    pub fn factor(&mut self) -> Result<(), Fc3dError> {
        self.factored = false;
        if !self.values.iter().all(|v| v.is_finite()) {
            return Err(Fc3dError::Unsupported(
                "a sparse Cholesky factorization of a matrix with a non-finite entry".into(),
            ));
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        self.symbolic
            .factorize_numeric_llt(
                &mut self.factor,
                mat,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|e| Fc3dError::Unsupported(format!("not positive definite ({e:?})")))?;
        self.factored = true;
        Ok(())
    }

    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Whether a numeric factorization started now is predicted to end by `deadline`
    /// ([`LuCost::ends_by_at`] [`CHOLESKY_FLOPS_PER_SECOND`] of [`checked_cholesky_cost`]'s prediction in the symbolic
    /// analysis' order, made at the first call under a deadline and kept). Without a deadline:
    /// true, with no work. Fails as [`checked_cholesky_cost`] does (`what` names the matrix).
    pub fn factor_ends_by(
        &mut self,
        deadline: Option<std::time::Instant>,
        what: &str,
    ) -> Result<bool, Fc3dError> {
        factor_ends_by_kept(
            &mut self.cost,
            deadline,
            CHOLESKY_FLOPS_PER_SECOND,
            || match self.symbolic.perm() {
                Some(perm) => checked_cholesky_cost(self.pattern.as_ref(), perm, what),
                None => {
                    let mut identity = try_vec(self.n, 0usize, what)?;
                    identity.iter_mut().enumerate().for_each(|(i, x)| *x = i);
                    let perm = faer::perm::PermRef::new_checked(&identity, &identity, self.n);
                    checked_cholesky_cost(self.pattern.as_ref(), perm, what)
                }
            },
        )
    }

    /// The prediction [`SparseCholesky::factor_ends_by`] made, if it made one.
    pub fn predicted_cost(&self) -> Option<LuCost> {
        self.cost
    }

    /// Solves `A x = rhs` in place with the last factorization (which must exist).
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        assert!(
            self.factored,
            "SparseCholesky::solve_in_place before a factorization"
        );
        debug_assert_eq!(rhs.len(), self.n);
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, self.n, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }

    /// `y <- y + A x` with the stored values (both triangles).
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        let (col_ptr, row_idx) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for j in 0..self.n {
            for k in col_ptr[j]..col_ptr[j + 1] {
                let i = row_idx[k];
                y[i] += self.values[k] * x[j];
                if i != j {
                    y[j] += self.values[k] * x[i];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_symmetric_positive_definite_system() {
        // A 1D Laplacian plus a shift, given by both triangles and duplicates.
        let n = 50;
        let mut positions = Vec::new();
        let mut values = Vec::new();
        for i in 0..n {
            positions.push((i, i));
            values.push(2.5);
            if i + 1 < n {
                positions.push((i + 1, i));
                values.push(-0.5);
                positions.push((i, i + 1));
                values.push(-0.5);
            }
        }
        let (mut a, slots) = SparseCholesky::from_positions(n, &positions, "test").unwrap();
        assert_eq!(a.nnz(), 2 * n - 1);
        let vals = a.values_mut();
        for (k, &s) in slots.iter().enumerate() {
            // Each off-diagonal entry is given twice: its value once in the lower triangle.
            let (i, j) = positions[k];
            if i >= j {
                vals[s] += values[k];
            }
        }
        a.factor().unwrap();
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut b = vec![0.0; n];
        a.mul_add(&x, &mut b);
        a.solve_in_place(&mut b);
        for (bi, xi) in b.iter().zip(&x) {
            assert!((bi - xi).abs() < 1e-12);
        }
        // Not positive definite: refused.
        a.values_mut().iter_mut().for_each(|v| *v = -*v);
        assert!(a.factor().is_err());
        assert!(!a.is_factored());
    }

    #[test]
    fn a_factorization_is_predicted_only_under_a_deadline() {
        use std::time::{Duration, Instant};
        let n = 60;
        let positions: Vec<(usize, usize)> =
            (0..n).flat_map(|i| (0..=i).map(move |j| (i, j))).collect();
        let (mut a, _) = SparseCholesky::from_positions(n, &positions, "test").unwrap();
        assert!(a.factor_ends_by(None, "test").unwrap());
        assert_eq!(a.predicted_cost(), None);
        let far = Instant::now() + Duration::from_secs(3600);
        assert!(a.factor_ends_by(Some(far), "test").unwrap());
        // A dense Cholesky: sum_j c_j^2, half the LU's; the factor's n (n + 1) / 2 entries.
        let cost = a.predicted_cost().unwrap();
        let dense: f64 = (1..=n).map(|c| (c * c) as f64).sum();
        assert_eq!(cost.flops, dense);
        assert_eq!(cost.factor_entries, (n * (n + 1) / 2) as f64);
        assert!(!a.factor_ends_by(Some(Instant::now()), "test").unwrap());
    }
}
