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

/// CPU seconds per stored entry of W for what comes before a sparse factorization and cannot
/// be interrupted (assembling the column-compressed matrix, ADMM's `W + rho I` or NSN's Newton
/// matrix, faer's symbolic LU: COLAMD ordering and symbolic factorization, and
/// [`checked_lu_cost`]'s own symbolic Cholesky), on a small W; the cost per entry grows with W's
/// size (see [`ANALYSIS_GROWTH_ENTRIES`]). Measured on this project's machine as the time ADMM
/// and NSN-AC took to stop out of time before their first factorization (`fc3d solve --solver
/// ADMM --tol 1e-4 --budget 1s gen:contacts=N,piles=4,seed=1`, the factorization refused by
/// [`LuCost::ends_by`]; load about 3, so about 2/3 of a core): 1.7e-7 s per entry of wall
/// clock at 10^4 contacts (0.28 s, 1.7e6 entries), 2.0e-7 at 3·10^4 (1.09 s), 2.7e-7 at 10^5
/// (5.1 s, 1.9e7 entries); in CPU time at 10^5 (`convergence_bench solve --scene
/// contacts=100000,piles=4,seed=1,shape=spheres --method NSN-AC --budget 30`, the whole call)
/// 2.9e-7 (5.5 s, load 8.8) and 3.7e-7 (6.9 s, load 10.5).
pub const ANALYSIS_SECONDS_PER_ENTRY: f64 = 1e-7;

/// The set-up's cost per entry is [`ANALYSIS_SECONDS_PER_ENTRY`] times `1 + entries /
/// ANALYSIS_GROWTH_ENTRIES`: the ordering and the symbolic factorization follow the fill, which
/// grows faster than W. With 5e6 the prediction is above every CPU time measured: 1.34e-7 s per
/// entry at 1.7e6 entries (measured 1.1e-7 in CPU time), 2.1e-7 at 5.4e6 (1.3e-7), 4.7e-7 at
/// 1.9e7 (2.9e-7 and 3.7e-7); below 10^5 entries (the shared problems) it is within 2% of the
/// constant rate.
pub const ANALYSIS_GROWTH_ENTRIES: f64 = 5e6;

/// Predicted flops per second of faer's sparse LU on the global formulation's matrices
/// ([`crate::math::sparse_lu::SparseLu`]: `M + rho H H^T`, the IPM's `M + P̃^T S P̃`, the global
/// Newton matrix), whose fronts are denser than W's. Measured in CPU time of the first
/// factorization on generated sphere piles in the global form (4 piles, 10^4 and 4·10^4
/// contacts, load about 4 on 2 cores): the IPM's matrix 5.0e9 and 8.3e9 flops/s, the Newton
/// matrix (its prediction from `A + A^T` is above its fill) 1.35e10 and 1.73e10. 2e10 is above
/// every rate measured (1.16x the fastest).
pub const GLOBAL_LU_FLOPS_PER_SECOND: f64 = 2e10;

/// Predicted flops per second of faer's sparse Cholesky
/// ([`crate::math::sparse_cholesky::SparseCholesky`], supernodal: dense blocks), for the flops
/// of [`checked_cholesky_cost`]. Measured in CPU time of SSN-ALM's first factorization on the
/// same piles: 1.7e10 flops/s at 10^4 contacts, 2.35e10 at 4·10^4; 3e10 is above both.
pub const CHOLESKY_FLOPS_PER_SECOND: f64 = 3e10;

/// CPU seconds per position (a `(row, column)` pair, repeats counted) of the assembly of a
/// global-form matrix before its first factorization (gathering and sorting the positions, the
/// fill-reducing order and symbolic analysis of the merged pattern, which is far smaller, and
/// the cost prediction): linear, measured 1.0e-7-1.7e-7 s per position in CPU time on
/// generated global sphere piles of 10^4 and 4·10^4 contacts (4 piles; ADMM 1.1e-7 and
/// 1.3e-7, the IPM 1.0e-7 and 1.2e-7, SSN-ALM 1.0e-7 and 1.2e-7, the global Newton 1.5e-7 and
/// 1.7e-7; load about 4). The per-position rate is [`ANALYSIS_SECONDS_PER_ENTRY`], below
/// every one measured.
pub fn assembly_seconds(positions: usize, share: f64) -> f64 {
    positions as f64 * ANALYSIS_SECONDS_PER_ENTRY / share.clamp(MIN_CPU_SHARE, 1.0)
}

