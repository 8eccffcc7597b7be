//! Solving the global problem from plain arrays (`fc3d_solve_global_*`): M and H in compressed
//! rows, in coordinates, or M as dense diagonal blocks of a size the host gives, copied into
//! fc3d's storage; r, u, v and the result written only on success.

use std::os::raw::{c_double, c_int};
use std::time::Instant;

use super::settings::{is_global_id, release_options};
use super::solve::{count, indices, size_of};
use super::{Fc3dResult, Fc3dSettings};
use crate::matrix::c_slice;
use crate::options::create_options;
use crate::params::global::global_config_from_c;
use crate::{
    ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_SIZE, FC3D_ERR_UNSUPPORTED_SOLVER,
};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::global::{solve_global, GlobalConfig, GlobalProblem};
use fc3d_core::CsrMatrix;

/// The solver a NULL settings stands for: 600 (NSGS on the reduced problem, Siconos' defaults),
/// as NULL means NSGS (500) for the local solves.
const DEFAULT_GLOBAL_ID: c_int = 600;

/// The configuration of `settings` (NULL: [`DEFAULT_GLOBAL_ID`]); a local id is refused.
unsafe fn global_config(settings: *const Fc3dSettings) -> CResult<GlobalConfig> {
    if settings.is_null() {
        let o = create_options(DEFAULT_GLOBAL_ID)?;
        let c = global_config_from_c(&*o);
        release_options(o);
        return c;
    }
    let o = &*(*settings).options;
    if !is_global_id(o.solverId) {
        return Err(CError::new(
            FC3D_ERR_UNSUPPORTED_SOLVER,
            format!(
                "solver id {} is not a global solver: fc3d_solve_global_* run the ids 600-615 \
                 (600 NSGS_WR, 605 GFC3D_NSGS, 607 GFC3D_NSN_AC, 613 ADMM, 615 IPM, ...); the \
                 local solves take the local ids",
                o.solverId
            ),
        ));
    }
    global_config_from_c(o)
}

/// Solves `problem` from `r` with `settings`, writing r, u, v and the result only on success.
unsafe fn solve_global_into(
    problem: &GlobalProblem<'_>,
    r: *mut c_double,
    u: *mut c_double,
    v: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> CResult<c_int> {
    if result.is_null() {
        return Err(CError::null("result"));
    }
    let (n, ndof) = (problem.size(), problem.ndof());
    let r_in = c_slice(r as *const c_double, n, "r")?;
    c_slice(u as *const c_double, n, "u")?;
    c_slice(v as *const c_double, ndof, "v")?;
    let config = global_config(settings)?;
    let mut rr = try_copy(r_in, "r")?;
    let mut uu = try_vec(n, 0.0, "u")?;
    let mut vv = try_vec(ndof, 0.0, "v")?;
    let start = Instant::now();
    let report = solve_global(problem, &config, &mut rr, &mut uu, &mut vv)?;
    let seconds = start.elapsed().as_secs_f64();
    if n > 0 {
        std::ptr::copy_nonoverlapping(rr.as_ptr(), r, n);
        std::ptr::copy_nonoverlapping(uu.as_ptr(), u, n);
    }
    if ndof > 0 {
        std::ptr::copy_nonoverlapping(vv.as_ptr(), v, ndof);
    }
    *result = Fc3dResult {
        info: report.status.info_code(),
        iterations: i64::try_from(report.iterations).unwrap_or(i64::MAX),
        error: report.error,
        seconds,
    };
    if verbose() > 0 {
        eprintln!(
            "fc3d: {} on {} contacts, {} unknowns: {:?} after {} iterations, global error {:e}",
            config.method.label(),
            problem.n_contacts(),
            ndof,
            report.status,
            report.iterations,
            report.error
        );
    }
    Ok(report.status.info_code())
}

/// The problem of M and H (already built) and the host's q, b, mu, copied.
unsafe fn global_problem(
    m: CsrMatrix,
    h: CsrMatrix,
    nc: usize,
    q: *const c_double,
    b: *const c_double,
    mu: *const c_double,
) -> CResult<GlobalProblem<'static>> {
    let ndof = m.nrows();
    let q = try_copy(c_slice(q, ndof, "q")?, "q")?;
    let b = try_copy(c_slice(b, 3 * nc, "b")?, "b")?;
    let mu = try_copy(c_slice(mu, nc, "mu")?, "mu")?;
    Ok(GlobalProblem::new(m, h, q, b, mu)?)
}

