//! The 2D law as a linear complementarity problem LCP(M, q̃) of size `3 nc` (the reformulation
//! of Siconos' `fc2d_tolcp`), solved by lexicographic Lemke (id 404) or by enumeration of the
//! complementary bases (id 405).
//!
//! Per contact, `z = (r_N, r_T + mu r_N, s)` and `w = (u_N, u_T + s, mu r_N - r_T)` with
//! `0 <= z ⟂ w >= 0`: the first pair is Signorini's condition, the last two put `r` in the cone
//! and make `s = max(0, -u_T)` with `u_T = 0` inside the cone and `u_T` pointing against `r_T` on
//! its boundary. So `r = (z_0, (z_1 - w_2) / 2)` and `u = (w_0, w_1 - z_2)`. Unlike Siconos,
//! which uses the friction coefficient of the row contact where the column's belongs, the
//! substitution `r_T = z_1 - mu r_N` uses each column contact's own mu (the two agree when all
//! contacts share one mu).

use crate::alloc::try_collect;
use crate::contract::{deadline_passed, Limits, SolverOutcome};
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::problem::FrictionProblem;

/// LCP(M, q̃) in dense row-major form, `M` of size `m x m`.
pub struct PlanarLcp {
    pub size: usize,
    pub m: Vec<f64>,
    pub q: Vec<f64>,
}

impl PlanarLcp {
    /// The reformulation of `problem`.
    pub fn new(problem: &FrictionProblem<'_, 2>) -> Result<Self, Fc3dError> {
        let nc = problem.n_contacts();
        let size = nc.checked_mul(3).ok_or_else(|| {
            Fc3dError::InvalidStructure(format!("{nc} contacts overflow the LCP size"))
        })?;
        let mut m = try_vec(
            size.checked_mul(size)
                .ok_or_else(|| Fc3dError::OutOfMemory {
                    what: "the LCP matrix".into(),
                    bytes: usize::MAX,
                })?,
            0.0,
            "the LCP matrix",
        )?;
        let mu = problem.mu();
        problem.w().for_each_entry(|row, col, v| {
            let (i, a, j) = (row / 2, row % 2, col / 2);
            let lcp_row = 3 * i + a;
            if col % 2 == 0 {
                m[lcp_row * size + 3 * j] += v;
            } else {
                m[lcp_row * size + 3 * j + 1] += v;
                m[lcp_row * size + 3 * j] -= mu[j] * v;
            }
        });
        for i in 0..nc {
            m[(3 * i + 1) * size + 3 * i + 2] += 1.0;
            m[(3 * i + 2) * size + 3 * i] += 2.0 * mu[i];
            m[(3 * i + 2) * size + 3 * i + 1] -= 1.0;
        }
        let mut q = try_vec(size, 0.0, "the LCP vector")?;
        for (c, qc) in problem.q().chunks_exact(2).enumerate() {
            q[3 * c] = qc[0];
            q[3 * c + 1] = qc[1];
        }
        Ok(PlanarLcp { size, m, q })
    }

    /// `(r, u)` of the friction problem from a solution `(z, w)` of the LCP.
    pub fn to_contact(z: &[f64], w: &[f64], r: &mut [f64], u: &mut [f64]) {
        for c in 0..r.len() / 2 {
            r[2 * c] = z[3 * c];
            r[2 * c + 1] = 0.5 * (z[3 * c + 1] - w[3 * c + 2]);
            u[2 * c] = w[3 * c];
            u[2 * c + 1] = w[3 * c + 1] - z[3 * c + 2];
        }
    }
}

/// How an LCP solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LcpEnd {
    Solved,
    /// Lemke: the entering column has no positive entry (a secondary ray); enumeration: no case
    /// is feasible.
    NoSolutionFound,
    IterationLimit,
    OutOfTime,
}

