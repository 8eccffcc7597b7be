//! One entry point for every solver family: input checks shared by all of them, the trivial-case
//! shortcut, dispatch, and the final independent error measurement.

use crate::error::{check_finite, Fc3dError};
use crate::measure::natural_map_error;
use crate::nsgs;
use crate::nsn::{self, NsnOptions};
use crate::options::NsgsOptions;
use crate::problem::FrictionProblem;
use crate::prox::{self, ProxOptions};
use crate::report::{SolveReport, SolveStatus};

/// Which solver to run, with its typed options.
///
/// A new family plugs in as: a variant here (one options struct with documented defaults), an
/// arm in each method below and in [`solve_with_observer`]'s dispatch (a function
/// `fn(&FrictionProblem, &Options, r, u, observer) -> Result<SolverOutcome, Fc3dError>` that
/// starts from the `r` given and validates before touching it), an arm in
/// `capi::options::config_from_c` and a `Defaults` row there, and a family in `bench::spec`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolverConfig {
    /// Nonsmooth Gauss-Seidel (Siconos id 500).
    Nsgs(NsgsOptions),
    /// Projection / extragradient methods on the VI form (Siconos ids 505, 506, 507, 511, 512).
    Vi(crate::vi::ViOptions),
    /// ADMM on the local formulation (Siconos id 523).
    Admm(crate::admm::AdmmOptions),
    /// Tresca successive approximation (Siconos id 503).
    Tresca(crate::tresca::TrescaOptions),
    /// Panagiotopoulos alternating fixed point (Siconos id 522).
    Pfp(crate::pfp::PfpOptions),
    /// ACLM fixed point on the SOCLCP relaxation (Siconos id 516).
    Aclm(crate::soclcp::AclmOptions),
    /// The SOCLCP relaxation solved on its own (Siconos id 517).
    Soclcp(crate::soclcp::SoclcpOptions),
    /// Nonsmooth Newton: Alart-Curnier / Jean-Moreau (504), Fischer-Burmeister (513), natural
    /// map (520).
    Nsn(NsnOptions),
    /// Proximal point method with an NSN-AC or NSGS internal solver (502).
    Prox(ProxOptions),
}

impl SolverConfig {
    pub fn tolerance(&self) -> f64 {
        match self {
            SolverConfig::Nsgs(o) => o.tolerance,
            SolverConfig::Vi(o) => o.tolerance,
            SolverConfig::Admm(o) => o.tolerance,
            SolverConfig::Tresca(o) => o.tolerance,
            SolverConfig::Pfp(o) => o.tolerance,
            SolverConfig::Aclm(o) => o.tolerance,
            SolverConfig::Soclcp(o) => o.tolerance,
            SolverConfig::Nsn(o) => o.tolerance,
            SolverConfig::Prox(o) => o.tolerance,
        }
    }

    pub fn max_iter(&self) -> usize {
        match self {
            SolverConfig::Nsgs(o) => o.max_iter,
            SolverConfig::Vi(o) => o.max_iter,
            SolverConfig::Admm(o) => o.max_iter,
            SolverConfig::Tresca(o) => o.max_iter,
            SolverConfig::Pfp(o) => o.max_iter,
            SolverConfig::Aclm(o) => o.max_iter,
            SolverConfig::Soclcp(o) => o.max_iter,
            SolverConfig::Nsn(o) => o.max_iter,
            SolverConfig::Prox(o) => o.max_iter,
        }
    }

    /// Wall-clock budget, if any.
    pub fn time_budget(&self) -> Option<std::time::Duration> {
        match self {
            SolverConfig::Nsgs(o) => o.time_budget,
            SolverConfig::Vi(o) => o.time_budget,
            SolverConfig::Admm(o) => o.time_budget,
            SolverConfig::Tresca(o) => o.time_budget,
            SolverConfig::Pfp(o) => o.time_budget,
            SolverConfig::Aclm(o) => o.time_budget,
            SolverConfig::Soclcp(o) => o.time_budget,
            SolverConfig::Nsn(o) => o.time_budget,
            SolverConfig::Prox(o) => o.time_budget,
        }
    }

