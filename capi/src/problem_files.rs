//! `FrictionContactProblem` in files and streams: Siconos' .dat reader (a file, or an FCLIB
//! .hdf5 file through `fclib`) and writers, and the summary printed by `frictionContact_display`,
//! through `host_problem` (the same functions serve the rolling and global structs).
//!
//! A problem read is allocated as `problem.rs` describes: release it with
//! `frictionContactProblem_free`.

#![allow(non_snake_case)]

use std::ffi::c_char;
use std::os::raw::c_int;
use std::ptr::null_mut;

use super::alloc::{c_box, c_free, CStore};
use super::fclib::{is_fclib_file, read_fclib_problem};
use super::host_problem::{self, release_array, release_matrix, HostProblem};
use super::matrix::matrix_from_read;
use super::problem::{any_problem_from_c, AnyProblem};
use super::types::FrictionContactProblem;
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::Fc3dError;
use fc3d_core::io::dat::{read_dat_file_into, read_dat_into, ReadProblem};
use fc3d_core::problem::FrictionProblem;

/// The C problem of a problem a reader stored in C arrays: q, mu and W's storage become the
/// problem's as they are (see `matrix_from_read`), so that a read holds one copy of everything.
/// Everything is freed on failure.
fn problem_from_read(p: ReadProblem<CStore>) -> CResult<*mut FrictionContactProblem> {
    let ReadProblem {
        dimension,
        w,
        q,
        mu,
    } = p;
    let nc = c_int::try_from(mu.len())
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many contacts for a C int"))?;
    let dimension = c_int::try_from(dimension)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_PROBLEM, "invalid dimension"))?;
    let out = c_box(FrictionContactProblem {
        dimension,
        numberOfContacts: nc,
        M: null_mut(),
        q: null_mut(),
        mu: null_mut(),
    })?;
    match matrix_from_read(w) {
        Ok(m) => {
            // SAFETY: out is the fresh problem allocated above; q and mu are handed over.
            unsafe {
                (*out).M = m;
                (*out).q = q.into_raw();
                (*out).mu = mu.into_raw();
            }
            Ok(out)
        }
        Err(e) => {
            // SAFETY: out owns nothing yet.
            unsafe { c_free(out) };
            Err(e)
        }
    }
}

impl HostProblem for FrictionContactProblem {
    type View<'a> = AnyProblem<'a>;
    type Read = ReadProblem<CStore>;

    fn empty() -> Self {
        FrictionContactProblem {
            dimension: 0,
            numberOfContacts: 0,
            M: null_mut(),
            q: null_mut(),
            mu: null_mut(),
        }
    }

    unsafe fn release(&mut self) {
        release_matrix(&mut self.M);
        release_array(&mut self.q);
        release_array(&mut self.mu);
    }

    unsafe fn view(&self) -> CResult<AnyProblem<'_>> {
        any_problem_from_c(self)
    }

    fn write(view: &AnyProblem<'_>, mut out: &mut dyn std::io::Write) -> std::io::Result<()> {
        match view {
            AnyProblem::Spatial(p) => fc3d_core::io::dat::write_dat(p, &mut out),
            AnyProblem::Planar(p) => fc3d_core::io::dat::write_dat(p, &mut out),
        }
    }

    fn display(view: &AnyProblem<'_>) {
        match view {
            AnyProblem::Spatial(p) => display(p),
            AnyProblem::Planar(p) => display(p),
        }
    }

    fn read(
        stream: &mut dyn std::io::Read,
        len: Option<u64>,
        label: &str,
    ) -> Result<(ReadProblem<CStore>, u64), Fc3dError> {
        read_dat_into::<CStore, _>(stream, len, label)
    }

    fn to_c(read: ReadProblem<CStore>) -> CResult<*mut Self> {
        problem_from_read(read)
    }

    /// A `.dat` file, or an FCLIB file (one that starts with the HDF5 signature or is named
    /// `.hdf5` / `.h5`) as `frictionContact_fclib_read` reads it.
    fn read_file(path: &str) -> CResult<*mut Self> {
        if is_fclib_file(path) {
            return read_fclib_problem(path);
        }
        problem_from_read(read_dat_file_into::<CStore>(std::path::Path::new(path))?)
    }
}

/// Reads a problem from a Siconos .dat file, or from an FCLIB .hdf5 file (one that starts with
/// the HDF5 signature or is named `.hdf5` / `.h5`) as `frictionContact_fclib_read` does. A .dat
/// file is read in chunks up to its last friction coefficient (see `frictionContact_newFromFile`;
/// a declared size larger than the file can hold fails before it is read). NULL on failure (see
/// `fc3d_last_error_message`).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_new_from_filename(
    filename: *const c_char,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContact_new_from_filename",
        |_| null_mut(),
        || host_problem::new_from_filename(filename),
    )
}

/// Reads a problem in the .dat format from an open stream, as Siconos does: up to the last
/// friction coefficient, in chunks, never to the end of a stream that goes on. On success a
/// stream that can seek is left at the first token after the problem (a pipe: after the
/// whitespace that follows it); on failure a stream that can seek is put back where it was.
/// NULL on failure: `FC3D_ERR_PARSE` (malformed or truncated text, a stream that stops making
/// tokens such as `/dev/zero`), `FC3D_ERR_OUT_OF_MEMORY` (a stream going on with values beyond
/// what can be allocated), `FC3D_ERR_IO`, `FC3D_ERR_NULL_POINTER`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_newFromFile(
    file: *mut libc::FILE,
) -> *mut FrictionContactProblem {
    ffi_guard(
        "frictionContact_newFromFile",
        |_| null_mut(),
        || host_problem::new_from_file(file),
    )
}

/// Writes `problem` to an open stream in the .dat format (round-trip exact numbers).
/// Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_printInFile(
    problem: *mut FrictionContactProblem,
    file: *mut libc::FILE,
) -> c_int {
    ffi_guard(
        "frictionContact_printInFile",
        |c| c,
        || host_problem::print_in_file(problem, file),
    )
}

/// Writes `problem` to the file `filename` (created or truncated). Returns 0 on success.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_printInFilename(
    problem: *mut FrictionContactProblem,
    filename: *mut c_char,
) -> c_int {
    ffi_guard(
        "frictionContact_printInFilename",
        |c| c,
        || host_problem::print_in_filename(problem, filename),
    )
}

/// Prints a summary of the problem (sizes, storage, mu, q) to stdout.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn frictionContact_display(problem: *mut FrictionContactProblem) {
    ffi_guard(
        "frictionContact_display",
        |_| (),
        || host_problem::display(problem),
    )
}

fn display<const D: usize>(p: &FrictionProblem<'_, D>) {
    println!(
        "FrictionContactProblem: dimension {D}, {} contacts, W {}x{} ({}), ||q|| = {:e}",
        p.n_contacts(),
        p.w().nrows(),
        p.w().ncols(),
        p.w().storage_name(),
        fc3d_core::math::linalg::norm(p.q())
    );
    println!("  mu = {:?}", p.mu());
    println!("  q = {:?}", p.q());
}
