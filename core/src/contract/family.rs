//! What a solver family provides to the one dispatch in `config`: its name and Siconos id, the
//! Siconos defaults of the common limits, the check of its own settings, and its run.

use super::{Limits, Observer, SolverOutcome};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;

/// A solver family's settings (the part of a [`crate::SolverConfig`] specific to the family).
///
/// `run` starts from the reaction in `r` and leaves its answer there; `u` is work space (the
/// caller recomputes `u = W r + q` and the error). Everything that can fail is checked before
/// `r` is touched: on `Err`, `r` is unchanged.
pub(crate) trait Family {
    /// The named configurations of the family with their defaults (one per Siconos id or
    /// variant the family offers).
    fn presets() -> Vec<Self>
    where
        Self: Sized + Default,
    {
        vec![Self::default()]
    }
    /// Short name, also the name `fc3d bench` accepts (`NSGS`, `VI-FPP`, `NSN-AC`, ...).
    fn name(&self) -> &'static str;
    /// Label of a configured solver in tables and legends (`NSGS/565`, `NSN-AC/GP`, ...).
    fn label(&self) -> String;
    /// The Siconos solver id this configuration runs as.
    fn siconos_id(&self) -> i32;
    /// Siconos' default `(tolerance, max_iter)` for this family.
    fn default_limits(&self) -> (f64, usize);
    /// Checks the family's own settings (the limits are checked by the caller).
    fn validate(&self) -> Result<(), Fc3dError>;
    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError>;
}