/// A matrix of `rows x cols` in compressed rows from the host's arrays, checked.
unsafe fn csr_of(
    rows: usize,
    cols: usize,
    nnz: i64,
    row_ptr: *const i64,
    col_idx: *const i64,
    values: *const c_double,
    name: &str,
) -> CResult<CsrMatrix> {
    let nnz = count(nnz, &format!("{name}_nnz"))?;
    let ptr_name = format!("{name}_row_ptr");
    let idx_name = format!("{name}_col_idx");
    let row_ptr = indices(c_slice(row_ptr, rows + 1, &ptr_name)?, &ptr_name)?;
    let col_idx = indices(c_slice(col_idx, nnz, &idx_name)?, &idx_name)?;
    let values = c_slice(values, nnz, &format!("{name}_values"))?;
    if row_ptr[rows] != nnz {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!(
                "{ptr_name}[{rows}] = {} but {name}_nnz = {nnz}",
                row_ptr[rows]
            ),
        ));
    }
    Ok(CsrMatrix::from_csr(rows, cols, &row_ptr, &col_idx, values)?)
}

/// A matrix of `rows x cols` from the host's triplets, checked (duplicates summed).
unsafe fn coo_of(
    rows: usize,
    cols: usize,
    nnz: i64,
    row_idx: *const i64,
    col_idx: *const i64,
    values: *const c_double,
    name: &str,
) -> CResult<CsrMatrix> {
    let nnz = count(nnz, &format!("{name}_nnz"))?;
    let (rn, cn) = (format!("{name}_rows"), format!("{name}_cols"));
    let row_idx = indices(c_slice(row_idx, nnz, &rn)?, &rn)?;
    let col_idx = indices(c_slice(col_idx, nnz, &cn)?, &cn)?;
    let values = c_slice(values, nnz, &format!("{name}_values"))?;
    let mut triplets = try_vec(nnz, (0, 0, 0.0), &format!("the entries of {name}"))?;
    for (t, ((&i, &j), &x)) in triplets
        .iter_mut()
        .zip(row_idx.iter().zip(&col_idx).zip(values))
    {
        *t = (i, j, x);
    }
    Ok(CsrMatrix::from_triplets(rows, cols, &triplets)?)
}

/// Solves the global problem: find the global velocity v (`ndof`), the local velocity u and the
/// reaction r (`3 n_contacts` each) with `M v = q + H r`, `u = H^T v + b` and Coulomb's law
/// between u and r at each contact (Siconos' `gfc3d_driver`). M (`ndof x ndof`, invertible) and
/// H (`ndof x 3 n_contacts`) are in compressed rows: `m_row_ptr` (`ndof + 1` entries),
/// `m_col_idx` and `m_values` (`m_nnz` each, 0-based; unsorted columns and duplicates are
/// accepted), and the same for H. `q` has `ndof` entries, `b` `3 n_contacts`, `mu` `n_contacts`.
/// `r` holds the initial reaction and receives the result, `u` and `v` receive theirs (v solves
/// `M v = q + H r` to round-off). `settings` may be NULL (600, NSGS on the reduced problem, with
/// Siconos' defaults) or of a global id 600-615. M and H are never modified. Returns the
/// result's `info` (0..3) or a negative `FC3D_ERR_*` code; `result->error` is Siconos' global
/// error of the returned `(r, u, v)`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_global_csr(
    ndof: i64,
    n_contacts: i64,
    m_nnz: i64,
    m_row_ptr: *const i64,
    m_col_idx: *const i64,
    m_values: *const c_double,
    h_nnz: i64,
    h_row_ptr: *const i64,
    h_col_idx: *const i64,
    h_values: *const c_double,
    q: *const c_double,
    b: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    v: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_global_csr",
        |c| c,
        || {
            let n = count(ndof, "ndof")?;
            let (nc, m3) = size_of(n_contacts)?;
            let m = csr_of(n, n, m_nnz, m_row_ptr, m_col_idx, m_values, "m")?;
            let h = csr_of(n, m3, h_nnz, h_row_ptr, h_col_idx, h_values, "h")?;
            let p = global_problem(m, h, nc, q, b, mu)?;
            solve_global_into(&p, r, u, v, settings, result)
        },
    )
}

