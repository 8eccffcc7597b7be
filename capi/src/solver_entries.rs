//! Siconos' direct solver entries of `fc3d_Solvers.h` (`fc3d_DeSaxceFixedPoint`, `fc3d_admm`,
//! ...), `fc3d_checkTrivialCase` and `fc3d_set_internalsolver_tolerance`.
//!
//! Siconos' `fc3d_driver` dispatches on `options->solverId` to one of these; a host may also call
//! one directly with options made for its id. Here each entry runs `fc3d_driver`'s path for the
//! ids it stands for, so an entry and the driver give the same answer. The entries of what fc3d
//! does not provide (the GAMS ones, the Tresca sub-solvers) refuse with
//! `FC3D_ERR_UNSUPPORTED_SOLVER` and a message.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::driver::solver_entry;
use super::matrix::c_slice;
use super::params::internal_solver_tolerance;
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, CError, CResult, FC3D_ERR_UNSUPPORTED_SOLVER};

/// Siconos' NSGS on velocities (`SICONOS_FRICTION_3D_NSGSV`, 501).
/// As `fc3d_driver` for options of id 501 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nsgs_velocity(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_nsgs_velocity",
        &[501],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' proximal point algorithm (`SICONOS_FRICTION_3D_PROX`, 502).
/// As `fc3d_driver` for options of id 502 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_proximal(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_proximal",
        &[502],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' Tresca fixed point (`SICONOS_FRICTION_3D_TFP`, 503).
/// As `fc3d_driver` for options of id 503 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_TrescaFixedPoint(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_TrescaFixedPoint",
        &[503],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' Alart-Curnier nonsmooth Newton (`SICONOS_FRICTION_3D_NSN_AC`, 504).
/// As `fc3d_driver` for options of id 504 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nonsmooth_Newton_AlartCurnier(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_nonsmooth_Newton_AlartCurnier",
        &[504],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' De Saxcé fixed point (`SICONOS_FRICTION_3D_DSFP`, 505).
/// As `fc3d_driver` for options of id 505 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_DeSaxceFixedPoint(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_DeSaxceFixedPoint",
        &[505],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' VI fixed-point projection (`SICONOS_FRICTION_3D_VI_FPP`, 506).
/// As `fc3d_driver` for options of id 506 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_VI_FixedPointProjection(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_VI_FixedPointProjection",
        &[506],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' VI extra-gradient (`SICONOS_FRICTION_3D_VI_EG`, 507).
/// As `fc3d_driver` for options of id 507 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_VI_ExtraGradient(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_VI_ExtraGradient",
        &[507],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' hyperplane projection (`SICONOS_FRICTION_3D_HP`, 508).
/// As `fc3d_driver` for options of id 508 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_HyperplaneProjection(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_HyperplaneProjection",
        &[508],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' fixed-point projection (`SICONOS_FRICTION_3D_FPP`, 511).
/// As `fc3d_driver` for options of id 511 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_fixedPointProjection(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_fixedPointProjection",
        &[511],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' extra-gradient (`SICONOS_FRICTION_3D_EG`, 512).
/// As `fc3d_driver` for options of id 512 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_ExtraGradient(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_ExtraGradient",
        &[512],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' Fischer-Burmeister nonsmooth Newton (`SICONOS_FRICTION_3D_NSN_FB`, 513).
/// As `fc3d_driver` for options of id 513 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nonsmooth_Newton_FischerBurmeister(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_nonsmooth_Newton_FischerBurmeister",
        &[513],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' GAMS entry for id 514: it needs GAMS, a commercial solver fc3d does not ship.
/// Always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_AVI_gams_path(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_AVI_gams_path", GAMS, info);
}

/// Siconos' GAMS entry for id 515: it needs GAMS, a commercial solver fc3d does not ship.
/// Always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_AVI_gams_pathvi(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_AVI_gams_pathvi", GAMS, info);
}

/// Siconos' ACLM fixed point (`SICONOS_FRICTION_3D_ACLMFP`, 516).
/// As `fc3d_driver` for options of id 516 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_ACLMFixedPoint(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_ACLMFixedPoint",
        &[516],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' SOCLCP reformulation (`SICONOS_FRICTION_3D_SOCLCP`, 517).
/// As `fc3d_driver` for options of id 517 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_SOCLCP(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_SOCLCP",
        &[517],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' GAMS entry for id 518: it needs GAMS, a commercial solver fc3d does not ship.
/// Always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_lcp_gams_path(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_lcp_gams_path", GAMS, info);
}

/// Siconos' GAMS entry for id 519: it needs GAMS, a commercial solver fc3d does not ship.
/// Always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_lcp_gams_pathvi(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_lcp_gams_pathvi", GAMS, info);
}

/// Siconos' natural-map nonsmooth Newton (`SICONOS_FRICTION_3D_NSN_NM`, 520).
/// As `fc3d_driver` for options of id 520 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nonsmooth_Newton_NaturalMap(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_nonsmooth_Newton_NaturalMap",
        &[520],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' second Alart-Curnier Newton (`SICONOS_FRICTION_3D_NSN_AC_TEST`, 521).
/// As `fc3d_driver` for options of id 521 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_nonsmooth_Newton_AlartCurnier2(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_nonsmooth_Newton_AlartCurnier2",
        &[521],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' Panagiotopoulos fixed point (`SICONOS_FRICTION_3D_PFP`, 522).
