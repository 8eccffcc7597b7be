//! The entry point of every solve: the input checks shared by all families, the rescaling, the
//! trivial-case shortcut, the dispatch, and the one post-processing path that measures the error
//! of the returned `(r, u)` and sets the status from it.

use crate::alloc::try_collect;
use crate::config::{scalar_factors, PlanarConfig, Rescaling, RollingConfig, SolverConfig};
use crate::contract::{IterationEvent, Observer, SolveReport, SolveStatus, SolverOutcome};
use crate::error::{check_finite, try_copy, try_vec, Fc3dError};
use crate::matrix::Delassus;
use crate::measure::{natural_map_error, rolling_error};
use crate::problem::{FrictionProblem, FrictionProblem2d, RollingProblem};

/// The host's reaction and velocity arrays: `n` entries each, a finite initial reaction.
fn check_iterate(n: usize, r: &[f64], u: &[f64]) -> Result<(), Fc3dError> {
    if r.len() != n {
        return Err(Fc3dError::dims("reaction", n, r.len()));
    }
    if u.len() != n {
        return Err(Fc3dError::dims("velocity", n, u.len()));
    }
    check_finite("initial reaction", r)
}

/// Solves `problem` from the initial guess in `r`; on success `r` and `u = W r + q` hold the
/// result and the report holds the error measured on them.
///
/// On an `Err` found before the run (dimensions, settings, a non-finite initial reaction), `r`
/// and `u` are left untouched. An error found during or after the run leaves intermediate values
/// in them: running out of memory in a factorization, or a non-finite entry of a W that is a
/// view of a host's blocks (looked for only when the error comes out non-finite, see
/// [`Delassus::check_finite`](crate::matrix::Delassus::check_finite)). A caller that needs them
/// intact solves into copies, as the C API does.
pub fn solve(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
) -> Result<SolveReport, Fc3dError> {
    solve_with_observer(problem, config, r, u, &mut |_| {})
}

/// The check a caller makes before solving in arrays it must find untouched on failure (the C
/// `fc3d_driver_in_place`): with a method that [fails only before it
/// starts](crate::config::Method::fails_only_before_start), a W without NaN or infinite entries
/// leaves nothing for a run to fail on once it touched `r`. A view of a host's blocks is read in
/// full (the other storages were checked when they were built), on the threads the configured
/// sweep runs on.
pub fn check_w_before_solving_in_place(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
) -> Result<(), Fc3dError> {
    match &config.method {
        crate::config::Method::Nsgs(options) => {
            crate::solvers::nsgs::check_finite_on_threads(problem.w(), options)
        }
        _ => problem.w().check_finite(),
    }
}

