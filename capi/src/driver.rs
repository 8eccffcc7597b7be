//! `fc3d_driver`, `fc3d_nsgs` and `fc3d_compute_error`.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int};

use super::matrix::c_slice;
use super::params::{
    config_from_c, planar_config_from_c, write_outputs, DPARAM_DUMONT_CRITERION, DPARAM_RESIDU,
    IPARAM_ITER_DONE,
};
use super::problem::{planar_problem_from_c, problem_view_from_c};
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_OPTION};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::measure::relative_natural_map_error;
use fc3d_core::problem::FrictionProblem;
use fc3d_core::{
    solve_planar_with_observer, solve_with_observer, Fc3dError, IterationEvent, Observer,
    SolveReport, SolverConfig,
};

/// What `fc3d_driver` read from the options and writes back into, to detect a callback that
/// freed or changed them during the solve (`solver_options_delete` in a callback, a new array, a
/// new value in a slot). The output slots (`iparam[1]`, `dparam[1]`, `dparam[18]`) may change:
/// a callback may run another solve with the same options.
struct OptionsSeal {
    solver_id: c_int,
    sizes: (c_int, c_int),
    arrays: (*mut c_int, *mut c_double),
    internal: (usize, *mut *mut SolverOptions),
    /// The internal solver pointers (at most `FC3D_OPTIONS_MAX_INTERNAL_SOLVERS`: the tree was
    /// checked).
    slots: Vec<*mut SolverOptions>,
    iparam: [c_int; SIZE],
    dparam: [u64; SIZE],
}

const SIZE: usize = crate::OPTIONS_PARAM_SIZE as usize;

/// The internal solver pointers of options whose tree `config_from_c` checked (none when the
/// count is above the limit or the array is gone: a change the seal sees anyway).
unsafe fn internal_slots(o: &SolverOptions) -> Vec<*mut SolverOptions> {
    let n = o.numberOfInternalSolvers;
    if n == 0
        || n > crate::option_tree::FC3D_OPTIONS_MAX_INTERNAL_SOLVERS as usize
        || o.internalSolvers.is_null()
    {
        return Vec::new();
    }
    std::slice::from_raw_parts(o.internalSolvers, n).to_vec()
}

impl OptionsSeal {
    /// The seal of options `config_from_c` accepted (arrays of at least `SIZE` slots).
    unsafe fn of(o: &SolverOptions) -> Self {
        let mut seal = OptionsSeal {
            solver_id: o.solverId,
            sizes: (o.iSize, o.dSize),
            arrays: (o.iparam, o.dparam),
            internal: (o.numberOfInternalSolvers, o.internalSolvers),
            slots: internal_slots(o),
            iparam: [0; SIZE],
            dparam: [0; SIZE],
        };
        for k in 0..SIZE {
            seal.iparam[k] = *o.iparam.add(k);
            seal.dparam[k] = (*o.dparam.add(k)).to_bits();
        }
        seal
    }

    /// What changed, if anything.
    unsafe fn changed(&self, o: &SolverOptions) -> Option<String> {
        if o.solverId != self.solver_id {
            return Some(format!("solverId {} -> {}", self.solver_id, o.solverId));
        }
        if (o.iSize, o.dSize) != self.sizes || (o.iparam, o.dparam) != self.arrays {
            return Some("iparam, dparam, iSize or dSize replaced or released".into());
        }
        if (o.numberOfInternalSolvers, o.internalSolvers) != self.internal
            || internal_slots(o) != self.slots
        {
            return Some("internal solvers replaced or released".into());
        }
        for k in (0..SIZE).filter(|&k| k != IPARAM_ITER_DONE) {
            if *o.iparam.add(k) != self.iparam[k] {
                return Some(format!(
                    "iparam[{k}] {} -> {}",
                    self.iparam[k],
                    *o.iparam.add(k)
                ));
            }
        }
        for k in (0..SIZE).filter(|&k| k != DPARAM_RESIDU && k != DPARAM_DUMONT_CRITERION) {
            let now = *o.dparam.add(k);
            if now.to_bits() != self.dparam[k] {
                return Some(format!(
                    "dparam[{k}] {} -> {now}",
                    f64::from_bits(self.dparam[k])
                ));
            }
        }
        None
    }
}

