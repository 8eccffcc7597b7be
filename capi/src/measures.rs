//! The error measures of Siconos' `fc3d_compute_error.h` besides `fc3d_compute_error`: the
//! per-contact accumulation, the error on velocities and the Tresca error.
//!
//! Each follows Siconos' formula, normalisation, return value (0 when `error <= tolerance`, 1
//! otherwise) and outputs (which arrays it overwrites). Invalid input: a negative `FC3D_ERR_*`
//! code (0 for the `void` ones), nothing written, the reason in `fc3d_last_error_message`.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::matrix::c_slice;
use super::problem::problem_from_c;
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, CError, CResult};
use fc3d_core::error::try_vec;
use fc3d_core::math::cone::{project_on_cone, project_on_cylinder, project_on_dual_cone};
use fc3d_core::math::linalg::{norm2, Vec3};

unsafe fn vec3(p: *const c_double, what: &str) -> CResult<Vec3> {
    if p.is_null() {
        return Err(CError::null(what));
    }
    Ok([*p, *p.add(1), *p.add(2)])
}

/// `|r - P(r - v)|^2` with the projection `project`: the per-contact term of the natural-map
/// errors; also returns `r - P(r - v)`, which Siconos leaves in its work array.
fn natural_map_term(r: &Vec3, v: &Vec3, project: impl Fn(&Vec3) -> Vec3) -> (f64, Vec3) {
    let p = project(&[r[0] - v[0], r[1] - v[1], r[2] - v[2]]);
    let d = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2], d)
}

/// Siconos' per-contact error term: adds `|r - P_K(r - (u_N + mu |u_T|, u_T))|^2` to `*error`
/// and leaves `r - P_K(...)` in `worktmp[0..3]`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_unitary_compute_and_add_error(
    r: *mut c_double,
    u: *mut c_double,
    mu: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) {
    ffi_guard(
        "fc3d_unitary_compute_and_add_error",
        |_| (),
        || {
            let (r, u) = (vec3(r, "r")?, vec3(u, "u")?);
            if error.is_null() || worktmp.is_null() {
                return Err(CError::null("error or worktmp"));
            }
            let v = [u[0] + mu * norm2(u[1], u[2]), u[1], u[2]];
            let (term, d) = natural_map_term(&r, &v, |x| project_on_cone(x, mu));
            std::ptr::copy_nonoverlapping(d.as_ptr(), worktmp, 3);
            *error += term;
            Ok(())
        },
    )
}

/// Siconos' Tresca per-contact term: adds `|z - P_C(R)(z - w)|^2` to `*error` (C(R) the cylinder
/// `{x_N >= 0, |x_T| <= R}`) and leaves `z - P_C(R)(z - w)` in `worktmp[0..3]`. (Siconos'
/// cylinder routine also pushes `x_T` out to the radius when `x_N < 0`, which is not the
/// projection; here it is the projection.)
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_Tresca_unitary_compute_and_add_error(
    z: *mut c_double,
    w: *mut c_double,
    R: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) {
    ffi_guard(
        "fc3d_Tresca_unitary_compute_and_add_error",
        |_| (),
        || {
            let (z, w) = (vec3(z, "z")?, vec3(w, "w")?);
            if error.is_null() || worktmp.is_null() {
                return Err(CError::null("error or worktmp"));
            }
            let (term, d) = natural_map_term(&z, &w, |x| project_on_cylinder(x, R));
            std::ptr::copy_nonoverlapping(d.as_ptr(), worktmp, 3);
            *error += term;
            Ok(())
        },
    )
}

/// Siconos' error on velocities: overwrites `z` with `q + M w` (as Siconos does: `w` is the
/// argument, `z` the result), then `error = sqrt(sum_c |d_c|^2) / (|q| + 1)` with
/// `d_c = w_c - (P_N - mu |P_T|, P_T)` and `P` the projection on the dual cone `K*_mu` of
/// `(w_N + mu |w_T|, w_T) - z_c`. Returns 0 when `error <= tolerance`, else 1.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_compute_error_velocity(
    problem: *mut FrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    options: *mut SolverOptions,
    error: *mut c_double,
) -> c_int {
    let _ = options;
    ffi_guard(
        "fc3d_compute_error_velocity",
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
            let wv = c_slice(w as *const c_double, n, "w")?;
            c_slice(z as *const c_double, n, "z")?;
            let mut zv = try_vec(n, 0.0, "z")?;
            p.velocity(wv, &mut zv);
            let mut sum = 0.0;
            for (c, &mu) in p.mu().iter().enumerate() {
                let (wc, zc) = (&wv[3 * c..3 * c + 3], &zv[3 * c..3 * c + 3]);
                let x = [
                    wc[0] + mu * norm2(wc[1], wc[2]) - zc[0],
                    wc[1] - zc[1],
                    wc[2] - zc[2],
                ];
                let pr = project_on_dual_cone(&x, mu);
                let d = [
                    wc[0] - (pr[0] - mu * norm2(pr[1], pr[2])),
                    wc[1] - pr[1],
                    wc[2] - pr[2],
                ];
                sum += d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            }
            let norm_q = p.q().iter().map(|v| v * v).sum::<f64>().sqrt();
            let e = sum.sqrt() / (norm_q + 1.0);
            std::ptr::copy_nonoverlapping(zv.as_ptr(), z, n);
            *error = e;
            Ok(if e > tolerance { 1 } else { 0 })
        },
    )
}