/// Lexicographic Lemke with the covering vector `d = 1`: at most `max_pivots` pivots. Writes
/// `z` and `w = M z + q̃`; returns how it ended and the pivots done.
pub fn lemke(
    lcp: &PlanarLcp,
    max_pivots: usize,
    deadline: Option<std::time::Instant>,
    z: &mut [f64],
    w: &mut [f64],
) -> Result<(LcpEnd, usize), Fc3dError> {
    let m = lcp.size;
    z.iter_mut().for_each(|v| *v = 0.0);
    if lcp.q.iter().all(|&v| v >= 0.0) {
        w.copy_from_slice(&lcp.q);
        return Ok((LcpEnd::Solved, 0));
    }
    // Tableau of `w - M z - d z0 = q̃` in the current basis, row-major: columns w (m), z (m),
    // z0, right-hand side. Its w columns hold B^-1, which breaks ratio ties lexicographically.
    let cols = 2 * m + 2;
    let z0 = 2 * m;
    let rhs = 2 * m + 1;
    let mut t = try_vec(
        m.checked_mul(cols).ok_or_else(|| Fc3dError::OutOfMemory {
            what: "the Lemke tableau".into(),
            bytes: usize::MAX,
        })?,
        0.0,
        "the Lemke tableau",
    )?;
    for i in 0..m {
        let row = &mut t[i * cols..(i + 1) * cols];
        row[i] = 1.0;
        for j in 0..m {
            row[m + j] = -lcp.m[i * m + j];
        }
        row[z0] = -1.0;
        row[rhs] = lcp.q[i];
    }
    // basis[i]: the variable basic in row i (0..m w, m..2m z, 2m z0).
    let mut basis = try_collect(0..m, "the Lemke basis")?;
    let mut column = try_vec(m, 0.0, "the Lemke pivot column")?;

    // First pivot: z0 enters at the level that makes every w nonnegative; the row of the most
    // negative q̃ (lexicographically smallest) leaves.
    let first = (0..m)
        .filter(|&i| t[i * cols + rhs] < 0.0)
        .reduce(|a, b| {
            if lexicographically_less(&t, cols, m, rhs, b, -1.0, a, -1.0, true) {
                b
            } else {
                a
            }
        })
        .expect("some q̃ is negative");
    pivot(&mut t, cols, m, first, z0, &mut column);
    let mut leaving = basis[first];
    basis[first] = z0;
    let mut pivots = 1;
    loop {
        if leaving == z0 {
            break;
        }
        if pivots >= max_pivots {
            read_solution(&t, cols, &basis, m, z, w, lcp);
            return Ok((LcpEnd::IterationLimit, pivots));
        }
        if deadline_passed(deadline) {
            read_solution(&t, cols, &basis, m, z, w, lcp);
            return Ok((LcpEnd::OutOfTime, pivots));
        }
        let entering = if leaving < m {
            leaving + m
        } else {
            leaving - m
        };
        let scale = (0..m)
            .map(|i| t[i * cols + entering].abs())
            .fold(0.0, f64::max);
        let threshold = scale * 1e-13;
        let mut best: Option<usize> = None;
        for i in 0..m {
            let a = t[i * cols + entering];
            if a > threshold {
                best = match best {
                    None => Some(i),
                    Some(b) => {
                        let ab = t[b * cols + entering];
                        if lexicographically_less(&t, cols, m, rhs, i, a, b, ab, false) {
                            Some(i)
                        } else {
                            Some(b)
                        }
                    }
                };
            }
        }
        let Some(row) = best else {
            read_solution(&t, cols, &basis, m, z, w, lcp);
            return Ok((LcpEnd::NoSolutionFound, pivots));
        };
        pivot(&mut t, cols, m, row, entering, &mut column);
        leaving = basis[row];
        basis[row] = entering;
        pivots += 1;
    }
    read_solution(&t, cols, &basis, m, z, w, lcp);
    resolve_final_basis(lcp, &basis, z, w)?;
    Ok((LcpEnd::Solved, pivots))
}

