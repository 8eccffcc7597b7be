//! What a sparse LU factorization will cost, predicted from the symbolic analysis before the
//! numeric factorization starts: a factorization cannot be interrupted, so a family under a
//! time budget (ADMM, NSN, PROX through NSN) asks first whether it can end in time and whether
//! its factors fit in memory.
//!
//! faer factors `A Q` (Q: its COLAMD column order) with partial row pivoting. The matrices
//! factored here (`W + rho I`, NSN's Newton matrix) have a structurally symmetric pattern and
//! are rarely pivoted off the diagonal, so the prediction is the factorization without row
//! pivoting: `L` and `U^T` with the pattern of the Cholesky factor of `Q^T (A + A^T) Q`, whose
//! column counts `c_j` the symbolic Cholesky analysis gives in near-linear time. Factor entries
//! `sum_j (2 c_j - 1)` and flops `sum_j 2 c_j^2` (pivot column `j` updates a `c_j x c_j`
//! block, a multiply and an add each). Pivoting away from the diagonal adds fill (the
//! prediction is then low: measured 0.5x-1x of faer's factors on generated piles, see
//! [`FLOPS_PER_SECOND`]); the duration is the flops over a rate taken above the fastest one
//! measured, so that a factorization is refused only when even that rate could not end it in
//! time.

use std::time::Duration;

use crate::error::Fc3dError;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::simplicial::{
    prefactorize_symbolic_cholesky, prefactorize_symbolic_cholesky_scratch,
};
use faer::sparse::SymbolicSparseColMatRef;

/// Predicted flops per second of faer's sparse LU (sequential), used to turn
/// [`LuCost::flops`] into a duration. Measured with
/// `cargo run --release -p fc3d-core --example lu_cost -- 500 1000 2000 5000 10000` on this
/// project's machine (2 cores shared with other jobs, load average about 7, Dec. 2026) on
/// generated sphere piles (`W + I`; the predicted factor entries equal faer's to within 0.1%,
/// no off-diagonal pivoting): 3.2e9 flops/s at 500 contacts rising to 8.2e9 at 10^4 (larger
/// supernodes); 20k contacts in 4 piles: 6.1e9. 1e10 is above every measured rate (1.2x the
/// fastest): the predicted duration is shorter than the factorizations measured, so a
/// factorization is refused only when it would have overrun the budget on this machine (an
/// idle machine may be faster by up to the load factor, and then a factorization that would
/// just have fitted is refused).
pub const FLOPS_PER_SECOND: f64 = 1e10;

/// Seconds per stored entry of W for what comes before a sparse factorization and cannot be
/// interrupted: assembling the column-compressed matrix (ADMM's `W + rho I`, NSN's Newton
/// matrix), faer's symbolic LU (COLAMD ordering and symbolic factorization) and
/// [`checked_lu_cost`]'s own symbolic Cholesky. Measured on this project's machine (load about 3,
/// Dec. 2026) as the time ADMM and NSN-AC took to stop out of time before their first
/// factorization (`fc3d solve --solver ADMM --tol 1e-4 --budget 1s gen:contacts=N,piles=4,seed=1`,
/// the factorization refused by [`LuCost::ends_by`]): 1.7e-7 s per entry at 10^4 contacts
/// (0.28 s, 1.7e6 entries), 2.0e-7 at 3·10^4 (1.09 s), 2.7e-7 at 10^5 (5.1 s, 1.9e7 entries);
/// the analysis alone (`cargo run --release -p fc3d-core --example lu_cost -- predict piles=4
/// ...`) 8.1e-8 to 1.56e-7. 1e-7 is below every measured set-up rate: a set-up is refused only
/// when it would have overrun on a machine up to 1.7x faster than this one.
pub const ANALYSIS_SECONDS_PER_ENTRY: f64 = 1e-7;

/// Whether the set-up before a factorization (assembly and analysis) of a W of `stored_entries`
/// entries, started now, is predicted to end by `deadline` (always without one); see [`ANALYSIS_SECONDS_PER_ENTRY`].
pub fn analysis_ends_by(stored_entries: usize, deadline: Option<std::time::Instant>) -> bool {
    let seconds = stored_entries as f64 * ANALYSIS_SECONDS_PER_ENTRY;
    ends_by(
        Duration::try_from_secs_f64(seconds).unwrap_or(Duration::MAX),
        deadline,
    )
}

/// Whether work of `duration` started now ends by `deadline` (always without one; never when
/// the end is past what the clock can hold).
fn ends_by(duration: Duration, deadline: Option<std::time::Instant>) -> bool {
    deadline.is_none_or(|d| {
        std::time::Instant::now()
            .checked_add(duration)
            .is_some_and(|end| end <= d)
    })
}

