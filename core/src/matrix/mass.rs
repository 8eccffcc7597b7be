//! The matrix M of a global problem (a mass matrix, or an FE code's stiffness-like iteration
//! matrix: square and invertible, symmetric or not) factored once for every later solve.
//!
//! M is usually block diagonal, one block per body (DEM, multibody) or per element group: the
//! factorization finds the blocks itself, as the connected components of M's pattern (so a host
//! need not order its unknowns body by body), and factors each with a dense LU with partial
//! pivoting when the largest is at most [`DENSE_BLOCK_MAX`] unknowns. A general sparse M is
//! factored with faer's sparse LU ([`SparseLu`]). M itself is never modified.

use crate::error::{try_vec, Fc3dError};
use crate::math::sparse_lu::SparseLu;
use crate::matrix::CsrMatrix;

/// Largest block (unknowns of one connected component of M's pattern) factored densely; past
/// it the whole of M goes to the sparse LU. A dense LU of `s` unknowns costs `2 s^3 / 3` flops:
/// at 96 about 0.6 Mflop a block, below what the sparse LU's analysis costs per block.
pub const DENSE_BLOCK_MAX: usize = 96;

/// Largest normwise backward error `|M x - b| / (|M| |x| + |b|)` (infinity norms) accepted from
/// the check solve made when M is factored: a non-singular M gives about `n * 1e-16`.
const BACKWARD_ERROR_TOLERANCE: f64 = 1e-8;

/// M's LU factorization (block-diagonal dense or general sparse).
#[derive(Debug)]
pub struct MassFactor {
    n: usize,
    kind: Kind,
}

#[derive(Debug)]
enum Kind {
    Blocks(BlockLu),
    Sparse(Box<SparseLu>),
}

/// The diagonal blocks of M (after a symmetric permutation), each LU-factored in place.
#[derive(Debug)]
struct BlockLu {
    /// The unknowns of block k are `dofs[offsets[k]..offsets[k + 1]]` (increasing).
    dofs: Vec<usize>,
    offsets: Vec<usize>,
    /// Block k's `s x s` factors (row-major, L unit lower below the diagonal, U on and above)
    /// start at `factor_offsets[k]`.
    factor_offsets: Vec<usize>,
    factors: Vec<f64>,
    /// Row interchanges: at step i of block k, row i was swapped with row `pivots[offsets[k] + i]`
    /// (local indices).
    pivots: Vec<usize>,
    /// A block's right-hand side gathered (length of the largest block).
    work: Vec<f64>,
}

impl MassFactor {
    /// Factors a square M. Fails on a non-square, singular or numerically singular M.
    pub fn new(m: &CsrMatrix) -> Result<Self, Fc3dError> {
        let n = m.nrows();
        if m.ncols() != n {
            return Err(Fc3dError::dims(
                format!("M is {}x{}: M must be square", m.nrows(), m.ncols()),
                n,
                m.ncols(),
            ));
        }
        let (dofs, offsets) = connected_blocks(m)?;
        let largest = offsets.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0);
        let kind = if largest <= DENSE_BLOCK_MAX {
            Kind::Blocks(BlockLu::new(m, dofs, offsets)?)
        } else {
            Kind::Sparse(Box::new(sparse_factor(m)?))
        };
        let mut factor = MassFactor { n, kind };
        factor.check_backward_error(m)?;
        Ok(factor)
    }

    pub fn size(&self) -> usize {
        self.n
    }

    /// Whether M was factored block by block (and the blocks' unknowns, `dofs` and `offsets`
    /// as in [`MassFactor::blocks`]).
    pub fn is_block_diagonal(&self) -> bool {
        matches!(self.kind, Kind::Blocks(_))
    }

    /// The diagonal blocks of a block-diagonal M: block k holds the unknowns
    /// `dofs[offsets[k]..offsets[k + 1]]`. `None` for a general sparse M.
    pub fn blocks(&self) -> Option<(&[usize], &[usize])> {
        match &self.kind {
            Kind::Blocks(b) => Some((&b.dofs, &b.offsets)),
            Kind::Sparse(_) => None,
        }
    }

    /// Solves `M_k y = x` in place for block k of a block-diagonal M, `x` in the block's local
    /// numbering. Panics for a general sparse M.
    pub fn solve_block_in_place(&self, k: usize, x: &mut [f64]) {
        match &self.kind {
            Kind::Blocks(b) => b.solve_block(k, x),
            Kind::Sparse(_) => panic!("solve_block_in_place on a general sparse M"),
        }
    }

    /// `x <- M^-1 x`. Allocates nothing.
    pub fn solve_in_place(&mut self, x: &mut [f64]) {
        debug_assert_eq!(x.len(), self.n);
        match &mut self.kind {
            Kind::Blocks(b) => b.solve(x),
            Kind::Sparse(lu) => lu.solve_in_place(x),
        }
    }

    /// A solve of `M x = M 1` must give back `x = 1` to within a small backward error: the
    /// pivots' threshold catches exact singularity, this the numerical kind.
    fn check_backward_error(&mut self, m: &CsrMatrix) -> Result<(), Fc3dError> {
        let n = self.n;
        let ones = try_vec(n, 1.0, "M's check")?;
        let mut b = try_vec(n, 0.0, "M's check")?;
        m.mul_add(&ones, &mut b);
        let mut x = b.clone();
        self.solve_in_place(&mut x);
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return Err(Fc3dError::Unsupported(format!(
                "M is singular: solving with it gave x[{i}] = {}",
                x[i]
            )));
        }
        let mut residual: Vec<f64> = b.iter().map(|v| -v).collect();
        m.mul_add(&x, &mut residual);
        let inf = |s: &[f64]| s.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let mut row_sums = vec![0.0_f64; n];
        m.for_each_entry(|i, _, v| row_sums[i] += v.abs());
        let scale = inf(&row_sums) * inf(&x) + inf(&b);
        let r = inf(&residual);
        if r > BACKWARD_ERROR_TOLERANCE * scale {
            return Err(Fc3dError::Unsupported(format!(
                "M is numerically singular: a solve with it left a residual {r:e} for a scale \
                 {scale:e}"
            )));
        }
        Ok(())
    }
}

