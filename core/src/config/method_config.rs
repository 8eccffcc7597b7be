//! [`MethodConfig`]: a method and the limits of its run, the configuration shared by the 2D
//! ([`PlanarConfig`](super::PlanarConfig)) and rolling ([`RollingConfig`](super::RollingConfig))
//! solves.

use std::time::Duration;

use crate::contract::Limits;
use crate::error::Fc3dError;

/// What a list of methods (one problem kind's solver ids) gives its configuration.
pub trait MethodChoice {
    /// Siconos' default `(tolerance, max_iter)` for the method's id.
    fn default_limits(&self) -> (f64, usize);
    /// Checks the method's own settings.
    fn validate(&self) -> Result<(), Fc3dError>;
}

/// Which solver to run and how far.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MethodConfig<M> {
    /// Tolerance on the relative natural-map error (with the problem's cone) of the returned
    /// `(r, u)` (finite, >= 0).
    pub tolerance: f64,
    /// The method's iterations: sweeps (NSGS), iterations (CPG, ADMM), pivots (Lemke); not used
    /// by enumeration.
    pub max_iter: usize,
    /// Wall-clock budget (default `None`).
    pub time_budget: Option<Duration>,
    pub method: M,
}

impl<M: MethodChoice> MethodConfig<M> {
    /// `method` with Siconos' default limits for its id.
    pub fn new(method: M) -> Self {
        let (tolerance, max_iter) = method.default_limits();
        MethodConfig {
            tolerance,
            max_iter,
            time_budget: None,
            method,
        }
    }

    /// The limits the method runs under.
    pub fn limits(&self) -> Limits {
        Limits {
            tolerance: self.tolerance,
            max_iter: self.max_iter,
            time_budget: self.time_budget,
        }
    }

    /// Checks the limits and the method's own settings.
    pub fn validate(&self) -> Result<(), Fc3dError> {
        self.limits().validate()?;
        self.method.validate()
    }
}