/// Siconos' Tresca error: overwrites `w` with `M z + q`, then
/// `error = sqrt(sum_c |z_c - P_C(R_c)(z_c - w_c)|^2)`, divided by `norm` when
/// `|norm| > DBL_EPSILON`, with the radii `R_c = options->dWork[c]`. Returns 0 when
/// `error <= tolerance`, else 1.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_Tresca_compute_error(
    problem: *mut FrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    options: *mut SolverOptions,
    norm: c_double,
    error: *mut c_double,
) -> c_int {
    ffi_guard(
        "fc3d_Tresca_compute_error",
        |c| c,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if options.is_null() {
                return Err(CError::null("options"));
            }
            if error.is_null() {
                return Err(CError::null("error"));
            }
            let p = problem_from_c(&*problem)?;
            let n = p.size();
            let zv = c_slice(z as *const c_double, n, "z")?;
            c_slice(w as *const c_double, n, "w")?;
            let o = &*options;
            if o.dWorkSize < p.n_contacts() {
                return Err(CError::new(
                    super::FC3D_ERR_INVALID_OPTION,
                    format!(
                        "options->dWork holds {} radii for {} contacts",
                        o.dWorkSize,
                        p.n_contacts()
                    ),
                ));
            }
            let radii = c_slice(o.dWork as *const c_double, p.n_contacts(), "options->dWork")?;
            let mut wv = try_vec(n, 0.0, "w")?;
            p.velocity(zv, &mut wv);
            let mut sum = 0.0;
            for (c, &radius) in radii.iter().enumerate() {
                let zc = [zv[3 * c], zv[3 * c + 1], zv[3 * c + 2]];
                let wc = [wv[3 * c], wv[3 * c + 1], wv[3 * c + 2]];
                sum += natural_map_term(&zc, &wc, |x| project_on_cylinder(x, radius)).0;
            }
            let mut e = sum.sqrt();
            if norm.abs() > f64::EPSILON {
                e /= norm;
            }
            std::ptr::copy_nonoverlapping(wv.as_ptr(), w, n);
            *error = e;
            Ok(if e > tolerance { 1 } else { 0 })
        },
    )
}

/// Siconos' contact statistics: with `tol`, counts the contacts that take off (`u_N > tol`;
/// "ambiguous" when also `|r_N| > tol`), the closed ones (`r_N > tol`; ambiguous when also
/// `|u_N| > tol`), and among the closed ones those sticking (`|r_T|^2 < mu^2 r_N^2`) or sliding.
/// Prints them on one line to stdout, in Siconos' words, when the verbosity
/// (`numerics_set_verbose`) is at least `do_print`; nothing else is written. Invalid input:
/// nothing printed, the reason in `fc3d_last_error_message`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContactProblem_compute_statistics(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    tol: c_double,
    do_print: c_int,
) {
    ffi_guard(
        "frictionContactProblem_compute_statistics",
        |_| (),
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let nc = usize::try_from((*problem).numberOfContacts).map_err(|_| {
                CError::new(
                    super::FC3D_ERR_INVALID_SIZE,
                    format!("numberOfContacts = {}", (*problem).numberOfContacts),
                )
            })?;
            let n = nc.checked_mul(3).ok_or_else(|| {
                CError::new(super::FC3D_ERR_INVALID_SIZE, "3 numberOfContacts overflows")
            })?;
            let mu = c_slice((*problem).mu as *const c_double, nc, "problem->mu")?;
            let r = c_slice(reaction as *const c_double, n, "reaction")?;
            let u = c_slice(velocity as *const c_double, n, "velocity")?;
            let (mut take_off, mut closed, mut sticking, mut sliding) = (0, 0, 0, 0);
            let (mut ambiguous_take_off, mut ambiguous_closed) = (0, 0);
            for c in 0..nc {
                let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
                if uc[0] > tol {
                    take_off += 1;
                    if rc[0].abs() > tol {
                        ambiguous_take_off += 1;
                    }
                } else if rc[0] > tol {
                    closed += 1;
                    if uc[0].abs() > tol {
                        ambiguous_closed += 1;
                    }
                    if rc[1] * rc[1] + rc[2] * rc[2] - mu[c] * mu[c] * rc[0] * rc[0] < 0.0 {
                        sticking += 1;
                    } else {
                        sliding += 1;
                    }
                }
            }
            if super::verbose() >= do_print {
                println!(
                    "[Numerics] ---- FC3D - STAT  - Number of contact = {nc}\t,  take off = {take_off}\t, closed = {closed}\t, sliding = {sliding}\t,sticking = {sticking}\t, ambiguous take off = {ambiguous_take_off}\t, ambiguous closed = {ambiguous_closed}"
                );
            }
            Ok(())
        },
    )
}
