//! [`RollingConfig`]: the settings of a rolling-friction solve (Siconos' `rolling_fc3d` and
//! `rolling_fc2d` ids).

use std::time::Duration;

use crate::contract::Limits;
use crate::error::{require_setting, Fc3dError};
use crate::solvers::rolling::RollingMethod;

/// Which rolling solver to run and how far.
///
/// ```
/// use fc3d_core::{RollingConfig, RollingMethod, RollingNsgsOptions};
/// let config = RollingConfig::new(RollingMethod::Nsgs(RollingNsgsOptions::default()));
/// assert_eq!((config.tolerance, config.max_iter), (1e-4, 1000));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingConfig {
    /// Tolerance on the relative natural-map error (rolling cone) of the returned `(r, u)`.
    pub tolerance: f64,
    /// Sweeps (NSGS).
    pub max_iter: usize,
    /// Wall-clock budget (default `None`).
    pub time_budget: Option<Duration>,
    pub method: RollingMethod,
}

impl RollingConfig {
    /// `method` with Siconos' default limits for its id.
    pub fn new(method: RollingMethod) -> Self {
        let (tolerance, max_iter) = method.default_limits();
        RollingConfig {
            tolerance,
            max_iter,
            time_budget: None,
            method,
        }
    }

    pub fn limits(&self) -> Limits {
        Limits {
            tolerance: self.tolerance,
            max_iter: self.max_iter,
            time_budget: self.time_budget,
        }
    }

    pub fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.tolerance >= 0.0 && self.tolerance.is_finite(),
            "tolerance",
            self.tolerance,
            "finite and >= 0",
        )?;
        self.method.validate()
    }
}
