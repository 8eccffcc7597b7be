//! Problems read from files (`fc3d_problem_*`): an opaque handle holding the problem and W in
//! compressed rows, its arrays copied out or solved in place.

use std::ffi::{c_char, CStr};
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::solve::solve_into;
use super::{Fc3dProblem, Fc3dResult, Fc3dSettings};
use crate::matrix::c_slice;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_NULL_POINTER};

/// Reads a Siconos `.dat` problem (or FCLIB `.hdf5` when fc3d is built with FCLIB); NULL on
/// failure. Release with `fc3d_problem_free`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_read(path: *const c_char) -> *mut Fc3dProblem {
    ffi_guard(
        "fc3d_problem_read",
        |_| null_mut(),
        || {
            if path.is_null() {
                return Err(CError::null("path"));
            }
            let path = CStr::from_ptr(path).to_string_lossy().into_owned();
            let problem = fc3d_core::io::read_problem_file(std::path::Path::new(&path))?;
            let csr = problem.w().try_to_csr()?;
            Ok(Box::into_raw(Box::new(Fc3dProblem { problem, csr })))
        },
    )
}

/// Releases a problem read by `fc3d_problem_read` (NULL is accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_free(problem: *mut Fc3dProblem) {
    ffi_guard(
        "fc3d_problem_free",
        |_| (),
        || {
            if !problem.is_null() {
                drop(Box::from_raw(problem));
            }
            Ok(())
        },
    )
}

unsafe fn problem_ref<'a>(problem: *const Fc3dProblem) -> CResult<&'a Fc3dProblem> {
    problem
        .as_ref()
        .ok_or_else(|| CError::new(FC3D_ERR_NULL_POINTER, "problem is NULL"))
}

/// Number of contacts of the problem (-1 and the last error for NULL).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_contacts(problem: *const Fc3dProblem) -> i64 {
    ffi_guard(
        "fc3d_problem_contacts",
        |_| -1,
        || Ok(problem_ref(problem)?.problem.n_contacts() as i64),
    )
}

/// Number of stored entries of W in compressed rows (-1 for NULL).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_nnz(problem: *const Fc3dProblem) -> i64 {
    ffi_guard(
        "fc3d_problem_nnz",
        |_| -1,
        || Ok(problem_ref(problem)?.csr.nnz() as i64),
    )
}

/// Copies the problem into the caller's arrays: W in compressed rows (`row_ptr`: `3nc + 1`,
/// `col_idx` and `values`: `fc3d_problem_nnz` entries), `q` (`3nc`), `mu` (`nc`). Returns 0.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_get(
    problem: *const Fc3dProblem,
    row_ptr: *mut i64,
    col_idx: *mut i64,
    values: *mut c_double,
    q: *mut c_double,
    mu: *mut c_double,
) -> c_int {
    ffi_guard(
        "fc3d_problem_get",
        |c| c,
        || {
            let p = problem_ref(problem)?;
            let (n, nnz, nc) = (p.problem.size(), p.csr.nnz(), p.problem.n_contacts());
            c_slice(row_ptr as *const i64, n + 1, "row_ptr")?;
            c_slice(col_idx as *const i64, nnz, "col_idx")?;
            c_slice(values as *const c_double, nnz, "values")?;
            c_slice(q as *const c_double, n, "q")?;
            c_slice(mu as *const c_double, nc, "mu")?;
            for (k, &v) in p.csr.row_ptr().iter().enumerate() {
                *row_ptr.add(k) = v as i64;
            }
            for (k, &v) in p.csr.col_idx().iter().enumerate() {
                *col_idx.add(k) = v as i64;
            }
            if nnz > 0 {
                std::ptr::copy_nonoverlapping(p.csr.values().as_ptr(), values, nnz);
            }
            if n > 0 {
                std::ptr::copy_nonoverlapping(p.problem.q().as_ptr(), q, n);
                std::ptr::copy_nonoverlapping(p.problem.mu().as_ptr(), mu, nc);
            }
            Ok(0)
        },
    )
}

/// Solves a problem read by `fc3d_problem_read` in the storage of its file, as
/// `fc3d_solve_dense` does.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_solve(
    problem: *const Fc3dProblem,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_problem_solve",
        |c| c,
        || {
            let p = problem_ref(problem)?;
            solve_into(&p.problem, r, u, settings, result)
        },
    )
}
