//! The global error (`gfc3d_compute_error`, `gfc3d_compute_error_convex`), the global velocity
//! of a reaction (`..._computeGlobalVelocity`) and the reformulations between the local and
//! global forms, on the host's problems (never modified: M is factored in fc3d's own memory).

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::{global_from_c, global_rolling_from_c, global_to_c, AnyGlobal};
use crate::matrix::c_slice;
use crate::problem::{problem_from_c, problem_to_c};
use crate::rolling::rolling_to_c;
use crate::types::{
    FrictionContactProblem, GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem,
    RollingFrictionContactProblem, SolverOptions,
};
use crate::{ffi_guard, CError, CResult};
use fc3d_core::error::check_finite;
use fc3d_core::io::dat::{GlobalStorage, MatrixStorage};
use fc3d_core::matrix::CsrMatrix;
use fc3d_core::measure::{global_error_with_norm_q, ContactLaw, ErrorWork};
use fc3d_core::problem::GlobalProblem;

/// The error of `(reaction, globalVelocity)` with the given law; writes `velocity`.
#[allow(clippy::too_many_arguments)]
unsafe fn compute_error(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    global_velocity: *mut c_double,
    tolerance: c_double,
    norm_q: c_double,
    error: *mut c_double,
    law: ContactLaw,
) -> CResult<c_int> {
    let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
    if error.is_null() {
        return Err(CError::null("error"));
    }
    let view = global_from_c::<3>(p)?;
    let g = &view.problem;
    let r = c_slice(reaction as *const c_double, g.size(), "reaction")?;
    c_slice(velocity as *const c_double, g.size(), "velocity")?;
    let v = c_slice(
        global_velocity as *const c_double,
        g.ndof(),
        "globalVelocity",
    )?;
    check_finite("reaction", r)?;
    check_finite("globalVelocity", v)?;
    let mut u = vec![0.0; g.size()];
    let mut work = ErrorWork::new(g.ndof());
    let e = global_error_with_norm_q(g, law, r, &mut u, v, None, norm_q, &mut work);
    std::ptr::copy_nonoverlapping(u.as_ptr(), velocity, u.len());
    *error = e;
    Ok(c_int::from(e > tolerance))
}

/// Siconos' global error of `(reaction, globalVelocity)`: recomputes `velocity = H^T v + b`
/// (written to `velocity`, as Siconos does), then
/// `error = ||q + H r - M v|| / max(norm_q, ||M v||, ||H r||)
///        + sqrt(sum_c ||r_c - P_K(r_c - ũ_c)||^2) / max(||u||, ||r||)`
/// (ũ De Saxcé's velocity; a division is skipped when its denominator is at most the machine
/// epsilon) on the problem's own M and H. Returns 0 if `error <= tolerance`, 1 otherwise, a
/// negative code on invalid input (nothing written). `options` and `norm_b` are not read (Siconos
/// uses `options->dWork` as scratch and never reads `norm_b`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_compute_error(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    tolerance: c_double,
    options: *mut SolverOptions,
    norm_q: c_double,
    norm_b: c_double,
    error: *mut c_double,
) -> c_int {
    let _ = (options, norm_b);
    ffi_guard(
        "gfc3d_compute_error",
        |c| c,
        || {
            compute_error(
                problem,
                reaction,
                velocity,
                globalVelocity,
                tolerance,
                norm_q,
                error,
                ContactLaw::Coulomb,
            )
        },
    )
}

/// `gfc3d_compute_error` for the convex relaxation of the problem: the law's residual is
/// `r_c - P_K(r_c - u_c)` (no De Saxcé term). `velocity` is recomputed and written as well
/// (Siconos 4.4's version reads it without recomputing it, a defect fixed upstream later).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_compute_error_convex(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    tolerance: c_double,
    options: *mut SolverOptions,
    norm_q: c_double,
    norm_b: c_double,
    error: *mut c_double,
) -> c_int {
    let _ = (options, norm_b);
    ffi_guard(
        "gfc3d_compute_error_convex",
        |c| c,
        || {
            compute_error(
                problem,
                reaction,
                velocity,
                globalVelocity,
                tolerance,
                norm_q,
                error,
                ContactLaw::Convex,
            )
        },
    )
}

/// `v = M^-1 (q + H r)` of a core global problem into the host's array `v`.
unsafe fn global_velocity<const D: usize>(
    g: &GlobalProblem<'_, D>,
    reaction: *mut c_double,
    global_velocity: *mut c_double,
) -> CResult<c_int> {
    let r = c_slice(reaction as *const c_double, g.size(), "reaction")?;
    c_slice(
        global_velocity as *const c_double,
        g.ndof(),
        "globalVelocity",
    )?;
    check_finite("reaction", r)?;
    let mut operator = g.operator()?;
    let mut v = vec![0.0; g.ndof()];
    operator.global_velocity(g.q(), r, &mut v);
    std::ptr::copy_nonoverlapping(v.as_ptr(), global_velocity, v.len());
    Ok(0)
}

