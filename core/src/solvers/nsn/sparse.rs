//! The Newton matrix `J = A + B W` on a pattern fixed for the whole solve: W's 3x3 block pattern
//! plus the diagonal blocks, stored column-compressed for faer's sparse LU. The symbolic
//! factorization (fill-reducing ordering and elimination structure) is computed once; every
//! iteration refills the values through a slot map and refactors numerically.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par};

use crate::alloc::reserve;
use crate::contract::Fill;
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::math::linalg::Mat3;
use crate::math::lu_cost::{checked_lu_cost, LuCost};
use crate::math::lu_fill::lu_factor_nnz;
use crate::matrix::BlockSparseMatrix;

pub(crate) struct NewtonMatrix {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    /// For stored block k of W (block-CSR order), the value slot of its entry (i, j) at
    /// `slots[9 k + 3 i + j]`.
    slots: Vec<usize>,
    /// For each contact, the index of its diagonal block in W's block list.
    diagonal_block: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    workspace: MemBuffer,
    /// `nnz(L) + nnz(U)` of the first successful factorization (counted once: the row pivots
    /// of later ones may differ; the count costs 0.26x-0.4x of one numeric factorization,
    /// measured on box piles of 1k and 10k contacts).
    factor_nnz: Option<usize>,
    /// The predicted cost of one factorization (from the symbolic analysis).
    cost: LuCost,
    /// Whether `numeric` holds the factors of the current values.
    factored: bool,
}