/// The connected components of M's pattern (non-zero entries), as `(dofs, offsets)`: blocks in
/// the order of their smallest unknown, unknowns increasing within a block.
fn connected_blocks(m: &CsrMatrix) -> Result<(Vec<usize>, Vec<usize>), Fc3dError> {
    let n = m.nrows();
    let mut parent = try_vec(n, 0usize, "M's blocks")?;
    parent.iter_mut().enumerate().for_each(|(i, p)| *p = i);
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    m.for_each_entry(|i, j, v| {
        if v != 0.0 && i != j {
            let (a, b) = (root(&mut parent, i), root(&mut parent, j));
            // The smaller index is the root: a component is named by its smallest unknown.
            if a < b {
                parent[b] = a;
            } else if b < a {
                parent[a] = b;
            }
        }
    });
    // Count per root, then place the unknowns in increasing order.
    let mut count = try_vec(n + 1, 0usize, "M's blocks")?;
    let mut block_of_root = try_vec(n, usize::MAX, "M's blocks")?;
    let mut n_blocks = 0;
    for i in 0..n {
        let r = root(&mut parent, i);
        if block_of_root[r] == usize::MAX {
            block_of_root[r] = n_blocks;
            n_blocks += 1;
        }
        count[block_of_root[r] + 1] += 1;
    }
    count.truncate(n_blocks + 1);
    for k in 0..n_blocks {
        count[k + 1] += count[k];
    }
    let offsets = count.clone();
    let mut next = count;
    let mut dofs = try_vec(n, 0usize, "M's blocks")?;
    for i in 0..n {
        let k = block_of_root[root(&mut parent, i)];
        dofs[next[k]] = i;
        next[k] += 1;
    }
    Ok((dofs, offsets))
}

