//! The global functions of Siconos' `fclib_interface.h` (built by Siconos only with FCLIB):
//! `globalFrictionContact_fclib_read`, `globalFrictionContact_fclib_write` and
//! `globalRollingFrictionContact_fclib_write`. As the local ones (`crate::fclib`), they are
//! exported in every build and fail cleanly (NULL, or 0 with `FC3D_ERR_IO`) when libfc3d was
//! built without FCLIB support, and keep Siconos' return values (1 on success for the writers).
//!
//! Differences from Siconos 4.4: M and H of any storage are written (Siconos exits unless they
//! are sparse with a triplet form); the file is created or replaced through a temporary file
//! (FCLIB refuses a file that already holds the group); nothing exits the process.

#![allow(non_snake_case)]

use std::ffi::c_char;
use std::os::raw::c_int;
use std::path::Path;
use std::ptr::null_mut;

use super::{global_from_c, global_rolling_from_c, global_to_c};
use crate::fclib::{c_path, c_text, read_error, require_fclib};
use crate::types::{GlobalFrictionContactProblem, GlobalRollingFrictionContactProblem};
use crate::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::Fc3dError;
use fc3d_core::io::dat::{GlobalStorage, MatrixStorage};
use fc3d_core::io::FclibInfo;

/// Reads the global problem of the FCLIB file `path` into a C struct: M and H sparse with a
/// triplet form (as Siconos' `from_fclib_global` wraps FCLIB's triplets).
pub(super) fn read_global_fclib(path: &str) -> CResult<*mut GlobalFrictionContactProblem> {
    require_fclib(path, "read")?;
    let p = fc3d_core::io::read_fclib_global_file(Path::new(path)).map_err(read_error)?;
    let storage = GlobalStorage {
        m: MatrixStorage::Sparse,
        h: MatrixStorage::Sparse,
    };
    global_to_c(&p, &storage)
}

/// Reads the global problem (`/fclib_global`) of the FCLIB file `path`: M and H as sparse
/// matrices with a triplet form, q (FCLIB's f), b (FCLIB's w), mu. Release with
/// `globalFrictionContact_free`. NULL on failure (see `fc3d_last_error_message`), in particular
/// when libfc3d was built without FCLIB support.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_fclib_read(
    path: *const c_char,
) -> *mut GlobalFrictionContactProblem {
    ffi_guard(
        "globalFrictionContact_fclib_read",
        |_| null_mut(),
        || read_global_fclib(c_path(path)?),
    )
}

/// The common part of the writers: the checks Siconos makes (a problem with contacts) and the
/// FCLIB build, the info strings, then `write`; 1 on success. A refusal of the core writer
/// (matrices too large for FCLIB's int indices) is `FC3D_ERR_INVALID_SIZE`.
unsafe fn write_with(
    n_contacts: usize,
    path: *const c_char,
    [title, description, math]: [*mut c_char; 3],
    write: impl FnOnce(&Path, &FclibInfo) -> Result<(), Fc3dError>,
) -> CResult<c_int> {
    let path = c_path(path)?;
    if n_contacts == 0 {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            "a problem without contacts is not written (as Siconos)",
        ));
    }
    require_fclib(path, "written")?;
    let info = FclibInfo {
        title: c_text(title),
        description: c_text(description),
        math_info: c_text(math),
        number_of_degrees_of_freedom: None,
    };
    write(Path::new(path), &info).map_err(|e| match e {
        Fc3dError::Unsupported(m) => CError::new(FC3D_ERR_INVALID_SIZE, m),
        other => other.into(),
    })?;
    Ok(1)
}

/// Writes `problem` (dimension 3) to the FCLIB file `path` (created or replaced) as a global
/// problem: `/fclib_global` with M and H as triplets of their stored entries, whatever their
/// storage, f = q, w = b, mu, and the info group holding `title`, `description`, `mathInfo`
/// (each may be NULL: not written). Reading it back with `globalFrictionContact_fclib_read`
/// gives the same problem. Returns 1 on success and 0 on failure, as Siconos (fclib); on
/// failure `path` is left as it was and `fc3d_last_error_code()` says why (`FC3D_ERR_IO` when
/// the file cannot be written or libfc3d was built without FCLIB support). As Siconos, a
/// problem without contacts is not written (0, `FC3D_ERR_INVALID_SIZE`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalFrictionContact_fclib_write(
    problem: *mut GlobalFrictionContactProblem,
    title: *mut c_char,
    description: *mut c_char,
    mathInfo: *mut c_char,
    path: *const c_char,
) -> c_int {
    ffi_guard(
        "globalFrictionContact_fclib_write",
        |_| 0,
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = global_from_c::<3>(p)?;
            let texts = [title, description, mathInfo];
            write_with(view.problem.n_contacts(), path, texts, |path, info| {
                fc3d_core::io::write_fclib_global_file(&view.problem, path, info)
            })
        },
    )
}

/// Writes `problem` (dimension 5) to the FCLIB file `path` (created or replaced) as FCLIB's
/// `fclib_write_global_rolling` lays it out: `/fclib_global_rolling` with M and H as triplets,
/// f = q, w = b, mu, mu_r and the info group. Returns 1 on success and 0 on failure, as
/// `globalFrictionContact_fclib_write`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn globalRollingFrictionContact_fclib_write(
    problem: *mut GlobalRollingFrictionContactProblem,
    title: *mut c_char,
    description: *mut c_char,
    mathInfo: *mut c_char,
    path: *const c_char,
) -> c_int {
    ffi_guard(
        "globalRollingFrictionContact_fclib_write",
        |_| 0,
        || {
            let p = problem.as_ref().ok_or_else(|| CError::null("problem"))?;
            let view = global_rolling_from_c(p)?;
            let texts = [title, description, mathInfo];
            write_with(
                view.problem.base().n_contacts(),
                path,
                texts,
                |path, info| {
                    fc3d_core::io::write_fclib_global_rolling_file(&view.problem, path, info)
                },
            )
        },
    )
}