    /// Siconos id of the solver.
    pub fn siconos_id(&self) -> i32 {
        match self {
            SolverConfig::Nsgs(_) => 500,
            SolverConfig::Vi(o) => o.solver.siconos_id(),
            SolverConfig::Admm(_) => 523,
            SolverConfig::Tresca(_) => 503,
            SolverConfig::Pfp(_) => 522,
            SolverConfig::Aclm(_) => 516,
            SolverConfig::Soclcp(_) => 517,
            SolverConfig::Nsn(o) => o.formulation.siconos_id(),
            SolverConfig::Prox(_) => 502,
        }
    }

    /// Short human-readable name, e.g. `NSGS-565`.
    pub fn label(&self) -> String {
        match self {
            SolverConfig::Nsgs(o) => format!("NSGS/{}", o.local.kind.siconos_id()),
            SolverConfig::Vi(o) => o.solver.short_name().to_string(),
            SolverConfig::Admm(_) => "ADMM".to_string(),
            SolverConfig::Tresca(o) => format!("TFP/{}", o.inner.siconos_id()),
            SolverConfig::Pfp(o) => format!("PFP/{}", o.tangent.siconos_id()),
            SolverConfig::Aclm(_) => "ACLMFP".to_string(),
            SolverConfig::Soclcp(_) => "SOCLCP".to_string(),
            SolverConfig::Nsn(o) => o.label(),
            SolverConfig::Prox(o) => o.label(),
        }
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        let tol = self.tolerance();
        if !(tol >= 0.0) || !tol.is_finite() {
            return Err(Fc3dError::InvalidOption(format!(
                "tolerance must be finite and >= 0, got {tol}"
            )));
        }
        match self {
            SolverConfig::Nsgs(o) => {
                let lt = o.local.tolerance;
                if !(lt >= 0.0) || !lt.is_finite() {
                    return Err(Fc3dError::InvalidOption(format!(
                        "local tolerance must be finite and >= 0, got {lt}"
                    )));
                }
                if let crate::options::RhoRule::Constant(rho) = o.local.rho_rule {
                    if !(rho > 0.0) || !rho.is_finite() {
                        return Err(Fc3dError::InvalidOption(format!(
                            "constant rho must be finite and > 0, got {rho}"
                        )));
                    }
                }
            }
            SolverConfig::Vi(o) => o.validate()?,
            SolverConfig::Admm(o) => o.validate()?,
            SolverConfig::Tresca(o) => o.inner_tolerance.validate()?,
            SolverConfig::Pfp(o) => o.inner_tolerance.validate()?,
            SolverConfig::Aclm(o) => o.inner_tolerance.validate()?,
            SolverConfig::Soclcp(o) => o.validate()?,
            SolverConfig::Nsn(o) => nsn::validate(o)?,
            SolverConfig::Prox(o) => prox::validate(o)?,
        }
        Ok(())
    }
}

/// How a solver family's run ended. Every family returns this; [`solve_with_observer`] then sets
/// the status from the error it measures on the returned `(r, u)`.
pub(crate) struct SolverOutcome {
    /// Iterations done (sweeps for NSGS, Newton steps for NSN, ...).
    pub iterations: usize,
    /// The run stopped because its time budget was spent.
    pub out_of_time: bool,
    /// The natural-map error of the returned reaction when the family's last step measured it
    /// with [`natural_map_error`] on the host's storage, leaving `u = W r + q`; `None` when the
    /// caller must measure it (always safe).
    pub final_error: Option<f64>,
}

/// Progress of an iterative solver, handed to an observer after every iteration.
#[derive(Debug, Clone, Copy)]
pub struct IterationEvent<'a> {
    pub iteration: usize,
    pub reaction: &'a [f64],
    /// The error the solver tested at this iteration (cheap or full, as configured).
    pub error: f64,
}

/// Solves `problem` from the initial guess in `r`; on success `r` and `u = W r + q` hold the
/// result and the report holds the error measured on them.
///
/// On `Err`, `r` and `u` are left untouched.
pub fn solve(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
) -> Result<SolveReport, Fc3dError> {
    solve_with_observer(problem, config, r, u, &mut |_| {})
}