impl BlockLu {
    fn new(m: &CsrMatrix, dofs: Vec<usize>, offsets: Vec<usize>) -> Result<Self, Fc3dError> {
        let n = m.nrows();
        let n_blocks = offsets.len() - 1;
        let mut factor_offsets = try_vec(n_blocks + 1, 0usize, "M's factors")?;
        for k in 0..n_blocks {
            let s = offsets[k + 1] - offsets[k];
            factor_offsets[k + 1] = factor_offsets[k] + s * s;
        }
        let mut factors = try_vec(factor_offsets[n_blocks], 0.0, "M's factors")?;
        let mut pivots = try_vec(n, 0usize, "M's factors")?;
        // Local index of every unknown within its block.
        let mut local = try_vec(n, 0usize, "M's factors")?;
        for k in 0..n_blocks {
            for (l, &d) in dofs[offsets[k]..offsets[k + 1]].iter().enumerate() {
                local[d] = l;
            }
        }
        let (row_ptr, col_idx, values) = (m.row_ptr(), m.col_idx(), m.values());
        let mut largest = 0;
        for k in 0..n_blocks {
            let block_dofs = &dofs[offsets[k]..offsets[k + 1]];
            let s = block_dofs.len();
            largest = largest.max(s);
            let a = &mut factors[factor_offsets[k]..factor_offsets[k + 1]];
            for (li, &i) in block_dofs.iter().enumerate() {
                // A stored zero may join unknowns of two blocks (the blocks are the components
                // of the non-zero pattern): it adds nothing, and its column is not in this block.
                for p in (row_ptr[i]..row_ptr[i + 1]).filter(|&p| values[p] != 0.0) {
                    a[li * s + local[col_idx[p]]] += values[p];
                }
            }
            lu_in_place(a, s, &mut pivots[offsets[k]..offsets[k + 1]]).map_err(|row| {
                Fc3dError::Unsupported(format!(
                    "M is singular: its diagonal block of unknowns {}..={} (after grouping by \
                     coupling) has no pivot in row {}",
                    block_dofs[0],
                    block_dofs[s - 1],
                    block_dofs[row]
                ))
            })?;
        }
        Ok(BlockLu {
            dofs,
            offsets,
            factor_offsets,
            factors,
            pivots,
            work: try_vec(largest, 0.0, "M's factors")?,
        })
    }

    fn solve_block(&self, k: usize, x: &mut [f64]) {
        let s = self.offsets[k + 1] - self.offsets[k];
        lu_solve(
            &self.factors[self.factor_offsets[k]..self.factor_offsets[k + 1]],
            s,
            &self.pivots[self.offsets[k]..self.offsets[k + 1]],
            x,
        );
    }

    fn solve(&mut self, x: &mut [f64]) {
        for k in 0..self.offsets.len() - 1 {
            let block_dofs = &self.dofs[self.offsets[k]..self.offsets[k + 1]];
            let s = block_dofs.len();
            if s == 1 {
                // A diagonal M: one division an unknown.
                x[block_dofs[0]] /= self.factors[self.factor_offsets[k]];
                continue;
            }
            let mut work = std::mem::take(&mut self.work);
            for (w, &d) in work.iter_mut().zip(block_dofs) {
                *w = x[d];
            }
            self.solve_block(k, &mut work[..s]);
            for (w, &d) in work.iter().zip(block_dofs) {
                x[d] = *w;
            }
            self.work = work;
        }
    }
}

/// The sparse LU of a general M.
fn sparse_factor(m: &CsrMatrix) -> Result<SparseLu, Fc3dError> {
    let n = m.nrows();
    let mut positions = Vec::with_capacity(m.nnz() + n);
    m.for_each_entry(|i, j, _| positions.push((i, j)));
    // A structural diagonal: faer's LU pivots within the pattern.
    positions.extend((0..n).map(|i| (i, i)));
    let (mut lu, slots) = SparseLu::from_positions(n, &positions, "M")?;
    let values = lu.values_mut();
    let mut k = 0;
    m.for_each_entry(|_, _, v| {
        values[slots[k]] += v;
        k += 1;
    });
    lu.factor()
        .map_err(|e| Fc3dError::Unsupported(format!("M is singular: {e}")))?;
    Ok(lu)
}

/// LU with partial pivoting of the row-major `s x s` matrix `a`, in place. Fails with the row
/// of the first pivot that is zero or below `s * eps` times the block's largest entry.
fn lu_in_place(a: &mut [f64], s: usize, pivots: &mut [usize]) -> Result<(), usize> {
    let amax = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let threshold = s as f64 * f64::EPSILON * amax;
    for k in 0..s {
        let p = (k..s)
            .max_by(|&i, &j| a[i * s + k].abs().total_cmp(&a[j * s + k].abs()))
            .expect("k < s");
        pivots[k] = p;
        // A NaN pivot fails too.
        if a[p * s + k].abs().partial_cmp(&threshold) != Some(std::cmp::Ordering::Greater) {
            return Err(k);
        }
        if p != k {
            for j in 0..s {
                a.swap(k * s + j, p * s + j);
            }
        }
        let pivot = a[k * s + k];
        for i in k + 1..s {
            let l = a[i * s + k] / pivot;
            a[i * s + k] = l;
            if l != 0.0 {
                for j in k + 1..s {
                    a[i * s + j] -= l * a[k * s + j];
                }
            }
        }
    }
    Ok(())
}