/// The global velocity of a reaction: `globalVelocity = M^-1 (q + H reaction)`, M factored in
/// fc3d's memory (the host's M is left as it is; Siconos factors a dense M in place). Returns 0
/// on success, a negative code otherwise (a singular M, invalid input: nothing written).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_computeGlobalVelocity(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    globalVelocity: *mut c_double,
) -> c_int {
    ffi_guard(
        "globalFrictionContact_computeGlobalVelocity",
        |c| c,
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            if p.dimension == 2 {
                global_velocity(&global_from_c::<2>(p)?.problem, reaction, globalVelocity)
            } else {
                global_velocity(&global_from_c::<3>(p)?.problem, reaction, globalVelocity)
            }
        },
    )
}

/// The global velocity of a reaction for a global rolling problem, as
/// `globalFrictionContact_computeGlobalVelocity`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_computeGlobalVelocity(
    problem: *mut GlobalRollingFrictionContactProblem,
    reaction: *mut c_double,
    globalVelocity: *mut c_double,
) -> c_int {
    ffi_guard(
        "globalRollingFrictionContact_computeGlobalVelocity",
        |c| c,
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = global_rolling_from_c(p)?;
            global_velocity(view.problem.base(), reaction, globalVelocity)
        },
    )
}

/// The local problem of a global one: W = H^T M^-1 H (M factored block by block when it is
/// block diagonal, never inverted densely; for dimension 3 W is sparse-block with every block
/// that holds a non-zero entry and every diagonal block, for dimension 2 a sparse matrix),
/// `q = H^T M^-1 q + b`, mu copied. The host's M is left as it is (Siconos inverts a
/// sparse-block M in place). Release with `frictionContactProblem_free`. NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_reformulation_FrictionContact(
    problem: *mut GlobalFrictionContactProblem,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "globalFrictionContact_reformulation_FrictionContact",
        |_| null_mut(),
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = super::any_global_from_c(p)?;
            match &view.problem {
                AnyGlobal::Spatial(g) => problem_to_c(&g.reduce(&mut g.operator()?)?),
                AnyGlobal::Planar(g) => problem_to_c(&g.reduce(&mut g.operator()?)?),
            }
        },
    )
}

/// The local rolling problem of a global rolling one (W = H^T M^-1 H as a sparse matrix,
/// `q = H^T M^-1 q + b`, mu and mu_r copied), as
/// `globalFrictionContact_reformulation_FrictionContact`. Release with
/// `rollingFrictionContactProblem_free`. NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_reformulation_RollingFrictionContact(
    problem: *mut GlobalRollingFrictionContactProblem,
) -> *mut RollingFrictionContactProblem {
    ffi_guard(
        "globalRollingFrictionContact_reformulation_RollingFrictionContact",
        |_| null_mut(),
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = global_rolling_from_c(p)?;
            let mut operator = view.problem.base().operator()?;
            rolling_to_c(&view.problem.reduce(&mut operator)?)
        },
    )
}

/// A global problem whose reduction is the local problem FC(W, q, mu) exactly: with `m = 3 nc`
/// unknowns per copy, `M = [[I, 2I - W], [0, I]]` (`2m x 2m`, unit upper block triangular, so
/// invertible whatever W), `H = [I; I]`, q = 0 and b = the local q, so that
/// `H^T M^-1 H = W` and `H^T M^-1 q + b = q`: a solution `(r, u)` of either form is one of the
/// other (`v = (W r - r, r)`). M and H are sparse (triplet); the local problem is checked first
/// as the solvers check it and left as it is. Siconos 4.4 returns `M = W, H = I, b = 0`, whose
/// reduction is `W^-1`, not W (and prints H). Release with `globalFrictionContact_free`. NULL on
/// failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_reformulation_global_problem(
    problem: *mut FrictionContactProblem,
) -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "fc3d_reformulation_global_problem",
        |_| null_mut(),
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let local = problem_from_c(p)?;
            let m = local.size();
            let n = 2 * m;
            let mut mt: Vec<(usize, usize, f64)> = Vec::new();
            mt.try_reserve(n + m + local.w().nrows().saturating_mul(3))
                .map_err(|_| {
                    CError::from(fc3d_core::Fc3dError::OutOfMemory {
                        what: "the reformulated M".into(),
                        bytes: n.saturating_mul(24),
                    })
                })?;
            for i in 0..n {
                mt.push((i, i, 1.0));
            }
            for i in 0..m {
                mt.push((i, m + i, 2.0));
            }
            local.w().for_each_entry(|i, j, w| {
                if w != 0.0 {
                    mt.push((i, m + j, -w));
                }
            });
            let ht: Vec<(usize, usize, f64)> = (0..m)
                .flat_map(|i| [(i, i, 1.0), (m + i, i, 1.0)])
                .collect();
            let global = GlobalProblem::<3>::new(
                CsrMatrix::from_triplets(n, n, &mt)?,
                CsrMatrix::from_triplets(n, m, &ht)?,
                vec![0.0; n],
                local.q(),
                local.mu(),
            )?;
            let storage = GlobalStorage {
                m: MatrixStorage::Sparse,
                h: MatrixStorage::Sparse,
            };
            global_to_c(&global, &storage)
        },
    )
}
