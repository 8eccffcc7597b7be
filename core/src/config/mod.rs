//! [`SolverConfig`]: the settings of a solve in one place. The limits every family shares
//! (tolerance, iteration limit, time budget) and the rescaling are fields of the config, with the
//! family's Siconos defaults; [`Method`] holds what is specific to the family.

mod method;
mod method_config;
mod planar;
mod rescaling;
mod rolling;

pub use method::Method;
pub use method_config::{MethodChoice, MethodConfig};
pub use planar::PlanarConfig;
pub use rescaling::{scalar_factors, Rescaling};
pub use rolling::RollingConfig;

use std::time::Duration;

use crate::contract::Limits;
use crate::error::Fc3dError;

/// Which solver to run and how far.
///
/// ```
/// use fc3d_core::{NsgsOptions, SolverConfig};
/// let config = SolverConfig::new(NsgsOptions::default()).with_tolerance(1e-8);
/// assert_eq!((config.tolerance, config.max_iter), (1e-8, 1000));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverConfig {
    /// Tolerance on the relative natural-map error of the returned `(r, u)` (finite, >= 0).
    /// Default: the family's Siconos default (1e-4 NSGS, PROX, TFP, PFP, ACLMFP, SOCLCP; 1e-3
    /// VI family and NSN; 1e-6 ADMM).
    pub tolerance: f64,
    /// Iteration limit: sweeps (NSGS, SOCLCP), Newton steps (NSN), outer iterations (TFP, PFP,
    /// ACLMFP, PROX), projection steps (VI), ADMM iterations. Default: the family's Siconos
    /// default (1000; 20000 VI family and ADMM; 200 NSN).
    pub max_iter: usize,
    /// Wall-clock budget (default `None`). When it is spent, the solver stops after the current
    /// iteration and returns its best iterate with
    /// [`SolveStatus::TimeBudgetExhausted`](crate::SolveStatus::TimeBudgetExhausted).
    pub time_budget: Option<Duration>,
    /// Rescaling around the solver (default [`Rescaling::None`]).
    pub rescaling: Rescaling,
    /// The solver family and its own settings.
    pub method: Method,
}

impl SolverConfig {
    /// `method` with its family's default limits, no time budget, no rescaling.
    pub fn new(method: impl Into<Method>) -> Self {
        let method = method.into();
        let (tolerance, max_iter) = method.default_limits();
        SolverConfig {
            tolerance,
            max_iter,
            time_budget: None,
            rescaling: Rescaling::None,
            method,
        }
    }

    pub fn with_tolerance(self, tolerance: f64) -> Self {
        SolverConfig { tolerance, ..self }
    }

    pub fn with_max_iter(self, max_iter: usize) -> Self {
        SolverConfig { max_iter, ..self }
    }

    pub fn with_time_budget(self, time_budget: Option<Duration>) -> Self {
        SolverConfig {
            time_budget,
            ..self
        }
    }

    pub fn with_rescaling(self, rescaling: Rescaling) -> Self {
        SolverConfig { rescaling, ..self }
    }

    /// The limits the family runs under.
    pub fn limits(&self) -> Limits {
        Limits {
            tolerance: self.tolerance,
            max_iter: self.max_iter,
            time_budget: self.time_budget,
        }
    }

    /// Checks every setting against its documented range.
    pub fn validate(&self) -> Result<(), Fc3dError> {
        self.limits().validate()?;
        self.method.family().validate()
    }

    /// Siconos id of the solver.
    pub fn siconos_id(&self) -> i32 {
        self.method.siconos_id()
    }

    /// Short human-readable label, e.g. `NSGS/565`.
    pub fn label(&self) -> String {
        self.method.label()
    }
}

impl Default for SolverConfig {
    /// NSGS with Siconos' defaults.
    fn default() -> Self {
        SolverConfig::new(Method::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{PlanarMethod, RollingMethod};

    #[test]
    fn every_config_rejects_the_same_bad_limits() {
        let bad = [
            (f64::NAN, None),
            (-1e-4, None),
            (f64::INFINITY, None),
            (1e-4, Some(Duration::ZERO)),
        ];
        for (tolerance, time_budget) in bad {
            let limits = Limits {
                tolerance,
                max_iter: 10,
                time_budget,
            };
            assert!(limits.validate().is_err(), "{limits:?}");
            let mut solver = SolverConfig::default();
            (solver.tolerance, solver.time_budget) = (tolerance, time_budget);
            assert!(solver.validate().is_err(), "{limits:?}");
            let mut planar: PlanarConfig = MethodConfig::new(PlanarMethod::Cpg);
            (planar.tolerance, planar.time_budget) = (tolerance, time_budget);
            assert!(planar.validate().is_err(), "{limits:?}");
            let mut rolling: RollingConfig =
                MethodConfig::new(RollingMethod::Nsgs(Default::default()));
            (rolling.tolerance, rolling.time_budget) = (tolerance, time_budget);
            assert!(rolling.validate().is_err(), "{limits:?}");
        }
        let good = Limits {
            tolerance: 0.0,
            max_iter: 0,
            time_budget: Some(Duration::from_nanos(1)),
        };
        assert!(good.validate().is_ok());
    }
}