/// Solves `A x = b` in place from [`lu_in_place`]'s factors.
fn lu_solve(a: &[f64], s: usize, pivots: &[usize], x: &mut [f64]) {
    for (k, &p) in pivots.iter().enumerate().take(s) {
        x.swap(k, p);
    }
    for i in 1..s {
        let mut t = x[i];
        for j in 0..i {
            t -= a[i * s + j] * x[j];
        }
        x[i] = t;
    }
    for i in (0..s).rev() {
        let mut t = x[i];
        for j in i + 1..s {
            t -= a[i * s + j] * x[j];
        }
        x[i] = t / a[i * s + i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn residual(m: &CsrMatrix, x: &[f64], b: &[f64]) -> f64 {
        let mut r: Vec<f64> = b.iter().map(|v| -v).collect();
        m.mul_add(x, &mut r);
        r.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
    }

    #[test]
    fn stored_zeros_between_blocks_are_ignored() {
        // A host's sparse M (scipy, a FE assembly) may store zeros outside the blocks.
        let m = CsrMatrix::from_csr(
            3,
            3,
            &[0, 2, 3, 5],
            &[0, 1, 1, 0, 2],
            &[2.0, 0.0, 4.0, 0.0, 8.0],
        )
        .unwrap();
        let mut f = MassFactor::new(&m).unwrap();
        assert_eq!(f.blocks().unwrap().1, &[0, 1, 2, 3]);
        let mut x = vec![2.0, 4.0, 8.0];
        f.solve_in_place(&mut x);
        assert_eq!(x, [1.0, 1.0, 1.0]);
    }

    #[test]
    fn finds_interleaved_blocks_and_solves_them() {
        // Unknowns {0, 2} and {1, 3} are coupled, 4 alone; the blocks are not symmetric.
        let m = CsrMatrix::from_triplets(
            5,
            5,
            &[
                (0, 0, 2.0),
                (0, 2, 1.0),
                (2, 0, -1.0),
                (2, 2, 3.0),
                (1, 1, 0.0),
                (1, 3, 4.0),
                (3, 1, 5.0),
                (3, 3, 1.0),
                (4, 4, 7.0),
            ],
        )
        .unwrap();
        let mut f = MassFactor::new(&m).unwrap();
        let (dofs, offsets) = f.blocks().unwrap();
        assert_eq!(dofs, &[0, 2, 1, 3, 4]);
        assert_eq!(offsets, &[0, 2, 4, 5]);
        let b = [1.0, -2.0, 0.5, 3.0, 14.0];
        let mut x = b;
        f.solve_in_place(&mut x);
        assert!(residual(&m, &x, &b) < 1e-14, "{x:?}");
        assert_eq!(x[4], 2.0);
    }

    #[test]
    fn a_large_connected_m_goes_to_the_sparse_lu() {
        // A tridiagonal, non-symmetric M of 200 unknowns: one block above DENSE_BLOCK_MAX.
        let n = 200;
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i, i, 4.0));
            if i + 1 < n {
                t.push((i, i + 1, 1.0));
                t.push((i + 1, i, -0.5));
            }
        }
        let m = CsrMatrix::from_triplets(n, n, &t).unwrap();
        let mut f = MassFactor::new(&m).unwrap();
        assert!(!f.is_block_diagonal());
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        f.solve_in_place(&mut x);
        assert!(residual(&m, &x, &b) < 1e-13);
    }

    #[test]
    fn singular_m_is_refused_with_a_message() {
        let m = CsrMatrix::from_triplets(
            3,
            3,
            &[
                (0, 0, 1.0),
                (0, 1, 2.0),
                (1, 0, 2.0),
                (1, 1, 4.0),
                (2, 2, 1.0),
            ],
        )
        .unwrap();
        let e = MassFactor::new(&m).unwrap_err().to_string();
        assert!(e.contains("singular"), "{e}");
        let empty_row = CsrMatrix::from_triplets(2, 2, &[(0, 0, 1.0)]).unwrap();
        assert!(MassFactor::new(&empty_row).is_err());
        let not_square = CsrMatrix::from_triplets(2, 3, &[(0, 0, 1.0)]).unwrap();
        assert!(MassFactor::new(&not_square).is_err());
    }
}
