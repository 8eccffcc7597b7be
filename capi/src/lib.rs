//! The C ABI: a thin layer that converts Siconos-layout structs into core types, validates
//! them, calls the core and converts back. It holds no numerics.
//!
//! Contract (also in README.md, "C API contract"):
//! * Every `extern "C"` function runs inside [`ffi_guard`]: a Rust panic is caught and turned into
//!   [`FC3D_ERR_INTERNAL`]; nothing unwinds into C, nothing aborts or exits.
//! * Functions returning `int` return 0 on success, 1 when a solver ran but did not reach its
//!   tolerance, and a negative `FC3D_ERR_*` code for rejected input. Functions returning a pointer
//!   return NULL on failure. `void` functions leave their outputs unchanged on failure. In all
//!   cases [`fc3d_last_error_message`] returns the reason (per thread), and it is printed to
//!   stderr when `numerics_set_verbose(>0)`.
//! * Outputs (reaction, velocity, iparam[1], dparam[1], out-pointers) are written only on success.
//! * Memory that C may free (problem arrays, matrices, options arrays) is allocated with the C
//!   allocator (`malloc`), so `free` and the `_free`/`_delete` functions may be mixed as in Siconos.

pub mod types;

mod alloc;
mod driver;
mod lmgc;
mod matrix;
mod options;
mod params;
mod problem;
mod stream;

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::os::raw::c_int;
use std::sync::atomic::{AtomicI32, Ordering};

use fc3d_core::error::Fc3dError;

/// Success (and "converged" for solvers).
pub const FC3D_OK: c_int = 0;
/// A solver ran and returned its best iterate, but the error is above the tolerance.
pub const FC3D_NOT_CONVERGED: c_int = 1;
/// A solver ran until its time budget (`dparam[FC3D_DPARAM_TIME_BUDGET]`) was spent; the
/// reaction is the best iterate it measured, and its error is above the tolerance.
pub const FC3D_TIME_BUDGET_EXHAUSTED: c_int = 2;
/// A solver of a relaxed problem (SOCLCP, id 517) solved its relaxation to the tolerance, but
/// the result is not a Coulomb solution: `dparam[1]`, the Coulomb natural-map error of the
/// returned reaction, is above the tolerance (some contact slides).
pub const FC3D_RELAXED_NOT_COULOMB: c_int = 3;
/// Index in `dparam` of fc3d's wall-clock budget in seconds (0, the default: no budget). An index
/// Siconos' fc3d solvers leave unused.
pub const FC3D_DPARAM_TIME_BUDGET: c_int = 19;
/// Index in `dparam` where NSGS writes Dumont's criterion (37) at its last test when it ran with
/// `iparam[7] = FC3D_ERROR_EVALUATION_DUMONT` (output; untouched otherwise). Unused by Siconos.
pub const FC3D_DPARAM_DUMONT_CRITERION: c_int = 18;
/// Value of NSGS's `iparam[7]` (error evaluation) selecting Dumont's criterion (37) as the
/// stopping test, beside Siconos' 0 (full), 1 (light) and 2 (light with full final). The
/// reported error `dparam[1]` stays the natural-map error.
pub const FC3D_ERROR_EVALUATION_DUMONT: c_int = 20;
/// Length of iparam and dparam (Siconos' OPTIONS_PARAM_SIZE).
pub const OPTIONS_PARAM_SIZE: c_int = 20;
/// fc3d's value of a local solver's `iparam[9]` (rho strategy) for Dumont's rule
/// `rho_N = rho_T = alpha / W_NN`, with alpha in `dparam[3]` (Siconos 4.4 uses 0..=4). Default
/// of the local solvers `FC3D_ONECONTACT_EBP` and `FC3D_ONECONTACT_EAL` (alpha = 1).
pub const FC3D_RHO_STRATEGY_DUMONT: c_int = 10;
/// fc3d's one-contact solver ids are in 568..=599, a range Siconos 4.4 leaves free (its
/// one-contact solvers use 550..=567). FP-VI-UPK of Acary-Brémond-Huber's Table 3 on one contact:
/// projection steps with the self-adaptive rho rule (98), started from rho strategy iparam[9]
/// (default 1, spectral norm). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_FP_VI_UPK: c_int = 570;
/// Dumont's EBP (2021): Newton on the bipotential fixed point `r = P_K(r - rho ũ)` with the
/// condensed 3x3 system (32); rho by iparam[9] (default `FC3D_RHO_STRATEGY_DUMONT`, alpha =
/// dparam[3] = 1). Use it as NSGS's internal solver.
pub const FC3D_ONECONTACT_EBP: c_int = 571;
/// Dumont's EAL (2021): Newton on the augmented-Lagrangian fixed point; the same function as
/// the Alart-Curnier Newton 550, with Dumont's rho (`FC3D_RHO_STRATEGY_DUMONT`) by default.
pub const FC3D_ONECONTACT_EAL: c_int = 572;