/// [`solve`] with an observer called after every iteration (the C `Callback`). Under a
/// rescaling the observer sees iterates mapped back to the host's units.
pub fn solve_with_observer(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolveReport, Fc3dError> {
    solve_with_runner(problem, config, r, u, observer, &mut run_family)
}

/// Runs the configured family on a problem (the host's, or its rescaled copy).
pub(crate) type Runner<'a> = dyn FnMut(
        &FrictionProblem<'_>,
        &SolverConfig,
        &mut [f64],
        &mut [f64],
        &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError>
    + 'a;

/// The family's own run: everything it needs is prepared from the problem.
fn run_family(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    config
        .method
        .family()
        .run(problem, &config.limits(), r, u, observer)
}

/// [`solve_with_observer`] with the family run by `runner` (a workspace's, which reuses the
/// structures it prepared for an earlier problem); the checks, rescaling, trivial case and
/// post-processing are the ones every solve goes through.
pub(crate) fn solve_with_runner(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
    runner: &mut Runner<'_>,
) -> Result<SolveReport, Fc3dError> {
    check_iterate(problem.size(), r, u)?;
    config.validate()?;
    let outcome = match config.rescaling {
        Rescaling::None => run(problem, config, r, u, observer, runner)?,
        Rescaling::Scalar => run_rescaled(problem, config, r, observer, runner)?,
    };
    let report = finish(problem, config, outcome, r, u);
    // A view of a host's blocks is not read for NaNs and infinities up front (that pass would
    // cost a sweep): a non-finite entry of W makes W r + q, and so the error, non-finite
    // whatever r is (NaN * 0 and inf * 0 are NaN), so it is looked for only then.
    if !report.error.is_finite() {
        problem.w().check_finite()?;
    }
    Ok(report)
}

/// Runs the configured family on `problem`, after the trivial case (Siconos): when no contact is
/// pushed into penetration by q, the answer is r = 0, u = q.
fn run(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
    runner: &mut Runner<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    if problem.q().chunks_exact(3).all(|qc| qc[0] >= -f64::EPSILON) {
        r.iter_mut().for_each(|v| *v = 0.0);
        return Ok(SolverOutcome::stopped(0, false));
    }
    // A dense W that is mostly zero blocks is solved through its sparse-block form (same values).
    if let Some(view) = problem.w().sparse_block_view() {
        let view = problem.with_w(Delassus::SparseBlock(view))?;
        return runner(&view, config, r, u, observer);
    }
    runner(problem, config, r, u, observer)
}

/// [`run`] on FC(s W, t q, mu) with the factors of [`scalar_factors`]; `r` is mapped to and from
/// the rescaled units, and nothing measured in those units is passed on as the host's error.
fn run_rescaled(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    observer: &mut Observer<'_>,
    runner: &mut Runner<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let n = problem.size();
    let (s, t) = scalar_factors(problem);
    let scaled_q = try_collect(problem.q().iter().map(|v| t * v), "the rescaled q")?;
    let mu = try_copy(problem.mu(), "mu")?;
    let scaled = FrictionProblem::new(problem.w().scaled(s)?, scaled_q, mu)?;
    let to_host = s / t;
    let mut r_s = try_collect(r.iter().map(|v| v / to_host), "the rescaled reaction")?;
    let mut u_s = try_vec(n, 0.0, "the rescaled velocity")?;
    let mut host_r = try_vec(n, 0.0, "the reaction in the host's units")?;
    let mut mapped = |ev: &IterationEvent<'_>| {
        for (h, v) in host_r.iter_mut().zip(ev.reaction) {
            *h = to_host * v;
        }
        observer(&IterationEvent {
            iteration: ev.iteration,
            reaction: &host_r,
            error: ev.error,
        });
    };
    let outcome = run(&scaled, config, &mut r_s, &mut u_s, &mut mapped, runner)?;
    for (h, v) in r.iter_mut().zip(&r_s) {
        *h = to_host * v;
    }
    // Dumont's criterion is absolute: it stays in the rescaled units, where the run measured it.
    Ok(outcome.with_final_error(None))
}

/// The post-processing every solve ends with. The reported error is always the natural-map error
/// of the returned `(r, u)` on the host's problem and storage, whatever the solver's own stopping
/// test was: measured here unless the family's last step measured exactly that (same function,
/// same `r`, `u = W r + q`). The status follows from that error.
fn finish(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    outcome: SolverOutcome,
    r: &mut [f64],
    u: &mut [f64],
) -> SolveReport {
    let mut error = match outcome.final_error {
        Some(e) => e,
        None => natural_map_error(problem, r, u),
    };
    // Last line of defence of the contract "r and u are finite": a finite r can still give an
    // infinite W r + q (entries near the overflow threshold). Then the host gets r = 0, u = q,
    // with the error of that pair, rather than infinities.
    if !error.is_finite() || !r.iter().chain(u.iter()).all(|v| v.is_finite()) {
        r.iter_mut().for_each(|v| *v = 0.0);
        error = natural_map_error(problem, r, u);
    }
    let status = if error <= config.tolerance {
        if grows_where_no_solution_is(problem, r, u, error) {
            SolveStatus::Unbounded
        } else {
            SolveStatus::Converged
        }
    } else if outcome.diverged {
        SolveStatus::Unbounded
    } else if outcome.relaxation_converged {
        SolveStatus::RelaxationNotCoulomb
    } else if outcome.out_of_time {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    };
    SolveReport {
        status,
        iterations: outcome.iterations,
        error,
        dumont_criterion: outcome.dumont_criterion,
        // A rho of the rescaled problem is not one of the host's.
        final_rho: outcome
            .final_rho
            .filter(|_| config.rescaling == Rescaling::None),
        stages: outcome.stages,
        fill: outcome.fill,
        products: outcome.products,
        f32_sweeps: outcome.f32_sweeps,
    }
}