/// As `fc3d_solve_global_csr` with M and H as triplets: `(m_rows[k], m_cols[k], m_values[k])`
/// for `k < m_nnz`, the same for H (0-based, any order, duplicates summed).
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_global_coo(
    ndof: i64,
    n_contacts: i64,
    m_nnz: i64,
    m_rows: *const i64,
    m_cols: *const i64,
    m_values: *const c_double,
    h_nnz: i64,
    h_rows: *const i64,
    h_cols: *const i64,
    h_values: *const c_double,
    q: *const c_double,
    b: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    v: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_global_coo",
        |c| c,
        || {
            let n = count(ndof, "ndof")?;
            let (nc, m3) = size_of(n_contacts)?;
            let m = coo_of(n, n, m_nnz, m_rows, m_cols, m_values, "m")?;
            let h = coo_of(n, m3, h_nnz, h_rows, h_cols, h_values, "h")?;
            let p = global_problem(m, h, nc, q, b, mu)?;
            solve_global_into(&p, r, u, v, settings, result)
        },
    )
}

/// As `fc3d_solve_global_csr` with M block diagonal, given as `n_blocks` dense blocks of
/// `block_size x block_size` (column-major, one after the other: `n_blocks * block_size^2`
/// values; `ndof = n_blocks * block_size`), as a rigid-body host stores its masses (6 a body);
/// H in compressed rows as there.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_global_blocks(
    n_blocks: i64,
    block_size: i64,
    m_blocks: *const c_double,
    n_contacts: i64,
    h_nnz: i64,
    h_row_ptr: *const i64,
    h_col_idx: *const i64,
    h_values: *const c_double,
    q: *const c_double,
    b: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    v: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_global_blocks",
        |c| c,
        || {
            let nb = count(n_blocks, "n_blocks")?;
            let bs = count(block_size, "block_size")?;
            let too_large = || {
                CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("{nb} blocks of size {bs} are too large"),
                )
            };
            let n = nb.checked_mul(bs).ok_or_else(too_large)?;
            let per_block = bs.checked_mul(bs).ok_or_else(too_large)?;
            let len = nb.checked_mul(per_block).ok_or_else(too_large)?;
            let values = c_slice(m_blocks, len, "m_blocks")?;
            let mut triplets = try_vec(len, (0, 0, 0.0), "the entries of M")?;
            for (k, (t, &x)) in triplets.iter_mut().zip(values).enumerate() {
                // Entry (i, j) of block `block`, column-major.
                let (block, within) = (k / per_block, k % per_block);
                let (i, j) = (within % bs, within / bs);
                *t = (block * bs + i, block * bs + j, x);
            }
            // Exact zeros are dropped by the pattern: the blocks found are M's own.
            triplets.retain(|t| t.2 != 0.0);
            let m = CsrMatrix::from_triplets(n, n, &triplets)?;
            drop(triplets);
            let (nc, m3) = size_of(n_contacts)?;
            let h = csr_of(n, m3, h_nnz, h_row_ptr, h_col_idx, h_values, "h")?;
            let p = global_problem(m, h, nc, q, b, mu)?;
            solve_global_into(&p, r, u, v, settings, result)
        },
    )
}