impl NewtonMatrix {
    /// The pattern of `A + B W` for block-diagonal A, B. `w` must hold every diagonal block.
    pub fn new(w: &BlockSparseMatrix) -> Result<Self, Fc3dError> {
        let nc = w.n_block_rows();
        let n = 3 * nc;
        let (row_ptr, col_idx) = (w.row_ptr(), w.col_idx());
        let n_blocks = col_idx.len();
        // Transpose the block structure: blocks of each block column, in increasing block row.
        let what = "NSN: the pattern of the Newton matrix";
        let mut col_count = try_vec(nc + 1, 0usize, what)?;
        for &b in col_idx {
            col_count[b + 1] += 1;
        }
        for b in 0..nc {
            col_count[b + 1] += col_count[b];
        }
        let mut next = try_copy(&col_count, what)?;
        let mut by_column = try_vec(n_blocks, (0usize, 0usize), what)?; // (block row, block index)
        let mut diagonal_block = try_vec(nc, usize::MAX, what)?;
        for c in 0..nc {
            for (k, &b) in col_idx
                .iter()
                .enumerate()
                .take(row_ptr[c + 1])
                .skip(row_ptr[c])
            {
                by_column[next[b]] = (c, k);
                next[b] += 1;
                if b == c {
                    diagonal_block[c] = k;
                }
            }
        }
        if let Some(c) = diagonal_block.iter().position(|&k| k == usize::MAX) {
            return Err(Fc3dError::MissingDiagonalBlock { contact: c });
        }
        let entries = n_blocks
            .checked_mul(9)
            .ok_or_else(|| Fc3dError::OutOfMemory {
                what: what.to_string(),
                bytes: usize::MAX,
            })?;
        let mut col_ptr = try_vec(0, 0usize, what)?;
        reserve(&mut col_ptr, n + 1, what)?;
        let mut row_idx = try_vec(0, 0usize, what)?;
        reserve(&mut row_idx, entries, what)?;
        let mut slots = try_vec(entries, 0usize, what)?;
        col_ptr.push(0);
        for b in 0..nc {
            let blocks = &by_column[col_count[b]..col_count[b + 1]];
            for j in 0..3 {
                for &(c, k) in blocks {
                    for i in 0..3 {
                        slots[9 * k + 3 * i + j] = row_idx.len();
                        row_idx.push(3 * c + i);
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        let nnz = row_idx.len();
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let symbolic = factorize_symbolic_lu(pattern.as_ref(), Default::default())
            .map_err(|e| Fc3dError::Unsupported(format!("sparse LU analysis failed: {e:?}")))?;
        let cost = checked_lu_cost(pattern.as_ref(), symbolic.col_perm(), "NSN: LU factors")?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let workspace = MemBuffer::try_new(req)
            .map_err(|_| Fc3dError::Unsupported("out of memory for the sparse LU".into()))?;
        Ok(NewtonMatrix {
            n,
            pattern,
            slots,
            diagonal_block,
            values: try_vec(nnz, 0.0, "NSN: the values of the Newton matrix")?,
            symbolic,
            numeric: NumericLu::new(),
            workspace,
            factor_nnz: None,
            cost,
            factored: false,
        })
    }

    #[allow(clippy::needless_range_loop)] // i, j index rows and columns of three arrays at once
    /// Fills `J = A + B (W + w_shift I)` (A, B: one 3x3 block per contact, row-major).
    pub fn fill(&mut self, w: &BlockSparseMatrix, a: &[Mat3], b: &[Mat3], w_shift: f64) {
        let (row_ptr, col_idx) = (w.row_ptr(), w.col_idx());
        for c in 0..self.diagonal_block.len() {
            let bc = &b[c];
            for k in row_ptr[c]..row_ptr[c + 1] {
                let wk = w.block(k); // column-major
                for i in 0..3 {
                    for j in 0..3 {
                        let v = bc[i][0] * wk[3 * j]
                            + bc[i][1] * wk[1 + 3 * j]
                            + bc[i][2] * wk[2 + 3 * j];
                        self.values[self.slots[9 * k + 3 * i + j]] = v;
                    }
                }
                if col_idx[k] == c {
                    for i in 0..3 {
                        for j in 0..3 {
                            self.values[self.slots[9 * k + 3 * i + j]] +=
                                a[c][i][j] + w_shift * bc[i][j];
                        }
                    }
                }
            }
        }
    }

    /// Adds `lambda D` to the filled J, D diagonal with, for contact c, the largest magnitude
    /// of J's diagonal block `J_cc` (at least 1e-12 times the largest over the contacts): the
    /// regularisation is relative to each contact's own rows, whose scales differ by orders
    /// (rho W for a sticking contact, the identity for a separating one).
    pub fn regularize(&mut self, lambda: f64) {
        let block_scale = |m: &Self, k: usize| {
            (0..9).fold(0.0_f64, |s, e| s.max(m.values[m.slots[9 * k + e]].abs()))
        };
        let largest = self
            .diagonal_block
            .iter()
            .fold(0.0_f64, |s, &k| s.max(block_scale(self, k)));
        let floor = if largest > 0.0 { 1e-12 * largest } else { 1.0 };
        for c in 0..self.diagonal_block.len() {
            let k = self.diagonal_block[c];
            let shift = lambda * block_scale(self, k).max(floor);
            for i in 0..3 {
                self.values[self.slots[9 * k + 4 * i]] += shift;
            }
        }
    }

    /// The predicted cost of one factorization.
    pub fn cost(&self) -> LuCost {
        self.cost
    }

    /// The fill of the first factorization, once one succeeded.
    pub fn factor_fill(&self) -> Option<Fill> {
        self.factor_nnz.map(|factor_nnz| Fill {
            matrix_nnz: self.values.len(),
            factor_nnz,
        })
    }

    /// Factors the current values. False when the factorization fails (a non-finite entry, a
    /// structurally singular pattern); there are then no factors to solve with.
    pub fn factor(&mut self) -> bool {
        self.factored = false;
        if !self.values.iter().all(|v| v.is_finite()) {
            return false;
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let stack = MemStack::new(&mut self.workspace);
        let lu = match self.symbolic.factorize_numeric_lu(
            &mut self.numeric,
            mat,
            Par::Seq,
            stack,
            Default::default(),
        ) {
            Ok(lu) => lu,
            Err(_) => return false,
        };
        if self.factor_nnz.is_none() {
            self.factor_nnz = lu_factor_nnz(
                self.n,
                self.pattern.col_ptr(),
                self.pattern.row_idx(),
                lu.row_perm().arrays().1,
                lu.col_perm().arrays().0,
            );
        }
        self.factored = true;
        true
    }

    /// Solves `J x = rhs` in place with the factors of the last successful
    /// [`NewtonMatrix::factor`]. False (rhs then unspecified) when there are none or the
    /// solution is not finite.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> bool {
        debug_assert_eq!(rhs.len(), self.n);
        if !self.factored {
            return false;
        }
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, self.n, 1),
            Par::Seq,
            MemStack::new(&mut self.workspace),
        );
        rhs.iter().all(|v| v.is_finite())
    }

    /// Factors the current values and solves `J x = rhs` in place.
    #[cfg(test)]
    pub fn solve(&mut self, rhs: &mut [f64]) -> bool {
        self.factor() && self.solve_in_place(rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_coupled_two_contact_system() {
        // W with an off-diagonal block in one direction only (non-symmetric pattern).
        let d0 = [4.0, 1.0, 0.0, 0.5, 3.0, 0.2, 0.0, 0.1, 2.0];
        let d1 = [5.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.3, 0.0, 6.0];
        let off = [1.0, 0.0, 0.5, 0.0, -1.0, 0.0, 0.2, 0.0, 0.7];
        let w =
            BlockSparseMatrix::new(2, 2, vec![0, 2, 3], vec![0, 1, 1], vec![d0, off, d1]).unwrap();
        let mut m = NewtonMatrix::new(&w).unwrap();
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let zero = [[0.0; 3]; 3];
        // J = 0 + I (W + 0.5 I).
        m.fill(&w, &[zero, zero], &[id, id], 0.5);
        let x = [1.0, -2.0, 0.5, 3.0, 0.25, -1.0];
        let mut rhs = vec![0.0; 6];
        let dw = crate::matrix::Delassus::SparseBlock(w.clone());
        dw.mul_add(&x, &mut rhs);
        for i in 0..6 {
            rhs[i] += 0.5 * x[i];
        }
        assert!(m.solve(&mut rhs));
        for i in 0..6 {
            assert!((rhs[i] - x[i]).abs() < 1e-12, "{rhs:?}");
        }
        // Refill with other values on the same pattern and solve again.
        m.fill(&w, &[id, id], &[zero, zero], 0.0);
        let mut rhs2 = x.to_vec();
        assert!(m.solve(&mut rhs2));
        assert_eq!(rhs2, x.to_vec());
    }

    /// The regularisation of each contact is relative to its own diagonal block of J.
    #[test]
    fn regularization_follows_each_contacts_scale() {
        let d0 = [4.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 2.0];
        let d1 = [0.5, 0.0, 0.0, 0.0, 0.25, 0.0, 0.0, 0.0, 0.125];
        let w = BlockSparseMatrix::new(2, 2, vec![0, 1, 2], vec![0, 1], vec![d0, d1]).unwrap();
        let mut m = NewtonMatrix::new(&w).unwrap();
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let zero = [[0.0; 3]; 3];
        m.fill(&w, &[zero, zero], &[id, id], 0.0);
        m.regularize(0.5);
        // J = diag(4, 3, 2, 0.5, 0.25, 0.125) + 0.5 diag(4, 4, 4, 0.5, 0.5, 0.5).
        let mut x = vec![6.0, 5.0, 4.0, 0.75, 0.5, 0.375];
        assert!(m.solve(&mut x));
        for v in x {
            assert!((v - 1.0).abs() < 1e-15, "{v}");
        }
    }

    #[test]
    fn singular_matrix_is_reported() {
        let d0 = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let w = BlockSparseMatrix::new(1, 1, vec![0, 1], vec![0], vec![d0]).unwrap();
        let mut m = NewtonMatrix::new(&w).unwrap();
        let zero = [[0.0; 3]; 3];
        m.fill(&w, &[zero], &[zero], 0.0);
        let mut rhs = vec![1.0, 1.0, 1.0];
        assert!(!m.solve(&mut rhs));
    }

    /// The fill reported for a box scene's Newton matrix is the fill of the permuted matrix
    /// faer factored: the permutations are those of `P J Q = L U` (a dense elimination of
    /// `P J Q` without pivoting keeps |L| <= 1, as partial pivoting does), its numerically
    /// nonzero factor entries are as many as counted structurally, and a block-diagonal W
    /// (isolated contacts) has no fill at all: 9 entries a contact in J, L and U.
    #[test]
    #[allow(clippy::needless_range_loop)] // a dense elimination by row and column indices
    fn reported_fill_is_that_of_the_factors() {
        use crate::scenes::{box_piles, sphere_piles, PileSpec};
        let spec = PileSpec {
            contacts: 120,
            piles: 1,
            seed: 3,
        };
        let p = box_piles(&spec).unwrap();
        let w = p.w().to_block_sparse().unwrap();
        let nc = w.n_block_rows();
        let mut m = NewtonMatrix::new(&w).unwrap();
        assert_eq!(m.factor_fill(), None);
        // J = A + B W with generic diagonal blocks.
        let a: Vec<Mat3> = (0..nc)
            .map(|c| {
                let x = 0.1 * (c % 7) as f64;
                [[1.0 + x, 0.2, 0.0], [0.1, 0.5, 0.3 - x], [0.0, x, 0.7]]
            })
            .collect();
        let b: Vec<Mat3> = (0..nc)
            .map(|c| {
                let x = 0.05 * (c % 5) as f64;
                [[0.5, x, 0.1], [0.2, 1.0, 0.0], [x, 0.3, 0.8]]
            })
            .collect();
        m.fill(&w, &a, &b, 0.0);
        m.regularize(1e-3);
        let mut rhs = vec![1.0; 3 * nc];
        assert!(m.solve(&mut rhs));
        let fill = m.factor_fill().unwrap();
        assert_eq!(fill.matrix_nnz, 9 * w.n_blocks());
        // The permutations faer used, and P J Q densely.
        let lu = LuRef::new_unchecked(&m.symbolic, &m.numeric);
        let (rows, _) = lu.row_perm().arrays();
        let (cols, _) = lu.col_perm().arrays();
        let n = 3 * nc;
        let mut dense = vec![vec![0.0; n]; n];
        let (cp, ri) = (m.pattern.col_ptr(), m.pattern.row_idx());
        for j in 0..n {
            for k in cp[j]..cp[j + 1] {
                dense[ri[k]][j] = m.values[k];
            }
        }
        let mut pjq: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| dense[rows[i]][cols[j]]).collect())
            .collect();
        let scale = pjq.iter().flatten().fold(0.0_f64, |s, v| s.max(v.abs()));
        for k in 0..n {
            let pivot = pjq[k][k];
            assert!(pivot != 0.0, "zero pivot {k}");
            for i in k + 1..n {
                let l = pjq[i][k] / pivot;
                assert!(
                    l.abs() <= 1.0 + 1e-12,
                    "|L[{i}][{k}]| = {l}: not faer's pivots"
                );
                pjq[i][k] = l;
                if l != 0.0 {
                    for j in k + 1..n {
                        pjq[i][j] -= l * pjq[k][j];
                    }
                }
            }
        }
        let numeric_nnz = pjq
            .iter()
            .flatten()
            .filter(|v| v.abs() > 1e-13 * scale)
            .count();
        eprintln!(
            "box scene, {nc} contacts: nnz(J) {}, nnz(L) + nnz(U) {} (numerically nonzero {numeric_nnz}), ratio {:.2}",
            fill.matrix_nnz,
            fill.factor_nnz,
            fill.ratio()
        );
        assert!(numeric_nnz <= fill.factor_nnz);
        assert!(numeric_nnz as f64 >= 0.95 * fill.factor_nnz as f64);
        assert!(fill.factor_nnz > fill.matrix_nnz, "a box pile fills in");

        // Isolated contacts: no fill.
        let isolated = sphere_piles(&PileSpec {
            contacts: 6,
            piles: 6,
            seed: 1,
        })
        .unwrap();
        let w = isolated.w().to_block_sparse().unwrap();
        assert_eq!(w.n_blocks(), 6);
        let mut m = NewtonMatrix::new(&w).unwrap();
        m.fill(&w, &a[..6], &b[..6], 0.0);
        let mut rhs = vec![1.0; 18];
        assert!(m.solve(&mut rhs));
        let fill = m.factor_fill().unwrap();
        assert_eq!((fill.matrix_nnz, fill.factor_nnz), (54, 54));
        assert_eq!(fill.ratio(), 1.0);
    }
}
