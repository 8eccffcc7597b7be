//! Siconos' rolling-friction functions (`RollingFrictionContactProblem.h`,
//! `rolling_fc_Solvers.h`, `rolling_fc3d_compute_error.h`, `rolling_fc2d_compute_error.h`,
//! `rolling_fc3d_driver` and `rolling_fc2d_driver`): the struct's life cycle and files, the error
//! functions on the host's arrays, and the drivers, which run the core's rolling NSGS.
//!
//! Ownership (as in Siconos): `rollingFrictionContactProblem_new_with_data` keeps the given
//! pointers (no copy); `rollingFrictionContactProblem_free` releases `M` (its storage and the
//! struct), `q`, `mu`, `mu_r` and the problem struct. Problems read from files are allocated
//! the same way.

#![allow(non_snake_case)]

use std::ffi::c_char;
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_box, c_copy, c_free};
use super::driver::solve_into_host;
use super::host_problem::{self, release_array, release_matrix, HostProblem};
use super::matrix::{c_slice, matrix_to_c, nm_clear_impl};
use super::params::rolling_config_from_c;
use super::problem::parts_from_c;
use super::types::{RollingFrictionContactProblem, SolverOptions};
use super::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::{try_copy, try_vec, Fc3dError};
use fc3d_core::io::dat::{read_rolling_dat, RollingDatProblem};
use fc3d_core::math::rolling::{project_on_rolling_cone, rolling_modified_velocity};
use fc3d_core::measure::relative_rolling_error;
use fc3d_core::problem::RollingProblem;
use fc3d_core::solve_rolling_with_observer;

/// The core view of a C rolling problem of dimension `D` (5 or 3); dense W, q, mu and mu_r are
/// borrowed, not copied.
pub(crate) unsafe fn rolling_problem_from_c<'a, const D: usize>(
    p: &'a RollingFrictionContactProblem,
) -> CResult<RollingProblem<'a, D>> {
    if usize::try_from(p.dimension) != Ok(D) {
        let hint = match (p.dimension, D) {
            (3, 5) => " (a 2D rolling problem: solve it with rolling_fc2d_driver)",
            (5, 3) => " (a 3D rolling problem: solve it with rolling_fc3d_driver)",
            _ => "",
        };
        return Err(CError::new(
            FC3D_ERR_INVALID_PROBLEM,
            format!(
                "rolling problem of dimension {} where {D} is needed{hint}",
                p.dimension
            ),
        ));
    }
    let (w, q, mu) = parts_from_c::<D>(p.numberOfContacts, p.M, p.q, p.mu)?;
    let mu_r = c_slice(p.mu_r as *const c_double, mu.len(), "problem->mu_r")?;
    Ok(RollingProblem::<D>::new(w, q, mu, mu_r)?)
}

/// A rolling problem of the dimension it declares (5 or 3).
pub(crate) enum AnyRolling<'a> {
    Spatial(RollingProblem<'a, 5>),
    Planar(RollingProblem<'a, 3>),
}

unsafe fn any_rolling_from_c(p: &RollingFrictionContactProblem) -> CResult<AnyRolling<'_>> {
    if p.dimension == 3 {
        rolling_problem_from_c::<3>(p).map(AnyRolling::Planar)
    } else {
        rolling_problem_from_c::<5>(p).map(AnyRolling::Spatial)
    }
}

/// A C-allocated rolling problem holding a copy of `p`.
pub(crate) fn rolling_to_c<const D: usize>(
    p: &RollingProblem<'_, D>,
) -> CResult<*mut RollingFrictionContactProblem> {
    let nc = c_int::try_from(p.n_contacts())
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many contacts for a C int"))?;
    let m = matrix_to_c(p.w())?;
    let release = |ptrs: &[*mut c_double]| unsafe {
        for &x in ptrs {
            c_free(x);
        }
        nm_clear_impl(m);
        c_free(m);
    };
    let q = c_copy(p.q()).inspect_err(|_| release(&[]))?;
    let mu = c_copy(p.mu()).inspect_err(|_| release(&[q]))?;
    let mu_r = c_copy(p.mu_r()).inspect_err(|_| release(&[q, mu]))?;
    c_box(RollingFrictionContactProblem {
        dimension: D as c_int,
        numberOfContacts: nc,
        M: m,
        q,
        mu,
        mu_r,
    })
    .inspect_err(|_| release(&[q, mu, mu_r]))
}