/// As `fc3d_driver` for options of id 522 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_Panagiotopoulos_FixedPoint(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_Panagiotopoulos_FixedPoint",
        &[522],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' ADMM (`SICONOS_FRICTION_3D_ADMM`, 523).
/// As `fc3d_driver` for options of id 523 (another id is refused with
/// `FC3D_ERR_INVALID_OPTION`); the result code is written to `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_admm(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    solver_entry(
        "fc3d_admm",
        &[523],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' enumerative solver for one contact (`SICONOS_FRICTION_3D_ONECONTACT_QUARTIC`, 562,
/// and `_QUARTIC_NU`, 563) as a direct entry: as `fc3d_driver` for options of one of these ids;
/// the result code is written to `*info` and returned (Siconos returns it too).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_unitary_enumerative(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) -> c_int {
    solver_entry(
        "fc3d_unitary_enumerative",
        &[562, 563],
        problem,
        reaction,
        velocity,
        info,
        options,
    )
}

// Siconos' Tresca sub-solvers take the cylinder radii from `options->dWork` and solve a Tresca
// problem, not FC(W, q, mu): fc3d has no Tresca problem, so both entries refuse.

pub(crate) const GAMS: &str = "needs GAMS, a commercial solver fc3d does not ship";
const TRESCA: &str =
    "solves Siconos' Tresca sub-problem (radii in options->dWork), which fc3d does not provide";

/// The refusal of an entry fc3d does not provide, written to `*info`.
pub(crate) unsafe fn refuse_entry(name: &str, reason: &str, info: *mut c_int) {
    let code = ffi_guard(
        name,
        |c| c,
        || -> CResult<c_int> {
            Err(CError::new(
                FC3D_ERR_UNSUPPORTED_SOLVER,
                format!("{name} {reason}"),
            ))
        },
    );
    if !info.is_null() {
        *info = code;
    }
}

/// Siconos' Tresca sub-solver entry for id 566 (cylinder radii in `options->dWork`). Not
/// provided: always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing
/// else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_VI_FixedPointProjection_Cylinder(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_VI_FixedPointProjection_Cylinder", TRESCA, info);
}

/// Siconos' Tresca sub-solver entry for id 567 (cylinder radii in `options->dWork`). Not
/// provided: always refused with `FC3D_ERR_UNSUPPORTED_SOLVER` (written to `*info`), nothing
/// else written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_ConvexQP_ProjectedGradient_Cylinder(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let _ = (problem, reaction, velocity, options);
    refuse_entry("fc3d_ConvexQP_ProjectedGradient_Cylinder", TRESCA, info);
}

/// Siconos' take-off test: when every `q_N >= -DBL_EPSILON`, `r = 0, u = q` solves the problem:
/// writes them and returns 0; otherwise returns -1 and writes nothing. `options` is not used.
/// Invalid input returns a negative `FC3D_ERR_*` code (nothing written); as
/// `FC3D_ERR_NULL_POINTER` is -1 too, `fc3d_last_error_code` tells a refusal from "not trivial"
/// (it is `FC3D_OK` after a call that ran).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_checkTrivialCase(
    problem: *mut FrictionContactProblem,
    velocity: *mut c_double,
    reaction: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    let _ = options;
    ffi_guard(
        "fc3d_checkTrivialCase",
        |c| c,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let p = &*problem;
            if p.dimension != 3 {
                return Err(CError::new(
                    super::FC3D_ERR_INVALID_PROBLEM,
                    format!(
                        "dimension {} (fc3d_checkTrivialCase is for 3D problems)",
                        p.dimension
                    ),
                ));
            }
            if p.numberOfContacts < 0 {
                return Err(CError::new(
                    super::FC3D_ERR_INVALID_SIZE,
                    format!("numberOfContacts = {}", p.numberOfContacts),
                ));
            }
            let n = 3 * p.numberOfContacts as usize;
            let q = c_slice(p.q as *const c_double, n, "problem->q")?;
            c_slice(velocity as *const c_double, n, "velocity")?;
            c_slice(reaction as *const c_double, n, "reaction")?;
            if q.chunks_exact(3).any(|c| c[0] < -f64::EPSILON) {
                return Ok(-1);
            }
            std::ptr::copy_nonoverlapping(q.as_ptr(), velocity, n);
            std::ptr::write_bytes(reaction, 0, n);
            Ok(0)
        },
    )
}

/// Siconos' rule for the tolerance of an internal solver of a fixed-point method, by
/// `options->iparam[2]` (internal error strategy): adaptive (0):
/// `max(error / dparam[2], dparam[0] / nc)`; adaptive per contact (2): `error / (dparam[2] nc)`;
/// given value (1): unchanged. Written to `internalsolver_options->dparam[0]`. An unknown
/// strategy, NULL or too short arrays: nothing written, the reason in `fc3d_last_error_message`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_set_internalsolver_tolerance(
    problem: *mut FrictionContactProblem,
    options: *mut SolverOptions,
    internalsolver_options: *mut SolverOptions,
    error: c_double,
) {
    ffi_guard(
        "fc3d_set_internalsolver_tolerance",
        |_| (),
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if options.is_null() {
                return Err(CError::null("options"));
            }
            if internalsolver_options.is_null() {
                return Err(CError::null("internalsolver_options"));
            }
            let nc = (*problem).numberOfContacts;
            if let Some(tol) = internal_solver_tolerance(&*options, nc, error, true)? {
                super::params::set_tolerance(&mut *internalsolver_options, tol)?;
            }
            Ok(())
        },
    )
}
