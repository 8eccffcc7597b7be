//! Reading `/fclib_global` and reducing it to the local form: M factored once (sparse Cholesky,
//! else LU), `W = H^T M^-1 H`, `q = H^T M^-1 f + w`.

use std::collections::{BTreeMap, BTreeSet};

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, MatMut, Side};
use hdf5_metno as hdf5;

use super::reader::Reader;
use super::sparse::SparseEntries;
use crate::alloc::{bytes_of, ensure_headroom};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

/// Right-hand sides solved together when reducing a global problem.
const SOLVE_CHUNK: usize = 32;
/// Largest relative difference between `M[i][j]` and `M[j][i]` for M to count as symmetric.
const SYMMETRY_TOLERANCE: f64 = 1e-12;
/// Largest normwise backward error `|M x - b| / (|M| |x| + |b|)` (infinity norms) accepted from a
/// solve with M; Cholesky and LU of a non-singular M give about `ndof * 1e-16`.
const BACKWARD_ERROR_TOLERANCE: f64 = 1e-8;

impl Reader {
    pub(super) fn read_global(
        &self,
        g: &hdf5::Group,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let gp = "/fclib_global";
        self.spacedim(g, gp)?;
        if g.link_exists("G") {
            return Err(Fc3dError::Unsupported(format!(
                "{}: {gp}/G present: global problems with bilateral constraints (G, b) are not \
                 supported",
                self.label
            )));
        }
        let m = self.matrix(g, gp, "M")?;
        if m.nrows != m.ncols {
            return Err(self.invalid(format!(
                "{gp}/M is {}x{}, expected a square matrix",
                m.nrows, m.ncols
            )));
        }
        let ndof = m.nrows;
        let h = self.matrix(g, gp, "H")?;
        if h.nrows != ndof {
            return Err(self.invalid(format!("{gp}/H has {} rows but M has {ndof}", h.nrows)));
        }
        let nc = self.contacts(&format!("{gp}/H"), h.ncols)?;
        let vp = format!("{gp}/vectors");
        let v = self.group(g, gp, "vectors")?;
        let f = self.floats(&v, &vp, "f")?;
        self.check_len(&format!("{vp}/f"), f.len(), ndof, "the size of M")?;
        let w = self.floats(&v, &vp, "w")?;
        self.check_len(&format!("{vp}/w"), w.len(), h.ncols, "the columns of H")?;
        let mu = self.floats(&v, &vp, "mu")?;
        self.check_len(&format!("{vp}/mu"), mu.len(), nc, "one per contact")?;
        let (w_entries, q) = reduce_global(ndof, &m.entries, &h, &f, &w)
            .map_err(|e| self.invalid(format!("reducing the global problem: {e}")))?;
        self.problem(h.ncols, &w_entries, q, mu)
    }
}

/// `(row, column, value)` entries of a sparse matrix.
type Entries = Vec<(usize, usize, f64)>;

/// A factorization of M.
pub(super) enum MassFactor {
    Cholesky(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
}

impl MassFactor {
    fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        match self {
            MassFactor::Cholesky(f) => f.solve_in_place(rhs),
            MassFactor::Lu(f) => f.solve_in_place(rhs),
        }
    }
}

/// M (square, `ndof`) with duplicates summed, factored, and what the backward-error check needs.
pub(super) struct MassSolver {
    ndof: usize,
    /// Summed entries `(row, col, value)`.
    entries: Vec<(usize, usize, f64)>,
    /// Infinity norm of M (largest absolute row sum).
    norm_inf: f64,
    pub(super) factor: MassFactor,
}

impl MassSolver {
    pub(super) fn new(ndof: usize, raw: &[(usize, usize, f64)]) -> Result<Self, String> {
        let mut summed = BTreeMap::<(usize, usize), f64>::new();
        for &(i, j, v) in raw {
            *summed.entry((i, j)).or_insert(0.0) += v;
        }
        let entries: Vec<(usize, usize, f64)> = summed
            .iter()
            .filter(|(_, &v)| v != 0.0)
            .map(|(&(i, j), &v)| (i, j, v))
            .collect();
        let mut row_sums = vec![0.0; ndof];
        let mut amax = 0.0_f64;
        for &(i, _, v) in &entries {
            row_sums[i] += v.abs();
            amax = amax.max(v.abs());
        }
        let norm_inf = row_sums.iter().copied().fold(0.0, f64::max);
        let symmetric = entries.iter().all(|&(i, j, v)| {
            let t = summed.get(&(j, i)).copied().unwrap_or(0.0);
            (v - t).abs() <= SYMMETRY_TOLERANCE * amax
        });
        let triplets: Vec<Triplet<usize, usize, f64>> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let mat = SparseColMat::<usize, f64>::try_new_from_triplets(ndof, ndof, &triplets)
            .map_err(|e| format!("M cannot be stored by faer: {e:?}"))?;
        let cholesky = if symmetric {
            mat.sp_cholesky(Side::Lower).ok()
        } else {
            None
        };
        let factor = match cholesky {
            Some(llt) => MassFactor::Cholesky(llt),
            None => MassFactor::Lu(Box::new(
                mat.sp_lu()
                    .map_err(|e| format!("M is singular (sparse LU: {e:?})"))?,
            )),
        };
        Ok(MassSolver {
            ndof,
            entries,
            norm_inf,
            factor,
        })
    }

