//! The solver families, one module each, in the order of the seed paper's tables: nonsmooth
//! Gauss-Seidel, the VI / fixed-point projection family, nonsmooth Newton, the proximal point
//! method, the optimization-based fixed points (Tresca, Panagiotopoulos, ACLM, and the SOCLCP
//! relaxation they build on, with the accelerated first-order solvers of their convex
//! sub-problems in `accelerated`) and ADMM. Each family's settings implement
//! [`crate::contract::Family`]; `config` dispatches to them.

pub mod accelerated;
pub mod aclm;
pub mod admm;
pub mod auto;
pub mod nsgs;
pub mod nsn;
pub mod pfp;
pub mod planar;
pub mod prox;
pub mod rolling;
pub mod soclcp;
pub mod tresca;
pub mod vi;

/// Where a factorizing run (NSN, PROX's Newton, ADMM) stops before its set-up, which cannot be
/// interrupted (the assembly and faer's symbolic analysis, predicted by
/// [`crate::math::lu_cost::analysis_ends_by`]): when it would end past `deadline`, `u = W r + q`
/// for r as it came (`set_velocity`) and the outcome "out of time after 0 iterations"; `None`
/// when there is time.
pub(crate) fn stop_before_analysis(
    w: &crate::matrix::Delassus<'_>,
    deadline: Option<std::time::Instant>,
    set_velocity: impl FnOnce(),
) -> Option<crate::contract::SolverOutcome> {
    if crate::math::lu_cost::analysis_ends_by(w.stored_entries(), deadline) {
        return None;
    }
    set_velocity();
    Some(crate::contract::SolverOutcome::stopped(0, true))
}