/// `fc3d_driver` (`in_place` false) and `fc3d_driver_in_place`.
unsafe fn driver_impl(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
    in_place: bool,
) -> CResult<c_int> {
    if problem.is_null() {
        return Err(CError::null("problem"));
    }
    if options.is_null() {
        return Err(CError::null("options"));
    }
    let config = config_from_c(&*options)?;
    // The host's sparse-block W is read in place: no copy (the solve checks its values).
    let p = problem_view_from_c(&*problem)?;
    // In the host's arrays only when nothing can fail once they are touched.
    let in_place =
        in_place && config.method.fails_only_before_start() && (*options).callback.is_null();
    let report = if in_place {
        solve_in_host_arrays(&p, &config, reaction, velocity, options)?
    } else {
        solve_into_host(&p, reaction, velocity, options, |r, u, observer| {
            solve_with_observer(&p, &config, r, u, observer)
        })?
    };
    if verbose() > 0 {
        eprintln!(
            "fc3d: {}{} on {} contacts: {:?} after {} iterations, error {:e} (tolerance {:e})",
            config.label(),
            if in_place { " in place" } else { "" },
            p.n_contacts(),
            report.status,
            report.iterations,
            report.error,
            config.tolerance
        );
        print_fill(&report);
        eprint!("{}", auto_stage_lines(&report));
    }
    Ok(report.status.info_code())
}

/// The verbose line of a factorizing solver's fill (`SolveReport::fill`).
pub(crate) fn print_fill(report: &SolveReport) {
    if let Some(f) = report.fill {
        eprintln!(
            "fc3d: sparse LU fill: nnz(A) {}, nnz(L)+nnz(U) {} ({:.2}x)",
            f.matrix_nnz,
            f.factor_nnz,
            f.ratio()
        );
    }
}

/// The verbose lines (each ending with a newline) of the stages AUTO took, empty for another
/// solver: `fc3d_driver` and `fc3d_workspace_driver` print them alike.
pub(crate) fn auto_stage_lines(report: &fc3d_core::SolveReport) -> String {
    let mut lines = String::new();
    if let Some(log) = &report.stages {
        for (k, s) in log.stages().enumerate() {
            lines.push_str(&format!(
                "fc3d: AUTO stage {}: {} {} iterations, error {:e}, {}\n",
                k + 1,
                s.kind.name(),
                s.iterations,
                s.error,
                s.end.name()
            ));
        }
    }
    lines
}

/// `fc2d_driver`'s work: the 2D problem and options read, solved, written back.
pub(crate) unsafe fn planar_driver_impl(
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
    let config = planar_config_from_c(&*options)?;
    let p = planar_problem_from_c(&*problem)?;
    let report = solve_into_host(&p, reaction, velocity, options, |r, u, observer| {
        solve_planar_with_observer(&p, &config, r, u, observer)
    })?;
    if verbose() > 0 {
        eprintln!(
            "fc3d: 2D solver {} on {} contacts: {:?} after {} iterations, error {:e} (tolerance {:e})",
            config.method.siconos_id(),
            p.n_contacts(),
            report.status,
            report.iterations,
            report.error,
            config.tolerance
        );
    }
    Ok(report.status.info_code())
}