/// Whether `r` is (nearly) a ray of no solution on one island of the problem (a connected
/// component of the contact graph through W's nonzero entries: an independent problem, and the
/// whole problem has no solution when one of them has none). On island I with contacts C_I, the
/// direction `d = r_I / ||r_I||` satisfies `W_I d = 0` up to the size of the error (`||W_I d|| <=
/// min(RAY_NULL error, RAY_NULL_CAP) max_{C_I}|W_ii|`: W r stays bounded while r grows) and q
/// pushes along it (`q_I·d <= -RAY_PUSH ||q_I||`, and `< 0`). Then `u = W r + q` hardly depends
/// on how far r goes along d, and the relative error `|residual| / ||r||` falls below any
/// tolerance as `||r||` grows, although no r solves the problem (along d, `u_I = q_I`, and
/// complementarity would need `q_I·d >= 0`). A solution of a stiff problem (small W, large r)
/// is not flagged: its `W r` balances q, so `||W_I d||` is of the order of the island's
/// diagonal. Island by island, not on the whole W, because independent parts may differ in
/// scale by orders of magnitude (piles of different stiffness side by side): measured against
/// the largest diagonal entry of the whole W, the large reaction of a soft part looked like a
/// ray (a Capsules problem beside Confeti-ex03 was reported unbounded at an error of 1.2e-7).
/// On a connected W it is the same test as on the whole problem.
fn grows_where_no_solution_is(
    problem: &FrictionProblem<'_>,
    r: &[f64],
    u: &[f64],
    error: f64,
) -> bool {
    let n = problem.n_contacts();
    let (q, w) = (problem.q(), problem.w());
    // 4 bytes a contact and 48 an island, after the run: the peak of a converged solve at scale
    // is the run's, not this test's. Should even that be unavailable (or the contacts too many
    // to number in 32 bits), the result is judged by its error alone.
    let Ok(n32) = u32::try_from(n) else {
        return false;
    };
    let Ok(mut island) = try_vec(n, 0u32, "islands of W") else {
        return false;
    };
    // Islands by union-find over the contacts (path halving, union by index: an island's root
    // is its smallest contact).
    island.iter_mut().zip(0..n32).for_each(|(p, c)| *p = c);
    let root = |parent: &mut Vec<u32>, mut c: usize| {
        while parent[c] as usize != c {
            parent[c] = parent[parent[c] as usize];
            c = parent[c] as usize;
        }
        c
    };
    let coupled = w.for_each_coupling(|i, j| {
        let (a, b) = (root(&mut island, i), root(&mut island, j));
        if a != b {
            island[a.max(b)] = a.min(b) as u32;
        }
    });
    if coupled.is_err() {
        return false;
    }
    // Number the islands in the order of their roots: a root comes before the other contacts
    // of its island, so each contact finds its root already numbered.
    for c in 0..n {
        island[c] = root(&mut island, c) as u32;
    }
    let mut n_islands = 0u32;
    for c in 0..n {
        let r = island[c] as usize;
        island[c] = if r == c {
            n_islands += 1;
            n_islands - 1
        } else {
            island[r]
        };
    }
    let Ok(mut sums) = try_vec(n_islands as usize, [0.0_f64; 6], "ray test") else {
        return false;
    };
    // Per island: ||r_I||^2, ||q_I||^2, q_I·r_I, ||W_I r_I||^2
    // (r and W r divided by the island's largest |r| entry, so that a reaction beyond 1e154, a
    // ray followed with a growing step, gives finite sums), the island's largest diagonal entry
    // and its largest |r| entry.
    const LARGEST: usize = 5;
    for (c, rc) in r.chunks_exact(3).enumerate() {
        let l = &mut sums[island[c] as usize][LARGEST];
        *l = rc.iter().fold(*l, |m, v| m.max(v.abs()));
    }
    for c in 0..n {
        let s = &mut sums[island[c] as usize];
        let l = s[LARGEST];
        if !(l > 0.0 && l.is_finite()) {
            continue;
        }
        for k in 3 * c..3 * c + 3 {
            s[0] += (r[k] / l).powi(2);
            s[1] += q[k] * q[k];
            s[2] += q[k] * (r[k] / l);
            // W r = u - q.
            s[3] += ((u[k] - q[k]) / l).powi(2);
        }
        if let Some(b) = w.diagonal_block(c) {
            s[4] = s[4]
                .max(b[0][0].abs())
                .max(b[1][1].abs())
                .max(b[2][2].abs());
        }
    }
    let null = (RAY_NULL * error.max(f64::EPSILON)).min(RAY_NULL_CAP);
    // The reaction that grows along a ray is the one that makes the relative error small: an
    // island whose reactions are negligible next to the largest carries none (a contact taking
    // off with |r| ~ 1e-17 has an arbitrary direction d, and u - q = W r rounds to 0 there).
    let largest = sums.iter().fold(0.0_f64, |m, s| m.max(s[LARGEST]));
    sums.iter().any(|&[rr, qq, qr, wr, diag, l]| {
        if !(rr > 0.0) || l < RAY_SHARE * largest {
            return false;
        }
        // d = (r_I / largest_I) / sqrt(rr).
        let (q_d, w_d) = (qr / rr.sqrt(), (wr / rr).sqrt());
        q_d < 0.0 && q_d <= -RAY_PUSH * qq.sqrt() && w_d <= null * diag
    })
}