/// The pivots accumulate rounding in the tableau; the final basis is solved again from M and q̃
/// (Gaussian elimination with partial pivoting), and that solution replaces the tableau's when it
/// is feasible and closer to complementarity.
fn resolve_final_basis(
    lcp: &PlanarLcp,
    basis: &[usize],
    z: &mut [f64],
    w: &mut [f64],
) -> Result<(), Fc3dError> {
    let m = lcp.size;
    // Columns of [I, -M] for the basic variables: w_j -> e_j, z_j -> -M e_j.
    let mut a = try_vec(m * m, 0.0, "the Lemke final basis")?;
    let mut x = try_copy(&lcp.q, "the Lemke final basis")?;
    for (k, &b) in basis.iter().enumerate() {
        for i in 0..m {
            a[i * m + k] = if b < m {
                if i == b {
                    1.0
                } else {
                    0.0
                }
            } else {
                -lcp.m[i * m + (b - m)]
            };
        }
    }
    if !matches!(solve_dense(&mut a, &mut x, m, None), Elimination::Solved) {
        return Ok(());
    }
    let mut z_new = try_vec(m, 0.0, "the Lemke final basis")?;
    for (k, &b) in basis.iter().enumerate() {
        if b >= m {
            z_new[b - m] = x[k].max(0.0);
        }
    }
    let mut w_new = try_vec(m, 0.0, "the Lemke final basis")?;
    lcp_velocity(lcp, &z_new, &mut w_new);
    if complementarity_gap(&z_new, &w_new) < complementarity_gap(z, w) {
        z.copy_from_slice(&z_new);
        w.copy_from_slice(&w_new);
    }
    Ok(())
}

/// `sum_i |min(z_i, w_i)|`: zero exactly at a solution of the LCP.
fn complementarity_gap(z: &[f64], w: &[f64]) -> f64 {
    z.iter().zip(w).map(|(a, b)| a.min(*b).abs()).sum()
}

/// Whether row `i` (ratio `(rhs_i, B^-1_i) / a_i`) comes lexicographically before row `k`.
/// `negate`: compare the negated ratios (the first pivot, where every `a` is -1).
#[allow(clippy::too_many_arguments)]
fn lexicographically_less(
    t: &[f64],
    cols: usize,
    m: usize,
    rhs: usize,
    i: usize,
    ai: f64,
    k: usize,
    ak: f64,
    negate: bool,
) -> bool {
    let key = |row: usize, a: f64, col: usize| {
        let v = t[row * cols + col] / a;
        if negate {
            -v
        } else {
            v
        }
    };
    // Relative ties only: the data may be tiny (q of order 1e-15 in real problems).
    let tolerance = 1e-13;
    for col in std::iter::once(rhs).chain(0..m) {
        let (x, y) = (key(i, ai, col), key(k, ak, col));
        let scale = x.abs().max(y.abs());
        if x < y - tolerance * scale {
            return true;
        }
        if x > y + tolerance * scale {
            return false;
        }
    }
    false
}

/// Gauss-Jordan pivot of the tableau on `(row, col)`.
fn pivot(t: &mut [f64], cols: usize, m: usize, row: usize, col: usize, column: &mut [f64]) {
    for i in 0..m {
        column[i] = t[i * cols + col];
    }
    let p = column[row];
    for v in &mut t[row * cols..(row + 1) * cols] {
        *v /= p;
    }
    let (before, rest) = t.split_at_mut(row * cols);
    let (pivot_row, after) = rest.split_at_mut(cols);
    for (i, other) in before.chunks_exact_mut(cols).enumerate().chain(
        after
            .chunks_exact_mut(cols)
            .enumerate()
            .map(|(k, r)| (row + 1 + k, r)),
    ) {
        let f = column[i];
        if f != 0.0 {
            for (x, y) in other.iter_mut().zip(pivot_row.iter()) {
                *x -= f * y;
            }
        }
    }
}

