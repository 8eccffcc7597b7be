//! Proximal point method (PROX, Siconos id 502; Algorithm 8 of Acary-Brémond-Huber with
//! omega = 1): from `r_k`, solve the regularized problem FC(W + a_k I, q - a_k r_k, mu) with an
//! internal solver (NSN-AC: PPA-NSN-AC, or NSGS: PPA-NSGS-AC) to the internal tolerance
//! `max(error_k / 10, tol / n_contacts)` (Siconos' adaptive rule), and take its solution as
//! `r_{k+1}`. The shift follows Siconos 4.4's proximal strategy: with `alpha > 0` it starts at
//! `sigma error_0^nu` and, after each step, becomes `sigma error_{k+1}^nu` when the internal
//! solve converged and `10 a_k` when it did not; with `alpha < 0` it is the fixed `-alpha`.

use std::time::{Duration, Instant};

use crate::contract::{BestIterate, Family, IterationEvent, Limits, Observer, Run, SolverOutcome};
use crate::error::{require_setting, Fc3dError};
use crate::measure::natural_map_error;
use crate::problem::FrictionProblem;
use crate::solvers::nsgs::{nsgs, NsgsOptions};
use crate::solvers::nsn::{NewtonSolver, NsnFormulation, NsnOptions};

/// The solver of the regularized problems. Its tolerance is the internal tolerance of each
/// proximal step; its other settings (rho, line search, local solver, ...) are used as given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProxInternal {
    /// Alart-Curnier nonsmooth Newton (Siconos' default, 504).
    NsnAc(NsnOptions),
    /// Nonsmooth Gauss-Seidel (500).
    Nsgs(NsgsOptions),
}

impl ProxInternal {
    fn family(&self) -> &dyn Family {
        match self {
            ProxInternal::NsnAc(n) => n,
            ProxInternal::Nsgs(g) => g,
        }
    }
}

/// Settings of the proximal point method, Siconos 4.4's defaults. Its limits default to 1000
/// proximal iterations and a tolerance of 1e-4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProxOptions {
    /// Siconos' alpha (dparam[3], default 1e4): > 0 selects the variable shift (its value is
    /// then not used, as in Siconos), < 0 the fixed shift `-alpha`.
    pub alpha: f64,
    /// Factor of the shift rule `a_k = sigma error_k^nu` (dparam[4], 5).
    pub sigma: f64,
    /// Exponent of the shift rule (dparam[5], 1).
    pub nu: f64,
    /// Internal solver (NSN-AC with Siconos' 504 defaults).
    pub internal: ProxInternal,
    /// Iteration limit of each internal solve; `None` (default) takes the internal solver's own
    /// default (200 Newton iterations, 1000 NSGS sweeps).
    pub internal_max_iter: Option<usize>,
}

impl Default for ProxOptions {
    fn default() -> Self {
        ProxOptions {
            alpha: 1e4,
            sigma: 5.0,
            nu: 1.0,
            internal: ProxInternal::NsnAc(NsnOptions::new(NsnFormulation::AlartCurnier)),
            internal_max_iter: None,
        }
    }
}

impl ProxOptions {
    /// Short label: `PROX/NSN-AC` or `PROX/NSGS`.
    pub fn label(&self) -> String {
        match self.internal {
            ProxInternal::NsnAc(_) => "PROX/NSN-AC".into(),
            ProxInternal::Nsgs(_) => "PROX/NSGS".into(),
        }
    }
}

impl ProxOptions {
    fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.alpha.is_finite() && self.alpha.abs() >= 1e-12,
            "prox.alpha",
            self.alpha,
            "finite with |alpha| >= 1e-12 (> 0 variable shift, < 0 fixed shift -alpha)",
        )?;
        for (setting, v) in [("prox.sigma", self.sigma), ("prox.nu", self.nu)] {
            require_setting(v > 0.0 && v.is_finite(), setting, v, "finite and > 0")?;
        }
        if let ProxInternal::NsnAc(n) = &self.internal {
            if !matches!(
                n.formulation,
                NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau
            ) {
                return Err(Fc3dError::InvalidOption(
                    "the proximal method's Newton solver must use the Alart-Curnier or \
                     Jean-Moreau formulation"
                        .into(),
                ));
            }
        }
        self.internal.family().validate()
    }

    /// The iteration limit of each internal solve.
    fn internal_max_iter(&self) -> usize {
        self.internal_max_iter
            .unwrap_or_else(|| self.internal.family().default_limits().1)
    }
}

impl Family for ProxOptions {
    fn presets() -> Vec<Self> {
        vec![
            ProxOptions::default(),
            ProxOptions {
                internal: ProxInternal::Nsgs(NsgsOptions::default()),
                ..ProxOptions::default()
            },
        ]
    }

