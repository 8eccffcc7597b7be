//! Projection methods on the variational-inequality form of FC(W, q, mu) (section 4 and Table 1
//! of Acary-Brémond-Huber): with De Saxcé's map
//!
//! `F(r) = W r + q + g(W r + q)`, `g(u)_c = (mu_c ||u_{T,c}||, 0, 0)`,
//!
//! r solves the problem iff `r = P_K(r - rho F(r))` for any `rho > 0` (K the product of the
//! Coulomb cones). Two iterations are built on that map:
//!
//! * fixed point (Algorithm 1, rule (95)): `r_{k+1} = P_K(r_k - rho_k F(r_k))`;
//! * extragradient (Algorithm 2, rule (96)): `r̄ = P_K(r_k - rho_k F(r_k))`,
//!   `r_{k+1} = P_K(r_k - rho_k F(r̄))`;
//!
//! with either a fixed `rho` or the self-adaptive Armijo-type rule of Algorithm 3, whose ratio is
//! Khobotov's (98) (UPK) or Solodov-Tseng's (99) (UPTS).
//!
//! Siconos exposes five ids over these: DSFP 505 (fixed point, fixed rho: "FP-DS"), VI_FPP 506
//! and VI_EG 507 (through its generic VI solvers), FPP 511 and EG 512 (written directly on the
//! friction problem). They differ only in defaults, so they share this one implementation;
//! [`ViSolver`] keeps the id for labels and the C layer.

use std::time::Instant;

use crate::cone::{modified_velocity, project_on_cone};
use crate::error::Fc3dError;
use crate::measure::{cheap_error, natural_map_error_of};
use crate::options::ErrorEvaluation;
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};

/// The Siconos solver a [`ViOptions`] stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViSolver {
    /// De Saxcé's fixed point with a fixed rho, "FP-DS" [505 DSFP].
    DeSaxceFixedPoint,
    /// Fixed-point projection through the VI solvers [506 VI_FPP].
    ViFixedPointProjection,
    /// Extragradient through the VI solvers [507 VI_EG].
    ViExtraGradient,
    /// Fixed-point projection on the friction problem [511 FPP].
    FixedPointProjection,
    /// Extragradient on the friction problem [512 EG].
    ExtraGradient,
}

/// The two iterations of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViIteration {
    /// Rule (95): one projection per iteration.
    FixedPoint,
    /// Rule (96): a prediction and a correction per iteration.
    ExtraGradient,
}

impl ViSolver {
    pub const ALL: [ViSolver; 5] = [
        ViSolver::DeSaxceFixedPoint,
        ViSolver::ViFixedPointProjection,
        ViSolver::ViExtraGradient,
        ViSolver::FixedPointProjection,
        ViSolver::ExtraGradient,
    ];

    pub fn siconos_id(self) -> i32 {
        match self {
            ViSolver::DeSaxceFixedPoint => 505,
            ViSolver::ViFixedPointProjection => 506,
            ViSolver::ViExtraGradient => 507,
            ViSolver::FixedPointProjection => 511,
            ViSolver::ExtraGradient => 512,
        }
    }

    pub fn from_siconos_id(id: i32) -> Option<Self> {
        ViSolver::ALL.into_iter().find(|s| s.siconos_id() == id)
    }

    /// Short name used in labels and by `fc3d bench` (`DSFP`, `VI-FPP`, `VI-EG`, `FPP`, `EG`).
    pub fn short_name(self) -> &'static str {
        match self {
            ViSolver::DeSaxceFixedPoint => "DSFP",
            ViSolver::ViFixedPointProjection => "VI-FPP",
            ViSolver::ViExtraGradient => "VI-EG",
            ViSolver::FixedPointProjection => "FPP",
            ViSolver::ExtraGradient => "EG",
        }
    }

    pub fn iteration(self) -> ViIteration {
        match self {
            ViSolver::DeSaxceFixedPoint
            | ViSolver::ViFixedPointProjection
            | ViSolver::FixedPointProjection => ViIteration::FixedPoint,
            ViSolver::ViExtraGradient | ViSolver::ExtraGradient => ViIteration::ExtraGradient,
        }
    }
}

