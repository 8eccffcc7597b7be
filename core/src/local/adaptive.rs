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