/// `z` from the basic variables of the tableau, then `w = M z + q̃`.
fn read_solution(
    t: &[f64],
    cols: usize,
    basis: &[usize],
    m: usize,
    z: &mut [f64],
    w: &mut [f64],
    lcp: &PlanarLcp,
) {
    z.iter_mut().for_each(|v| *v = 0.0);
    for (i, &b) in basis.iter().enumerate() {
        if (m..2 * m).contains(&b) {
            z[b - m] = t[i * cols + 2 * m + 1].max(0.0);
        }
    }
    lcp_velocity(lcp, z, w);
}

/// `w = M z + q̃`.
fn lcp_velocity(lcp: &PlanarLcp, z: &[f64], w: &mut [f64]) {
    let m = lcp.size;
    for ((wi, row), qi) in w.iter_mut().zip(lcp.m.chunks_exact(m)).zip(&lcp.q) {
        *wi = qi + row.iter().zip(z).map(|(a, b)| a * b).sum::<f64>();
    }
}

/// The largest LCP whose every case enumeration visits when neither an iteration limit nor a
/// time budget bounds it: `2^32` cases (size 32, 10 contacts). A larger problem sets one of the
/// two (Siconos' default, no iteration limit, would run for years).
pub const UNBOUNDED_ENUMERATION_SIZE: usize = 32;

/// The case enumeration tries at `step` (0, 1, ...), in Siconos' order: from `seed` (a seed
/// past the last case starts at case 0), then one by one, wrapping around after the last of the
/// `2^m` cases. Case `k` frees `w_j` where bit `j` of `k` is set and `z_j` elsewhere, so the
/// unknowns past the 64th keep `z` free. (Siconos 4.4 counts the `2^m` cases in 64 bits: from
/// `m = 64` on the count is 0 and it tries no case at all.)
fn enumeration_case(m: usize, seed: u64, step: u64) -> u64 {
    match u32::try_from(m).ok().and_then(|m| 1u64.checked_shl(m)) {
        Some(cases) => {
            let first = if seed >= cases { 0 } else { seed };
            (first + step % cases) % cases
        }
        None => seed.wrapping_add(step),
    }
}

/// Refuses to enumerate the cases of an LCP of `m` unknowns with neither a limit of cases nor a
/// deadline when they are more than `2^32` (see [`UNBOUNDED_ENUMERATION_SIZE`]).
fn check_enumeration_bounds(
    m: usize,
    max_cases: usize,
    deadline: Option<std::time::Instant>,
) -> Result<(), Fc3dError> {
    if max_cases == 0 && deadline.is_none() && m > UNBOUNDED_ENUMERATION_SIZE {
        return Err(Fc3dError::InvalidSetting {
            setting: "max_iter",
            value: "0".into(),
            requirement: "positive (the cases to try), or a time budget set: enumeration \
                          (Siconos 405) of more than 10 contacts has more than 2^32 cases",
        });
    }
    Ok(())
}

/// Whether case `case` frees `w_j` (else `z_j`).
fn frees_w(case: u64, j: usize) -> bool {
    j < 64 && case >> j & 1 == 1
}