/// A required pointer argument (or a pointer inside a struct) is NULL.
pub const FC3D_ERR_NULL_POINTER: c_int = -1;
/// Sizes are negative, inconsistent, or too large.
pub const FC3D_ERR_INVALID_SIZE: c_int = -2;
/// Unknown or unsupported matrix storage, or an inconsistent sparse structure.
pub const FC3D_ERR_INVALID_STORAGE: c_int = -3;
/// NaN or infinity in W, q, mu or the initial reaction.
pub const FC3D_ERR_NON_FINITE: c_int = -4;
/// An option value out of range (iparam/dparam), or an option not implemented.
pub const FC3D_ERR_INVALID_OPTION: c_int = -5;
/// A solver id that fc3d does not implement.
pub const FC3D_ERR_UNSUPPORTED_SOLVER: c_int = -6;
/// The problem is ill-posed as given: mu < 0, a missing diagonal block, dimension != 3.
pub const FC3D_ERR_INVALID_PROBLEM: c_int = -7;
/// A malformed or truncated problem file.
pub const FC3D_ERR_PARSE: c_int = -8;
/// A file could not be opened, read or written.
pub const FC3D_ERR_IO: c_int = -9;
/// A bug in fc3d (a caught panic). Please report it.
pub const FC3D_ERR_INTERNAL: c_int = -99;

static VERBOSE: AtomicI32 = AtomicI32::new(0);

thread_local! {
    static LAST_ERROR: RefCell<(c_int, CString)> = RefCell::new((FC3D_OK, CString::default()));
}

/// A rejected call: return code and message.
#[derive(Debug, Clone)]
pub(crate) struct CError {
    pub code: c_int,
    pub message: String,
}

impl CError {
    pub fn new(code: c_int, message: impl Into<String>) -> Self {
        CError {
            code,
            message: message.into(),
        }
    }
    pub fn null(what: &str) -> Self {
        CError::new(FC3D_ERR_NULL_POINTER, format!("{what} is NULL"))
    }
}

impl From<Fc3dError> for CError {
    fn from(e: Fc3dError) -> Self {
        let code = match &e {
            Fc3dError::DimensionMismatch { .. } => FC3D_ERR_INVALID_SIZE,
            Fc3dError::NonFinite { .. } => FC3D_ERR_NON_FINITE,
            Fc3dError::NegativeFriction { .. } | Fc3dError::MissingDiagonalBlock { .. } => {
                FC3D_ERR_INVALID_PROBLEM
            }
            Fc3dError::InvalidStructure(_) | Fc3dError::Unsupported(_) => FC3D_ERR_INVALID_STORAGE,
            Fc3dError::UnsupportedSolver { .. } => FC3D_ERR_UNSUPPORTED_SOLVER,
            Fc3dError::InvalidOption(_) | Fc3dError::InvalidSetting { .. } => {
                FC3D_ERR_INVALID_OPTION
            }
            Fc3dError::Parse { .. } => FC3D_ERR_PARSE,
            Fc3dError::Io { .. } => FC3D_ERR_IO,
        };
        CError::new(code, e.to_string())
    }
}

pub(crate) type CResult<T> = Result<T, CError>;

/// Records `e` as the calling thread's last error (printed when verbose) and returns its code.
pub(crate) fn record(function: &str, e: CError) -> c_int {
    let msg = format!("fc3d: {function}: {}", e.message);
    if VERBOSE.load(Ordering::Relaxed) > 0 {
        eprintln!("{msg}");
    }
    let c = CString::new(msg.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|l| *l.borrow_mut() = (e.code, c));
    e.code
}

pub(crate) fn verbose() -> i32 {
    VERBOSE.load(Ordering::Relaxed)
}

/// Runs `body` with panics caught. `Err` and panics are recorded as the last error and mapped
/// to `on_error(code)`.
pub(crate) fn ffi_guard<T>(
    function: &str,
    on_error: impl FnOnce(c_int) -> T,
    body: impl FnOnce() -> CResult<T>,
) -> T {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(body)) {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => on_error(record(function, e)),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            on_error(record(
                function,
                CError::new(FC3D_ERR_INTERNAL, format!("internal error: {what}")),
            ))
        }
    }
}

/// The message of the last failed fc3d call on this thread ("" if none). The pointer stays
/// valid until the next failing fc3d call on the same thread; do not free it.
#[no_mangle]
pub extern "C" fn fc3d_last_error_message() -> *const c_char {
    ffi_guard(
        "fc3d_last_error_message",
        |_| std::ptr::null(),
        || Ok(LAST_ERROR.with(|l| l.borrow().1.as_ptr())),
    )
}

/// The code of the last failed fc3d call on this thread (0 if none).
#[no_mangle]
pub extern "C" fn fc3d_last_error_code() -> c_int {
    ffi_guard(
        "fc3d_last_error_code",
        |c| c,
        || Ok(LAST_ERROR.with(|l| l.borrow().0)),
    )
}

/// Clears the last error of this thread.
#[no_mangle]
pub extern "C" fn fc3d_clear_last_error() {
    ffi_guard(
        "fc3d_clear_last_error",
        |_| (),
        || {
            LAST_ERROR.with(|l| *l.borrow_mut() = (FC3D_OK, CString::default()));
            Ok(())
        },
    )
}

/// Siconos' verbosity switch: > 0 prints rejected calls and solver summaries to stderr.
#[no_mangle]
#[allow(non_snake_case)]
pub extern "C" fn numerics_set_verbose(newVerboseMode: c_int) {
    VERBOSE.store(newVerboseMode, Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc3d_core::LocalSolverKind;

    /// The C names of fc3d's one-contact ids are the core's ids.
    #[test]
    fn one_contact_ids_are_the_cores() {
        for (id, kind) in [
            (FC3D_ONECONTACT_FP_VI_UPK, LocalSolverKind::FpViUpk),
            (FC3D_ONECONTACT_EBP, LocalSolverKind::EnhancedBipotential),
            (
                FC3D_ONECONTACT_EAL,
                LocalSolverKind::EnhancedAugmentedLagrangian,
            ),
        ] {
            assert_eq!(id, kind.siconos_id());
        }
    }
}
