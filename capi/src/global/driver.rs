//! `gfc3d_driver`, `g_rolling_fc3d_driver`, `gfc3d_LmgcDriver` and the solver entries of
//! `gfc3d_Solvers.h` / `global_rolling_fc_Solvers.h`.
//!
//! Every solve runs on copies of the host's `reaction` (the initial guess), `velocity` and
//! `globalVelocity`, written back only on success, with `iparam[1]` (iterations) and
//! `dparam[1]`: the global error (Siconos' `gfc3d_compute_error`) of the returned
//! `(r, u, v)`, measured on the host's M and H, which are never modified. On return `v` solves
//! `M v = q + H r` to round-off and `u = H^T v + b`. Nothing is printed unless
//! `numerics_set_verbose(>0)`.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int, c_uint};

use super::{global_from_c, global_rolling_from_c, GlobalView};
use crate::alloc::c_free;
use crate::driver::entry_with_info;
use crate::matrix::c_slice;
use crate::option_tree::delete_contents;
use crate::options::create_options;
use crate::params::global::{
    global_config_from_c, global_rolling_config_from_c, lmgc_overrides, write_global_outputs,
};
use crate::params::{internal_solver_tolerance, set_tolerance};
use crate::solver_entries::{refuse_entry, GAMS};
use crate::types::{
    GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem, SolverOptions,
};
use crate::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::global::{solve_global, solve_global_rolling, GlobalReport};
use fc3d_core::matrix::CsrMatrix;
use fc3d_core::problem::GlobalProblem;
use fc3d_core::Fc3dError;

/// Runs `solve` on copies of the host's arrays (`reaction` of `size` values is the initial
/// guess) and writes them back, with the outputs, only on success.
unsafe fn solve_into_host(
    size: usize,
    ndof: usize,
    reaction: *mut c_double,
    velocity: *mut c_double,
    global_velocity: *mut c_double,
    options: *mut SolverOptions,
    solve: impl FnOnce(&mut [f64], &mut [f64], &mut [f64]) -> Result<GlobalReport, Fc3dError>,
) -> CResult<GlobalReport> {
    let r_in = c_slice(reaction as *const c_double, size, "reaction")?;
    c_slice(velocity as *const c_double, size, "velocity")?;
    c_slice(global_velocity as *const c_double, ndof, "globalVelocity")?;
    let mut r = r_in.to_vec();
    let (mut u, mut v) = (vec![0.0; size], vec![0.0; ndof]);
    let report = solve(&mut r, &mut u, &mut v)?;
    std::ptr::copy_nonoverlapping(r.as_ptr(), reaction, size);
    std::ptr::copy_nonoverlapping(u.as_ptr(), velocity, size);
    std::ptr::copy_nonoverlapping(v.as_ptr(), global_velocity, ndof);
    write_global_outputs(&mut *options, &report);
    Ok(report)
}

fn print_report(what: &str, nc: usize, report: &GlobalReport, tolerance: f64) {
    eprintln!(
        "fc3d: {what} on {nc} contacts: {:?} after {} iterations, global error {:e} \
         (tolerance {tolerance:e})",
        report.status, report.iterations, report.error
    );
}

/// `gfc3d_driver`'s work on a core global problem.
unsafe fn solve_global_problem(
    view: &GlobalView<GlobalProblem<'_, 3>>,
    reaction: *mut c_double,
    velocity: *mut c_double,
    global_velocity: *mut c_double,
    options: *mut SolverOptions,
) -> CResult<c_int> {
    let config = global_config_from_c(&*options)?;
    let p = &view.problem;
    let report = solve_into_host(
        p.size(),
        p.ndof(),
        reaction,
        velocity,
        global_velocity,
        options,
        |r, u, v| solve_global(p, &config, r, u, v),
    )?;
    if verbose() > 0 {
        let what = format!("gfc3d_driver {}", config.method.label());
        print_report(&what, p.n_contacts(), &report, config.tolerance);
    }
    Ok(report.status.info_code())
}

unsafe fn driver_impl(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    global_velocity: *mut c_double,
    options: *mut SolverOptions,
) -> CResult<c_int> {
    let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
    if options.is_null() {
        return Err(CError::null("options"));
    }
    // The options first: an id fc3d refuses costs no conversion of M and H.
    global_config_from_c(&*options)?;
    let view = global_from_c::<3>(p)?;
    solve_global_problem(&view, reaction, velocity, global_velocity, options)
}