    /// Solves `M X = B` in place (`x` holds B on entry), checking every column is finite and has
    /// a small normwise backward error.
    pub(super) fn solve(&self, x: &mut Mat<f64>) -> Result<(), String> {
        let b = x.clone();
        self.factor.solve_in_place(x.as_mut());
        let k = x.ncols();
        let mut residual = b.clone();
        for &(i, j, v) in &self.entries {
            for c in 0..k {
                residual[(i, c)] -= v * x[(j, c)];
            }
        }
        for c in 0..k {
            let xc = x.col_as_slice(c);
            if let Some(i) = xc.iter().position(|v| !v.is_finite()) {
                return Err(format!(
                    "M is singular: solving with it gave x[{i}] = {}",
                    xc[i]
                ));
            }
            let inf = |s: &[f64]| s.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            let r = inf(residual.col_as_slice(c));
            let scale = self.norm_inf * inf(xc) + inf(b.col_as_slice(c));
            if r > BACKWARD_ERROR_TOLERANCE * scale {
                return Err(format!(
                    "M is numerically singular: a solve with it left a residual {r:e} for a \
                     scale {scale:e}"
                ));
            }
        }
        Ok(())
    }
}

/// `W = H^T M^-1 H` as `(row, col, value)` entries (exact zeros left out) and
/// `q = H^T M^-1 f + w`. Errors are messages about M.
pub(super) fn reduce_global(
    ndof: usize,
    m_entries: &[(usize, usize, f64)],
    h: &SparseEntries,
    f: &[f64],
    w: &[f64],
) -> Result<(Entries, Vec<f64>), String> {
    let n = h.ncols;
    // Work below without a fallible path (faer's matrices, per-row lists, a map of M's entries):
    // x, its copy and the residual of SOLVE_CHUNK columns, the row sums, the lists of H by row
    // and column, the summed entries of M.
    let work = bytes_of(ndof, 8 * (3 * SOLVE_CHUNK + 1) + 24)
        .saturating_add(bytes_of(n, 24 + 8))
        .saturating_add(bytes_of(h.entries.len(), 2 * 16))
        .saturating_add(bytes_of(m_entries.len(), 128));
    ensure_headroom(work, "reducing the global problem").map_err(|e| e.to_string())?;
    let solver = MassSolver::new(ndof, m_entries)?;
    debug_assert_eq!(solver.ndof, ndof);
    let mut h_cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut h_rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); ndof];
    for &(i, j, v) in &h.entries {
        if v != 0.0 {
            h_cols[j].push((i, v));
            h_rows[i].push((j, v));
        }
    }
    // y = H^T x for a dense x, visiting only the rows of H where x is non-zero.
    let mut acc = vec![0.0; n];
    let mut touched = BTreeSet::new();
    let mut transpose_product = |x: &[f64], out: &mut dyn FnMut(usize, f64)| {
        touched.clear();
        for (r, &xr) in x.iter().enumerate() {
            if xr != 0.0 {
                for &(c, v) in &h_rows[r] {
                    acc[c] += v * xr;
                    touched.insert(c);
                }
            }
        }
        for &c in touched.iter() {
            out(c, acc[c]);
            acc[c] = 0.0;
        }
    };

    let mut w_entries = Vec::new();
    let mut start = 0;
    while start < n {
        let k = SOLVE_CHUNK.min(n - start);
        let mut x = Mat::<f64>::zeros(ndof, k);
        for jj in 0..k {
            for &(r, v) in &h_cols[start + jj] {
                x[(r, jj)] += v;
            }
        }
        solver.solve(&mut x)?;
        for jj in 0..k {
            let j = start + jj;
            transpose_product(x.col_as_slice(jj), &mut |c, v| {
                if v != 0.0 {
                    w_entries.push((c, j, v));
                }
            });
        }
        start += k;
    }

    let mut y = Mat::<f64>::zeros(ndof, 1);
    y.col_as_slice_mut(0).copy_from_slice(f);
    solver.solve(&mut y)?;
    let mut q = w.to_vec();
    transpose_product(y.col_as_slice(0), &mut |c, v| q[c] += v);
    Ok((w_entries, q))
}