/// The ratio Algorithm 3 compares with `L` to accept a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepRatio {
    /// (98), Khobotov: `rho ||F(r) - F(r̄)|| / ||r - r̄||` (UPK, Siconos' default).
    Khobotov,
    /// (99), Solodov-Tseng: `rho (r - r̄)·(F(r) - F(r̄)) / ||r - r̄||^2` (UPTS).
    SolodovTseng,
}

/// Algorithm 3's parameters (Siconos' constants by default).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAdaptiveStep {
    /// rho of the first iteration (default 1).
    pub initial_rho: f64,
    pub ratio: StepRatio,
    /// Reduction factor of a rejected trial, in (0, 1) (default 2/3).
    pub nu: f64,
    /// Increase factor applied after an easily accepted step, > 1 (default 3/2 = 1/nu).
    pub increase: f64,
    /// Acceptance threshold on the ratio, in (0, 1) (default 0.9).
    pub l: f64,
    /// Below this ratio the next rho is increased, in (0, L) (default 0.3).
    pub l_min: f64,
    /// Trials per iteration; the last one is taken when none is accepted (default 10).
    pub max_trials: usize,
}

impl Default for SelfAdaptiveStep {
    fn default() -> Self {
        SelfAdaptiveStep {
            initial_rho: 1.0,
            ratio: StepRatio::Khobotov,
            nu: 2.0 / 3.0,
            increase: 1.5,
            l: 0.9,
            l_min: 0.3,
            max_trials: 10,
        }
    }
}

/// How rho is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepSize {
    /// The same rho at every iteration.
    Fixed(f64),
    /// Algorithm 3.
    SelfAdaptive(SelfAdaptiveStep),
}

/// Options of the VI / fixed-point family (Siconos ids 505, 506, 507, 511, 512).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViOptions {
    pub solver: ViSolver,
    /// Maximum iterations (default 20000 for every id).
    pub max_iter: usize,
    /// Tolerance on the natural-map error (default 1e-3 for every id).
    pub tolerance: f64,
    /// Default: `Fixed(1.0)` for 505 and 511, `SelfAdaptive` with Siconos' constants for 506,
    /// 507 and 512.
    pub step: StepSize,
    /// Default: `LightWithFullFinal` for 506 and 507 (Siconos' iparam[7] = 1), `Full` for the
    /// others. The light error is the cheap error (134) `||r_{k+1} - r_k|| / ||r_{k+1}||`.
    pub error_evaluation: ErrorEvaluation,
    /// Wall-clock budget (default none): the run stops after the iteration that spends it.
    pub time_budget: Option<std::time::Duration>,
}

impl ViOptions {
    /// Siconos 4.4's defaults for `solver`.
    pub fn new(solver: ViSolver) -> Self {
        let (step, error_evaluation) = match solver {
            ViSolver::DeSaxceFixedPoint | ViSolver::FixedPointProjection => {
                (StepSize::Fixed(1.0), ErrorEvaluation::Full)
            }
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::default()),
                ErrorEvaluation::LightWithFullFinal,
            ),
            ViSolver::ExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::default()),
                ErrorEvaluation::Full,
            ),
        };
        ViOptions {
            solver,
            max_iter: 20000,
            tolerance: 1e-3,
            step,
            error_evaluation,
            time_budget: None,
        }
    }

    /// Checks the step parameters (the tolerance is checked by the caller).
    pub fn validate(&self) -> Result<(), Fc3dError> {
        let bad = |what: &str, v: f64, range: &str| {
            Err(Fc3dError::InvalidOption(format!(
                "{}: {what} = {v} must be {range}",
                self.solver.short_name()
            )))
        };
        if self.error_evaluation == ErrorEvaluation::DumontCriterion {
            return Err(Fc3dError::InvalidOption(format!(
                "{}: Dumont's criterion is a stopping test of NSGS sweeps (it needs the velocities \
                 contacts were solved with); use Full, Light or LightWithFullFinal",
                self.solver.short_name()
            )));
        }
        match self.step {
            StepSize::Fixed(rho) => {
                if !(rho > 0.0 && rho.is_finite()) {
                    return bad("rho", rho, "finite and > 0");
                }
            }
            StepSize::SelfAdaptive(s) => {
                if self.solver == ViSolver::DeSaxceFixedPoint {
                    return Err(Fc3dError::InvalidOption(
                        "DSFP (505) is the fixed-rho fixed point: use StepSize::Fixed".into(),
                    ));
                }
                if !(s.initial_rho > 0.0 && s.initial_rho.is_finite()) {
                    return bad("initial rho", s.initial_rho, "finite and > 0");
                }
                if !(s.nu > 0.0 && s.nu < 1.0) {
                    return bad("nu", s.nu, "in (0, 1)");
                }
                if !(s.increase >= 1.0 && s.increase.is_finite()) {
                    return bad("rho increase factor", s.increase, "finite and >= 1");
                }
                if !(s.l > 0.0 && s.l < 1.0) {
                    return bad("L", s.l, "in (0, 1)");
                }
                if !(s.l_min >= 0.0 && s.l_min < s.l) {
                    return bad("Lmin", s.l_min, "in [0, L)");
                }
                if s.max_trials == 0 {
                    return Err(Fc3dError::InvalidOption(format!(
                        "{}: the line search needs at least one trial",
                        self.solver.short_name()
                    )));
                }
            }
        }
        Ok(())
    }
}