/// Whether the assembly of a global-form matrix of `positions` positions
/// ([`assembly_seconds`]), started now, is predicted to end by `deadline` (always without one)
/// at the share of a core the load leaves.
pub fn assembly_ends_by(positions: usize, deadline: Option<std::time::Instant>) -> bool {
    ends_by_under_load(assembly_seconds(positions, 1.0), deadline)
}

/// The least share of a core [`cpu_share`] assumes.
pub const MIN_CPU_SHARE: f64 = 1.0 / 32.0;

/// Predicted wall-clock seconds of the set-up before a factorization of a W of `stored_entries`
/// entries, on a process that gets `share` of a core.
pub fn analysis_seconds(stored_entries: usize, share: f64) -> f64 {
    let entries = stored_entries as f64;
    entries * ANALYSIS_SECONDS_PER_ENTRY * (1.0 + entries / ANALYSIS_GROWTH_ENTRIES)
        / share.clamp(MIN_CPU_SHARE, 1.0)
}

/// Whether the set-up before a factorization (assembly and analysis) of a W of `stored_entries`
/// entries, started now, is predicted to end by `deadline` (always without one), at the share
/// of a core the machine's load leaves ([`cpu_share`]); see [`analysis_seconds`]. Neither the
/// set-up nor a factorization can be interrupted: on a loaded machine (load 10 on 2 cores, a
/// fifth of a core a process) the set-up of NSN-AC on a pile of 10^5 contacts took 39.8 s of a
/// 30 s budget while its CPU time (6.9 s) fitted.
pub fn analysis_ends_by(stored_entries: usize, deadline: Option<std::time::Instant>) -> bool {
    ends_by_under_load(analysis_seconds(stored_entries, 1.0), deadline)
}

/// Whether work of `cpu_seconds` on a whole core, started now, ends by `deadline` at the share
/// of a core the load leaves ([`cpu_share`]). The load is read only when the work would not fit
/// at the least share ([`MIN_CPU_SHARE`]): on the small problems, where ADMM asks before every
/// change of rho, no system call is made.
fn ends_by_under_load(cpu_seconds: f64, deadline: Option<std::time::Instant>) -> bool {
    let Some(deadline) = deadline else {
        return true;
    };
    let fits = |seconds: f64| {
        ends_by(
            Duration::try_from_secs_f64(seconds).unwrap_or(Duration::MAX),
            Some(deadline),
        )
    };
    fits(cpu_seconds / MIN_CPU_SHARE) || fits(cpu_seconds / cpu_share())
}

/// The share of a core a single-threaded computation can expect on a machine of `cores`
/// cores whose run queue holds `load` processes (the load average): `cores / load` when the
/// machine is oversubscribed, 1 otherwise, at least [`MIN_CPU_SHARE`].
pub fn cpu_share_of(load: f64, cores: usize) -> f64 {
    let cores = cores.max(1) as f64;
    if load.is_finite() && load > cores {
        (cores / load).max(MIN_CPU_SHARE)
    } else {
        1.0
    }
}

