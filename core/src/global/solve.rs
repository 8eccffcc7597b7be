//! The entry point of a global solve: input checks, the case without contacts, the dispatch,
//! and the report of the global error of the returned `(r, u, v)` measured on the host's M and
//! H.

use std::time::{Duration, Instant};

use super::config::{GlobalConfig, GlobalMethod, GlobalRollingConfig};
use super::rescaling::{GlobalRescaling, Scaling};
use super::{aclm, admm, alm, hform, ipm, jacobi, newton, vi};
use crate::config::{MethodConfig, SolverConfig};
use crate::contract::{Limits, Observer, SolveReport, SolveStatus, SolverOutcome};
use crate::error::{check_finite, try_vec, Fc3dError};
use crate::matrix::HForm;
use crate::measure::{global_error, global_rolling_error, ContactLaw};
use crate::problem::{GlobalProblem, GlobalRollingProblem};
use crate::solve::{solve_rolling, solve_with_observer};

/// What a global solve returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalReport {
    pub status: SolveStatus,
    /// Iterations of the method (for a reduction: of its local solves, all rounds).
    pub iterations: usize,
    /// Siconos' global error ([`global_error`], Coulomb's law) of the returned
    /// `(r, u, v)`, measured on the host's M and H.
    pub error: f64,
    /// For a reduction, the last local solve's report (its error is the local problem's).
    pub local: Option<SolveReport>,
}

impl GlobalReport {
    pub fn converged(&self) -> bool {
        self.status == SolveStatus::Converged
    }
}

/// The host's arrays: `r`, `u` of the problem's size, `v` of M's size, a finite initial `r`.
fn check_arrays(
    size: usize,
    ndof: usize,
    r: &[f64],
    u: &[f64],
    v: &[f64],
) -> Result<(), Fc3dError> {
    if r.len() != size {
        return Err(Fc3dError::dims("reaction", size, r.len()));
    }
    if u.len() != size {
        return Err(Fc3dError::dims("velocity", size, u.len()));
    }
    if v.len() != ndof {
        return Err(Fc3dError::dims("global velocity", ndof, v.len()));
    }
    check_finite("initial reaction", r)
}

/// Solves the global problem from the reaction in `r`; on success `r`, `u = H^T v + b` and
/// `v` (`M v = q + H r` to round-off) hold the result and the report holds its global error.
/// M is factored once (block by block when it is block diagonal); neither M nor H is
/// modified.
///
/// On an `Err` found before the run (dimensions, settings, a singular M), the arrays are left
/// untouched; later errors may leave intermediate values in them (the C API solves into
/// copies).
pub fn solve_global(
    problem: &GlobalProblem<'_>,
    config: &GlobalConfig,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
) -> Result<GlobalReport, Fc3dError> {
    solve_global_with_observer(problem, config, r, u, v, &mut |_| {})
}

