//! FCLIB `.hdf5` files through the C ABI: Siconos 4.4's `frictionContact_fclib_read` and
//! `frictionContact_fclib_write` (its `fclib_interface.h`), and the HDF5 branch of
//! `frictionContact_new_from_filename`.
//!
//! The functions are exported whether or not libfc3d was built with FCLIB support (the `fclib`
//! feature of this crate, or of fc3d-core), so that a host links against either build. Without
//! it they fail cleanly: `frictionContact_fclib_read` returns NULL, `frictionContact_fclib_write`
//! returns 0 with `fc3d_last_error_code()` = `FC3D_ERR_IO`, and `fc3d_last_error_message()` says
//! that FCLIB support is missing and how to build it; nothing is written.
//!
//! Differences from Siconos 4.4 (whose fclib calls exit the process on most errors):
//! * `frictionContact_fclib_write` keeps Siconos' (fclib's) return values, a drop-in's first
//!   duty, unlike fc3d's own `int` functions: 1 on success, 0 on failure, where Siconos returns 0
//!   or exits; the `FC3D_ERR_*` code of a failure is in `fc3d_last_error_code()`.
//! * The file is created or replaced (Siconos refuses a file that already holds a local problem),
//!   through a temporary file renamed at the end: on failure `path` is left as it was.
//! * W keeps its storage through a write and a read (the W group carries the attribute
//!   `fc3d_storage`, which other FCLIB readers ignore); a file without it (written by Siconos or
//!   FCLIB) is read as Siconos reads it, in sparse-block storage.
//! * `frictionContact_fclib_read` also reads a file holding only a global problem
//!   (`/fclib_global`), reduced to the local form W = H^T M^-1 H, q = H^T M^-1 f + w.

#![allow(non_snake_case)]

use std::ffi::{c_char, CStr};
use std::os::raw::c_int;
use std::path::Path;
use std::ptr::null_mut;

use super::problem::{problem_from_c, problem_to_c};
use super::types::FrictionContactProblem;
use super::{
    ffi_guard, CError, CResult, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE, FC3D_ERR_IO,
    FC3D_ERR_PARSE,
};
use fc3d_core::error::Fc3dError;
use fc3d_core::io::{FclibInfo, FCLIB_AVAILABLE};

/// Whether `frictionContact_new_from_filename` reads `path` as an FCLIB file: it starts with the
/// HDF5 signature, or its extension is `.hdf5` / `.h5` (then the FCLIB reader names what is
/// wrong with it). Everything else is read as a Siconos `.dat` file.
pub(crate) fn is_fclib_file(path: &str) -> bool {
    let path = Path::new(path);
    fc3d_core::io::is_hdf5_file(path) || fc3d_core::io::has_fclib_extension(path)
}

/// Fails with `FC3D_ERR_IO` and a message naming the file when libfc3d has no FCLIB support.
pub(crate) fn require_fclib(path: &str, done: &str) -> CResult<()> {
    if FCLIB_AVAILABLE {
        Ok(())
    } else {
        Err(CError::new(
            FC3D_ERR_IO,
            format!(
                "{path}: FCLIB .hdf5 files cannot be {done}: libfc3d was built without FCLIB \
                 support (rebuild it with `cargo build --release -p fc3d --features fclib`, \
                 which needs libhdf5-dev and pkg-config)"
            ),
        ))
    }
}

/// The error of a failed read: a malformed FCLIB file is `FC3D_ERR_PARSE`, a problem fc3d does
/// not solve (2D, extra constraints) `FC3D_ERR_INVALID_PROBLEM`, the rest as everywhere.
pub(crate) fn read_error(e: Fc3dError) -> CError {
    match e {
        Fc3dError::InvalidStructure(m) => CError::new(FC3D_ERR_PARSE, m),
        Fc3dError::Unsupported(m) => CError::new(FC3D_ERR_INVALID_PROBLEM, m),
        other => other.into(),
    }
}

/// Reads the FCLIB file `path` into a C-allocated problem.
pub(crate) fn read_fclib_problem(path: &str) -> CResult<*mut FrictionContactProblem> {
    require_fclib(path, "read")?;
    let p = fc3d_core::io::read_fclib_file(Path::new(path)).map_err(read_error)?;
    problem_to_c(&p)
}

/// A path argument as UTF-8.
pub(crate) unsafe fn c_path<'a>(path: *const c_char) -> CResult<&'a str> {
    if path.is_null() {
        return Err(CError::null("path"));
    }
    CStr::from_ptr(path)
        .to_str()
        .map_err(|_| CError::new(FC3D_ERR_IO, "path is not valid UTF-8"))
}

/// An optional info string (NULL: not written); invalid UTF-8 is replaced by U+FFFD.
pub(crate) unsafe fn c_text(text: *const c_char) -> Option<String> {
    (!text.is_null()).then(|| CStr::from_ptr(text).to_string_lossy().into_owned())
}

/// Reads the FCLIB file `path`: its local problem (`/fclib_local`), or else its global problem
/// (`/fclib_global`) reduced to the local form W = H^T M^-1 H, q = H^T M^-1 f + w. W has the
/// storage fc3d recorded when it wrote the file, otherwise Siconos' sparse-block storage.
/// Release the result with `frictionContactProblem_free`. NULL on failure (see
/// `fc3d_last_error_message`), in particular when libfc3d was built without FCLIB support.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_fclib_read(
    path: *const c_char,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContact_fclib_read",
        |_| null_mut(),
        || read_fclib_problem(c_path(path)?),
    )
}

/// Writes `problem` to the FCLIB file `path` (created or replaced) as a local problem:
/// `/fclib_local` with W in compressed rows, q, mu, and the info group holding `title`,
/// `description`, `mathInfo` (each may be NULL: not written) and the attribute
/// `numberOfDegreeOfFreedom` = `ndof`, as Siconos writes it. Reading the file back with
/// `frictionContact_fclib_read` gives the same problem, bit for bit, W in the same storage.
/// Returns 1 on success and 0 on failure, as Siconos (fclib) does; on failure `path` is left as
/// it was and `fc3d_last_error_code()` says why (`FC3D_ERR_IO` when the file cannot be written
/// or libfc3d was built without FCLIB support).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_fclib_write(
    problem: *mut FrictionContactProblem,
    title: *mut c_char,
    description: *mut c_char,
    mathInfo: *mut c_char,
    path: *const c_char,
    ndof: c_int,
) -> c_int {
    ffi_guard(
        "frictionContact_fclib_write",
        |_| 0,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let path = c_path(path)?;
            let p = problem_from_c(&*problem)?;
            require_fclib(path, "written")?;
            let info = FclibInfo {
                title: c_text(title),
                description: c_text(description),
                math_info: c_text(mathInfo),
                number_of_degrees_of_freedom: Some(ndof),
            };
            fc3d_core::io::write_fclib_file(&p, Path::new(path), &info).map_err(|e| match e {
                // The only refusal left from C: a W too large for FCLIB's int indices.
                Fc3dError::Unsupported(m) => CError::new(FC3D_ERR_INVALID_SIZE, m),
                other => other.into(),
            })?;
            Ok(1)
        },
    )
}