    fn name(&self) -> &'static str {
        match self.internal {
            ProxInternal::NsnAc(_) => "PROX",
            ProxInternal::Nsgs(_) => "PROX-NSGS",
        }
    }

    fn label(&self) -> String {
        ProxOptions::label(self)
    }

    fn siconos_id(&self) -> i32 {
        502
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        ProxOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        prox(problem, self, limits, r, u, observer)
    }
}

/// Runs the proximal point method from the reaction in `r`.
fn prox(
    problem: &FrictionProblem<'_>,
    options: &ProxOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    // The budget counts from here: the copy of W and the symbolic analysis are part of it.
    let run = limits.start();
    if matches!(options.internal, ProxInternal::NsnAc(_)) {
        if let Some(stop) =
            super::stop_before_analysis(problem.w(), run.deadline(), || problem.velocity(r, u))
        {
            return Ok(stop);
        }
    }
    let (mut state, _) = ProxState::reusing(problem, options, None)?;
    state.run(problem, &run, r, u, observer)
}

/// The proximal iteration between calls: the Newton solver of the regularized problems (its
/// matrix and symbolic factorization built once) and the shift the next step takes. AUTO runs
/// PROX in chunks through one state, so a chunk goes on where the last one stopped instead of
/// starting over (analysis and shift rule) from its iterate.
pub(crate) struct ProxState {
    options: ProxOptions,
    newton: Option<NewtonSolver>,
    shifted_q: Vec<f64>,
    /// The shift of the next proximal step; `None`: from the shift rule at the first step.
    shift: Option<f64>,
}

impl ProxState {
    /// The state of PROX with `options` on `problem`, taking over `kept`'s Newton matrix and
    /// symbolic factorization when W's block pattern is the one it was built for (see
    /// [`NewtonSolver::reusing`]); whether it did.
    pub(crate) fn reusing(
        problem: &FrictionProblem<'_>,
        options: &ProxOptions,
        kept: Option<NewtonSolver>,
    ) -> Result<(Self, bool), Fc3dError> {
        options.validate()?;
        let (newton, reused) = match &options.internal {
            ProxInternal::NsnAc(n) => {
                let (solver, reused) = NewtonSolver::reusing(problem, n, kept)?;
                (Some(solver), reused)
            }
            ProxInternal::Nsgs(_) => (None, false),
        };
        let shifted_q = crate::error::try_vec(problem.size(), 0.0, "proximal right-hand side")?;
        Ok((
            ProxState {
                options: *options,
                newton,
                shifted_q,
                shift: None,
            },
            reused,
        ))
    }

    /// The next run starts the shift rule over (a new stage from another iterate).
    pub(crate) fn restart(&mut self) {
        self.shift = None;
    }

    /// The Newton solver, for a workspace to keep.
    pub(crate) fn into_newton(self) -> Option<NewtonSolver> {
        self.newton
    }

