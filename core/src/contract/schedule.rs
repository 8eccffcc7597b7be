//! When the sweeping families (NSGS, the VI family) measure the error they stop on: the full
//! natural-map error, the cheap increment error (134), or the cheap one confirmed by the full one.

use crate::measure::cheap_error;

/// Which error a sweeping family tests for convergence (Siconos iparam[7]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorEvaluation {
    /// The full natural-map error after every iteration (one extra W r product for NSGS).
    Full,
    /// Only the cheap increment error (134); the returned error is still the full one.
    Light,
    /// Cheap error each iteration; when it passes, confirm with the full error and tighten the
    /// cheap tolerance if the full one does not pass (Siconos' default for NSGS).
    LightWithFullFinal,
    /// Dumont's global criterion (37) (NSGS only): the mean over contacts of the motion error
    /// (how far the velocity a contact was solved with is from `W r + q` after the sweep), the
    /// distance of `r_c` to its cone, the bi-potential `|u·r + mu r_N ||u_T|||` and the
    /// penetration `max(0, -u_N)`. It is absolute (in the units of `r·u`), so its tolerance is
    /// the solver's tolerance taken in those units. The reported error stays the natural-map
    /// error; the criterion is reported beside it
    /// ([`SolveReport::dumont_criterion`](crate::SolveReport)).
    DumontCriterion,
}

/// What [`ErrorSchedule::test`] asks its caller to measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// The relative natural-map error of the current `r`.
    NaturalMap,
    /// Dumont's criterion (37) of the current `r`.
    DumontCriterion,
}

/// The result of one test.
#[derive(Debug, Clone, Copy)]
pub struct Test {
    /// The error tested (cheap, full or Dumont's, as scheduled); the last tested one when this
    /// iteration was not a test.
    pub error: f64,
    /// `error` is the full natural-map error of the current `r`.
    pub full: bool,
    pub converged: bool,
    /// This iteration was a test.
    pub tested: bool,
    /// [`ErrorEvaluation::LightWithFullFinal`]: the cheap test passed but the full error is above
    /// the tolerance, and the cheap tolerance tightened to 0 (the iteration left r unchanged).
    /// Siconos' NSGS stops there; a deterministic sweep from the same r can only repeat. Also set
    /// when the measured error is not finite.
    pub stalled: bool,
}

/// The error-evaluation schedule of a run: which error is measured, how often, and the cheap
/// tolerance that [`ErrorEvaluation::LightWithFullFinal`] tightens.
#[derive(Debug, Clone)]
pub struct ErrorSchedule {
    evaluation: ErrorEvaluation,
    tolerance: f64,
    light_tolerance: f64,
    /// The test runs every `frequency` iterations (and at the last allowed one).
    frequency: usize,
    max_iter: usize,
    last_tested: f64,
}

impl ErrorSchedule {
    pub fn new(
        evaluation: ErrorEvaluation,
        tolerance: f64,
        frequency: usize,
        max_iter: usize,
    ) -> Self {
        ErrorSchedule {
            evaluation,
            tolerance,
            light_tolerance: tolerance,
            frequency: frequency.max(1),
            max_iter,
            last_tested: f64::INFINITY,
        }
    }

    /// Forgets what earlier tests learnt of the ratio of cheap to full error (the cheap test
    /// passes at the tolerance again): when the iteration changes (a mixed-precision sweep
    /// leaving its f32 copy).
    pub fn restart_light(&mut self) {
        self.light_tolerance = self.tolerance;
    }

    /// The test after iteration `iteration`, whose squared increment `||r_new - r_old||^2` is
    /// `increment_sq`; `measure` computes the full natural-map error or Dumont's criterion of the
    /// current `r` when the schedule needs one.
    pub fn test(
        &mut self,
        iteration: usize,
        increment_sq: f64,
        r: &[f64],
        measure: impl FnOnce(Measure) -> f64,
    ) -> Test {
        self.test_with(iteration, || cheap_error(increment_sq, r), measure)
    }

    /// [`ErrorSchedule::test`] with the cheap error given by the caller (a family whose cheap
    /// error is not the increment (134), such as Siconos' VI extragradient).
    pub fn test_light(
        &mut self,
        iteration: usize,
        light: f64,
        measure: impl FnOnce(Measure) -> f64,
    ) -> Test {
        self.test_with(iteration, || light, measure)
    }

    fn test_with(
        &mut self,
        iteration: usize,
        light: impl FnOnce() -> f64,
        measure: impl FnOnce(Measure) -> f64,
    ) -> Test {
        let tested = iteration.is_multiple_of(self.frequency) || iteration == self.max_iter;
        if !tested {
            return Test {
                error: self.last_tested,
                full: false,
                converged: false,
                tested,
                stalled: false,
            };
        }
        let tol = self.tolerance;
        let mut stalled = false;
        let (error, full, converged) = match self.evaluation {
            ErrorEvaluation::Full => {
                let e = measure(Measure::NaturalMap);
                (e, true, e <= tol)
            }
            ErrorEvaluation::Light => {
                let e = light();
                (e, false, e <= tol)
            }
            ErrorEvaluation::LightWithFullFinal => {
                let light = light();
                if light <= self.light_tolerance {
                    let full = measure(Measure::NaturalMap);
                    if full > tol {
                        // Assume full/light stays roughly proportional and ask the cheap error
                        // for what the full one still lacks.
                        self.light_tolerance = light * tol / full;
                        stalled = self.light_tolerance <= 0.0 || self.light_tolerance.is_nan();
                    }
                    (full, true, full <= tol)
                } else {
                    (light, false, false)
                }
            }
            ErrorEvaluation::DumontCriterion => {
                let e = measure(Measure::DumontCriterion);
                (e, false, e <= tol)
            }
        };
        // A non-finite measured error (a NaN or infinity in W or q reaches every error through
        // W r + q) cannot improve by iterating: stop at once rather than at the iteration limit.
        if (full || self.evaluation == ErrorEvaluation::DumontCriterion) && !error.is_finite() {
            stalled = true;
        }
        self.last_tested = error;
        Test {
            error,
            full,
            converged,
            tested,
            stalled,
        }
    }
}
