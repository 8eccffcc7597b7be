//! Nonsmooth Newton methods (Algorithm 4, Table 2 of Acary-Brémond-Huber): Newton on
//! `F(r) = 0` for the Alart-Curnier, Jean-Moreau, Fischer-Burmeister or natural-map function,
//! with `J = A + B W` assembled on W's fixed block pattern and solved with faer's sparse LU
//! (symbolic factorization reused), globalised by a line search on `||F||^2 / 2`.
//!
//! The direction is the plain Newton one where J is regular; where it is numerically singular
//! (hyperstatic contacts: a box on 4 points), or cannot be factored, a regularised Newton step
//! (see `direction`); when no regularised matrix can be factored either, the fixed-point
//! direction `-F` (for the natural map `r - F(r)` is the projected step). A step is only taken
//! if its merit is finite, so r stays finite. A run that does not converge returns the best
//! iterate it measured.

mod direction;
pub(crate) mod jacobian;
pub(crate) mod linesearch;
mod settings;
mod sparse;

pub use settings::{NsnFormulation, NsnLineSearch, NsnOptions, NONMONOTONE_MEMORY};

/// One contact's Alart-Curnier residual `F(r, u)` (or, with `jean_moreau`, the Jean-Moreau one)
/// at independent `r` and `u`, with `dF/dr` and `dF/du` (row-major): the per-contact pieces NSN
/// assembles, for hosts that assemble their own Newton (Siconos' `computeAlartCurnierSTD`).
pub fn alart_curnier_parts(
    r: &Vec3,
    u: &Vec3,
    mu: f64,
    rho_n: f64,
    rho_t: f64,
    jean_moreau: bool,
) -> (Vec3, Mat3, Mat3) {
    let formulation = if jean_moreau {
        NsnFormulation::JeanMoreau
    } else {
        NsnFormulation::AlartCurnier
    };
    residual(formulation, r, u, &ContactData { mu, rho_n, rho_t })
}

use std::time::{Duration, Instant};

use crate::contract::{Family, IterationEvent, Limits, Observer, Run, SolverOutcome};
use crate::error::Fc3dError;
use crate::local::AlgorithmVariant;
use crate::math::linalg::{norm, Mat3, Vec3};
use crate::matrix::BlockSparseMatrix;
use crate::measure::{absolute_natural_map_residual, relative_scale};
use crate::problem::FrictionProblem;
use direction::{Direction, Jacobian, NewtonLinearSolver, Step};
use jacobian::{residual, ContactData};

/// How a [`NewtonSolver::run`] ended.
pub(crate) struct RunOutcome {
    pub iterations: usize,
    pub converged: bool,
    pub out_of_time: bool,
    /// Relative natural-map error of the returned r (for the problem that was solved).
    pub error: f64,
    /// Iterations whose direction came from the regularised Newton matrix (J numerically
    /// singular).
    pub regularized: usize,
}

/// Everything a Newton solve needs, allocated once: W's block copy, the Newton matrix with its
/// symbolic factorization, and the work vectors. Reusable for problems `(W + shift I, q', mu)`
/// with the same W (the proximal point method solves a sequence of them).
pub(crate) struct NewtonSolver {
    options: NsnOptions,
    w: BlockSparseMatrix<'static>,
    linear: NewtonLinearSolver,
    data: Vec<ContactData>,
    a: Vec<Mat3>,
    b: Vec<Mat3>,
    f: Vec<f64>,
    /// The direction of the current iteration and its images under W and J.
    step: Step,
    best_r: Vec<f64>,
    /// Duration of the last Newton iteration of any [`NewtonSolver::run`] of this solve: the
    /// estimate that gates the next one, also the first one of the next run (the proximal point
    /// method runs one per proximal step). Before the first iteration, the factorization's
    /// duration predicted from the symbolic analysis (`math::lu_cost`).
    last_iteration_time: Duration,
}

impl NewtonSolver {
    pub fn new(problem: &FrictionProblem<'_>, options: &NsnOptions) -> Result<Self, Fc3dError> {
        Ok(Self::reusing(problem, options, None)?.0)
    }

