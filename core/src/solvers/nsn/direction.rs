//! The Newton direction: `J d = -F` with `J = A + B (W + shift I)`, for Jacobians that may be
//! singular.
//!
//! A hyperstatic contact set (a box on 4 points, a stack of them) makes W rank-deficient, and
//! with it the rows of J of every sticking contact: the Newton system is singular and the
//! solutions of `F(r) = 0` are not isolated (r is free along the self-equilibrated impulses). A
//! partial-pivoting LU then meets a pivot at rounding level, does not fail, and returns a
//! direction whose null-space part is rounding noise divided by that pivot: often larger than the
//! step itself, so the line search cuts it to nothing and Newton stalls. Siconos' MUMPS detects
//! such null pivots (ICNTL(24)) and fixes them; faer's sparse LU reports neither its pivots nor a
//! rank.
//!
//! So the direction is checked instead of the factors: `x = J^-1 (J d)` is solved with the same
//! factors and compared with `d`. Both carry the rounding the factors amplify, so
//! `|x - d| / |d|` estimates the relative error of `d` (about `eps cond(J)`, O(1) at a null
//! pivot). A well-conditioned J passes for the price of one more triangular solve, and its
//! direction is the plain Newton one (Siconos' iterate wherever Siconos' factorization is
//! regular).
//!
//! A direction that fails is recomputed from `J + mu D` (D: per contact, the largest entry of its
//! diagonal block of J), the regularised Newton step of Levenberg-Marquardt type for equations
//! with non-isolated solutions: with `mu` proportional to the current error the step is bounded
//! (the null-space part is at most rounding / mu) and tends to the Newton step as the error
//! vanishes, which keeps fast local convergence. Two candidates come from the same factors: that
//! step, and the step refined against J itself (`d += (J + mu D)^-1 (-F - J d)`, which converges
//! to the near-minimal-norm solution of a consistent system); the one with the smaller merit at
//! the full step is taken (measured on the generated box towers and the shared problems: either
//! one alone stalls on some of them, see docs/newton.md). When `J + mu D` cannot be factored, mu
//! grows a hundredfold at a time; when no regularised matrix can be factored, the fixed-point
//! direction `-F` is taken. A singular J tends to stay singular from one iteration to the next
//! (the contacts that make it so keep sticking), so while directions keep needing regularisation
//! the plain factorization is only tried every [`PLAIN_RETRY_PERIOD`] iterations.

use super::sparse::NewtonMatrix;
use crate::error::Fc3dError;
use crate::math::linalg::Mat3;
use crate::matrix::BlockSparseMatrix;

/// The relative error of a Newton direction (estimated by the re-solve) above which it is
/// recomputed regularised.
const PROBE_TOLERANCE: f64 = 1e-6;
/// `mu = REGULARIZATION_PER_ERROR x` the relative natural-map error of the iterate.
const REGULARIZATION_PER_ERROR: f64 = 0.03;
/// The smallest mu: rounding amplified by 1 / mu stays below 1e-4 of the step.
const MIN_REGULARIZATION: f64 = 1e-12;
/// Refinement steps of the second candidate.
const REFINEMENT_STEPS: usize = 3;
/// While directions keep needing regularisation, the plain factorization is tried once every
/// this many iterations (on the towers of docs/newton.md: the same iterations within 1 %, 40 %
/// less time on 4000 contacts).
const PLAIN_RETRY_PERIOD: usize = 4;

/// How the direction of an iteration was obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Direction {
    /// The Newton direction from the LU factors of J.
    Newton,
    /// From `J + mu D` (J numerically singular), refined against J or not.
    Regularized { mu: f64, refined: bool },
    /// `-F` (no regularised matrix could be factored).
    FixedPoint,
}

/// J as an operator: W (with the proximal shift) and the per-contact blocks A, B.
pub(crate) struct Jacobian<'a> {
    pub w: &'a BlockSparseMatrix<'static>,
    pub a: &'a [Mat3],
    pub b: &'a [Mat3],
    pub shift: f64,
}

impl Jacobian<'_> {
    /// `wx <- (W + shift I) x`, `jx <- A x + B wx`.
    pub fn apply(&self, x: &[f64], wx: &mut [f64], jx: &mut [f64]) {
        wx.iter_mut().for_each(|v| *v = 0.0);
        self.w.mul_add(x, wx);
        if self.shift != 0.0 {
            wx.iter_mut()
                .zip(x)
                .for_each(|(w, xi)| *w += self.shift * xi);
        }
        for (c, (a, b)) in self.a.iter().zip(self.b).enumerate() {
            let (xc, wc) = (&x[3 * c..3 * c + 3], &wx[3 * c..3 * c + 3]);
            for i in 0..3 {
                jx[3 * c + i] = a[i][0] * xc[0]
                    + a[i][1] * xc[1]
                    + a[i][2] * xc[2]
                    + b[i][0] * wc[0]
                    + b[i][1] * wc[1]
                    + b[i][2] * wc[2];
            }
        }
    }
}