/// The predicted cost of one numeric LU factorization.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LuCost {
    /// Upper bound of `nnz(L) + nnz(U)` (the diagonal counted once).
    pub factor_entries: f64,
    /// Upper bound of the floating-point operations.
    pub flops: f64,
}

impl LuCost {
    /// The factorization's duration at [`FLOPS_PER_SECOND`].
    pub fn duration(&self) -> Duration {
        Duration::try_from_secs_f64(self.flops / FLOPS_PER_SECOND).unwrap_or(Duration::MAX)
    }

    /// Whether a factorization started now is predicted to end by `deadline` (always without
    /// one).
    pub fn ends_by(&self, deadline: Option<std::time::Instant>) -> bool {
        ends_by(self.duration(), deadline)
    }

    /// Memory the factors need: a value and a row index per entry.
    pub fn bytes(&self) -> f64 {
        self.factor_entries * (std::mem::size_of::<f64>() + std::mem::size_of::<usize>()) as f64
    }

    /// Whether the factors cannot fit in the memory the system says is available
    /// (`MemAvailable` of `/proc/meminfo`; never on systems without it).
    pub fn exceeds_available_memory(&self) -> bool {
        available_memory().is_some_and(|available| self.bytes() > available as f64)
    }
}

/// [`predict_lu_cost`], then the check every factorizing family makes before its first
/// numeric factorization: an [`Fc3dError::OutOfMemory`] naming `what` when the prediction's
/// work arrays cannot be allocated or the factors would not fit in the available memory. The
/// caller compares [`LuCost::duration`] with its deadline.
pub fn checked_lu_cost(
    a: SymbolicSparseColMatRef<'_, usize>,
    col_perm: PermRef<'_, usize>,
    what: &str,
) -> Result<LuCost, Fc3dError> {
    let n = a.ncols();
    let cost = predict_lu_cost(a, col_perm).ok_or_else(|| Fc3dError::OutOfMemory {
        what: format!("{what} (analysis)"),
        bytes: n.saturating_add(a.compute_nnz()).saturating_mul(3 * 8),
    })?;
    if cost.exceeds_available_memory() {
        return Err(Fc3dError::OutOfMemory {
            what: format!("{what} (predicted from the symbolic analysis)"),
            bytes: cost.bytes() as usize,
        });
    }
    Ok(cost)
}

/// Predicts the cost of factoring the `n x n` matrix of pattern `a` in the column order
/// `col_perm` (faer's `SymbolicLu::col_perm`). `None` when the work arrays (a few vectors of
/// `n` and a permuted copy of the pattern) cannot be allocated.
pub fn predict_lu_cost(
    a: SymbolicSparseColMatRef<'_, usize>,
    col_perm: PermRef<'_, usize>,
) -> Option<LuCost> {
    let n = a.ncols();
    if a.nrows() != n {
        return None;
    }
    // The upper triangle of Q^T (A + A^T) Q, column by column (repeats are harmless).
    let (col_ptr, row_idx) = (a.col_ptr(), a.row_idx());
    let position = col_perm.arrays().1;
    let mut b_ptr = zeros(n + 1)?;
    for j in 0..n {
        for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
            b_ptr[position[i].max(position[j]) + 1] += 1;
        }
    }
    for j in 0..n {
        b_ptr[j + 1] += b_ptr[j];
    }
    let mut b_idx = zeros(b_ptr[n])?;
    let mut next = b_ptr.clone();
    for j in 0..n {
        for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
            let (pi, pj) = (position[i], position[j]);
            let (row, col) = (pi.min(pj), pi.max(pj));
            b_idx[next[col]] = row;
            next[col] += 1;
        }
    }
    drop(next);
    let b = SymbolicSparseColMatRef::new_unsorted_checked(n, n, &b_ptr, None, &b_idx);
    let mut etree = vec_of(n, 0isize)?;
    let mut counts = zeros(n)?;
    let mut buffer =
        MemBuffer::try_new(prefactorize_symbolic_cholesky_scratch::<usize>(n, b_ptr[n])).ok()?;
    prefactorize_symbolic_cholesky(&mut etree, &mut counts, b, MemStack::new(&mut buffer));
    let (mut factor_entries, mut flops) = (0.0, 0.0);
    for &c in &counts {
        let c = c as f64;
        factor_entries += 2.0 * c - 1.0;
        flops += 2.0 * c * c;
    }
    Some(LuCost {
        factor_entries,
        flops,
    })
}