/// Enumeration of the complementary bases in Siconos' order (see [`enumeration_case`]): each
/// case solves the square system whose columns are `M`'s `j`-th where `z_j` is free and `-e_j`
/// where `w_j` is, and the first case whose every free variable is `>= -tolerance ||q̃||_inf`
/// is the solution. (Siconos compares with `-tolerance` itself; relative to q̃ the test does not
/// accept every case of a problem whose data are of order 1e-15, as some real 2D problems are.)
/// At most `max_cases` cases (0: every case, for an LCP of at most
/// [`UNBOUNDED_ENUMERATION_SIZE`] unknowns or under a `deadline`); the deadline is tested in
/// every case's elimination too, as a case of a large LCP takes long. Returns how it ended and
/// the cases tried; unless solved, `z = 0` and `w = q̃`.
pub fn enumerate(
    lcp: &PlanarLcp,
    tolerance: f64,
    seed: u64,
    max_cases: usize,
    deadline: Option<std::time::Instant>,
    z: &mut [f64],
    w: &mut [f64],
) -> Result<(LcpEnd, usize), Fc3dError> {
    let m = lcp.size;
    check_enumeration_bounds(m, max_cases, deadline)?;
    let every_case = u32::try_from(m)
        .ok()
        .and_then(|m| 1u64.checked_shl(m))
        .unwrap_or(u64::MAX);
    let cases = match max_cases {
        0 => every_case,
        k => every_case.min(k as u64),
    };
    let slack = tolerance * lcp.q.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut a = try_vec(m * m, 0.0, "the enumeration system")?;
    let mut x = try_vec(m, 0.0, "the enumeration system")?;
    z.iter_mut().for_each(|v| *v = 0.0);
    w.copy_from_slice(&lcp.q);
    let mut tried = 0usize;
    for step in 0..cases {
        if deadline_passed(deadline) {
            return Ok((LcpEnd::OutOfTime, tried));
        }
        let case = enumeration_case(m, seed, step);
        tried += 1;
        // Columns: M's j-th where z_j is free, -e_j where w_j is; right-hand side -q̃.
        for i in 0..m {
            for j in 0..m {
                a[i * m + j] = if !frees_w(case, j) {
                    lcp.m[i * m + j]
                } else if i == j {
                    -1.0
                } else {
                    0.0
                };
            }
            x[i] = -lcp.q[i];
        }
        match solve_dense(&mut a, &mut x, m, deadline) {
            Elimination::Solved => {}
            Elimination::Singular => continue,
            Elimination::OutOfTime => return Ok((LcpEnd::OutOfTime, tried)),
        }
        if x.iter().all(|&v| v >= -slack && v.is_finite()) {
            for j in 0..m {
                if frees_w(case, j) {
                    z[j] = 0.0;
                    w[j] = x[j];
                } else {
                    z[j] = x[j];
                    w[j] = 0.0;
                }
            }
            return Ok((LcpEnd::Solved, tried));
        }
    }
    let end = if cases < every_case {
        LcpEnd::IterationLimit
    } else {
        LcpEnd::NoSolutionFound
    };
    Ok((end, tried))
}

/// How a dense elimination ended.
enum Elimination {
    Solved,
    Singular,
    OutOfTime,
}

/// Solves `a x = b` in place (`a` row-major `m x m`, overwritten; `b` becomes `x`) by Gaussian
/// elimination with partial pivoting; stops at a zero or non-finite pivot, and when `deadline`
/// passes (tested once per pivot row).
fn solve_dense(
    a: &mut [f64],
    b: &mut [f64],
    m: usize,
    deadline: Option<std::time::Instant>,
) -> Elimination {
    for k in 0..m {
        if deadline_passed(deadline) {
            return Elimination::OutOfTime;
        }
        let p = (k..m)
            .max_by(|&i, &j| a[i * m + k].abs().total_cmp(&a[j * m + k].abs()))
            .expect("k < m");
        if a[p * m + k] == 0.0 || !a[p * m + k].is_finite() {
            return Elimination::Singular;
        }
        if p != k {
            for j in 0..m {
                a.swap(p * m + j, k * m + j);
            }
            b.swap(p, k);
        }
        let d = a[k * m + k];
        for i in k + 1..m {
            let f = a[i * m + k] / d;
            if f != 0.0 {
                for j in k..m {
                    a[i * m + j] -= f * a[k * m + j];
                }
                b[i] -= f * b[k];
            }
        }
    }
    for k in (0..m).rev() {
        let mut s = b[k];
        for j in k + 1..m {
            s -= a[k * m + j] * b[j];
        }
        b[k] = s / a[k * m + k];
    }
    Elimination::Solved
}