fn dat_to_c(p: &RollingDatProblem) -> CResult<*mut RollingFrictionContactProblem> {
    match p {
        RollingDatProblem::Spatial(p) => rolling_to_c(p),
        RollingDatProblem::Planar(p) => rolling_to_c(p),
    }
}

impl HostProblem for RollingFrictionContactProblem {
    type View<'a> = AnyRolling<'a>;
    type Read = RollingDatProblem;

    fn empty() -> Self {
        RollingFrictionContactProblem {
            dimension: 0,
            numberOfContacts: 0,
            M: null_mut(),
            q: null_mut(),
            mu: null_mut(),
            mu_r: null_mut(),
        }
    }

    unsafe fn release(&mut self) {
        release_matrix(&mut self.M);
        release_array(&mut self.q);
        release_array(&mut self.mu);
        release_array(&mut self.mu_r);
    }

    unsafe fn view(&self) -> CResult<AnyRolling<'_>> {
        any_rolling_from_c(self)
    }

    fn write(view: &AnyRolling<'_>, mut out: &mut dyn std::io::Write) -> std::io::Result<()> {
        match view {
            AnyRolling::Spatial(p) => fc3d_core::io::dat::write_rolling_dat(p, &mut out),
            AnyRolling::Planar(p) => fc3d_core::io::dat::write_rolling_dat(p, &mut out),
        }
    }

    fn display(view: &AnyRolling<'_>) {
        match view {
            AnyRolling::Spatial(p) => display(p),
            AnyRolling::Planar(p) => display(p),
        }
    }

    fn read(
        stream: &mut dyn std::io::Read,
        len: Option<u64>,
        label: &str,
    ) -> Result<(RollingDatProblem, u64), Fc3dError> {
        read_rolling_dat(stream, len, label)
    }

    fn to_c(read: RollingDatProblem) -> CResult<*mut Self> {
        dat_to_c(&read)
    }
}

/// An empty rolling problem (dimension 0, no data). Release with
/// `rollingFrictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn rollingFrictionContactProblem_new() -> *mut RollingFrictionContactProblem {
    ffi_guard(
        "rollingFrictionContactProblem_new",
        |_| null_mut(),
        host_problem::new::<RollingFrictionContactProblem>,
    )
}

/// A rolling problem that takes `M`, `q`, `mu` and `mu_r` as they are (no copy): they then
/// belong to the problem and are released by `rollingFrictionContactProblem_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn rollingFrictionContactProblem_new_with_data(
    dim: c_int,
    nc: c_int,
    M: *mut super::types::NumericsMatrix,
    q: *mut c_double,
    mu: *mut c_double,
    mu_r: *mut c_double,
) -> *mut RollingFrictionContactProblem {
    ffi_guard(
        "rollingFrictionContactProblem_new_with_data",
        |_| null_mut(),
        || {
            c_box(RollingFrictionContactProblem {
                dimension: dim,
                numberOfContacts: nc,
                M,
                q,
                mu,
                mu_r,
            })
        },
    )
}

/// Releases `M` (storage and struct), `q`, `mu`, `mu_r` and the problem struct. NULL is a
/// no-op (Siconos asserts it is not NULL).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContactProblem_free(
    problem: *mut RollingFrictionContactProblem,
) {
    ffi_guard(
        "rollingFrictionContactProblem_free",
        |_| (),
        || host_problem::free(problem),
    )
}