    /// [`NewtonSolver::new`], keeping `previous`'s Newton matrix pattern and symbolic
    /// factorization when `problem`'s W has the same 3x3 block pattern as the W `previous` was
    /// built for (a time stepper whose contact set did not change): only the values are replaced.
    /// The flag tells whether `previous` was reused.
    pub fn reusing(
        problem: &FrictionProblem<'_>,
        options: &NsnOptions,
        previous: Option<NewtonSolver>,
    ) -> Result<(Self, bool), Fc3dError> {
        options.validate()?;
        let w = problem.w().to_block_sparse()?;
        if let Some(mut kept) = previous {
            if kept.w.row_ptr() == w.row_ptr() && kept.w.col_idx() == w.col_idx() {
                kept.options = *options;
                kept.w = w;
                kept.last_iteration_time = kept.linear.matrix().cost().duration();
                return Ok((kept, true));
            }
        }
        let linear = NewtonLinearSolver::new(&w)?;
        let predicted = linear.matrix().cost().duration();
        let n = problem.size();
        let nc = problem.n_contacts();
        let solver = NewtonSolver {
            options: *options,
            w,
            linear,
            data: vec![
                ContactData {
                    mu: 0.0,
                    rho_n: 1.0,
                    rho_t: 1.0
                };
                nc
            ],
            a: vec![[[0.0; 3]; 3]; nc],
            b: vec![[[0.0; 3]; 3]; nc],
            f: vec![0.0; n],
            step: Step::new(n),
            best_r: vec![0.0; n],
            last_iteration_time: predicted,
        };
        Ok((solver, false))
    }

    /// The fill of the Newton matrix's factorization (the first one that succeeded).
    pub fn fill(&self) -> Option<crate::contract::Fill> {
        self.linear.matrix().factor_fill()
    }

    /// `u <- (W + shift I) r + q`.
    fn velocity(&self, q: &[f64], shift: f64, r: &[f64], u: &mut [f64]) {
        u.copy_from_slice(q);
        self.w.mul_add(r, u);
        if shift != 0.0 {
            u.iter_mut().zip(r).for_each(|(ui, ri)| *ui += shift * ri);
        }
    }

    /// F, A, B at (r, u); returns the merit `||F||^2 / 2`.
    fn evaluate(&mut self, r: &[f64], u: &[f64]) -> f64 {
        let form = self.options.formulation;
        let mut sum = 0.0;
        for (c, d) in self.data.iter().enumerate() {
            let (f, a, b) = residual(form, &take3(r, c), &take3(u, c), d);
            self.f[3 * c..3 * c + 3].copy_from_slice(&f);
            self.a[c] = a;
            self.b[c] = b;
            sum += f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
        }
        0.5 * sum
    }

