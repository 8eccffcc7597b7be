//! The global formulation (Siconos' gfc3d family): M, H, q, b, mu given, find `(v, u, r)` with
//! `M v = q + H r`, `u = H^T v + b` and the contact law between u and r. The host's M and H are
//! never modified; every reported error is Siconos' global error measured on them.
//!
//! * [`GlobalProblem`], [`GlobalRollingProblem`]: the data, validated (in `problem`, so that
//!   readers and scenes can build them);
//! * [`GlobalConfig`], [`GlobalMethod`]: which solver (Siconos' ids 600-615, 5000) and how far;
//! * [`solve_global`], [`solve_global_rolling`]: the solve and its [`GlobalReport`];
//! * [`global_error`]: Siconos' `gfc3d_compute_error` (and its convex variant).
//!
//! The reduction to the local problem goes through [`crate::matrix::HForm`] (W = H^T M^-1 H
//! with M factored block by block, never a dense inverse).

mod aclm;
mod admm;
mod alm;
mod config;
mod hform;
mod ipm;
mod jacobi;
mod newton;
mod rescaling;
mod solve;
mod vi;

pub use crate::measure::{
    global_error, global_error_with, global_rolling_error, ContactLaw, ErrorWork,
};
pub use crate::problem::{GlobalProblem, GlobalRollingProblem};
pub use aclm::GlobalAclmOptions;
pub use admm::GlobalAdmmOptions;
pub use alm::GlobalAlmOptions;
pub use config::{
    global_rolling_default, GlobalConfig, GlobalMethod, GlobalRollingConfig, HFORM_ID,
};
pub use hform::HFormSweep;
pub use ipm::IpmOptions;
pub use jacobi::JacobiOptions;
pub use newton::GlobalNewtonOptions;
pub use rescaling::GlobalRescaling;
pub use solve::{solve_global, solve_global_rolling, solve_global_with_observer, GlobalReport};

/// The entries a factorizing global solver's set-up handles before its first factorization
/// (M's, then per contact the square of the unknowns its rows of `H^T` touch, `couplings`
/// entries for `k` touched unknowns, and `extra`), the count
/// [`crate::math::lu_cost::assembly_ends_by`] predicts the set-up's duration from. The rows of
/// `H^T` are not counted one by one (that would be a pass of the set-up itself): with `nnz(H)`
/// spread evenly, a contact touches `nnz(H) / (3 n_c)` unknowns, the fewest its rows can touch
/// when each touches the same ones; `couplings` is convex, so the count is at most the set-up's
/// (a set-up is refused only when even the fewest entries cannot be handled in time).
fn set_up_entries(
    problem: &GlobalProblem<'_>,
    couplings: impl Fn(f64) -> f64,
    extra: usize,
) -> usize {
    let nc = problem.n_contacts().max(1) as f64;
    let touched = problem.h().nnz() as f64 / (3.0 * nc);
    let entries = problem.m().nnz() as f64 + nc * couplings(touched) + extra as f64;
    if entries < usize::MAX as f64 {
        entries as usize
    } else {
        usize::MAX
    }
}