/// Reads a rolling problem from a Siconos .dat file (dimension, contacts, W, q, mu, mu_r). NULL
/// on failure (see `fc3d_last_error_message`; Siconos exits the process).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContact_new_from_filename(
    filename: *const c_char,
) -> *mut RollingFrictionContactProblem {
    ffi_guard(
        "rollingFrictionContact_new_from_filename",
        |_| null_mut(),
        || host_problem::new_from_filename(filename),
    )
}

/// Reads a rolling problem in the .dat format from an open stream, up to its last rolling
/// coefficient (a stream that can seek is left at the next token, or put back where it was on
/// failure). NULL on failure.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContact_newFromFile(
    file: *mut libc::FILE,
) -> *mut RollingFrictionContactProblem {
    ffi_guard(
        "rollingFrictionContact_newFromFile",
        |_| null_mut(),
        || host_problem::new_from_file(file),
    )
}

/// Writes `problem` to an open stream in the rolling .dat format (round-trip exact numbers).
/// Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContact_printInFile(
    problem: *mut RollingFrictionContactProblem,
    file: *mut libc::FILE,
) -> c_int {
    ffi_guard(
        "rollingFrictionContact_printInFile",
        |c| c,
        || host_problem::print_in_file(problem, file),
    )
}

/// Writes `problem` to the file `filename` (created or truncated). Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContact_printInFilename(
    problem: *mut RollingFrictionContactProblem,
    filename: *mut c_char,
) -> c_int {
    ffi_guard(
        "rollingFrictionContact_printInFilename",
        |c| c,
        || host_problem::print_in_filename(problem, filename),
    )
}

/// Prints a summary of the problem (sizes, storage, mu, mu_r, q) to stdout.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContact_display(
    problem: *mut RollingFrictionContactProblem,
) {
    ffi_guard(
        "rollingFrictionContact_display",
        |_| (),
        || host_problem::display(problem),
    )
}

fn display<const D: usize>(p: &RollingProblem<'_, D>) {
    println!(
        "RollingFrictionContactProblem: dimension {D}, {} contacts, W {}x{} ({}), ||q|| = {:e}",
        p.n_contacts(),
        p.w().nrows(),
        p.w().ncols(),
        p.w().storage_name(),
        fc3d_core::math::linalg::norm(p.q())
    );
    println!("  mu = {:?}", p.mu());
    println!("  mu_r = {:?}", p.mu_r());
    println!("  q = {:?}", p.q());
}

/// Counts the contacts by status at tolerance `tol` (taking off: `u_N > tol`; closed: `r_N >
/// tol`, sticking when `||r_T|| < mu r_N`, sliding otherwise; ambiguous when the complementary
/// quantity exceeds `tol` as well) and prints the counts when `do_print` is non-zero. Siconos
/// 4.4 reads contact c at `3 c` whatever the dimension (the components of other contacts for a
/// 5D problem); fc3d reads it at `dimension * c`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rollingFrictionContactProblem_compute_statistics(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    tol: c_double,
    do_print: c_int,
) {
    ffi_guard(
        "rollingFrictionContactProblem_compute_statistics",
        |_| (),
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let (d, nc, mu) = match any_rolling_from_c(&*problem)? {
                AnyRolling::Spatial(p) => (5, p.n_contacts(), try_copy(p.mu(), "mu")?),
                AnyRolling::Planar(p) => (3, p.n_contacts(), try_copy(p.mu(), "mu")?),
            };
            let r = c_slice(reaction as *const c_double, d * nc, "reaction")?;
            let u = c_slice(velocity as *const c_double, d * nc, "velocity")?;
            let (mut take_off, mut closed, mut sticking, mut sliding) = (0, 0, 0, 0);
            let (mut ambiguous_take_off, mut ambiguous_closed) = (0, 0);
            for c in 0..nc {
                let k = d * c;
                if u[k] > tol {
                    take_off += 1;
                    if r[k].abs() > tol {
                        ambiguous_take_off += 1;
                    }
                } else if r[k] > tol {
                    closed += 1;
                    if u[k].abs() > tol {
                        ambiguous_closed += 1;
                    }
                    let rt_sq: f64 = (1..=(d - 1) / 2).map(|j| r[k + j] * r[k + j]).sum();
                    if rt_sq - mu[c] * mu[c] * r[k] * r[k] < 0.0 {
                        sticking += 1;
                    } else {
                        sliding += 1;
                    }
                }
            }
            if do_print != 0 {
                println!(
                    "---- RFC - STAT  - Number of contact = {nc}\t,  take off = {take_off}\t, \
                     closed = {closed}\t, sliding = {sliding}\t,sticking = {sticking}\t, \
                     ambiguous take off = {ambiguous_take_off}\t, ambiguous closed = \
                     {ambiguous_closed}"
                );
            }
            Ok(())
        },
    )
}