/// Runs `solve` on copies of the host's `reaction` (initial guess) and `velocity`, calling the
/// host's callback after each iteration, and writes the result and the outputs (`iparam[1]`,
/// `dparam[1]`) only on success. A callback must not free or change the options (nor the
/// problem) during the solve: the options are checked after each call, the callback is not
/// called again once they changed, and the solve is then refused (nothing written).
pub(crate) unsafe fn solve_into_host<const D: usize>(
    p: &FrictionProblem<'_, D>,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
    solve: impl FnOnce(&mut [f64], &mut [f64], &mut Observer<'_>) -> Result<SolveReport, Fc3dError>,
) -> CResult<SolveReport> {
    let n = p.size();
    let r_in = c_slice(reaction as *const c_double, n, "reaction")?;
    c_slice(velocity as *const c_double, n, "velocity")?;

    // Work on copies: the host's arrays are written only on success.
    let mut r = try_copy(r_in, "the reaction")?;
    let mut u = try_vec(n, 0.0, "the velocity")?;
    let callback = (*options).callback;
    // What the callback is handed, allocated before the solve when there is one.
    let with_callback = !callback.is_null() && (*callback).collectStatsIteration.is_some();
    let scratch_len = if with_callback { n } else { 0 };
    let mut scratch_r = try_vec(scratch_len, 0.0, "the reaction handed to the callback")?;
    let mut scratch_u = try_vec(scratch_len, 0.0, "the velocity handed to the callback")?;
    let seal = OptionsSeal::of(&*options);
    let mut tampered: Option<String> = None;
    let mut observer = |ev: &IterationEvent<'_>| {
        if callback.is_null() || tampered.is_some() {
            return;
        }
        let cb = &*callback;
        // (A host that sets the function during the solve is not called: nothing was allocated.)
        if let (Some(f), true) = (cb.collectStatsIteration, scratch_r.len() == n) {
            scratch_r.copy_from_slice(ev.reaction);
            p.velocity(ev.reaction, &mut scratch_u);
            f(
                cb.env,
                n as c_int,
                scratch_r.as_mut_ptr(),
                scratch_u.as_mut_ptr(),
                ev.error,
                std::ptr::null_mut(),
            );
            tampered = seal.changed(&*options);
        }
    };
    let report = solve(&mut r, &mut u, &mut observer)?;
    if let Some(what) = tampered.or_else(|| seal.changed(&*options)) {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("the options changed during the solve ({what}): a callback must not free or modify the options; nothing was written"),
        ));
    }

    std::ptr::copy_nonoverlapping(r.as_ptr(), reaction, n);
    std::ptr::copy_nonoverlapping(u.as_ptr(), velocity, n);
    write_outputs(&mut *options, &report);
    Ok(report)
}

/// Solves the problem with the solver `options->solverId`, starting from `reaction`.
/// Returns 0 when converged (error <= dparam[0]), 1 when the solver stopped above the
/// tolerance at its iteration limit (reaction, velocity hold its last iterate), 2
/// (`FC3D_TIME_BUDGET_EXHAUSTED`) when the time budget `dparam[FC3D_DPARAM_TIME_BUDGET]` ran out
/// (they hold the best iterate measured), a negative `FC3D_ERR_*` code when the
/// input is rejected (nothing is written). On return >= 0, `iparam[1]` holds the iterations
/// and `dparam[1]` the error measured on the returned `(reaction, velocity)`; for VI_FPP (506)
/// and VI_EG (507) with a self-adaptive rho, `dparam[3]` holds `-rho` for the rho the run ended
/// with, as Siconos' VI solvers leave it (a host reusing the options starts from it).
/// The options tree is checked first: a cycle of internal solvers, or a chain deeper than
/// `FC3D_OPTIONS_MAX_DEPTH`, is refused with `FC3D_ERR_INVALID_OPTION`. `options->callback`
/// must not free or modify the options (nor the problem or the arrays) during the solve: a
/// change to the options struct or its slots is detected after each call, and the solve is then
/// refused with `FC3D_ERR_INVALID_OPTION` (nothing written; the callback is not called again).
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
        || driver_impl(problem, reaction, velocity, options, false),
    )
}

/// As `fc3d_driver`, solving in the host's `reaction` and `velocity` arrays instead of copies
/// of them: a call holds 48 bytes a contact less (the peak memory of a solve at 10^5 contacts
/// and more). Nothing is written on failure still: before touching the arrays, W is checked for
/// NaN and infinite entries (one pass over W's values, which `fc3d_driver` does not make: about
/// half a sweep's memory traffic on a sparse-block W, shared by the threads of a coloured or
/// islands NSGS), and only a solver whose run can fail solely before
/// it starts solves in place (NSGS, id 500, any decomposition). With another solver, or with
/// `options->callback` set (a callback that changed the options would make the call fail after
/// the solve), the call is `fc3d_driver`'s, copies included. `reaction` and `velocity` must not
/// overlap each other, `q` or `mu` (refused with `FC3D_ERR_INVALID_STORAGE`), nor W's blocks.
/// Returns what `fc3d_driver` returns.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_driver_in_place(
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "fc3d_driver_in_place",
        |c| c,
        || driver_impl(problem, reaction, velocity, options, true),
    )
}

