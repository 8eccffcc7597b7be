//! Solving from plain arrays (`fc3d_solve_*`): W dense, in compressed rows, in coordinates or
//! in 3x3 blocks, copied into fc3d's storage; r, u and the result written only on success.

use std::os::raw::{c_double, c_int};
use std::time::Instant;

use super::settings::release_options;
use super::{Fc3dResult, Fc3dSettings};
use crate::matrix::c_slice;
use crate::options::create_options;
use crate::params::config_from_c;
use crate::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::{
    solve, BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix, FrictionProblem, SolverConfig,
};

pub(super) fn count(v: i64, what: &str) -> CResult<usize> {
    usize::try_from(v)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, format!("{what} = {v} is negative")))
}

/// `3 n_contacts`, checked.
pub(super) fn size_of(n_contacts: i64) -> CResult<(usize, usize)> {
    let nc = count(n_contacts, "n_contacts")?;
    let n = nc.checked_mul(3).ok_or_else(|| {
        CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("n_contacts = {nc} is too large"),
        )
    })?;
    Ok((nc, n))
}

pub(super) fn indices(v: &[i64], what: &str) -> CResult<Vec<usize>> {
    let mut out = try_vec(v.len(), 0, what)?;
    for (o, &x) in out.iter_mut().zip(v) {
        *o = count(x, what)?;
    }
    Ok(out)
}

/// Solves `problem` from `r` with `settings` (NULL: NSGS with Siconos' defaults), writing r, u
/// and the result only on success.
pub(super) unsafe fn solve_into(
    problem: &FrictionProblem<'_>,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> CResult<c_int> {
    if result.is_null() {
        return Err(CError::null("result"));
    }
    let n = problem.size();
    let r_in = c_slice(r as *const c_double, n, "r")?;
    c_slice(u as *const c_double, n, "u")?;
    let config = settings_config(settings)?;
    let mut rr = try_copy(r_in, "r")?;
    let mut uu = try_vec(n, 0.0, "u")?;
    let start = Instant::now();
    let report = solve(problem, &config, &mut rr, &mut uu)?;
    let seconds = start.elapsed().as_secs_f64();
    if n > 0 {
        std::ptr::copy_nonoverlapping(rr.as_ptr(), r, n);
        std::ptr::copy_nonoverlapping(uu.as_ptr(), u, n);
    }
    *result = Fc3dResult {
        info: report.status.info_code(),
        iterations: i64::try_from(report.iterations).unwrap_or(i64::MAX),
        error: report.error,
        seconds,
    };
    if verbose() > 0 {
        eprintln!(
            "fc3d: {} on {} contacts: {:?} after {} iterations, error {:e}",
            config.label(),
            problem.n_contacts(),
            report.status,
            report.iterations,
            report.error
        );
        crate::driver::print_fill(&report);
    }
    Ok(report.status.info_code())
}

/// The configuration `settings` describe (NULL: NSGS with Siconos' defaults), checked; for the
/// solves here and for libraries built on this one (fc3d-mpi).
///
/// # Safety
/// `settings` is NULL or made by `fc3d_settings_new` and not yet freed.
pub unsafe fn settings_config(settings: *const Fc3dSettings) -> CResult<SolverConfig> {
    if settings.is_null() {
        let o = create_options(500)?;
        let c = config_from_c(&*o);
        release_options(o);
        c
    } else {
        config_from_c(&*(*settings).options)
    }
}

unsafe fn problem_from(
    w: Delassus<'static>,
    nc: usize,
    q: *const c_double,
    mu: *const c_double,
) -> CResult<FrictionProblem<'static>> {
    let q = try_copy(c_slice(q, 3 * nc, "q")?, "q")?;
    let mu = try_copy(c_slice(mu, nc, "mu")?, "mu")?;
    Ok(FrictionProblem::new(w, q, mu)?)
}

/// Solves FC(W, q, mu) with W dense, column-major `3nc x 3nc`. `r` holds the initial reaction and
/// receives the result, `u` receives `W r + q`; `settings` may be NULL (NSGS, Siconos'
/// defaults). Returns the result's `info` (0..3) or a negative `FC3D_ERR_*` code.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_dense(
    n_contacts: i64,
    w: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_dense",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let len = n.checked_mul(n).ok_or_else(|| {
                CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("a dense W of {n} rows is too large"),
                )
            })?;
            let values = try_copy(c_slice(w, len, "W")?, "W")?;
            let w = Delassus::Dense(DenseMatrix::new(n, n, values)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W in compressed rows: `row_ptr` (`3nc + 1` entries), `col_idx`
/// and `values` (`nnz` entries each, 0-based; unsorted columns and duplicates are accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_csr(
    n_contacts: i64,
    nnz: i64,
    row_ptr: *const i64,
    col_idx: *const i64,
    values: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_csr",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let nnz = count(nnz, "nnz")?;
            let row_ptr = indices(c_slice(row_ptr, n + 1, "row_ptr")?, "row_ptr")?;
            let col_idx = indices(c_slice(col_idx, nnz, "col_idx")?, "col_idx")?;
            let values = c_slice(values, nnz, "values")?;
            if row_ptr[n] != nnz {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("row_ptr[{n}] = {} but nnz = {nnz}", row_ptr[n]),
                ));
            }
            let w = Delassus::Sparse(CsrMatrix::from_csr(n, n, &row_ptr, &col_idx, values)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W as `nnz` triplets `(rows[k], cols[k], values[k])` (0-based, any
/// order, duplicates summed).
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_coo(
    n_contacts: i64,
    nnz: i64,
    rows: *const i64,
    cols: *const i64,
    values: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_coo",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let nnz = count(nnz, "nnz")?;
            let rows = indices(c_slice(rows, nnz, "rows")?, "rows")?;
            let cols = indices(c_slice(cols, nnz, "cols")?, "cols")?;
            let values = c_slice(values, nnz, "values")?;
            let mut triplets = try_vec(nnz, (0, 0, 0.0), "the entries of W")?;
            for (t, ((&i, &j), &v)) in triplets.iter_mut().zip(rows.iter().zip(&cols).zip(values)) {
                *t = (i, j, v);
            }
            let w = Delassus::Sparse(CsrMatrix::from_triplets(n, n, &triplets)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W as `n_blocks` 3x3 blocks in block-compressed rows:
/// `block_row_ptr` (`nc + 1` entries), `block_col_idx` (`n_blocks`, 0-based) and `blocks`
/// (`9 n_blocks` values, each block column-major). Every diagonal block must be present.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_blocks(
    n_contacts: i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_idx: *const i64,
    blocks: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_blocks",
        |c| c,
        || {
            let (nc, _) = size_of(n_contacts)?;
            let nb = count(n_blocks, "n_blocks")?;
            let row_ptr = indices(
                c_slice(block_row_ptr, nc + 1, "block_row_ptr")?,
                "block_row_ptr",
            )?;
            let col_idx = indices(
                c_slice(block_col_idx, nb, "block_col_idx")?,
                "block_col_idx",
            )?;
            let len = nb.checked_mul(9).ok_or_else(|| {
                CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("n_blocks = {nb} is too large"),
                )
            })?;
            let values = c_slice(blocks, len, "blocks")?;
            let mut blocks = try_vec(nb, [0.0; 9], "the blocks of W")?;
            for (a, b) in blocks.iter_mut().zip(values.chunks_exact(9)) {
                a.copy_from_slice(b);
            }
            let w =
                Delassus::SparseBlock(BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}
