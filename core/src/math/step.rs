//! Siconos' constants of the self-adaptive step rule (Algorithm 3 of Acary-Brémond-Huber, the
//! rule of FP-VI-UPK): a trial step of size rho is accepted when its ratio (98) is at most `L`,
//! rejected steps shrink rho by `NU`, and an accepted step whose ratio is below `L_MIN` lets
//! rho grow by `1 / NU`. The VI family exposes them as settings; the one-contact projection
//! solvers and the Tresca sub-problem use them as they are.

/// Reduction factor of a rejected trial.
pub const NU: f64 = 2.0 / 3.0;
/// Acceptance threshold on the ratio.
pub const L: f64 = 0.9;
/// Below this ratio the next rho grows.
pub const L_MIN: f64 = 0.3;
