//! Siconos' 2D friction functions (`fc2d_Solvers.h`, `fc2d_compute_error.h`, `fc2d_driver`):
//! the driver and the direct solver entries run the core's 2D solvers; the error functions and
//! the CPG projections are Siconos' formulas on the host's arrays.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::driver::planar_driver_impl;
use super::matrix::c_slice;
use super::problem::planar_problem_from_c;
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, CError, FC3D_ERR_INVALID_OPTION, FC3D_ERR_INVALID_SIZE};
use fc3d_core::measure::{absolute_natural_map_residual_d, contact_residual_sq_d};
use fc3d_core::solvers::planar::cpg::{project_direction, project_step, Status};

/// Solves the 2D problem (`problem->dimension` = 2) with the solver `options->solverId`: 400
/// NSGS, 402 CPG, 404 Lemke, 405 enumeration (any other id: `FC3D_ERR_UNSUPPORTED_SOLVER`). NSGS
/// starts from `reaction`; CPG, Lemke and enumeration start from zero, as Siconos' do. W may be
/// dense, sparse-block (2x2 blocks) or sparse. Returns 0 when the natural-map error of the
/// returned `(reaction, velocity)` is at most `dparam[0]`, 1 when the solver stopped above it
/// (Lemke: a secondary ray or the pivot limit; enumeration: no feasible case, or `iparam[0]`
/// cases tried), 2 when the time budget `dparam[FC3D_DPARAM_TIME_BUDGET]` ran out, a negative
/// `FC3D_ERR_*` code when the input is rejected (nothing written). Enumeration tries the cases
/// in Siconos' order, at most `iparam[0]` of them (0, Siconos' default: every case); with 0 and
/// no time budget a problem of more than 10 contacts (2^33 cases and more) is refused with
/// `FC3D_ERR_INVALID_OPTION`. On return >= 0, `iparam[1]` holds the iterations (sweeps, CPG
/// iterations, pivots, cases tried) and `dparam[1]` the error measured on the returned pair.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_driver(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "fc2d_driver",
        |c| c,
        || planar_driver_impl(problem, reaction, velocity, options),
    )
}

/// A direct 2D solver entry: `fc2d_driver` for options of solver `id`, the result code in
/// `*info`.
unsafe fn direct(
    name: &'static str,
    id: c_int,
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let code = ffi_guard(
        name,
        |c| c,
        || {
            if info.is_null() {
                return Err(CError::null("info"));
            }
            if !options.is_null() && (*options).solverId != id {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "{name} called with options for solver {} (it needs {id})",
                        (*options).solverId
                    ),
                ));
            }
            planar_driver_impl(problem, reaction, velocity, options)
        },
    );
    if !info.is_null() {
        *info = code;
    }
}

/// Siconos' dense 2D NSGS entry: the 2D NSGS (400) of `fc2d_driver`, whatever W's storage.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_nsgs_dense(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    direct(
        "fc2d_nsgs_dense",
        400,
        problem,
        reaction,
        velocity,
        info,
        options,
    )
}

/// Siconos' sparse-block 2D NSGS entry: the 2D NSGS (400) of `fc2d_driver`, whatever W's
/// storage.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_nsgs_sbm(
    problem: *mut FrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    direct("fc2d_nsgs_sbm", 400, problem, z, w, info, options)
}

/// Siconos' CPG entry (402), as `fc2d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_cpg(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    direct("fc2d_cpg", 402, problem, reaction, velocity, info, options)
}

/// Siconos' Lemke entry (404), as `fc2d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_lexicolemke(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    direct(
        "fc2d_lexicolemke",
        404,
        problem,
        reaction,
        velocity,
        info,
        options,
    )
}

/// Siconos' enumeration entry (405), as `fc2d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_enum(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    direct("fc2d_enum", 405, problem, reaction, velocity, info, options)
}

/// Writes Siconos' 2D NSGS defaults into the slots of `options` that carry them: `iparam[5]`
/// (no shuffling) = 0 and `iparam[7]` (error evaluation) = 2, light with full final. Nothing
/// else changes. NULL options, or arrays shorter than 8, are refused (nothing written).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_nsgs_set_default(options: *mut SolverOptions) {
    ffi_guard(
        "fc2d_nsgs_set_default",
        |_| (),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let o = &mut *options;
            if o.iparam.is_null() || o.iSize < 8 {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("options->iparam must hold 8 slots (iSize = {})", o.iSize),
                ));
            }
            let defaults = super::params::defaults(400)?;
            for k in [5, 7] {
                *o.iparam.add(k) = defaults.iparam[k];
            }
            Ok(())
        },
    )
}