/// Solves the global problem (`problem->dimension` = 3) with the solver `options->solverId`
/// from the initial reaction in `reaction`: the `_WR` ids 600 (NSGS), 602 (PROX), 603 (DSFP),
/// 604 (TFP), 606 (NSN-AC) and 614 (ADMM) reduce it to the local problem
/// FC(H^T M^-1 H, H^T M^-1 q + b, mu) (M factored once, block by block when it is block
/// diagonal, never inverted densely nor modified) and run their local solver with the options
/// read as that solver's (600 as 500, ...), tightening its tolerance until the global error
/// meets `dparam[0]`; 601 (Siconos exits), 608 / 609 (GAMS) and the direct solvers not
/// implemented yet are refused with `FC3D_ERR_UNSUPPORTED_SOLVER` and the reason (never an
/// exit). Returns 0 when the global error of the returned `(r, u, v)` is at most `dparam[0]`, 1
/// when the solver stopped above it, 2 when the time budget `dparam[FC3D_DPARAM_TIME_BUDGET]` ran
/// out, a negative code when the input is rejected (nothing written). On return >= 0:
/// `reaction`, `velocity` = `H^T v + b` and `globalVelocity` = `M^-1 (q + H r)` hold the result,
/// `iparam[1]` the iterations (of the local solves, all rounds) and `dparam[1]` the global error
/// (`gfc3d_compute_error` with `norm_q = ||q||`) of the returned triple on the host's M and H. A
/// problem without contacts gets `v = M^-1 q`. `options->callback` is not called.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_driver(
    problem: *mut GlobalFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "gfc3d_driver",
        |c| c,
        || driver_impl(problem, reaction, velocity, globalVelocity, options),
    )
}

/// Solves the global rolling problem (`problem->dimension` = 5) with the solver 5000: the
/// reduction to the local rolling problem (as `gfc3d_driver`'s `_WR` ids) solved by the rolling
/// NSGS with the options read as those of 3000 and its internal solver. Any other id is refused
/// with `FC3D_ERR_UNSUPPORTED_SOLVER`. Returns and writes as `gfc3d_driver`; `dparam[1]` is the
/// global error with the rolling law.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn g_rolling_fc3d_driver(
    problem: *mut GlobalRollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "g_rolling_fc3d_driver",
        |c| c,
        || rolling_driver_impl(problem, reaction, velocity, globalVelocity, options),
    )
}

unsafe fn rolling_driver_impl(
    problem: *mut GlobalRollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    global_velocity: *mut c_double,
    options: *mut SolverOptions,
) -> CResult<c_int> {
    let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
    if options.is_null() {
        return Err(CError::null("options"));
    }
    let config = global_rolling_config_from_c(&*options)?;
    let view = global_rolling_from_c(p)?;
    let base = view.problem.base();
    let report = solve_into_host(
        base.size(),
        base.ndof(),
        reaction,
        velocity,
        global_velocity,
        options,
        |r, u, v| solve_global_rolling(&view.problem, &config, r, u, v),
    )?;
    if verbose() > 0 {
        print_report(
            "g_rolling_fc3d_driver",
            base.n_contacts(),
            &report,
            config.tolerance,
        );
    }
    Ok(report.status.info_code())
}

/// A 1-based coordinate matrix (`nz` entries at `row[k]`, `col[k]` in `1..=rows`, `1..=cols`)
/// as compressed rows; duplicates are summed.
unsafe fn coordinates(
    name: &str,
    data: *mut c_double,
    nz: c_uint,
    row: *mut c_uint,
    col: *mut c_uint,
    rows: usize,
    cols: usize,
) -> CResult<CsrMatrix> {
    let nz = nz as usize;
    let x = c_slice(data as *const c_double, nz, &format!("{name}data"))?;
    let r = c_slice(row as *const c_uint, nz, &format!("row{name}"))?;
    let c = c_slice(col as *const c_uint, nz, &format!("col{name}"))?;
    let mut triplets = Vec::new();
    triplets.try_reserve_exact(nz).map_err(|_| {
        CError::from(Fc3dError::OutOfMemory {
            what: format!("the entries of {name}"),
            bytes: nz.saturating_mul(24),
        })
    })?;
    for k in 0..nz {
        let (i, j) = (r[k] as usize, c[k] as usize);
        if i == 0 || i > rows || j == 0 || j > cols {
            return Err(CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!("{name} entry {k} at 1-based ({i}, {j}) is outside a {rows}x{cols} matrix"),
            ));
        }
        if !x[k].is_finite() {
            return Err(Fc3dError::NonFinite {
                what: format!("{name}data"),
                index: k,
            }
            .into());
        }
        triplets.push((i - 1, j - 1, x[k]));
    }
    Ok(CsrMatrix::from_triplets(rows, cols, &triplets)?)
}