impl Default for ViOptions {
    /// VI_FPP (506) with Siconos' defaults.
    fn default() -> Self {
        ViOptions::new(ViSolver::ViFixedPointProjection)
    }
}

/// `u = W r + q` and `f = F(r) = u + g(u)`.
fn evaluate(problem: &FrictionProblem<'_>, r: &[f64], u: &mut [f64], f: &mut [f64]) {
    problem.velocity(r, u);
    for ((fc, uc), &mu) in f
        .chunks_exact_mut(3)
        .zip(u.chunks_exact(3))
        .zip(problem.mu())
    {
        fc.copy_from_slice(&modified_velocity(&[uc[0], uc[1], uc[2]], mu));
    }
}

/// `out = P_K(r - rho f)`, contact by contact.
fn project_step(mu: &[f64], r: &[f64], f: &[f64], rho: f64, out: &mut [f64]) {
    for (c, &m) in mu.iter().enumerate() {
        let k = 3 * c;
        let x = [
            r[k] - rho * f[k],
            r[k + 1] - rho * f[k + 1],
            r[k + 2] - rho * f[k + 2],
        ];
        out[k..k + 3].copy_from_slice(&project_on_cone(&x, m));
    }
}

fn distance_sq(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Entries below 1e100 in magnitude: squares and sums of squares stay finite, so every norm and
/// error of such an iterate is finite. A diverging iteration is stopped before leaving this set.
fn bounded(v: &[f64]) -> bool {
    v.iter().all(|x| x.abs() < DIVERGENCE_BOUND)
}

const DIVERGENCE_BOUND: f64 = 1e100;

/// Algorithm 3's ratio for the trial `r̄` from `r` (F values `f`, `f̄`), 0 when `r̄ = r`.
fn step_ratio(kind: StepRatio, rho: f64, r: &[f64], rbar: &[f64], f: &[f64], fbar: &[f64]) -> f64 {
    let dr_sq = distance_sq(r, rbar);
    if dr_sq == 0.0 {
        return 0.0;
    }
    match kind {
        StepRatio::Khobotov => rho * distance_sq(f, fbar).sqrt() / dr_sq.sqrt(),
        StepRatio::SolodovTseng => {
            let dot: f64 = r
                .iter()
                .zip(rbar)
                .zip(f.iter().zip(fbar))
                .map(|((a, b), (fa, fb))| (a - b) * (fa - fb))
                .sum();
            rho * dot / dr_sq
        }
    }
}

/// Runs the method of `options` from the reaction in `r`; on return `u = W r + q`.
pub(crate) fn vi(
    problem: &FrictionProblem<'_>,
    options: &ViOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let n = problem.size();
    let mu = problem.mu();
    let tol = options.tolerance;
    let deadline = options.time_budget.map(|b| Instant::now() + b);
    let iteration_kind = options.solver.iteration();

    // Work vectors, allocated once: F at the current iterate, the trial (prediction) and its
    // velocity and F, and the extragradient's corrected iterate.
    let mut f = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut trial_u = vec![0.0; n];
    let mut trial_f = vec![0.0; n];
    let mut corrected = match iteration_kind {
        ViIteration::ExtraGradient => vec![0.0; n],
        ViIteration::FixedPoint => Vec::new(),
    };

    evaluate(problem, r, u, &mut f);
    let mut rho = match options.step {
        StepSize::Fixed(rho) => rho,
        StepSize::SelfAdaptive(s) => s.initial_rho,
    };
    let mut light_tol = tol;
    let mut last_measured = None;

    for iteration in 1..=options.max_iter {
        // Prediction, with Algorithm 3 when rho is self-adaptive.
        let mut rho_k = rho;
        let mut ratio = 0.0;
        let trials = match options.step {
            StepSize::Fixed(_) => 1,
            StepSize::SelfAdaptive(s) => s.max_trials,
        };
        for t in 0..trials {
            project_step(mu, r, &f, rho_k, &mut trial);
            evaluate(problem, &trial, &mut trial_u, &mut trial_f);
            let StepSize::SelfAdaptive(s) = options.step else {
                break;
            };
            let finite = bounded(&trial_f);
            ratio = if finite {
                step_ratio(s.ratio, rho_k, r, &trial, &f, &trial_f)
            } else {
                f64::INFINITY
            };
            if ratio <= s.l || t + 1 == trials {
                break;
            }
            rho_k *= s.nu;
        }

        // The new iterate: the prediction itself (fixed point) or the correction step.
        let (new_r, new_u, new_f) = match iteration_kind {
            ViIteration::FixedPoint => (&mut trial, &mut trial_u, &mut trial_f),
            ViIteration::ExtraGradient => {
                project_step(mu, r, &trial_f, rho_k, &mut corrected);
                evaluate(problem, &corrected, &mut trial_u, &mut trial_f);
                (&mut corrected, &mut trial_u, &mut trial_f)
            }
        };
        if !bounded(new_r) || !bounded(new_f) {
            // Diverged (rho far too large for W): keep the last bounded iterate and stop.
            return Ok(SolverOutcome {
                iterations: iteration,
                out_of_time: false,
                final_error: None,
            });
        }
        let increment_sq = distance_sq(r, new_r);
        r.copy_from_slice(new_r);
        u.copy_from_slice(new_u);
        f.copy_from_slice(new_f);
        if let StepSize::SelfAdaptive(s) = options.step {
            rho = if ratio < s.l_min {
                rho_k * s.increase
            } else {
                rho_k
            };
        }

        // u = W r + q holds exactly here, so the full error costs O(n) on top of the step.
        let (error, full, converged) = match options.error_evaluation {
            // (DumontCriterion is rejected by `validate`.)
            ErrorEvaluation::Full | ErrorEvaluation::DumontCriterion => {
                let e = natural_map_error_of(problem, r, u);
                (e, true, e <= tol)
            }
            ErrorEvaluation::Light => {
                let e = cheap_error(increment_sq, r);
                (e, false, e <= tol)
            }
            ErrorEvaluation::LightWithFullFinal => {
                let light = cheap_error(increment_sq, r);
                if light <= light_tol {
                    let full = natural_map_error_of(problem, r, u);
                    if full > tol && full > 0.0 {
                        // Ask the cheap error for what the full one still lacks.
                        light_tol = light * tol / full;
                    }
                    (full, true, full <= tol)
                } else {
                    (light, false, false)
                }
            }
        };
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        last_measured = full.then_some(error);
        if converged {
            return Ok(SolverOutcome {
                iterations: iteration,
                out_of_time: false,
                final_error: last_measured,
            });
        }
        if deadline.is_some_and(|d| Instant::now() >= d) {
            return Ok(SolverOutcome {
                iterations: iteration,
                out_of_time: true,
                final_error: last_measured,
            });
        }
    }
    Ok(SolverOutcome {
        iterations: options.max_iter,
        out_of_time: false,
        final_error: last_measured,
    })
}
