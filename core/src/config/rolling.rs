//! [`RollingConfig`]: the settings of a rolling-friction solve (Siconos' `rolling_fc3d` and
//! `rolling_fc2d` ids).

use super::method_config::{MethodChoice, MethodConfig};
use crate::error::Fc3dError;
use crate::solvers::rolling::RollingMethod;

/// Which rolling solver to run and how far.
///
/// ```
/// use fc3d_core::{RollingConfig, RollingMethod, RollingNsgsOptions};
/// let config = RollingConfig::new(RollingMethod::Nsgs(RollingNsgsOptions::default()));
/// assert_eq!((config.tolerance, config.max_iter), (1e-4, 1000));
/// ```
pub type RollingConfig = MethodConfig<RollingMethod>;

impl MethodChoice for RollingMethod {
    fn default_limits(&self) -> (f64, usize) {
        RollingMethod::default_limits(self)
    }
    fn validate(&self) -> Result<(), Fc3dError> {
        RollingMethod::validate(self)
    }
}
