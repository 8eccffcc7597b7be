//! Failed calls: the error type of the C layer, the panic boundary every exported function runs
//! in, and the per-thread last error a host reads back.

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::os::raw::c_int;
use std::sync::atomic::{AtomicI32, Ordering};

use crate::codes::*;
use fc3d_core::error::Fc3dError;

pub(crate) static VERBOSE: AtomicI32 = AtomicI32::new(0);

thread_local! {
    static LAST_ERROR: RefCell<(c_int, CString)> = RefCell::new((FC3D_OK, CString::default()));
}

/// A rejected call: return code and message.
#[derive(Debug, Clone)]
pub struct CError {
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
            Fc3dError::NegativeFriction { .. }
            | Fc3dError::MissingDiagonalBlock { .. }
            | Fc3dError::UnsupportedDimension { .. } => FC3D_ERR_INVALID_PROBLEM,
            Fc3dError::InvalidStructure(_) | Fc3dError::Unsupported(_) => FC3D_ERR_INVALID_STORAGE,
            Fc3dError::UnsupportedSolver { .. } => FC3D_ERR_UNSUPPORTED_SOLVER,
            Fc3dError::InvalidOption(_) | Fc3dError::InvalidSetting { .. } => {
                FC3D_ERR_INVALID_OPTION
            }
            Fc3dError::Parse { .. } => FC3D_ERR_PARSE,
            Fc3dError::Io { .. } => FC3D_ERR_IO,
            Fc3dError::OutOfMemory { .. } => FC3D_ERR_OUT_OF_MEMORY,
        };
        CError::new(code, e.to_string())
    }
}

pub type CResult<T> = Result<T, CError>;

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
pub fn ffi_guard<T>(
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
