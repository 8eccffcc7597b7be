//! [`PlanarConfig`]: the settings of a 2D solve (Siconos' `fc2d` ids).

use std::time::Duration;

use crate::contract::Limits;
use crate::error::{require_setting, Fc3dError};
use crate::solvers::planar::PlanarMethod;

/// Which 2D solver to run and how far.
///
/// ```
/// use fc3d_core::{PlanarConfig, PlanarMethod, PlanarNsgsOptions};
/// let config = PlanarConfig::new(PlanarMethod::Nsgs(PlanarNsgsOptions::default()));
/// assert_eq!((config.tolerance, config.max_iter), (1e-4, 1000));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarConfig {
    /// Tolerance on the relative natural-map error of the returned `(r, u)` (finite, >= 0).
    pub tolerance: f64,
    /// Sweeps (NSGS), iterations (CPG), pivots (Lemke); not used by enumeration.
    pub max_iter: usize,
    /// Wall-clock budget (default `None`).
    pub time_budget: Option<Duration>,
    pub method: PlanarMethod,
}

impl PlanarConfig {
    /// `method` with Siconos' default limits for its id.
    pub fn new(method: PlanarMethod) -> Self {
        let (tolerance, max_iter) = method.default_limits();
        PlanarConfig {
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