/// [`solve`] with an observer called after every iteration (the C `Callback`).
pub fn solve_with_observer(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolveReport, Fc3dError> {
    let n = problem.size();
    if r.len() != n {
        return Err(Fc3dError::dims("reaction", n, r.len()));
    }
    if u.len() != n {
        return Err(Fc3dError::dims("velocity", n, u.len()));
    }
    check_finite("initial reaction", r)?;
    config.validate()?;
    if let Some(b) = config.time_budget() {
        if b.is_zero() {
            return Err(Fc3dError::InvalidOption(
                "a time budget must be positive".into(),
            ));
        }
    }

    // Trivial case (Siconos): no contact is pushed into penetration by q, so r = 0, u = q.
    if problem.q().chunks_exact(3).all(|qc| qc[0] >= -f64::EPSILON) {
        r.iter_mut().for_each(|v| *v = 0.0);
        let error = natural_map_error(problem, r, u);
        let status = if error <= config.tolerance() {
            SolveStatus::Converged
        } else {
            SolveStatus::MaxIterationsReached
        };
        return Ok(SolveReport {
            status,
            iterations: 0,
            error,
            dumont_criterion: None,
        });
    }

    // SOCLCP solves a relaxation: whether the relaxed problem converged decides between
    // "not converged" and "converged to a relaxed solution that is not a Coulomb solution".
    let mut relaxation_converged = false;
    let (outcome, dumont_criterion) = match config {
        SolverConfig::Nsgs(o) => {
            let run = nsgs::nsgs(problem, o, r, u, observer)?;
            (run.outcome, run.dumont_criterion)
        }
        SolverConfig::Vi(o) => (crate::vi::vi(problem, o, r, u, observer)?, None),
        SolverConfig::Admm(o) => (crate::admm::admm(problem, o, r, u, observer)?, None),
        SolverConfig::Tresca(o) => (crate::tresca::tfp(problem, o, r, u, observer)?, None),
        SolverConfig::Pfp(o) => (crate::pfp::pfp(problem, o, r, u, observer)?, None),
        SolverConfig::Aclm(o) => (crate::soclcp::aclmfp(problem, o, r, u, observer)?, None),
        SolverConfig::Soclcp(o) => {
            let (outcome, relaxed) = crate::soclcp::soclcp(problem, o, r, u, observer)?;
            relaxation_converged = relaxed;
            (outcome, None)
        }
        SolverConfig::Nsn(o) => (nsn::nsn(problem, o, r, u, observer)?, None),
        SolverConfig::Prox(o) => (prox::prox(problem, o, r, u, observer)?, None),
    };

    // The reported error is always the natural-map error of the returned (r, u) on the host's
    // storage, whatever the solver's own stopping test was: measured here unless the solver's
    // last step already measured exactly that (same function, same r, u = W r + q).
    // NSGS's last test is that very computation (natural_map_error on the returned r, host
    // storage); for the other families one more W r product buys the guarantee without auditing
    // each family's bookkeeping.
    let mut error = match (config, outcome.final_error) {
        (SolverConfig::Nsgs(_), Some(e)) => e,
        _ => natural_map_error(problem, r, u),
    };
    // Last line of defence of the contract "r and u are finite": a finite r can still give an
    // infinite W r + q (entries near the overflow threshold). Then the host gets r = 0, u = q,
    // with the error of that pair, rather than infinities.
    if !error.is_finite() || !r.iter().chain(u.iter()).all(|v| v.is_finite()) {
        r.iter_mut().for_each(|v| *v = 0.0);
        error = natural_map_error(problem, r, u);
    }
    let status = if error <= config.tolerance() {
        SolveStatus::Converged
    } else if relaxation_converged {
        SolveStatus::RelaxationNotCoulomb
    } else if outcome.out_of_time {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    };
    Ok(SolveReport {
        status,
        iterations: outcome.iterations,
        error,
        dumont_criterion,
    })
}
