//! `gfc3d_driver`, `g_rolling_fc3d_driver` and `gfc3d_LmgcDriver` (the solver entries of
//! `gfc3d_Solvers.h` / `global_rolling_fc_Solvers.h`, which run them, are in `entries`).
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
use crate::matrix::c_slice;
use crate::option_tree::delete_contents;
use crate::options::create_options;
use crate::params::global::{
    global_config_from_c, global_rolling_config_from_c, lmgc_overrides, write_global_outputs,
};
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

pub(super) unsafe fn driver_impl(
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
/// meets `dparam[0]`; 605 (projected Jacobi), 607 (Newton on (v, u, r)), 610 / 611 (VI on
/// (v, r)), 612 (ACLMFP), 613 (ADMM) and 615 (IPM) solve it directly (docs/global.md: their
/// slots); 601 (Siconos exits) and 608 / 609 (GAMS) are refused with
/// `FC3D_ERR_UNSUPPORTED_SOLVER` and the reason (never an exit). Returns 0 when the global error of the returned `(r, u, v)` is at most `dparam[0]`, 1
/// when the solver stopped above it, 2 when the time budget `dparam[FC3D_DPARAM_TIME_BUDGET]` ran
/// out, 3 (`FC3D_RELAXED_NOT_COULOMB`) when a solver of the convex relaxation (613 or 615 with
/// UPDATE_S = NO) solved it but its result is not a Coulomb solution, a negative code when the input is rejected (nothing written). On return >= 0:
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

pub(super) unsafe fn rolling_driver_impl(
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