/// The drivers' work: the rolling problem of dimension `D` and the options read, solved,
/// written back (only on success).
unsafe fn rolling_driver_impl<const D: usize>(
    problem: *mut RollingFrictionContactProblem,
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
    let p = rolling_problem_from_c::<D>(&*problem)?;
    let config = rolling_config_from_c(&*options, D)?;
    let report = solve_into_host(p.base(), reaction, velocity, options, |r, u, observer| {
        solve_rolling_with_observer(&p, &config, r, u, observer)
    })?;
    if verbose() > 0 {
        eprintln!(
            "fc3d: rolling solver on {} contacts of dimension {D}: {:?} after {} iterations, \
             error {:e} (tolerance {:e})",
            p.n_contacts(),
            report.status,
            report.iterations,
            report.error,
            config.tolerance
        );
        super::driver::print_fill(&report);
    }
    Ok(report.status.info_code())
}

/// Solves the rolling problem (`problem->dimension` = 5) with the solver `options->solverId`:
/// 3000 NSGS, its local solver `internalSolvers[0]` 3001 (one projected step) or 3002 (the
/// projection iteration, default); 3003 ADMM (the options of the 3D ADMM 523, rescaling
/// refused as Siconos' rolling ADMM has none); any other id: `FC3D_ERR_UNSUPPORTED_SOLVER`.
/// When no contact is pushed into penetration (every `q_N >= -DBL_EPSILON`) the answer is
/// `reaction = 0`, `velocity = q` after 0 iterations, as Siconos. Returns 0 when the error of the
/// returned pair is at most `dparam[0]`, 1 when NSGS stopped above it, 2 when the time budget
/// `dparam[FC3D_DPARAM_TIME_BUDGET]` ran out, a negative `FC3D_ERR_*` code when the input is
/// rejected (nothing written). On return >= 0, `iparam[1]` holds the sweeps and `dparam[1]` the
/// error (`rolling_fc3d_compute_error` with `norm = ||q||`) measured on the returned pair.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_driver(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "rolling_fc3d_driver",
        |c| c,
        || rolling_driver_impl::<5>(problem, reaction, velocity, options),
    )
}

/// `rolling_fc3d_driver` for 2D rolling problems (`problem->dimension` = 3: normal, tangential,
/// rolling): 4000 NSGS with the local solver 3001 / 4001 (one projected step of length 1, as
/// Siconos' 2D step) or 3002 / 4002 (the projection iteration, default).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc2d_driver(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "rolling_fc2d_driver",
        |c| c,
        || rolling_driver_impl::<3>(problem, reaction, velocity, options),
    )
}

/// A direct NSGS entry: as the driver, the result code in `*info`. As in Siconos, a call with
/// `*info` = 0 returns at once (its NSGS takes 0 for "already solved" and does nothing).
unsafe fn nsgs_entry<const D: usize>(
    name: &'static str,
    problem: *mut RollingFrictionContactProblem,
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
            if *info == 0 {
                return Ok(0);
            }
            rolling_driver_impl::<D>(problem, reaction, velocity, options)
        },
    );
    if !info.is_null() {
        *info = code;
    }
}