fn zeros(n: usize) -> Option<Vec<usize>> {
    vec_of(n, 0)
}

fn vec_of<T: Clone>(n: usize, value: T) -> Option<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).ok()?;
    v.resize(n, value);
    Some(v)
}

/// `MemAvailable` of `/proc/meminfo`, in bytes.
fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::lu::factorize_symbolic_lu;
    use faer::sparse::SymbolicSparseColMat;

    fn pattern(n: usize, entries: &[(usize, usize)]) -> SymbolicSparseColMat<usize> {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(i, j) in entries {
            cols[j].push(i);
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for mut c in cols {
            c.sort_unstable();
            c.dedup();
            row_idx.extend(c);
            col_ptr.push(row_idx.len());
        }
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx)
    }

    #[test]
    fn an_analysis_is_refused_only_when_it_cannot_end_in_time() {
        use std::time::Instant;
        // 1e6 entries: 0.1 s predicted.
        assert!(analysis_ends_by(1_000_000, None));
        assert!(analysis_ends_by(
            1_000_000,
            Some(Instant::now() + Duration::from_secs(1))
        ));
        assert!(!analysis_ends_by(
            1_000_000,
            Some(Instant::now() + Duration::from_millis(10))
        ));
        assert!(!analysis_ends_by(1, Some(Instant::now())));
        assert!(!analysis_ends_by(
            usize::MAX,
            Some(Instant::now() + Duration::from_secs(1))
        ));
    }

    #[test]
    fn a_diagonal_matrix_costs_its_diagonal_and_a_dense_one_n_cubed() {
        let n = 40;
        let diagonal: Vec<_> = (0..n).map(|i| (i, i)).collect();
        let p = pattern(n, &diagonal);
        let symbolic = factorize_symbolic_lu(p.as_ref(), Default::default()).unwrap();
        let cost = predict_lu_cost(p.as_ref(), symbolic.col_perm()).unwrap();
        assert_eq!(cost.factor_entries, n as f64);
        assert_eq!(cost.flops, 2.0 * n as f64);

        let dense: Vec<_> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
        let p = pattern(n, &dense);
        let symbolic = factorize_symbolic_lu(p.as_ref(), Default::default()).unwrap();
        let cost = predict_lu_cost(p.as_ref(), symbolic.col_perm()).unwrap();
        // Column counts n, n-1, ..., 1.
        assert_eq!(cost.factor_entries, (n * n) as f64);
        let sum_sq: usize = (1..=n).map(|c| c * c).sum();
        assert_eq!(cost.flops, 2.0 * sum_sq as f64);
    }

    #[test]
    fn the_prediction_bounds_faer_s_factors() {
        // A banded pattern with a few long-range couplings, diagonally dominant.
        let n: usize = 300;
        let mut entries = Vec::new();
        for i in 0..n {
            for j in i.saturating_sub(4)..(i + 5).min(n) {
                entries.push((i, j));
            }
            entries.push((i, (i * 37) % n));
            entries.push(((i * 37) % n, i));
        }
        let p = pattern(n, &entries);
        // Diagonal entries 100, the others 1..7.
        let column_of = |k: usize| p.col_ptr().partition_point(|&start| start <= k) - 1;
        let values: Vec<f64> = (0..p.row_idx().len())
            .map(|k| match p.row_idx()[k] == column_of(k) {
                true => 100.0,
                false => 1.0 + (k % 7) as f64,
            })
            .collect();
        let symbolic = factorize_symbolic_lu(p.as_ref(), Default::default()).unwrap();
        let cost = predict_lu_cost(p.as_ref(), symbolic.col_perm()).unwrap();
        let mut numeric = faer::sparse::linalg::lu::NumericLu::new();
        let mut buffer = MemBuffer::new(
            symbolic.factorize_numeric_lu_scratch::<f64>(faer::Par::Seq, Default::default()),
        );
        let a = faer::sparse::SparseColMatRef::new(p.as_ref(), &values);
        let lu = symbolic
            .factorize_numeric_lu(
                &mut numeric,
                a,
                faer::Par::Seq,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .unwrap();
        let actual = crate::math::lu_fill::lu_factor_nnz(
            n,
            p.col_ptr(),
            p.row_idx(),
            lu.row_perm().arrays().1,
            lu.col_perm().arrays().0,
        )
        .unwrap();
        // lu_factor_nnz does not count L's unit diagonal; the prediction counts it once.
        assert!(cost.factor_entries >= actual as f64, "{cost:?} < {actual}");
        assert!(cost.flops >= 2.0 * actual as f64, "{cost:?}");
    }
}