/// Siconos' 2D error: recomputes `w = M z + q` (written to `w`), then
/// `error = sqrt(sum_c ||z_c - P_K(z_c - (w_N + mu |w_T|, w_T))||^2)`, divided by
/// `max(norm, ||z||, ||w||)` when that is above the machine epsilon (as Siconos: a smaller scale
/// leaves the error absolute). Returns 0 if `error <= tolerance`, 1 otherwise, a negative code
/// on invalid input (nothing written).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_compute_error(
    problem: *mut FrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    norm: c_double,
    error: *mut c_double,
) -> c_int {
    ffi_guard(
        "fc2d_compute_error",
        |c| c,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if error.is_null() {
                return Err(CError::null("error"));
            }
            let p = planar_problem_from_c(&*problem)?;
            let n = p.size();
            let r = c_slice(z as *const c_double, n, "z")?;
            c_slice(w as *const c_double, n, "w")?;
            fc3d_core::error::check_finite("z", r)?;
            let mut u = fc3d_core::error::try_vec(n, 0.0, "w")?;
            p.velocity(r, &mut u);
            let absolute = absolute_natural_map_residual_d::<2>(r, &u, p.mu());
            let norm_of = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let scale = norm.max(norm_of(r)).max(norm_of(&u));
            let e = if scale.abs() > f64::EPSILON {
                absolute / scale
            } else {
                absolute
            };
            std::ptr::copy_nonoverlapping(u.as_ptr(), w, n);
            *error = e;
            Ok(if e <= tolerance { 0 } else { 1 })
        },
    )
}

/// Adds the squared 2D natural-map residual of one contact (`r`, `u`: 2 values each) to
/// `*error`, as Siconos' `fc2d_unitary_compute_and_add_error`; `worktmp` (2 values) receives
/// `r - P_K(r - (u_N + mu |u_T|, u_T))`. NULL pointers are refused (nothing written).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_unitary_compute_and_add_error(
    r: *mut c_double,
    u: *mut c_double,
    mu: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) {
    ffi_guard(
        "fc2d_unitary_compute_and_add_error",
        |_| (),
        || {
            if error.is_null() {
                return Err(CError::null("error"));
            }
            let rc = c_slice(r as *const c_double, 2, "r")?;
            let uc = c_slice(u as *const c_double, 2, "u")?;
            c_slice(worktmp as *const c_double, 2, "worktmp")?;
            let (rc, uc) = ([rc[0], rc[1]], [uc[0], uc[1]]);
            let ut = [uc[0] + mu * uc[1].abs(), uc[1]];
            let p = fc3d_core::math::cone::project_on_cone_2d(&[rc[0] - ut[0], rc[1] - ut[1]], mu);
            *worktmp = rc[0] - p[0];
            *worktmp.add(1) = rc[1] - p[1];
            *error += contact_residual_sq_d::<2>(&rc, &uc, mu);
            Ok(())
        },
    )
}

/// Siconos' CPG step projection `fc2d_projc`: for each of the `*n / 2` contacts, the point `xi`
/// projected on the cone (`projc1`) and its status code (`projc2`: 0 open, 1 sliding backward,
/// 2 stick, 3 sliding forward), where a contact sliding before (`statusi`) whose direction
/// `pi` has no tangential part stays on its side. `fric` holds the friction coefficients.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_projc(
    xi: *mut c_double,
    n: *mut c_int,
    statusi: *mut c_int,
    pi: *mut c_double,
    fric: *mut c_double,
    projc1: *mut c_double,
    projc2: *mut c_int,
) {
    ffi_guard(
        "fc2d_projc",
        |_| (),
        || {
            let nc = contacts_of(n)?;
            let xi = c_slice(xi as *const c_double, 2 * nc, "xi")?;
            let statusi = c_slice(statusi as *const c_int, nc, "statusi")?;
            let pi = c_slice(pi as *const c_double, 2 * nc, "pi")?;
            let fric = c_slice(fric as *const c_double, nc, "fric")?;
            c_slice(projc1 as *const c_double, 2 * nc, "projc1")?;
            c_slice(projc2 as *const c_int, nc, "projc2")?;
            for c in 0..nc {
                let (rc, s) = project_step(
                    [xi[2 * c], xi[2 * c + 1]],
                    pi[2 * c + 1],
                    Status::from_code(statusi[c]),
                    fric[c],
                );
                *projc1.add(2 * c) = rc[0];
                *projc1.add(2 * c + 1) = rc[1];
                *projc2.add(c) = s.code();
            }
            Ok(())
        },
    )
}

/// Siconos' CPG direction projection `fc2d_projf`: for each of the `*n / 2` contacts, `y`
/// restricted to the moves its status `etat` allows (open: only closing; sliding forward:
/// `y_T <= 0`; sliding backward: `y_T >= 0`; stick: free), written to `projf1`. `fric` is not
/// used (as in Siconos).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc2d_projf(
    etat: *mut c_int,
    n: *mut c_int,
    y: *mut c_double,
    fric: *mut c_double,
    projf1: *mut c_double,
) {
    let _ = fric;
    ffi_guard(
        "fc2d_projf",
        |_| (),
        || {
            let nc = contacts_of(n)?;
            let etat = c_slice(etat as *const c_int, nc, "etat")?;
            let y = c_slice(y as *const c_double, 2 * nc, "y")?;
            c_slice(projf1 as *const c_double, 2 * nc, "projf1")?;
            for c in 0..nc {
                let d = project_direction([y[2 * c], y[2 * c + 1]], Status::from_code(etat[c]));
                *projf1.add(2 * c) = d[0];
                *projf1.add(2 * c + 1) = d[1];
            }
            Ok(())
        },
    )
}

/// The contacts of a size `*n` (2 per contact).
unsafe fn contacts_of(n: *mut c_int) -> super::CResult<usize> {
    if n.is_null() {
        return Err(CError::null("n"));
    }
    usize::try_from(*n)
        .map(|n| n / 2)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, format!("n = {} is negative", *n)))
}