/// A direction with its images: `d`, `wd = (W + shift I) d`, `jd = J d`.
pub(crate) struct Step {
    pub d: Vec<f64>,
    pub wd: Vec<f64>,
    pub jd: Vec<f64>,
}

impl Step {
    pub fn new(n: usize) -> Self {
        Step {
            d: vec![0.0; n],
            wd: vec![0.0; n],
            jd: vec![0.0; n],
        }
    }

    fn update_images(&mut self, jacobian: &Jacobian<'_>) {
        jacobian.apply(&self.d, &mut self.wd, &mut self.jd);
    }
}

/// The Newton matrix with its symbolic factorization and the work vectors of the direction
/// (allocated once per solver).
pub(crate) struct NewtonLinearSolver {
    matrix: NewtonMatrix,
    refined: Step,
    correction: Vec<f64>,
    /// Consecutive regularised directions of the current run.
    regularized_in_a_row: usize,
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

impl NewtonLinearSolver {
    /// The solver for Newton matrices on W's block pattern (see [`NewtonMatrix::new`]).
    pub fn new(w: &BlockSparseMatrix) -> Result<Self, Fc3dError> {
        let matrix = NewtonMatrix::new(w)?;
        let n = 3 * w.n_block_rows();
        Ok(NewtonLinearSolver {
            matrix,
            refined: Step::new(n),
            correction: vec![0.0; n],
            regularized_in_a_row: 0,
        })
    }

    pub fn matrix(&self) -> &NewtonMatrix {
        &self.matrix
    }

    /// A new run (another problem, or another proximal shift): the plain factorization is
    /// tried first again.
    pub fn start_run(&mut self) {
        self.regularized_in_a_row = 0;
    }

    /// Sets `step` to the direction for the residual `f` at an iterate of relative error
    /// `error`, and returns how it was obtained. `merit_at_full_step(d, wd)` is the merit at
    /// `r + d` (with `u + wd`); `out_of_time` is asked before every factorization after the
    /// first.
    pub fn direction(
        &mut self,
        jacobian: &Jacobian<'_>,
        f: &[f64],
        error: f64,
        step: &mut Step,
        out_of_time: &dyn Fn() -> bool,
        merit_at_full_step: &mut dyn FnMut(&[f64], &[f64]) -> f64,
    ) -> Direction {
        let negate_f = |d: &mut [f64]| d.iter_mut().zip(f).for_each(|(di, fi)| *di = -fi);
        let try_plain = self.regularized_in_a_row.is_multiple_of(PLAIN_RETRY_PERIOD);
        let matrix = &mut self.matrix;
        matrix.fill(jacobian.w, jacobian.a, jacobian.b, jacobian.shift);
        negate_f(&mut step.d);
        if try_plain && matrix.factor() && matrix.solve_in_place(&mut step.d) {
            step.update_images(jacobian);
            let probe = &mut self.correction;
            probe.copy_from_slice(&step.jd);
            if matrix.solve_in_place(probe) {
                let difference = probe
                    .iter()
                    .zip(&step.d)
                    .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
                if difference <= PROBE_TOLERANCE * max_abs(&step.d) {
                    self.regularized_in_a_row = 0;
                    return Direction::Newton;
                }
            }
        }
        let error = if error.is_finite() { error } else { 1.0 };
        let mut mu = (REGULARIZATION_PER_ERROR * error).clamp(MIN_REGULARIZATION, 1.0);
        loop {
            if out_of_time() {
                break;
            }
            let matrix = &mut self.matrix;
            matrix.fill(jacobian.w, jacobian.a, jacobian.b, jacobian.shift);
            matrix.regularize(mu);
            negate_f(&mut step.d);
            if matrix.factor() && matrix.solve_in_place(&mut step.d) {
                step.update_images(jacobian);
                let refined = self.refine(jacobian, f, step)
                    && merit_at_full_step(&self.refined.d, &self.refined.wd)
                        < merit_at_full_step(&step.d, &step.wd);
                if refined {
                    std::mem::swap(step, &mut self.refined);
                }
                self.regularized_in_a_row += 1;
                return Direction::Regularized { mu, refined };
            }
            if mu >= 1.0 {
                break;
            }
            mu = (100.0 * mu).min(1.0);
        }
        negate_f(&mut step.d);
        step.update_images(jacobian);
        Direction::FixedPoint
    }