/// Runs Lemke (`enumeration` false) or enumeration on the reformulation of `problem` and writes
/// `(r, u)`.
pub(crate) fn solve_by_lcp(
    problem: &FrictionProblem<'_, 2>,
    enumeration: bool,
    limits: &Limits,
    seed: u64,
    r: &mut [f64],
    u: &mut [f64],
) -> Result<SolverOutcome, Fc3dError> {
    // The budget counts the reformulation too (a dense matrix of (3 nc)^2 entries); an
    // enumeration without bounds is refused before it is built.
    let run = limits.start();
    if enumeration {
        check_enumeration_bounds(3 * problem.n_contacts(), run.max_iter, run.deadline())?;
    }
    let lcp = PlanarLcp::new(problem)?;
    let mut z = try_vec(lcp.size, 0.0, "the LCP unknowns")?;
    let mut w = try_vec(lcp.size, 0.0, "the LCP unknowns")?;
    let (end, iterations) = if enumeration {
        enumerate(
            &lcp,
            run.tolerance,
            seed,
            run.max_iter,
            run.deadline(),
            &mut z,
            &mut w,
        )?
    } else {
        lemke(&lcp, run.max_iter, run.deadline(), &mut z, &mut w)?
    };
    PlanarLcp::to_contact(&z, &w, r, u);
    // u comes from the LCP, not from W r + q on the host's storage: the caller measures.
    Ok(SolverOutcome::stopped(iterations, end == LcpEnd::OutOfTime))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Siconos' order: from the seed, one by one, wrapping around after the last case; a seed
    /// past the last case starts at 0; past 64 unknowns the case number does not wrap and the
    /// higher unknowns keep `z` free.
    #[test]
    fn cases_come_in_siconos_order() {
        let order = |m, seed| {
            (0..10)
                .map(|s| enumeration_case(m, seed, s))
                .collect::<Vec<_>>()
        };
        assert_eq!(order(3, 0), [0, 1, 2, 3, 4, 5, 6, 7, 0, 1]);
        assert_eq!(order(3, 6), [6, 7, 0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(order(3, 9), [0, 1, 2, 3, 4, 5, 6, 7, 0, 1]);
        assert_eq!(order(2001, 5), [5, 6, 7, 8, 9, 10, 11, 12, 13, 14]);
        assert!(frees_w(1 << 63, 63) && !frees_w(u64::MAX, 64) && !frees_w(u64::MAX, 2000));
    }

    /// LCP(M, q) with M = [[2, 1], [1, 2]], q = (-2, 1): z = (1, 0), w = (0, 2), case 2 (w_1
    /// free), found third; a limit of two cases stops before it, and so does a deadline past.
    #[test]
    fn the_first_feasible_case_is_found_within_the_limits() {
        let lcp = PlanarLcp {
            size: 2,
            m: vec![2.0, 1.0, 1.0, 2.0],
            q: vec![-2.0, 1.0],
        };
        let (mut z, mut w) = ([0.0; 2], [0.0; 2]);
        let got = enumerate(&lcp, 1e-12, 0, 0, None, &mut z, &mut w).unwrap();
        assert_eq!(got, (LcpEnd::Solved, 3));
        assert_eq!((z, w), ([1.0, 0.0], [0.0, 2.0]));
        let got = enumerate(&lcp, 1e-12, 0, 2, None, &mut z, &mut w).unwrap();
        assert_eq!(got, (LcpEnd::IterationLimit, 2));
        assert_eq!((z, w), ([0.0, 0.0], [-2.0, 1.0]));
        let past = std::time::Instant::now();
        let got = enumerate(&lcp, 1e-12, 0, 0, Some(past), &mut z, &mut w).unwrap();
        assert_eq!(got, (LcpEnd::OutOfTime, 0));
        // From seed 3 the order is 3, 0, 1, 2: the solution is the fourth case tried.
        let got = enumerate(&lcp, 1e-12, 3, 0, None, &mut z, &mut w).unwrap();
        assert_eq!(got, (LcpEnd::Solved, 4));
    }
}