/// Siconos' rolling NSGS entry (options of id 3000), result in `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_nsgs(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    nsgs_entry::<5>(
        "rolling_fc3d_nsgs",
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' rolling ADMM entry (options of id 3003): `rolling_fc3d_driver`, result in `*info`
/// (whatever `*info` held before, as Siconos').
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_admm(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    let code = ffi_guard(
        "rolling_fc3d_admm",
        |c| c,
        || {
            if info.is_null() {
                return Err(CError::null("info"));
            }
            if !options.is_null() && (*options).solverId != 3003 {
                return Err(CError::new(
                    super::FC3D_ERR_INVALID_OPTION,
                    format!(
                        "rolling_fc3d_admm called with options for solver {} (it needs 3003)",
                        (*options).solverId
                    ),
                ));
            }
            rolling_driver_impl::<5>(problem, reaction, velocity, options)
        },
    );
    if !info.is_null() {
        *info = code;
    }
}

/// Siconos' 2D rolling NSGS entry (options of id 4000), result in `*info`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc2d_nsgs(
    problem: *mut RollingFrictionContactProblem,
    reaction: *mut c_double,
    velocity: *mut c_double,
    info: *mut c_int,
    options: *mut SolverOptions,
) {
    nsgs_entry::<3>(
        "rolling_fc2d_nsgs",
        problem,
        reaction,
        velocity,
        info,
        options,
    );
}

/// Siconos' trivial case: when every contact has `q_N >= -DBL_EPSILON`, writes `velocity = q`,
/// `reaction = 0` and returns 0; otherwise returns -1 and writes nothing. `options` is not read.
unsafe fn check_trivial<const D: usize>(
    problem: *mut RollingFrictionContactProblem,
    velocity: *mut c_double,
    reaction: *mut c_double,
) -> CResult<c_int> {
    if problem.is_null() {
        return Err(CError::null("problem"));
    }
    let p = rolling_problem_from_c::<D>(&*problem)?;
    let n = p.size();
    c_slice(velocity as *const c_double, n, "velocity")?;
    c_slice(reaction as *const c_double, n, "reaction")?;
    if p.q().chunks_exact(D).any(|qc| qc[0] < -f64::EPSILON) {
        return Ok(-1);
    }
    std::ptr::copy_nonoverlapping(p.q().as_ptr(), velocity, n);
    std::ptr::write_bytes(reaction, 0, n);
    Ok(0)
}

/// Siconos' trivial-case test of `rolling_fc3d_driver` (see the driver).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_checkTrivialCase(
    problem: *mut RollingFrictionContactProblem,
    velocity: *mut c_double,
    reaction: *mut c_double,
    _options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "rolling_fc3d_checkTrivialCase",
        |c| c,
        || check_trivial::<5>(problem, velocity, reaction),
    )
}

/// Siconos' trivial-case test of `rolling_fc2d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc2d_checkTrivialCase(
    problem: *mut RollingFrictionContactProblem,
    velocity: *mut c_double,
    reaction: *mut c_double,
    _options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "rolling_fc2d_checkTrivialCase",
        |c| c,
        || check_trivial::<3>(problem, velocity, reaction),
    )
}

/// The rolling error of the dimension `D` (see `rolling_fc3d_compute_error`).
unsafe fn compute_error<const D: usize>(
    problem: *mut RollingFrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    norm: c_double,
    error: *mut c_double,
) -> CResult<c_int> {
    if problem.is_null() {
        return Err(CError::null("problem"));
    }
    if error.is_null() {
        return Err(CError::null("error"));
    }
    let p = rolling_problem_from_c::<D>(&*problem)?;
    let n = p.size();
    let r = c_slice(z as *const c_double, n, "z")?;
    c_slice(w as *const c_double, n, "w")?;
    fc3d_core::error::check_finite("z", r)?;
    let mut u = try_vec(n, 0.0, "w")?;
    p.velocity(r, &mut u);
    let e = relative_rolling_error::<D>(r, &u, p.mu(), p.mu_r(), norm);
    std::ptr::copy_nonoverlapping(u.as_ptr(), w, n);
    *error = e;
    Ok(if e > tolerance { 1 } else { 0 })
}