/// [`solve_global`] with an observer called after every iteration (for a reduction: of the
/// local solver, with the local error).
pub fn solve_global_with_observer(
    problem: &GlobalProblem<'_>,
    config: &GlobalConfig,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<GlobalReport, Fc3dError> {
    let entry = Instant::now();
    check_arrays(problem.size(), problem.ndof(), r, u, v)?;
    config.validate()?;
    let mut operator = problem.operator()?;
    // The budget counts from the call: what preparing M took is spent.
    let config = &MethodConfig {
        time_budget: config.time_budget.map(|b| {
            b.saturating_sub(entry.elapsed())
                .max(Duration::from_nanos(1))
        }),
        ..*config
    };
    if problem.n_contacts() == 0 {
        return Ok(without_contacts(
            &mut operator,
            problem.q(),
            v,
            |v| global_error(problem, ContactLaw::Coulomb, &[], &mut [], v),
            config.tolerance,
        ));
    }
    if config.method.rescaling() != GlobalRescaling::None {
        return solve_rescaled(problem, config, &mut operator, r, u, v, observer);
    }
    let limits = config.limits();
    let outcome = match &config.method {
        GlobalMethod::Reduced(method) => {
            let local = problem.reduce(&mut operator)?;
            return tightening(
                config.tolerance,
                config.max_iter,
                config.time_budget,
                r,
                u,
                &mut (&mut operator, v),
                |_, limits, r, u| {
                    let local_config = SolverConfig {
                        tolerance: limits.0,
                        max_iter: limits.1,
                        time_budget: limits.2,
                        ..SolverConfig::new(*method)
                    };
                    solve_with_observer(&local, &local_config, r, u, observer).map(Round::of_local)
                },
                |(operator, v), r, u| {
                    operator.global_velocity(problem.q(), r, v);
                    global_error(problem, ContactLaw::Coulomb, r, u, v)
                },
            );
        }
        GlobalMethod::Aclm(options) => {
            aclm::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::Admm(options) => {
            admm::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::Ipm(options) => {
            ipm::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::HForm(options) => {
            hform::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::ProjectedJacobi(options) => {
            jacobi::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::Newton(options) => {
            newton::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::AugmentedLagrangian(options) => {
            alm::run(problem, &mut operator, options, &limits, r, u, v, observer)?
        }
        GlobalMethod::Vi(options) => {
            return tightening(
                config.tolerance,
                config.max_iter,
                config.time_budget,
                r,
                u,
                &mut (&mut operator, v),
                |(operator, v), limits, r, u| {
                    let limits = Limits {
                        tolerance: limits.0,
                        max_iter: limits.1,
                        time_budget: limits.2,
                    };
                    let (outcome, vi_error) =
                        vi::run(problem, operator, options, &limits, r, u, v, observer)?;
                    Ok(Round {
                        status: own_status(&outcome, vi_error, limits.tolerance),
                        iterations: outcome.iterations,
                        own_error: vi_error,
                        local: None,
                    })
                },
                |(operator, v), r, u| {
                    operator.global_velocity(problem.q(), r, v);
                    global_error(problem, ContactLaw::Coulomb, r, u, v)
                },
            );
        }
    };
    Ok(finish(
        problem,
        &mut operator,
        config.tolerance,
        outcome,
        r,
        u,
        v,
    ))
}

/// Solves the rescaled problem ([`GlobalRescaling`]) from the rescaled `(r, u, v)` and maps
/// its result back; the error and the status are those of the original problem (Siconos
/// reports the rescaled problem's), which is solved again with a lower tolerance while the
/// rescaled one converged and the original one is above the tolerance.
fn solve_rescaled(
    problem: &GlobalProblem<'_>,
    config: &GlobalConfig,
    operator: &mut HForm,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<GlobalReport, Fc3dError> {
    let scaling = Scaling::of(problem, config.method.rescaling())?;
    let rescaled = scaling.apply(problem)?;
    let method = config.method.without_rescaling();
    let mut rs = try_vec(problem.size(), 0.0, "the rescaled reaction")?;
    let mut us = try_vec(problem.size(), 0.0, "the rescaled velocity")?;
    let mut vs = try_vec(problem.ndof(), 0.0, "the rescaled global velocity")?;
    tightening(
        config.tolerance,
        config.max_iter,
        config.time_budget,
        r,
        u,
        &mut (operator, v),
        |(_, v), limits, r, u| {
            scaling.to_rescaled((r, u, v), (&mut rs, &mut us, &mut vs));
            let round_config = GlobalConfig {
                tolerance: limits.0,
                max_iter: limits.1,
                time_budget: limits.2,
                method,
            };
            let report = solve_global_with_observer(
                &rescaled,
                &round_config,
                &mut rs,
                &mut us,
                &mut vs,
                observer,
            )?;
            scaling.to_original((&rs, &us, &vs), (r, u, v));
            Ok(Round {
                status: report.status,
                iterations: report.iterations,
                own_error: report.error,
                local: report.local,
            })
        },
        |(operator, v), r, u| {
            operator.global_velocity(problem.q(), r, v);
            global_error(problem, ContactLaw::Coulomb, r, u, v)
        },
    )
}

/// The status of a run by the error it stopped on, in its own measure.
fn own_status(outcome: &SolverOutcome, error: f64, tolerance: f64) -> SolveStatus {
    if error <= tolerance {
        SolveStatus::Converged
    } else if outcome.diverged {
        SolveStatus::Unbounded
    } else if outcome.out_of_time {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    }
}

/// The post-processing of a direct global solver: `v = M^-1 (q + H r)` and `u = H^T v + b`
/// from the returned reaction (unless the run's last step left exactly that triple and
/// measured it), the global error of the triple, and the status from it.
fn finish(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    tolerance: f64,
    outcome: SolverOutcome,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
) -> GlobalReport {
    let mut error = match outcome.final_error {
        Some(e) => e,
        None => {
            operator.global_velocity(problem.q(), r, v);
            global_error(problem, ContactLaw::Coulomb, r, u, v)
        }
    };
    // As in the local solve: a host never gets infinities; r = 0 and its velocities instead.
    if !error.is_finite()
        || !r
            .iter()
            .chain(u.iter())
            .chain(v.iter())
            .all(|x| x.is_finite())
    {
        r.iter_mut().for_each(|x| *x = 0.0);
        operator.global_velocity(problem.q(), r, v);
        error = global_error(problem, ContactLaw::Coulomb, r, u, v);
    }
    let status = if error <= tolerance {
        SolveStatus::Converged
    } else if outcome.diverged {
        SolveStatus::Unbounded
    } else if outcome.relaxation_converged {
        SolveStatus::RelaxationNotCoulomb
    } else if outcome.out_of_time {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    };
    GlobalReport {
        status,
        iterations: outcome.iterations,
        error,
        local: None,
    }
}

/// Solves a global rolling problem (Siconos' 5000): the reduction to the local rolling problem,
/// `config`'s rolling method on it, and the rolling global error
/// ([`global_rolling_error`]).
pub fn solve_global_rolling(
    problem: &GlobalRollingProblem<'_>,
    config: &GlobalRollingConfig,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
) -> Result<GlobalReport, Fc3dError> {
    let base = problem.base();
    check_arrays(base.size(), base.ndof(), r, u, v)?;
    config.validate()?;
    let mut operator = base.operator()?;
    if base.n_contacts() == 0 {
        return Ok(without_contacts(
            &mut operator,
            base.q(),
            v,
            |v| global_rolling_error(problem, &[], &mut [], v),
            config.tolerance,
        ));
    }
    let local = problem.reduce(&mut operator)?;
    let method = config.method;
    tightening(
        config.tolerance,
        config.max_iter,
        config.time_budget,
        r,
        u,
        &mut (&mut operator, v),
        |_, limits, r, u| {
            let local_config = GlobalRollingConfig {
                tolerance: limits.0,
                max_iter: limits.1,
                time_budget: limits.2,
                method,
            };
            solve_rolling(&local, &local_config, r, u).map(Round::of_local)
        },
        |(operator, v), r, u| {
            operator.global_velocity(base.q(), r, v);
            global_rolling_error(problem, r, u, v)
        },
    )
}

/// A problem without contacts: `v = M^-1 q`.
fn without_contacts(
    operator: &mut HForm,
    q: &[f64],
    v: &mut [f64],
    error_of: impl FnOnce(&[f64]) -> f64,
    tolerance: f64,
) -> GlobalReport {
    v.copy_from_slice(q);
    operator.solve_mass(v);
    let error = error_of(v);
    GlobalReport {
        status: if error <= tolerance {
            SolveStatus::Converged
        } else {
            SolveStatus::MaxIterationsReached
        },
        iterations: 0,
        error,
        local: None,
    }
}

/// The limits of one round of [`tightening`]: tolerance, iterations, budget.
type RoundLimits = (f64, usize, Option<Duration>);

/// One run of a solver that stops on its own error measure (a reduction's local solver, the
/// VI solvers' VI error).
struct Round {
    status: SolveStatus,
    iterations: usize,
    /// The error the run stopped on, in its own measure.
    own_error: f64,
    /// A reduction's local report.
    local: Option<SolveReport>,
}

impl Round {
    fn of_local(report: SolveReport) -> Round {
        Round {
            status: report.status,
            iterations: report.iterations,
            own_error: report.error,
            local: Some(report),
        }
    }
}

/// Runs a solver that stops on its own error measure (the local error of a reduction, the VI
/// error), then recovers v and measures the global error of the triple; while the run
/// converged in its measure but the global error is above the tolerance (a reduction's local
/// error normalises the same residual by `||q_loc||` too and has no balance term; the VI error
/// mixes the balance and the law), runs again from the result with its tolerance lowered in
/// the ratio of the two errors, within the iteration limit and the budget.
/// `state` (the operator and v) is lent to both closures in turn.
#[allow(clippy::too_many_arguments)]
fn tightening<S>(
    tolerance: f64,
    max_iter: usize,
    time_budget: Option<Duration>,
    r: &mut [f64],
    u: &mut [f64],
    state: &mut S,
    mut run_round: impl FnMut(&mut S, RoundLimits, &mut [f64], &mut [f64]) -> Result<Round, Fc3dError>,
    mut measure: impl FnMut(&mut S, &[f64], &mut [f64]) -> f64,
) -> Result<GlobalReport, Fc3dError> {
    let start = Instant::now();
    let mut round_tolerance = tolerance;
    let mut iterations = 0;
    loop {
        let budget = time_budget.map(|b| {
            b.saturating_sub(start.elapsed())
                .max(Duration::from_nanos(1))
        });
        let round = run_round(
            state,
            (round_tolerance, max_iter - iterations, budget),
            r,
            u,
        )?;
        iterations += round.iterations;
        let error = measure(state, r, u);
        let out_of_time = time_budget.is_some_and(|b| start.elapsed() >= b);
        let converged = round.status == SolveStatus::Converged;
        let tighten = converged
            && error > tolerance
            && error.is_finite()
            && iterations < max_iter
            && !out_of_time
            && round_tolerance > f64::EPSILON;
        if !tighten {
            let status = if error <= tolerance {
                SolveStatus::Converged
            } else if converged {
                if out_of_time {
                    SolveStatus::TimeBudgetExhausted
                } else {
                    SolveStatus::MaxIterationsReached
                }
            } else {
                round.status
            };
            return Ok(GlobalReport {
                status,
                iterations,
                error,
                local: round.local,
            });
        }
        // The run's own error is at most its tolerance; aim below the global tolerance by
        // the ratio seen, with a margin.
        let ratio = (round.own_error.max(f64::MIN_POSITIVE) / error).min(1.0);
        round_tolerance = (0.5 * tolerance * ratio).min(0.5 * round_tolerance);
    }
}