    /// Solves FC(W + shift I, q, mu) from `r` by Newton, within the limits of `run` (its
    /// tolerance on the relative natural-map error normalised by `||q||` of this q). `u`
    /// receives `(W + shift I) r + q`.
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &mut self,
        q: &[f64],
        mu: &[f64],
        shift: f64,
        run: &Run,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> RunOutcome {
        let form = self.options.formulation;
        for (c, d) in self.data.iter_mut().enumerate() {
            let mut wcc = self.w.diagonal_block(c).unwrap_or([[0.0; 3]; 3]);
            for (i, row) in wcc.iter_mut().enumerate() {
                row[i] += shift;
            }
            let (rho_n, rho_t) = crate::local::local_rho_of_variant(
                &wcc,
                self.options.rho_rule,
                self.options.variant,
            );
            *d = ContactData {
                mu: mu[c],
                rho_n,
                rho_t,
            };
        }
        let norm_q = norm(q);
        let error_of = |r: &[f64], u: &[f64]| {
            absolute_natural_map_residual(r, u, mu) / relative_scale(norm_q, r, u)
        };

        self.linear.start_run();
        self.velocity(q, shift, r, u);
        let mut merit = self.evaluate(r, u);
        let mut error = error_of(r, u);
        let mut best_error = error;
        self.best_r.copy_from_slice(r);
        let mut history = [merit; NONMONOTONE_MEMORY];
        let mut outcome = RunOutcome {
            iterations: 0,
            converged: error <= run.tolerance,
            out_of_time: false,
            error,
            regularized: 0,
        };
        if outcome.converged {
            return outcome;
        }
        for iteration in 1..=run.max_iter {
            // A factorization cannot be interrupted: an iteration expected (from the last one,
            // possibly of an earlier run, or before the first from the symbolic analysis) to
            // end past the deadline is not started.
            let estimated = iteration > 1 || self.last_iteration_time > Duration::ZERO;
            if estimated && run.cannot_afford(self.last_iteration_time) {
                outcome.out_of_time = true;
                break;
            }
            let iteration_start = Instant::now();
            // Newton direction J d = -F, regularised if J is numerically singular, else the
            // fixed-point direction.
            let (data, step) = (&self.data, &mut self.step);
            let direction = self.linear.direction(
                &Jacobian {
                    w: &self.w,
                    a: &self.a,
                    b: &self.b,
                    shift,
                },
                &self.f,
                error,
                step,
                &|| run.out_of_time(),
                &mut |d, wd| merit_along(form, data, r, u, d, wd, 1.0),
            );
            if matches!(direction, Direction::Regularized { .. }) {
                outcome.regularized += 1;
            }
            // q'(0) = F . J d.
            let slope: f64 = self.f.iter().zip(&step.jd).map(|(f, jd)| f * jd).sum();
            let reference = history.iter().copied().fold(merit, f64::max);
            let (d, wd) = (&step.d, &step.wd);
            let mut trial_merit = |t: f64| merit_along(form, data, r, u, d, wd, t);
            let step = match (self.options.variant, self.options.line_search) {
                (AlgorithmVariant::Siconos, NsnLineSearch::GoldsteinPrice) => {
                    linesearch::siconos_goldstein_price(
                        merit,
                        slope,
                        self.options.line_search_max_iter,
                        run.deadline(),
                        &mut trial_merit,
                    )
                    .or_else(|| {
                        // Siconos takes the full step; fc3d only a finite one.
                        let q = trial_merit(1.0);
                        q.is_finite()
                            .then_some(linesearch::Step { t: 1.0, merit: q })
                    })
                }
                _ => linesearch::search(
                    self.options.line_search,
                    merit,
                    slope,
                    reference,
                    self.options.line_search_max_iter,
                    run.deadline(),
                    &mut trial_merit,
                ),
            };
            outcome.iterations = iteration;
            let Some(step) = step else {
                // No finite trial point: keep r and stop.
                break;
            };
            r.iter_mut()
                .zip(&self.step.d)
                .for_each(|(ri, di)| *ri += step.t * di);
            self.velocity(q, shift, r, u);
            merit = self.evaluate(r, u);
            history[iteration % NONMONOTONE_MEMORY] = merit;
            error = error_of(r, u);
            if error < best_error {
                best_error = error;
                self.best_r.copy_from_slice(r);
            }
            observer(&IterationEvent {
                iteration,
                reaction: r,
                error,
            });
            self.last_iteration_time = iteration_start.elapsed();
            if let Some(stop) = run.end_of_iteration(iteration, error <= run.tolerance) {
                if !stop.out_of_time {
                    outcome.converged = true;
                    outcome.error = error;
                    return outcome;
                }
                outcome.out_of_time = true;
                break;
            }
        }
        if best_error < error || !error.is_finite() {
            r.copy_from_slice(&self.best_r);
            self.velocity(q, shift, r, u);
            error = best_error;
        }
        outcome.error = error;
        outcome
    }
}

/// The merit `||F||^2 / 2` at `(r + t d, u + t wd)`.
fn merit_along(
    form: NsnFormulation,
    data: &[ContactData],
    r: &[f64],
    u: &[f64],
    d: &[f64],
    wd: &[f64],
    t: f64,
) -> f64 {
    let mut sum = 0.0;
    for (c, dc) in data.iter().enumerate() {
        let rc = axpy(t, &take3(d, c), &take3(r, c));
        let uc = axpy(t, &take3(wd, c), &take3(u, c));
        let (f, _, _) = residual(form, &rc, &uc, dc);
        sum += f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
    }
    0.5 * sum
}

#[inline]
fn take3(x: &[f64], c: usize) -> Vec3 {
    [x[3 * c], x[3 * c + 1], x[3 * c + 2]]
}

#[inline]
fn axpy(t: f64, x: &Vec3, y: &Vec3) -> Vec3 {
    [y[0] + t * x[0], y[1] + t * x[1], y[2] + t * x[2]]
}

impl Family for NsnOptions {
    fn presets() -> Vec<Self> {
        [
            NsnFormulation::AlartCurnier,
            NsnFormulation::JeanMoreau,
            NsnFormulation::FischerBurmeister,
            NsnFormulation::NaturalMap,
        ]
        .into_iter()
        .map(NsnOptions::new)
        .collect()
    }