/// Siconos' rolling error: recomputes `w = M z + q` (written to `w`), then
/// `error = sqrt(sum_c ||z_c - P_K(z_c - ũ_c)||^2)` with the rolling cone and
/// `ũ = (w_N + mu ||w_T|| + mu_r ||w_R||, w_T, w_R)`, divided by `max(norm, ||z||, ||w||)` when
/// that is above the machine epsilon. Returns 0 if `error <= tolerance`, 1 otherwise, a negative
/// code on invalid input (nothing written). `options` is not read.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_compute_error(
    problem: *mut RollingFrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    _options: *mut SolverOptions,
    norm: c_double,
    error: *mut c_double,
) -> c_int {
    ffi_guard(
        "rolling_fc3d_compute_error",
        |c| c,
        || compute_error::<5>(problem, z, w, tolerance, norm, error),
    )
}

/// `rolling_fc2d_compute_error`: the same with the 2D rolling cone.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc2d_compute_error(
    problem: *mut RollingFrictionContactProblem,
    z: *mut c_double,
    w: *mut c_double,
    tolerance: c_double,
    _options: *mut SolverOptions,
    norm: c_double,
    error: *mut c_double,
) -> c_int {
    ffi_guard(
        "rolling_fc2d_compute_error",
        |c| c,
        || compute_error::<3>(problem, z, w, tolerance, norm, error),
    )
}

/// Adds the squared rolling natural-map residual of one contact (`r`, `u`: `D` values each) to
/// `*error`; `worktmp` (`D` values) receives `r - P_K(r - ũ)`. NULL pointers are refused
/// (nothing written).
unsafe fn unitary_error<const D: usize>(
    r: *mut c_double,
    u: *mut c_double,
    mu: c_double,
    mu_r: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) -> CResult<()> {
    if error.is_null() {
        return Err(CError::null("error"));
    }
    let rc = c_slice(r as *const c_double, D, "r")?;
    let uc = c_slice(u as *const c_double, D, "u")?;
    c_slice(worktmp as *const c_double, D, "worktmp")?;
    let (mut r_c, mut u_c) = ([0.0; D], [0.0; D]);
    r_c.copy_from_slice(rc);
    u_c.copy_from_slice(uc);
    let (rc, uc) = (r_c, u_c);
    let ut = rolling_modified_velocity(&uc, mu, mu_r);
    let mut x = rc;
    for (xk, uk) in x.iter_mut().zip(&ut) {
        *xk -= uk;
    }
    let p = project_on_rolling_cone(&x, mu, mu_r);
    let mut sum = 0.0;
    for k in 0..D {
        let d = rc[k] - p[k];
        *worktmp.add(k) = d;
        sum += d * d;
    }
    *error += sum;
    Ok(())
}

/// Siconos' `rolling_fc3d_unitary_compute_and_add_error` (5 values in `r`, `u`, `worktmp`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc3d_unitary_compute_and_add_error(
    r: *mut c_double,
    u: *mut c_double,
    mu: c_double,
    mur: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) {
    ffi_guard(
        "rolling_fc3d_unitary_compute_and_add_error",
        |_| (),
        || unitary_error::<5>(r, u, mu, mur, error, worktmp),
    )
}

/// Siconos' `rolling_fc2d_unitary_compute_and_add_error` (3 values in `r`, `u`, `worktmp`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn rolling_fc2d_unitary_compute_and_add_error(
    r: *mut c_double,
    u: *mut c_double,
    mu: c_double,
    mur: c_double,
    error: *mut c_double,
    worktmp: *mut c_double,
) {
    ffi_guard(
        "rolling_fc2d_unitary_compute_and_add_error",
        |_| (),
        || unitary_error::<3>(r, u, mu, mur, error, worktmp),
    )
}