/// The share of a core this process can expect now: [`cpu_share_of`] the 1-minute load average
/// (`/proc/loadavg`) and the parallelism available; 1 where the load is not known. Read without
/// allocating (ADMM asks before each refactorization).
pub fn cpu_share() -> f64 {
    use std::io::Read;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut buffer = [0u8; 64];
    let load = std::fs::File::open("/proc/loadavg")
        .and_then(|mut f| f.read(&mut buffer))
        .ok()
        .and_then(|len| std::str::from_utf8(&buffer[..len]).ok())
        .and_then(|text| text.split_whitespace().next()?.parse::<f64>().ok());
    load.map_or(1.0, |l| cpu_share_of(l, cores))
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
    /// one), at the share of a core the machine's load leaves ([`cpu_share`]).
    pub fn ends_by(&self, deadline: Option<std::time::Instant>) -> bool {
        self.ends_by_at(FLOPS_PER_SECOND, deadline)
    }

    /// [`LuCost::ends_by`] at `flops_per_second` on a whole core (a matrix class measured
    /// faster: [`GLOBAL_LU_FLOPS_PER_SECOND`], [`CHOLESKY_FLOPS_PER_SECOND`]).
    pub fn ends_by_at(&self, flops_per_second: f64, deadline: Option<std::time::Instant>) -> bool {
        ends_by_under_load(self.flops / flops_per_second, deadline)
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
    fitting_in_memory(predicted(a, col_perm, what)?, what)
}

/// [`checked_lu_cost`] of a Cholesky `L L^T` of a symmetric matrix stored by one triangle
/// (`a`, either), in its symmetric order `perm`: the LU prediction's `L` alone, half its flops
/// (`sum_j c_j^2`) and its entries with the diagonal once. Its duration is at
/// [`CHOLESKY_FLOPS_PER_SECOND`].
pub fn checked_cholesky_cost(
    a: SymbolicSparseColMatRef<'_, usize>,
    perm: PermRef<'_, usize>,
    what: &str,
) -> Result<LuCost, Fc3dError> {
    let n = a.ncols();
    let lu = predicted(a, perm, what)?;
    let cost = LuCost {
        factor_entries: (lu.factor_entries + n as f64) / 2.0,
        flops: lu.flops / 2.0,
    };
    fitting_in_memory(cost, what)
}

/// [`predict_lu_cost`], or an [`Fc3dError::OutOfMemory`] naming `what` when its work arrays
/// cannot be allocated.
fn predicted(
    a: SymbolicSparseColMatRef<'_, usize>,
    perm: PermRef<'_, usize>,
    what: &str,
) -> Result<LuCost, Fc3dError> {
    predict_lu_cost(a, perm).ok_or_else(|| Fc3dError::OutOfMemory {
        what: format!("{what} (analysis)"),
        bytes: a
            .ncols()
            .saturating_add(a.compute_nnz())
            .saturating_mul(3 * 8),
    })
}

/// Whether a numeric factorization started now ends by `deadline` at `flops_per_second`, by
/// the cost in `kept`, which `predict` fills at the first call under a deadline (a factor's
/// pattern is fixed: one prediction serves every later factorization). Without a deadline:
/// true, with no work.
pub fn factor_ends_by_kept(
    kept: &mut Option<LuCost>,
    deadline: Option<std::time::Instant>,
    flops_per_second: f64,
    predict: impl FnOnce() -> Result<LuCost, Fc3dError>,
) -> Result<bool, Fc3dError> {
    if deadline.is_none() {
        return Ok(true);
    }
    let cost = match *kept {
        Some(cost) => cost,
        None => *kept.insert(predict()?),
    };
    Ok(cost.ends_by_at(flops_per_second, deadline))
}

/// `cost`, or an [`Fc3dError::OutOfMemory`] naming `what` when its factors cannot fit in the
/// available memory.
fn fitting_in_memory(cost: LuCost, what: &str) -> Result<LuCost, Fc3dError> {
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
    fn the_set_up_prediction_covers_the_measured_overrun() {
        // NSN-AC on 4 sphere piles of 10^5 contacts (W: 18,752,284 entries): its set-up took
        // 5.5 and 6.9 CPU s (loads 8.8 and 10.5 on 2 cores), 13.8 and 39.8 s of wall clock.
        let entries = 18_752_284;
        assert!(analysis_seconds(entries, 1.0) > 6.9);
        // At load 10.5 on 2 cores the prediction passes the 30 s budget: refused up front.
        let loaded = cpu_share_of(10.5, 2);
        assert!((loaded - 2.0 / 10.5).abs() < 1e-15);
        assert!(analysis_seconds(entries, loaded) > 39.8);
        // Small problems: the constant rate (the Capsules: about 1e5 entries, 10 ms).
        assert!((analysis_seconds(100_000, 1.0) - 0.0102).abs() < 1e-12);
        // An idle or unknown load is a whole core; an absurd one is bounded.
        assert_eq!(cpu_share_of(0.5, 2), 1.0);
        assert_eq!(cpu_share_of(f64::NAN, 2), 1.0);
        assert_eq!(cpu_share_of(1e9, 2), MIN_CPU_SHARE);
        let share = cpu_share();
        assert!((MIN_CPU_SHARE..=1.0).contains(&share));
    }

    #[test]
    fn an_analysis_is_refused_only_when_it_cannot_end_in_time() {
        use std::time::Instant;
        // 1e6 entries: 0.12 s predicted on a whole core, up to 32x that under load.
        assert!(analysis_ends_by(1_000_000, None));
        assert!(analysis_ends_by(
            1_000_000,
            Some(Instant::now() + Duration::from_secs_f64(0.12 / cpu_share() + 1.0))
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