    /// `self.refined` <- `step` refined against J with the factors of `J + mu D`; false when a
    /// solve gives a non-finite vector.
    fn refine(&mut self, jacobian: &Jacobian<'_>, f: &[f64], step: &Step) -> bool {
        let (refined, correction) = (&mut self.refined, &mut self.correction);
        refined.d.copy_from_slice(&step.d);
        refined.jd.copy_from_slice(&step.jd);
        for _ in 0..REFINEMENT_STEPS {
            correction
                .iter_mut()
                .zip(f.iter().zip(&refined.jd))
                .for_each(|(c, (fi, jdi))| *c = -fi - jdi);
            if !self.matrix.solve_in_place(correction) {
                return false;
            }
            refined
                .d
                .iter_mut()
                .zip(correction.iter())
                .for_each(|(di, ci)| *di += ci);
            refined.update_images(jacobian);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::{box_towers, TowerMotion, TowerSpec};

    const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

    fn norm(x: &[f64]) -> f64 {
        x.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// W of one box on the ground on its 4 corners: 12 x 12, rank 6.
    fn one_box_on_the_ground() -> BlockSparseMatrix<'static> {
        let p = box_towers(&TowerSpec {
            towers: 1,
            height: 1,
            motion: TowerMotion::Rest,
            seed: 2,
        })
        .unwrap();
        p.w().to_block_sparse().unwrap()
    }

    /// `F = J x` for a given x: a consistent right-hand side.
    fn consistent_residual(jacobian: &Jacobian<'_>, x: &[f64]) -> Vec<f64> {
        let n = x.len();
        let (mut wx, mut f) = (vec![0.0; n], vec![0.0; n]);
        jacobian.apply(x, &mut wx, &mut f);
        f
    }

    /// One box on the ground, 4 contacts: W is 12 x 12 of rank 6. With every contact sticking
    /// (A = 0, B = rho I) J = rho W is singular and `J d = -F` is consistent. The plain LU
    /// direction is rejected by the re-solve; the regularised one solves the system to rounding
    /// and is no longer than the minimal-norm solution allows (|d| <= |x| for F = -J x).
    #[test]
    fn singular_consistent_system_gets_a_bounded_regularized_direction() {
        let w = one_box_on_the_ground();
        let (a, b) = (vec![[[0.0; 3]; 3]; 4], vec![IDENTITY; 4]);
        let jacobian = Jacobian {
            w: &w,
            a: &a,
            b: &b,
            shift: 0.0,
        };
        let x: Vec<f64> = (0..12).map(|i| ((i * 7) % 5) as f64 - 2.0).collect();
        let mut f = consistent_residual(&jacobian, &x);
        f.iter_mut().for_each(|v| *v = -*v);
        let mut solver = NewtonLinearSolver::new(&w).unwrap();
        let mut step = Step::new(12);
        // The merit of the linear model: the candidate that solves the system better wins.
        let mut residual_merit = |d: &[f64], _: &[f64]| {
            let jd = consistent_residual(&jacobian, d);
            jd.iter().zip(&f).map(|(a, b)| (a + b).powi(2)).sum::<f64>()
        };
        let direction = solver.direction(
            &jacobian,
            &f,
            1e-6,
            &mut step,
            &|| false,
            &mut residual_merit,
        );
        assert!(
            matches!(direction, Direction::Regularized { refined: true, .. }),
            "{direction:?}"
        );
        let residual: Vec<f64> = step.jd.iter().zip(&f).map(|(a, b)| a + b).collect();
        assert!(norm(&residual) <= 1e-12 * norm(&f), "{}", norm(&residual));
        assert!(
            norm(&step.d) <= norm(&x),
            "{} > {}",
            norm(&step.d),
            norm(&x)
        );
    }

    /// A regular J on the same box (A = I, B = I / 2: J = I + W / 2, positive definite): the
    /// direction is the plain LU one, J d = -F to rounding.
    #[test]
    fn regular_system_takes_the_plain_newton_direction() {
        let w = one_box_on_the_ground();
        let half = [[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]];
        let (a, b) = (vec![IDENTITY; 4], vec![half; 4]);
        let jacobian = Jacobian {
            w: &w,
            a: &a,
            b: &b,
            shift: 0.0,
        };
        let f: Vec<f64> = (0..12).map(|i| (i as f64 - 5.5) / 3.0).collect();
        let mut solver = NewtonLinearSolver::new(&w).unwrap();
        let mut step = Step::new(12);
        let direction = solver.direction(&jacobian, &f, 1.0, &mut step, &|| false, &mut |_, _| {
            unreachable!("no candidate to compare")
        });
        assert_eq!(direction, Direction::Newton);
        let residual: Vec<f64> = step.jd.iter().zip(&f).map(|(a, b)| a + b).collect();
        assert!(norm(&residual) <= 1e-14 * norm(&f));
    }
}
