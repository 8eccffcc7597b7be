//! Line searches on the merit `q(t) = ||F(r + t d)||^2 / 2` (section 5.5): Goldstein-Price
//! (Algorithm 5), Armijo (Algorithm 6) and its non-monotone variant. The merit is evaluated by a
//! closure so that the caller keeps its work vectors (nothing is allocated here).

use std::time::Instant;

use super::settings::NsnLineSearch;
use crate::contract::deadline_passed;

/// Sufficient-decrease parameter m1 (the paper advises m1 < 1/2 < m2).
pub(crate) const M1: f64 = 0.01;
/// Goldstein-Price's curvature parameter m2.
pub(crate) const M2: f64 = 0.99;
/// Goldstein-Price's extrapolation factor a > 1.
const EXTRAPOLATION: f64 = 2.0;
/// Steps are never extrapolated beyond this multiple of the Newton step.
const MAX_STEP: f64 = 8.0;

/// Result of a line search: the step and its (finite) merit, or `None` when no trial step gave
/// a finite merit.
pub(crate) struct Step {
    pub t: f64,
    pub merit: f64,
}

/// Searches a step along d. `q0` is the merit at t = 0, `slope` = q'(0), `reference` the merit to
/// decrease from (q0, or the largest recent merit for the non-monotone search). When the
/// conditions cannot be met within `max_iter` trials, the last finite trial is returned, as
/// Siconos does: Newton must be allowed to cross a kink of F.
/// The search also ends, with its best finite trial, once `deadline` has passed (after at least
/// one trial).
pub(crate) fn search(
    kind: NsnLineSearch,
    q0: f64,
    slope: f64,
    reference: f64,
    max_iter: usize,
    deadline: Option<Instant>,
    merit: &mut dyn FnMut(f64) -> f64,
) -> Option<Step> {
    let mut last: Option<Step> = None;
    let mut t = 1.0;
    match kind {
        NsnLineSearch::None => {
            let q = merit(t);
            return q.is_finite().then_some(Step { t, merit: q });
        }
        NsnLineSearch::Armijo | NsnLineSearch::NonMonotone => {
            let base = if kind == NsnLineSearch::Armijo {
                q0
            } else {
                reference
            };
            for trial in 0..max_iter.max(1) {
                if trial > 0 && deadline_passed(deadline) {
                    break;
                }
                let q = merit(t);
                if q.is_finite() {
                    if q <= base + M1 * t * slope.min(0.0) {
                        return Some(Step { t, merit: q });
                    }
                    if last.as_ref().is_none_or(|s| q < s.merit) {
                        last = Some(Step { t, merit: q });
                    }
                }
                t *= 0.5;
            }
        }
        NsnLineSearch::GoldsteinPrice => {
            let (mut t_left, mut t_right) = (0.0_f64, 0.0_f64);
            for trial in 0..max_iter.max(1) {
                if trial > 0 && deadline_passed(deadline) {
                    break;
                }
                let q = merit(t);
                if !q.is_finite() {
                    // Treat as far too long a step.
                    t_right = t;
                    t = 0.5 * (t_left + t_right);
                    continue;
                }
                let delta = (q - q0) / t;
                let too_long = delta > M1 * slope;
                let too_short = delta < M2 * slope;
                if !too_long && !too_short {
                    return Some(Step { t, merit: q });
                }
                if last.as_ref().is_none_or(|s| q < s.merit) {
                    last = Some(Step { t, merit: q });
                }
                if too_long {
                    t_right = t;
                }
                if too_short {
                    t_left = t;
                }
                t = if t_right == 0.0 {
                    (EXTRAPOLATION * t).min(MAX_STEP)
                } else {
                    0.5 * (t_left + t_right)
                };
                if t_right == 0.0 && t_left >= MAX_STEP {
                    break;
                }
            }
        }
    }
    last
}

/// Siconos 4.4's Goldstein-Price search of its global Newton methods: bisection of
/// `[lo, hi]` from `t = 1` with `hi` starting at 1e10 (so a first step found too short jumps
/// to about 5e9), the same tests as [`search`]. Returns the accepted step, or `None` when
/// `max_iter` trials accept none, a merit is not finite or the deadline passed: Siconos then
/// takes the full Newton step.
pub(crate) fn siconos_goldstein_price(
    q0: f64,
    slope: f64,
    max_iter: usize,
    deadline: Option<Instant>,
    merit: &mut dyn FnMut(f64) -> f64,
) -> Option<Step> {
    const UNBOUNDED: f64 = 1e10;
    if !q0.is_finite() {
        return None;
    }
    let (mut lo, mut hi) = (0.0_f64, UNBOUNDED);
    let mut t = 1.0;
    for trial in 0..max_iter {
        if trial > 0 && deadline_passed(deadline) {
            return None;
        }
        let q = merit(t);
        if !q.is_finite() {
            return None;
        }
        let delta = (q - q0) / t;
        let long_enough = delta >= M2 * slope;
        let short_enough = delta <= M1 * slope;
        if long_enough && short_enough {
            return Some(Step { t, merit: q });
        }
        if !long_enough {
            lo = t;
        } else {
            hi = t;
        }
        t = if t < UNBOUNDED { 0.5 * (lo + hi) } else { lo };
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// q(t) = (1 - t)^2 / 2 · 2 = (1 - t)^2: the exact Newton step t = 1 is accepted at once.
    #[test]
    fn newton_step_on_a_quadratic_is_accepted() {
        for kind in [
            NsnLineSearch::None,
            NsnLineSearch::GoldsteinPrice,
            NsnLineSearch::Armijo,
            NsnLineSearch::NonMonotone,
        ] {
            let mut calls = 0;
            let s = search(kind, 1.0, -2.0, 1.0, 20, None, &mut |t| {
                calls += 1;
                (1.0 - t) * (1.0 - t)
            })
            .unwrap();
            assert_eq!(s.t, 1.0, "{kind:?}");
            assert_eq!(calls, 1);
        }
    }

    /// A direction ten times too long: the searches shrink the step.
    #[test]
    fn overlong_direction_is_shortened() {
        for kind in [NsnLineSearch::GoldsteinPrice, NsnLineSearch::Armijo] {
            let s = search(kind, 1.0, -20.0, 1.0, 30, None, &mut |t| {
                (1.0 - 10.0 * t).powi(2)
            })
            .unwrap();
            assert!(s.t < 0.2 && s.merit < 1.0, "{kind:?}: t = {}", s.t);
        }
    }

    #[test]
    fn non_finite_merits_are_never_returned() {
        let s = search(NsnLineSearch::Armijo, 1.0, -2.0, 1.0, 5, None, &mut |t| {
            if t > 0.1 {
                f64::NAN
            } else {
                0.9
            }
        });
        assert!(s.unwrap().merit == 0.9);
        assert!(
            search(NsnLineSearch::None, 1.0, -2.0, 1.0, 5, None, &mut |_| {
                f64::INFINITY
            })
            .is_none()
        );
    }
}