    fn name(&self) -> &'static str {
        self.formulation.short_name()
    }

    fn label(&self) -> String {
        NsnOptions::label(self)
    }

    fn siconos_id(&self) -> i32 {
        self.formulation.siconos_id()
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-3, 200)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        NsnOptions::validate(self)
    }

    /// A nonsmooth Newton solve of `problem` from the reaction in `r`.
    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        // The budget counts from here: the copy of W and the symbolic analysis are part of it.
        let run = limits.start();
        if let Some(stop) =
            super::stop_before_analysis(problem.w(), run.deadline(), || problem.velocity(r, u))
        {
            return Ok(stop);
        }
        let mut solver = NewtonSolver::new(problem, self)?;
        Ok(nsn_on(&mut solver, problem, &run, r, u, observer))
    }
}

/// A nonsmooth Newton solve of `problem` with a solver prepared for it ([`NewtonSolver::new`] or
/// [`NewtonSolver::reusing`]).
pub(crate) fn nsn_on(
    solver: &mut NewtonSolver,
    problem: &FrictionProblem<'_>,
    run: &Run,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> SolverOutcome {
    let out = solver.run(problem.q(), problem.mu(), 0.0, run, r, u, observer);
    SolverOutcome::stopped(out.iterations, out.out_of_time).with_fill(solver.fill())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The regularised direction is taken only where J is numerically singular: never on a
    /// Rover problem (whose iterates are Siconos' own, 5 iterations for 504), at most iterations
    /// on a tower of two boxes on 4 points each (whose sticking contacts make J singular).
    #[test]
    fn only_singular_jacobians_take_the_regularized_direction() {
        let rover = crate::io::dat::read_dat_file(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shared/data/siconos/Rover4609.dat"
        )))
        .unwrap();
        let tower = crate::scenes::box_towers(&crate::scenes::TowerSpec {
            towers: 1,
            height: 2,
            motion: crate::scenes::TowerMotion::Settling,
            seed: 3,
        })
        .unwrap();
        let options = NsnOptions::new(NsnFormulation::AlartCurnier);
        let limits = Limits {
            tolerance: 1e-8,
            max_iter: 100,
            time_budget: None,
        };
        let mut outcomes = Vec::new();
        for p in [&rover, &tower] {
            let n = p.size();
            let mut solver = NewtonSolver::new(p, &options).unwrap();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let run = limits.start();
            let o = solver.run(p.q(), p.mu(), 0.0, &run, &mut r, &mut u, &mut |_| {});
            assert!(o.converged);
            outcomes.push((o.iterations, o.regularized));
        }
        assert_eq!(outcomes[0], (5, 0));
        let (iterations, regularized) = outcomes[1];
        assert!(iterations <= 15, "{iterations}");
        assert!(
            2 * regularized >= iterations,
            "{regularized} of {iterations}"
        );
    }

    /// The duration of the last Newton step is kept across runs (the proximal point method runs
    /// one per proximal step): once the solver has an estimate, a run whose deadline has passed
    /// starts no step; nor does a fresh solver, gated by the factorization's duration predicted
    /// from the symbolic analysis.
    #[test]
    fn a_step_that_cannot_be_afforded_is_not_started_in_a_later_run() {
        let p = crate::io::dat::read_dat_file(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shared/data/siconos/Rover4609.dat"
        )))
        .unwrap();
        let n = p.size();
        let options = NsnOptions::new(NsnFormulation::AlartCurnier);
        let limits = |time_budget| Limits {
            tolerance: 0.0,
            max_iter: 3,
            time_budget,
        };
        let mut solver = NewtonSolver::new(&p, &options).unwrap();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let free = limits(None).start();
        let o = solver.run(p.q(), p.mu(), 0.0, &free, &mut r, &mut u, &mut |_| {});
        assert_eq!((o.iterations, o.out_of_time), (3, false));
        assert!(solver.last_iteration_time > Duration::ZERO);

        let spent = limits(Some(Duration::from_nanos(1))).start();
        while !spent.out_of_time() {}
        let o = solver.run(p.q(), p.mu(), 0.0, &spent, &mut r, &mut u, &mut |_| {});
        assert_eq!((o.iterations, o.out_of_time), (0, true));

        let mut fresh = NewtonSolver::new(&p, &options).unwrap();
        assert!(fresh.last_iteration_time > Duration::ZERO);
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let o = fresh.run(p.q(), p.mu(), 0.0, &spent, &mut r, &mut u, &mut |_| {});
        assert_eq!((o.iterations, o.out_of_time), (0, true));
        assert!(r.iter().all(|&x| x == 0.0));
    }
}
