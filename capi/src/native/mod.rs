//! The native entry: solve from plain arrays, with names Siconos does not use (`fc3d_settings_*`,
//! `fc3d_solve_*`, `fc3d_problem_*`, `fc3d_version`), so a host can link Siconos beside fc3d's
//! native-only build (`libfc3d_native`, header `fc3d_native.h`). The Fortran, Python and Julia
//! bindings call this entry.
//!
//! Ownership: `fc3d_settings_new` and `fc3d_problem_read` return handles the caller releases with
//! `fc3d_settings_free` / `fc3d_problem_free`; every array is the caller's, read or written in
//! place. Sizes and indices are `int64_t`; W's (M's, H's) entries are copied into fc3d's storage.
//! On a negative return nothing is written (r, u, v, result and the settings stay as they were).

// cbindgen reads a module's own items, then its submodules in the order declared here: the order
// of include/fc3d.h and fc3d_native.h (settings, then solves, then problems read from files).
// The blank lines keep rustfmt from sorting the declarations.
pub(crate) mod settings;

mod solve;

mod global;

mod problem;

use std::ffi::c_char;
use std::os::raw::{c_double, c_int};

pub use solve::settings_config;

use crate::ffi_guard;
use crate::types::SolverOptions;
use fc3d_core::{CsrMatrix, FrictionProblem};

/// A solver and its settings (opaque): Siconos' options of a solver id, changed by the setters.
pub struct Fc3dSettings {
    options: *mut SolverOptions,
}

/// A problem read from a file (opaque), with W also kept in compressed rows for
/// `fc3d_problem_get`.
pub struct Fc3dProblem {
    problem: FrictionProblem<'static>,
    csr: CsrMatrix,
}

/// What a solve reports.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct Fc3dResult {
    /// 0 converged, 1 iteration limit, 2 time budget spent, 3 relaxed solution not Coulomb.
    pub info: c_int,
    /// Iterations (sweeps, Newton steps, ...) done.
    pub iterations: i64,
    /// The error of the returned solution: the natural-map error of `(r, u)` for the local
    /// solves, Siconos' global error (`gfc3d_compute_error`) of `(r, u, v)` for the global ones.
    pub error: c_double,
    /// Wall-clock time of the solve, seconds.
    pub seconds: c_double,
}

/// The library's version, e.g. "0.2.0" (a static string, do not free).
#[no_mangle]
pub extern "C" fn fc3d_version() -> *const c_char {
    ffi_guard(
        "fc3d_version",
        |_| concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast(),
        || Ok(concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()),
    )
}