/// Solves with `config` in the host's `reaction` (initial guess) and `velocity` arrays, after
/// the checks that leave nothing to fail once they are touched: the arrays do not overlap each
/// other, q or mu, and W holds no NaN or infinity. The outputs (`iparam[1]`, `dparam[1]`) are written on
/// success.
unsafe fn solve_in_host_arrays(
    p: &FrictionProblem<'_>,
    config: &SolverConfig,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> CResult<SolveReport> {
    let n = p.size();
    c_slice(reaction as *const c_double, n, "reaction")?;
    c_slice(velocity as *const c_double, n, "velocity")?;
    let arrays = [
        ("reaction", reaction as *const c_double, n),
        ("velocity", velocity as *const c_double, n),
        ("q", p.q().as_ptr(), n),
        ("mu", p.mu().as_ptr(), p.n_contacts()),
    ];
    for (i, a) in arrays.iter().enumerate().take(2) {
        for b in &arrays[i + 1..] {
            if overlap(a, b) {
                return Err(CError::new(
                    crate::FC3D_ERR_INVALID_STORAGE,
                    format!("fc3d_driver_in_place: {} overlaps {}", a.0, b.0),
                ));
            }
        }
    }
    // The one failure a run could otherwise find after it started.
    fc3d_core::check_w_before_solving_in_place(p, config)?;
    let report = fc3d_core::solve(
        p,
        config,
        std::slice::from_raw_parts_mut(reaction, n),
        std::slice::from_raw_parts_mut(velocity, n),
    )?;
    write_outputs(&mut *options, &report);
    Ok(report)
}

/// Whether two arrays `(name, start, length)` of doubles share memory.
fn overlap(a: &(&str, *const c_double, usize), b: &(&str, *const c_double, usize)) -> bool {
    let range = |(_, p, len): &(&str, *const c_double, usize)| {
        let start = *p as usize;
        start..start + len * std::mem::size_of::<c_double>()
    };
    let (x, y) = (range(a), range(b));
    !x.is_empty() && !y.is_empty() && x.start < y.end && y.start < x.end
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
    solver_entry(
        "fc3d_nsgs",
        &[500],
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// The body of Siconos' direct solver entries (`fc3d_nsgs`, `fc3d_DeSaxceFixedPoint`, ...):
/// `fc3d_driver` for options whose `solverId` is one of `accepted` (any other id is refused
/// with `FC3D_ERR_INVALID_OPTION`: Siconos would run the entry's algorithm on parameters laid
/// out for another solver), the result code written to `*info` (also a negative code) and
/// returned.
pub(crate) unsafe fn solver_entry(
    name: &str,
    accepted: &[c_int],
    problem: *mut FrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) -> c_int {
    entry_with_info(name, accepted, info, options, || {
        driver_impl(problem, reaction, velocity, options, false)
    })
}

/// The frame of the solver entries of every problem kind: `run` (a driver's work) for options
/// whose `solverId` is one of `accepted` (another id is refused with `FC3D_ERR_INVALID_OPTION`),
/// inside `ffi_guard`; the result code, also a negative one, written to `*info` (NULL refused)
/// and returned.
pub(crate) unsafe fn entry_with_info(
    name: &str,
    accepted: &[c_int],
    info: *mut c_int,
    options: *const SolverOptions,
    run: impl FnOnce() -> CResult<c_int>,
) -> c_int {
    let code = ffi_guard(
        name,
        |c| c,
        || {
            if info.is_null() {
                return Err(CError::null("info"));
            }
            if !options.is_null() && !accepted.contains(&(*options).solverId) {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "{name} called with options for solver {} (it runs solver {})",
                        (*options).solverId,
                        accepted
                            .iter()
                            .map(|id| id.to_string())
                            .collect::<Vec<_>>()
                            .join(" or ")
                    ),
                ));
            }
            run()
        },
    );
    if !info.is_null() {
        *info = code;
    }
    code
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
            let p = problem_view_from_c(&*problem)?;
            let n = p.size();
            let r = c_slice(z as *const c_double, n, "z")?;
            c_slice(w as *const c_double, n, "w")?;
            fc3d_core::error::check_finite("z", r)?;
            let mut u = try_vec(n, 0.0, "w")?;
            p.velocity(r, &mut u);
            let e = relative_natural_map_error(r, &u, p.mu(), norm.abs());
            // A non-finite value of W shows in the error (NaN * 0 is NaN): refused only then,
            // so that W is read once.
            if !e.is_finite() {
                p.w().check_finite()?;
            }
            std::ptr::copy_nonoverlapping(u.as_ptr(), w, n);
            *error = e;
            Ok(if e <= tolerance { 0 } else { 1 })
        },
    )
}
