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

mod settings;

pub use settings::{SelfAdaptiveStep, StepRatio, StepSize, ViIteration, ViOptions, ViSolver};

use crate::contract::{ErrorSchedule, Family, IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::Fc3dError;
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::math::linalg::{bounded, distance_sq};
use crate::measure::natural_map_error_of;
use crate::problem::FrictionProblem;

impl Family for ViOptions {
    fn presets() -> Vec<Self> {
        ViSolver::ALL.into_iter().map(ViOptions::new).collect()
    }

    fn name(&self) -> &'static str {
        self.solver.short_name()
    }

    fn label(&self) -> String {
        self.solver.short_name().to_string()
    }

    fn siconos_id(&self) -> i32 {
        self.solver.siconos_id()
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-3, 20000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        ViOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        vi(problem, self, limits, r, u, observer)
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
fn vi(
    problem: &FrictionProblem<'_>,
    options: &ViOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let n = problem.size();
    let mu = problem.mu();
    let run = limits.start();
    let mut schedule = ErrorSchedule::new(options.error_evaluation, run.tolerance, 1, run.max_iter);
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

    for iteration in 1..=run.max_iter {
        // Prediction, with Algorithm 3 when rho is self-adaptive.
        let mut rho_k = rho;
        let mut ratio = 0.0;
        let trials = match options.step {
            StepSize::Fixed(_) => 1,
            StepSize::SelfAdaptive(s) => s.max_trials,
        };
        for t in 0..trials {
            if t > 0 && run.out_of_time() {
                // The iteration ends with this trial; the loop stops after it.
                break;
            }
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
            return Ok(SolverOutcome::diverged(iteration));
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
        // (Dumont's criterion is rejected by `validate`.)
        let test = schedule.test(iteration, increment_sq, r, |_| {
            natural_map_error_of(problem, r, u)
        });
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error: test.error,
        });
        if let Some(outcome) = run.end_of_iteration(iteration, test.converged) {
            return Ok(outcome);
        }
    }
    Ok(run.exhausted())
}
