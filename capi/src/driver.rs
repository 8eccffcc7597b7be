//! `fc3d_driver`, `fc3d_nsgs` and `fc3d_compute_error`.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::matrix::c_slice;
use super::params::{config_from_c, write_outputs};
use super::problem::problem_from_c;
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_OPTION};
use fc3d_core::measure::{absolute_natural_map_residual, relative_scale};
use fc3d_core::{solve_with_observer, IterationEvent};

unsafe fn driver_impl(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> CResult<c_int> {
    if problem.is_null() {
        return Err(CError::null("problem"));
    }
    if options.is_null() {
        return Err(CError::null("options"));
    }
    let config = config_from_c(&*options)?;
    let p = problem_from_c(&*problem)?;
    let n = p.size();
    let r_in = c_slice(reaction as *const c_double, n, "reaction")?;
    c_slice(velocity as *const c_double, n, "velocity")?;

    // Work on copies: the host's arrays are written only on success.
    let mut r = r_in.to_vec();
    let mut u = vec![0.0; n];
    let callback = (*options).callback;
    let mut scratch_r = Vec::new();
    let mut scratch_u = Vec::new();
    let mut observer = |ev: &IterationEvent<'_>| {
        if callback.is_null() {
            return;
        }
        let cb = &*callback;
        if let Some(f) = cb.collectStatsIteration {
            scratch_r.clear();
            scratch_r.extend_from_slice(ev.reaction);
            scratch_u.resize(n, 0.0);
            p.velocity(ev.reaction, &mut scratch_u);
            f(
                cb.env,
                n as c_int,
                scratch_r.as_mut_ptr(),
                scratch_u.as_mut_ptr(),
                ev.error,
                std::ptr::null_mut(),
            );
        }
    };
    let report = solve_with_observer(&p, &config, &mut r, &mut u, &mut observer)?;

    std::ptr::copy_nonoverlapping(r.as_ptr(), reaction, n);
    std::ptr::copy_nonoverlapping(u.as_ptr(), velocity, n);
    write_outputs(&mut *options, &report);
    if verbose() > 0 {
        eprintln!(
            "fc3d: {} on {} contacts: {:?} after {} iterations, error {:e} (tolerance {:e})",
            config.label(),
            p.n_contacts(),
            report.status,
            report.iterations,
            report.error,
            config.tolerance
        );
    }
    Ok(report.status.info_code())
}

/// Solves the problem with the solver `options->solverId`, starting from `reaction`.
/// Returns 0 when converged (error <= dparam[0]), 1 when the solver stopped above the
/// tolerance at its iteration limit (reaction, velocity hold its last iterate), 2
/// (`FC3D_TIME_BUDGET_EXHAUSTED`) when the time budget `dparam[FC3D_DPARAM_TIME_BUDGET]` ran out
/// (they hold the best iterate measured), a negative `FC3D_ERR_*` code when the
/// input is rejected (nothing is written). On return >= 0, `iparam[1]` holds the iterations
/// and `dparam[1]` the error measured on the returned `(reaction, velocity)`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_driver(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "fc3d_driver",
        |c| c,
        || driver_impl(problem, reaction, velocity, options),
    )
}

/// Siconos' direct NSGS entry: as `fc3d_driver` with `options->solverId` = 500, the result
/// code written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nsgs(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let code = ffi_guard(
        "fc3d_nsgs",
        |c| c,
        || {
            if info.is_null() {
                return Err(CError::null("info"));
            }
            if !options.is_null() && (*options).solverId != 500 {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "fc3d_nsgs called with options for solver {}",
                        (*options).solverId
                    ),
                ));
            }
            driver_impl(problem, reaction, velocity, options)
        },
    );
    if !info.is_null() {
        *info = code;
    }
}

/// Siconos' error measure: recomputes `w = M z + q` (written to `w`), then
/// `error = ||z - P_K(z - (w_N + mu ||w_T||, w_T))|| / max(norm, ||z||, ||w||)`.
/// Returns 0 if `error <= tolerance`, 1 otherwise, a negative code on invalid input (nothing
/// written). `options` may be NULL.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_compute_error(
    problem: *mut FrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    options: *mut SolverOptions,
    norm: c_double,
    error: *mut c_double,
) -> c_int {
    let _ = options;
    ffi_guard(
        "fc3d_compute_error",
        |c| c,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if error.is_null() {
                return Err(CError::null("error"));
            }
            let p = problem_from_c(&*problem)?;
            let n = p.size();
            let r = c_slice(z as *const c_double, n, "z")?;
            c_slice(w as *const c_double, n, "w")?;
            fc3d_core::error::check_finite("z", r)?;
            let mut u = vec![0.0; n];
            p.velocity(r, &mut u);
            let abs = absolute_natural_map_residual(r, &u, p.mu());
            let e = abs / relative_scale(norm.abs(), r, &u);
            std::ptr::copy_nonoverlapping(u.as_ptr(), w, n);
            *error = e;
            Ok(if e <= tolerance { 0 } else { 1 })
        },
    )
}