    /// Runs PROX with the state's options in `run`'s limits.
    pub(crate) fn run(
        &mut self,
        problem: &FrictionProblem<'_>,
        run: &Run,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        let options = self.options;
        let internal_max_iter = options.internal_max_iter();
        let mut error = natural_map_error(problem, r, u);
        let mut best = BestIterate::try_new(r, error)?;
        if error <= run.tolerance {
            return Ok(SolverOutcome::stopped(0, false));
        }
        let mut iterations = 0;
        let mut out_of_time = false;
        let variable = options.alpha > 0.0;
        let mut shift = match self.shift {
            Some(shift) if variable => shift,
            _ if variable => options.sigma * error.powf(options.nu),
            _ => -options.alpha,
        };
        let tolerance_floor = run.tolerance / problem.n_contacts().max(1) as f64;
        let newton = &mut self.newton;
        let shifted_q = &mut self.shifted_q;
        for iteration in 1..=run.max_iter {
            iterations = iteration;
            for ((sq, q), ri) in shifted_q.iter_mut().zip(problem.q()).zip(r.iter()) {
                *sq = q - shift * ri;
            }
            let internal_tol = (error / 10.0).max(tolerance_floor);
            let (internal_converged, internal_out_of_time) = match &options.internal {
                ProxInternal::NsnAc(_) => {
                    let solver = newton.as_mut().expect("built for NSN-AC");
                    let inner = run.inner(internal_tol, internal_max_iter);
                    let outcome =
                        solver.run(shifted_q, problem.mu(), shift, &inner, r, u, &mut |_| {});
                    (outcome.converged, outcome.out_of_time)
                }
                ProxInternal::Nsgs(g) => {
                    let inner = FrictionProblem::new(
                        problem.w().shifted(shift)?,
                        shifted_q.clone(),
                        problem.mu().to_vec(),
                    )?;
                    // What is left of the budget; an exhausted one still allows one sweep.
                    let time_budget = run.deadline().map(|d| {
                        let left = d.saturating_duration_since(Instant::now());
                        left.max(Duration::from_nanos(1))
                    });
                    let inner_limits = Limits {
                        tolerance: internal_tol,
                        max_iter: internal_max_iter,
                        time_budget,
                    };
                    let outcome = nsgs(&inner, g, &inner_limits, r, u, &mut |_| {})?;
                    let inner_error = outcome
                        .final_error
                        .unwrap_or_else(|| natural_map_error(&inner, r, u));
                    (inner_error <= internal_tol, outcome.out_of_time)
                }
            };
            error = natural_map_error(problem, r, u);
            best.offer(r, error);
            observer(&IterationEvent {
                iteration,
                reaction: r,
                error,
            });
            if error <= run.tolerance {
                return Ok(SolverOutcome::stopped(iterations, false)
                    .with_fill(newton.as_ref().and_then(NewtonSolver::fill)));
            }
            if !error.is_finite() {
                break;
            }
            // An internal solve stopped by the budget (possibly before its first iteration,
            // which was expected to end past the deadline) ends the run: another proximal step
            // could not do more, and its unconverged solve must not inflate the shift.
            if internal_out_of_time || run.out_of_time() {
                out_of_time = true;
                break;
            }
            if variable {
                shift = if internal_converged {
                    options.sigma * error.powf(options.nu)
                } else {
                    10.0 * shift
                };
                if !(shift.is_finite() && shift > 0.0) {
                    break;
                }
                self.shift = Some(shift);
            }
        }
        best.restore_if_better(r, error);
        Ok(SolverOutcome::stopped(iterations, out_of_time)
            .with_fill(newton.as_ref().and_then(NewtonSolver::fill)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_run_in_chunks_goes_on_as_one_run() {
        // AUTO runs PROX in chunks through one state: while the error falls at every step (no
        // earlier iterate restored at a chunk's end), two chunks of 3 steps give one run of 6,
        // bit for bit (a shift rule started over would not: sigma * error at the second chunk's
        // first step instead of the rule's value).
        let p = crate::scenes::sphere_piles(&crate::scenes::PileSpec {
            contacts: 60,
            piles: 1,
            seed: 3,
        })
        .unwrap();
        let options = ProxOptions::default();
        let limits = |max_iter| Limits {
            tolerance: 1e-14,
            max_iter,
            time_budget: None,
        };
        let n = p.size();
        let (mut r1, mut u1) = (vec![0.0; n], vec![0.0; n]);
        let mut errors = Vec::new();
        let whole = prox(&p, &options, &limits(6), &mut r1, &mut u1, &mut |e| {
            errors.push(e.error)
        })
        .unwrap();
        assert_eq!(whole.iterations, 6);
        assert!(errors.windows(2).all(|e| e[1] < e[0]), "{errors:?}");
        let (mut state, reused) = ProxState::reusing(&p, &options, None).unwrap();
        assert!(!reused);
        let (mut r2, mut u2) = (vec![0.0; n], vec![0.0; n]);
        for _ in 0..2 {
            let o = state
                .run(&p, &limits(3).start(), &mut r2, &mut u2, &mut |_| {})
                .unwrap();
            assert_eq!(o.iterations, 3);
        }
        assert_eq!(r1, r2);
        // The next step takes the shift the state holds: one step from a held shift x is one
        // step of the fixed shift x; restarted, it is the rule's sigma * error again.
        let held = 0.37;
        let fixed = ProxOptions {
            alpha: -held,
            ..options
        };
        let (mut r3, mut u3) = (vec![0.0; n], vec![0.0; n]);
        prox(&p, &fixed, &limits(1), &mut r3, &mut u3, &mut |_| {}).unwrap();
        for restart in [false, true] {
            state.shift = Some(held);
            if restart {
                state.restart();
            }
            let (mut r4, mut u4) = (vec![0.0; n], vec![0.0; n]);
            state
                .run(&p, &limits(1).start(), &mut r4, &mut u4, &mut |_| {})
                .unwrap();
            assert_eq!(r3 == r4, !restart, "restart {restart}");
        }
        // A kept Newton matrix for the same pattern is taken over.
        let newton = state.into_newton();
        assert!(newton.is_some());
        assert!(ProxState::reusing(&p, &options, newton).unwrap().1);
    }
}
