//! The self-adaptive projection iteration on one contact, shared by 553 (cone steps along the
//! De Saxcé velocity), 564 (augmented-Lagrangian steps on the cylinder) and 570 (553 from another
//! rho): steps `r <- P(r - rho f(r))` with the step rule of [`crate::math::step`]: shrink rho by
//! `NU` while `rho ||f(r+) - f(r)|| > L ||r+ - r||`, grow it by `1 / NU` after a step whose
//! ratio is below `L_MIN`, until the natural-map residual of the contact is below the tolerance.

use std::time::Instant;

use super::{LocalOutcome, LocalProblem};
use crate::contract::past_deadline;
use crate::math::linalg::{norm3, sub3, Vec3};
use crate::math::step::{L, L_MIN, NU};

/// The map a projection iteration steps along: the field `f(r)` and the projected step.
pub(crate) trait ProjectionStep {
    /// The field the step moves against at `r` (the De Saxcé velocity, or the velocity).
    fn field(&self, p: &LocalProblem<'_>, r: &Vec3) -> Vec3;
    /// `P(r - rho f)`.
    fn step(&self, p: &LocalProblem<'_>, r: &Vec3, field: &Vec3, rho: f64) -> Vec3;
    /// The natural-map residual `||r - P_K(r - ũ)||` of the contact at `r`, whose field is
    /// `field`.
    fn residual(&self, p: &LocalProblem<'_>, r: &Vec3, field: &Vec3) -> f64;
}

/// Runs the iteration from `r` with initial step `rho` to the relative residual `tolerance`,
/// `max_iter` steps or the `deadline`. A non-finite step stops it with `r` at the last finite
/// iterate.
pub(crate) fn self_adaptive_projection(
    map: &impl ProjectionStep,
    p: &LocalProblem<'_>,
    mut rho: f64,
    tolerance: f64,
    max_iter: usize,
    deadline: Option<Instant>,
    r: &mut Vec3,
) -> LocalOutcome {
    let mut field = map.field(p, r);
    for it in 0..max_iter {
        if past_deadline(deadline, it) {
            return LocalOutcome {
                converged: false,
                iterations: it,
            };
        }
        let next = map.step(p, r, &field, rho);
        let step = norm3(&sub3(&next, r));
        if step == 0.0 || !step.is_finite() {
            return LocalOutcome {
                converged: step == 0.0,
                iterations: it,
            };
        }
        let next_field = map.field(p, &next);
        let ratio = rho * norm3(&sub3(&next_field, &field)) / step;
        if ratio > L && rho > f64::MIN_POSITIVE {
            rho *= NU;
            continue;
        }
        *r = next;
        field = next_field;
        if ratio < L_MIN {
            rho /= NU;
        }
        if map.residual(p, r, &field) <= tolerance * p.scale(r) {
            return LocalOutcome {
                converged: true,
                iterations: it + 1,
            };
        }
    }
    LocalOutcome {
        converged: p.residual(r) <= tolerance * p.scale(r),
        iterations: max_iter,
    }
}

/// Largest reaction entry [`siconos_cone_iteration`] moves to.
const REACTION_CAP: f64 = 1e150;

/// Trial steps per iteration of [`siconos_cone_iteration`] before the last trial is taken.
const SICONOS_TRIALS: usize = 10;

/// Siconos 4.4's iteration of 553 (ProjectionOnConeWithLocalIteration), step for step: from
/// `rho = *step` (the contact's step length left by its previous solve; 1 at the first), each
/// iteration tries `r+ = P_K(r - rho_k ũ(r))` with `rho_k = rho, NU rho, ...` until
/// `rho_k ||u(r+) - u(r)|| <= L ||r+ - r||` or the tenth trial (taken in any case); the next
/// rho is `rho_k / NU` when the ratio fell below `L_MIN` and the error decreased, `rho_k`
/// otherwise. The error is the squared absolute residual `||r - P_K(r - ũ)||^2`, and the
/// iteration runs while it is above `tolerance` (the first iteration always runs). `*step`
/// receives the last rho.
pub(crate) fn siconos_cone_iteration(
    p: &LocalProblem<'_>,
    step: &mut f64,
    tolerance: f64,
    max_iter: usize,
    deadline: Option<Instant>,
    r: &mut Vec3,
) -> LocalOutcome {
    use crate::math::cone::{modified_velocity, project_on_cone};
    use crate::measure::contact_residual_sq;
    let mut rho = if *step > 0.0 && step.is_finite() {
        *step
    } else {
        1.0
    };
    let mut error = 1.0_f64;
    let mut it = 0;
    while error > tolerance && it < max_iter {
        if past_deadline(deadline, it) {
            break;
        }
        it += 1;
        let previous_error = error;
        let r_k = *r;
        let u_k = p.velocity(&r_k);
        let field = modified_velocity(&u_k, p.mu);
        let mut rho_k = rho;
        let (mut a1, mut a2) = (0.0, 0.0);
        let mut u = u_k;
        for trial in 0..SICONOS_TRIALS {
            if trial > 0 {
                rho_k *= NU;
            }
            *r = project_on_cone(
                &[
                    r_k[0] - rho_k * field[0],
                    r_k[1] - rho_k * field[1],
                    r_k[2] - rho_k * field[2],
                ],
                p.mu,
            );
            u = p.velocity(r);
            a1 = norm3(&sub3(&u_k, &u));
            a2 = norm3(&sub3(&r_k, r));
            if rho_k * a1 <= L * a2 {
                break;
            }
        }
        error = contact_residual_sq(r, &u, p.mu);
        rho = if rho_k * a1 < L_MIN * a2 && error < previous_error {
            rho_k / NU
        } else {
            rho_k
        };
        // Beyond REACTION_CAP the step follows a ray (no bounded solution, e.g. W_cc = 0 with
        // q_N < 0, where rho grows every iteration): stop before the reaction overflows.
        if !r.iter().all(|x| x.is_finite() && x.abs() <= REACTION_CAP) {
            *r = r_k;
            break;
        }
    }
    if rho > 0.0 && rho.is_finite() {
        *step = rho;
    }
    LocalOutcome {
        converged: error <= tolerance,
        iterations: it,
    }
}
