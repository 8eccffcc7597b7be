//! The solver entries of `gfc3d_Solvers.h` and `global_rolling_fc_Solvers.h`: each runs
//! `gfc3d_driver` (`g_rolling_fc3d_driver`) for options of its id, the result in `*info`; the
//! GAMS entries refuse; `gfc3d_checkTrivialCaseGlobal`, `gfc3d_sparseGlobalAlartCurnierInit` and
//! `gfc3d_set_internalsolver_tolerance` as Siconos 4.4 defines them.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::driver::{driver_impl, rolling_driver_impl};
use crate::driver::entry_with_info;
use crate::params::{internal_solver_tolerance, set_tolerance};
use crate::solver_entries::{refuse_entry, GAMS};
use crate::types::{
    GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem, SolverOptions,
};
use crate::{ffi_guard, CError};

/// The body of the solver entries of `gfc3d_Solvers.h` (problem, reaction, velocity, global
/// velocity): `gfc3d_driver` for options whose `solverId` is `id` (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`), the result code written to `*info` (also a negative one).
unsafe fn entry(
    name: &str,
    id: c_int,
    [problem, reaction, velocity, global_velocity]: [*mut std::ffi::c_void; 4],
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry_with_info(name, &[id], info, options, || {
        driver_impl(
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            global_velocity.cast(),
            options,
        )
    });
}

/// Siconos' NSGS on the reduced problem (`SICONOS_GLOBAL_FRICTION_3D_NSGS_WR`, 600).
/// As `gfc3d_driver` for options of id 600 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_nsgs_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_nsgs_wr",
        600,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' ADMM on the reduced problem (`SICONOS_GLOBAL_FRICTION_3D_ADMM_WR`, 614).
/// As `gfc3d_driver` for options of id 614 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_admm_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_admm_wr",
        614,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' Alart-Curnier Newton on the reduced problem (`..._NSN_AC_WR`, 606).
/// As `gfc3d_driver` for options of id 606 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_nonsmooth_Newton_AlartCurnier_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_nonsmooth_Newton_AlartCurnier_wr",
        606,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' proximal point on the reduced problem (`..._PROX_WR`, 602).
/// As `gfc3d_driver` for options of id 602 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_proximal_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_proximal_wr",
        602,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' De Saxcé fixed point on the reduced problem (`..._DSFP_WR`, 603).
/// As `gfc3d_driver` for options of id 603 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_DeSaxceFixedPoint_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_DeSaxceFixedPoint_wr",
        603,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' Tresca fixed point on the reduced problem (`..._TFP_WR`, 604).
/// As `gfc3d_driver` for options of id 604 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_TrescaFixedPoint_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_TrescaFixedPoint_wr",
        604,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' NSGS on velocities of the reduced problem (`..._NSGSV_WR`, 601): the driver
/// refuses 601 with the reason.
/// As `gfc3d_driver` for options of id 601 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_nsgs_velocity_wr(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_nsgs_velocity_wr",
        601,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' projected Jacobi on the global problem (`SICONOS_GLOBAL_FRICTION_3D_NSGS`, 605).
/// As `gfc3d_driver` for options of id 605 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_nsgs(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_nsgs",
        605,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' ACLM fixed point (`SICONOS_GLOBAL_FRICTION_3D_ACLMFP`, 612).
/// As `gfc3d_driver` for options of id 612 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_ACLMFixedPoint(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_ACLMFixedPoint",
        612,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' Alart-Curnier Newton on the global problem (`..._NSN_AC`, 607).
/// As `gfc3d_driver` for options of id 607 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_nonsmooth_Newton_AlartCurnier(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_nonsmooth_Newton_AlartCurnier",
        607,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' extra-gradient VI on (v, r) (`..._VI_EG`, 611).
/// As `gfc3d_driver` for options of id 611 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_VI_ExtraGradient(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_VI_ExtraGradient",
        611,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' fixed-point projection VI on (v, r) (`..._VI_FPP`, 610).
/// As `gfc3d_driver` for options of id 610 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_VI_FixedPointProjection(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_VI_FixedPointProjection",
        610,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' ADMM on the global problem (`SICONOS_GLOBAL_FRICTION_3D_ADMM`, 613).
/// As `gfc3d_driver` for options of id 613 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_ADMM(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_ADMM",
        613,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' interior point method (`SICONOS_GLOBAL_FRICTION_3D_IPM`, 615).
/// As `gfc3d_driver` for options of id 615 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_IPM(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry(
        "gfc3d_IPM",
        615,
        [
            problem.cast(),
            reaction.cast(),
            velocity.cast(),
            globalVelocity.cast(),
        ],
        info,
        options,
    );
}

/// Siconos' GAMS entry for id 608: it needs GAMS, a commercial solver fc3d does not ship.
/// Always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_AVI_gams_path(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("gfc3d_AVI_gams_path", GAMS, info);
}

/// Siconos' GAMS entry for id 609: refused as `gfc3d_AVI_gams_path`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_AVI_gams_pathvi(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("gfc3d_AVI_gams_pathvi", GAMS, info);
}

/// Siconos' trivial-case test of the global drivers, which always returns -1 (its body is
/// commented out in Siconos 4.4): nothing is read or written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn gfc3d_checkTrivialCaseGlobal(
    n: c_int,
    q: *mut c_double,
    velocity: *mut c_double,
    reaction: *mut c_double,
    globalVelocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    let _ = (n, q, velocity, reaction, globalVelocity, options);
    -1
}

/// As `gfc3d_checkTrivialCaseGlobal`, for the global rolling driver: always -1.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn grfc3d_checkTrivialCaseGlobal(
    n: c_int,
    q: *mut c_double,
    velocity: *mut c_double,
    reaction: *mut c_double,
    globalVelocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    let _ = (n, q, velocity, reaction, globalVelocity, options);
    -1
}

/// Siconos' initialisation of its sparse global Alart-Curnier Newton, whose body is empty in
/// Siconos 4.4: does nothing.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn gfc3d_sparseGlobalAlartCurnierInit(options: *mut SolverOptions) {
    let _ = options;
}

/// Siconos' rolling NSGS on the reduced global rolling problem (5000): as
/// `g_rolling_fc3d_driver` for options of id 5000 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn grfc3d_nsgs_wr(
    problem: *mut GlobalRollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    entry_with_info("grfc3d_nsgs_wr", &[5000], info, options, || {
        rolling_driver_impl(problem, reaction, velocity, globalVelocity, options)
    });
}

/// Siconos' rule for the tolerance of the internal solver of a global fixed-point method, by
/// `options->iparam[2]`: adaptive (0): `error / dparam[2]`; adaptive per contact (2):
/// `error / (dparam[2] nc)`; given value (1): unchanged. Written to
/// `internalsolver_options->dparam[0]`. An unknown strategy, NULL or too short arrays: nothing
/// written, the reason in `fc3d_last_error_message` (Siconos exits).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_set_internalsolver_tolerance(
    problem: *mut GlobalFrictionContactProblem,
    options: *mut SolverOptions,
    internalsolver_options: *mut SolverOptions,
    error: c_double,
) {
    ffi_guard(
        "gfc3d_set_internalsolver_tolerance",
        |_| (),
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let o = options.as_ref().ok_or_else(|| CError::null("options"))?;
            let internal = internalsolver_options
                .as_mut()
                .ok_or_else(|| CError::null("internalsolver_options"))?;
            if let Some(tol) = internal_solver_tolerance(o, p.numberOfContacts, error, false)? {
                set_tolerance(internal, tol)?;
            }
            Ok(())
        },
    )
}