/// LMGC90's global entry: M (`n x n`, `nzM` entries) and H (`n x 3 nc`, `nzH` entries) in
/// 1-based coordinates (row, column, value), q (n), b (3 nc) and mu (nc); the solver
/// `solver_id` with Siconos' defaults, over which every non-zero `iparam[i]` (`i < isize`) and
/// `dparam[i]` (`i < dsize`) is put (at most 20 of each), as Siconos does. Solves as
/// `gfc3d_driver` into `reaction`, `velocity` and `globalVelocity` (the initial reaction is
/// `reaction`); then `iparam[1]` holds the iterations (when `isize > 1`), `dparam[0]` the
/// tolerance used (as Siconos) and `dparam[1]` the global error of the result (when
/// `dsize > 1`). `verbose`, `outputFile` and `freq_output` are accepted and ignored (no file
/// output). The host's arrays are read, never modified but for the outputs. Returns as
/// `gfc3d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn gfc3d_LmgcDriver(
    reaction: *mut c_double,
    velocity: *mut c_double,
    globalVelocity: *mut c_double,
    q: *mut c_double,
    b: *mut c_double,
    mu: *mut c_double,
    Mdata: *mut c_double,
    nzM: c_uint,
    rowM: *mut c_uint,
    colM: *mut c_uint,
    Hdata: *mut c_double,
    nzH: c_uint,
    rowH: *mut c_uint,
    colH: *mut c_uint,
    n: c_uint,
    nc: c_uint,
    solver_id: c_int,
    isize: c_int,
    iparam: *mut c_int,
    dsize: c_int,
    dparam: *mut c_double,
    verbose: c_int,
    outputFile: c_int,
    freq_output: c_int,
) -> c_int {
    let _ = (verbose, outputFile, freq_output);
    ffi_guard(
        "gfc3d_LmgcDriver",
        |c| c,
        || {
            let (ndof, nc) = (n as usize, nc as usize);
            let size = nc
                .checked_mul(3)
                .filter(|&s| c_int::try_from(s).is_ok() && c_int::try_from(ndof).is_ok())
                .ok_or_else(|| {
                    CError::new(
                        FC3D_ERR_INVALID_SIZE,
                        format!("n = {n}, nc = {nc}: too large"),
                    )
                })?;
            let isize = usize::try_from(isize).unwrap_or(0);
            let dsize = usize::try_from(dsize).unwrap_or(0);
            let ip = c_slice(iparam as *const c_int, isize, "iparam")?;
            let dp = c_slice(dparam as *const c_double, dsize, "dparam")?;
            let qv = c_slice(q as *const c_double, ndof, "q")?;
            let bv = c_slice(b as *const c_double, size, "b")?;
            let muv = c_slice(mu as *const c_double, nc, "mu")?;
            let m = coordinates("M", Mdata, nzM, rowM, colM, ndof, ndof)?;
            let h = coordinates("H", Hdata, nzH, rowH, colH, ndof, size)?;
            let problem = GlobalProblem::<3>::new(m, h, qv, bv, muv)?;
            let view = GlobalView {
                problem,
                storage: Default::default(),
            };
            let options = create_options(solver_id)?;
            let o = &mut *options;
            lmgc_overrides(o, ip, dp);
            let result = solve_global_problem(&view, reaction, velocity, globalVelocity, options);
            if result.is_ok() {
                if isize > 1 {
                    *iparam.add(1) = *o.iparam.add(1);
                }
                if dsize > 0 {
                    *dparam = *o.dparam;
                }
                if dsize > 1 {
                    *dparam.add(1) = *o.dparam.add(1);
                }
            }
            delete_contents(options);
            c_free(options);
            result
        },
    )
}

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