/// `||W_I d|| <= RAY_NULL error max|W_ii|` (island I): W d vanishes like the error...
const RAY_NULL: f64 = 100.0;
/// ... and is at most this fraction of the island's diagonal whatever the tolerance (an error of order
/// one proves nothing about d).
const RAY_NULL_CAP: f64 = 1e-3;
/// `q_I·d <= -RAY_PUSH ||q_I||`: q pushes along d.
const RAY_PUSH: f64 = 1e-3;
/// An island is tested when its largest |r| entry is at least this fraction of the largest of
/// all.
const RAY_SHARE: f64 = 1e-2;

/// Solves the 2D `problem` with a Siconos `fc2d` solver from the initial guess in `r` (NSGS uses
/// it; CPG, Lemke and enumeration start from zero as Siconos' do). On success `r` and
/// `u = W r + q` hold the result and the report the natural-map error measured on them (the 2D
/// cone); on `Err`, `r` and `u` are left as [`solve`] leaves them.
pub fn solve_planar(
    problem: &FrictionProblem2d<'_>,
    config: &PlanarConfig,
    r: &mut [f64],
    u: &mut [f64],
) -> Result<SolveReport, Fc3dError> {
    solve_planar_with_observer(problem, config, r, u, &mut |_| {})
}

/// [`solve_planar`] with an observer called after every iteration of NSGS and CPG.
pub fn solve_planar_with_observer(
    problem: &FrictionProblem2d<'_>,
    config: &PlanarConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolveReport, Fc3dError> {
    check_iterate(problem.size(), r, u)?;
    config.validate()?;
    // Exactly, not up to rounding as in 3D: 2D problems with q of order 1e-18 exist, where a
    // q_N of -1e-19 matters relative to ||q||.
    let outcome = if problem.q().chunks_exact(2).all(|qc| qc[0] >= 0.0) {
        // No contact is pushed into penetration: r = 0, u = q.
        r.iter_mut().for_each(|v| *v = 0.0);
        SolverOutcome::stopped(0, false)
    } else {
        crate::solvers::planar::run(&config.method, problem, &config.limits(), r, u, observer)?
    };
    Ok(report_measured(outcome, config.tolerance, r, u, |r, u| {
        natural_map_error(problem, r, u)
    }))
}

/// Solves the rolling `problem` (contacts of dimension 5, or 3 for Siconos' `rolling_fc2d`) from
/// the initial guess in `r`. When no contact is pushed into penetration (every `q_N >=
/// -epsilon`, Siconos' trivial case) the answer is `r = 0`, `u = q` after no iteration. On
/// success `r` and `u = W r + q` hold the result and the report the natural-map error with the
/// rolling cone measured on them (Siconos' `rolling_fc3d_compute_error`); on `Err`, `r` and `u`
/// are left as [`solve`] leaves them.
pub fn solve_rolling<const D: usize>(
    problem: &RollingProblem<'_, D>,
    config: &RollingConfig,
    r: &mut [f64],
    u: &mut [f64],
) -> Result<SolveReport, Fc3dError> {
    solve_rolling_with_observer(problem, config, r, u, &mut |_| {})
}

/// [`solve_rolling`] with an observer called after every sweep.
pub fn solve_rolling_with_observer<const D: usize>(
    problem: &RollingProblem<'_, D>,
    config: &RollingConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolveReport, Fc3dError> {
    check_iterate(problem.size(), r, u)?;
    config.validate()?;
    let outcome = if problem.q().chunks_exact(D).all(|qc| qc[0] >= -f64::EPSILON) {
        r.iter_mut().for_each(|v| *v = 0.0);
        SolverOutcome::stopped(0, false)
    } else {
        crate::solvers::rolling::run(&config.method, problem, &config.limits(), r, u, observer)?
    };
    Ok(report_measured(outcome, config.tolerance, r, u, |r, u| {
        rolling_error(problem, r, u)
    }))
}

/// The report of a 2D or rolling run: the error the run measured last, or `error_of` measured
/// now; a non-finite result is replaced by r = 0 (whose error is then reported).
fn report_measured(
    outcome: SolverOutcome,
    tolerance: f64,
    r: &mut [f64],
    u: &mut [f64],
    error_of: impl Fn(&[f64], &mut [f64]) -> f64,
) -> SolveReport {
    let mut error = match outcome.final_error {
        Some(e) => e,
        None => error_of(r, u),
    };
    if !error.is_finite() || !r.iter().chain(u.iter()).all(|v| v.is_finite()) {
        r.iter_mut().for_each(|v| *v = 0.0);
        error = error_of(r, u);
    }
    let status = if error <= tolerance {
        SolveStatus::Converged
    } else if outcome.out_of_time {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    };
    SolveReport {
        status,
        iterations: outcome.iterations,
        error,
        dumont_criterion: outcome.dumont_criterion,
        final_rho: None,
        stages: outcome.stages,
        fill: outcome.fill,
        products: outcome.products,
        f32_sweeps: outcome.f32_sweeps,
    }
}

#[cfg(test)]
mod tests {
    use super::grows_where_no_solution_is;
    use crate::matrix::{Delassus, DenseMatrix};
    use crate::problem::FrictionProblem;

    /// Two independent contacts (W = I): the first pushed apart by q and carrying the
    /// reaction, the second taking off with a left-over reaction of 1e-17, along which q
    /// pushes and whose W r rounds to 0 in u - q. The second carries nothing of the reaction:
    /// not a ray (Siconos' ADMM test 58 on Capsules-i122-1617 was reported unbounded this way).
    #[test]
    fn an_island_with_a_negligible_reaction_is_not_a_ray() {
        let mut w = vec![0.0; 36];
        (0..6).for_each(|i| w[i + 6 * i] = 1.0);
        let w = Delassus::Dense(DenseMatrix::new(6, 6, w).unwrap());
        let q = vec![-1.0, 0.0, 0.0, -1.0, 0.0, 0.0];
        let p = FrictionProblem::new(w, q.clone(), vec![0.5, 0.5]).unwrap();
        let r = vec![1.0, 0.0, 0.0, 1e-17, 0.0, 0.0];
        let u: Vec<f64> = r.iter().zip(&q).map(|(ri, qi)| ri + qi).collect();
        assert_eq!(u[3] - q[3], 0.0, "W r rounds to 0 on the second contact");
        assert!(!grows_where_no_solution_is(&p, &r, &u, 1e-6));
    }
}
