//! [`PlanarConfig`]: the settings of a 2D solve (Siconos' `fc2d` ids).

use super::method_config::{MethodChoice, MethodConfig};
use crate::error::Fc3dError;
use crate::solvers::planar::PlanarMethod;

/// Which 2D solver to run and how far.
///
/// ```
/// use fc3d_core::{PlanarConfig, PlanarMethod, PlanarNsgsOptions};
/// let config = PlanarConfig::new(PlanarMethod::Nsgs(PlanarNsgsOptions::default()));
/// assert_eq!((config.tolerance, config.max_iter), (1e-4, 1000));
/// ```
pub type PlanarConfig = MethodConfig<PlanarMethod>;

impl MethodChoice for PlanarMethod {
    fn default_limits(&self) -> (f64, usize) {
        PlanarMethod::default_limits(self)
    }
    fn validate(&self) -> Result<(), Fc3dError> {
        PlanarMethod::validate(self)
    }
}
