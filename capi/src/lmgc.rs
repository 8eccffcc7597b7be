//! LMGC90's entry point: W given as 3x3 blocks at 1-based block coordinates.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_int, c_uint};

use super::alloc::c_free;
use super::matrix::c_slice;
use super::option_tree::delete_contents;
use super::options::create_options;
use super::params::config_from_c;
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::matrix::{BlockSparseMatrix, Delassus};
use fc3d_core::problem::FrictionProblem;
use fc3d_core::solve;

unsafe fn lmgc_impl(
    reaction: *mut c_double,
    velocity: *mut c_double,
    q: *mut c_double,
    mu: *mut c_double,
    W: *mut c_double,
    row: *mut c_uint,
    column: *mut c_uint,
    nc: c_uint,
    nb: c_uint,
    solver_id: c_int,
    tolerance: c_double,
    itermax: c_int,
) -> CResult<c_int> {
    let (nc, nb) = (nc as usize, nb as usize);
    let n = 3 * nc;
    let qv = c_slice(q as *const c_double, n, "q")?;
    let muv = c_slice(mu as *const c_double, nc, "mu")?;
    let wv = c_slice(W as *const c_double, 9 * nb, "W")?;
    let rows = c_slice(row as *const c_uint, nb, "row")?;
    let cols = c_slice(column as *const c_uint, nb, "column")?;
    let r_in = c_slice(reaction as *const c_double, n, "reaction")?;
    c_slice(velocity as *const c_double, n, "velocity")?;

    for k in 0..nb {
        if rows[k] == 0 || rows[k] as usize > nc || cols[k] == 0 || cols[k] as usize > nc {
            return Err(CError::new(
                FC3D_ERR_INVALID_SIZE,
                format!(
                    "block {k} at 1-based ({}, {}) is outside {nc}x{nc} blocks",
                    rows[k], cols[k]
                ),
            ));
        }
    }
    // Blocks by (row, column), in input order at one place (every array allocated fallibly).
    let mut order = try_vec(nb, 0usize, "the block order")?;
    order.iter_mut().enumerate().for_each(|(k, o)| *o = k);
    order.sort_unstable_by_key(|&k| (rows[k], cols[k], k));
    let mut row_ptr = try_vec(nc + 1, 0usize, "the block rows of W")?;
    for &k in &order {
        row_ptr[rows[k] as usize] += 1;
    }
    for i in 0..nc {
        row_ptr[i + 1] += row_ptr[i];
    }
    let mut col_idx = try_vec(nb, 0usize, "the block columns of W")?;
    let mut blocks = try_vec(nb, [0.0; 9], "the blocks of W")?;
    for ((c, b), &k) in col_idx.iter_mut().zip(&mut blocks).zip(&order) {
        *c = cols[k] as usize - 1;
        b.copy_from_slice(&wv[9 * k..9 * k + 9]);
    }
    let w = BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)?;
    let problem = FrictionProblem::new(Delassus::SparseBlock(w), qv, muv)?;

    // Siconos' defaults for the solver, with the given tolerance and iteration limit.
    let options = create_options(solver_id)?;
    let config = {
        let o = &mut *options;
        *o.iparam = itermax;
        *o.dparam = tolerance;
        let c = config_from_c(o);
        delete_contents(options);
        c_free(options);
        c?
    };
    let mut r = try_copy(r_in, "the reaction")?;
    let mut u = try_vec(n, 0.0, "the velocity")?;
    let report = solve(&problem, &config, &mut r, &mut u)?;
    std::ptr::copy_nonoverlapping(r.as_ptr(), reaction, n);
    std::ptr::copy_nonoverlapping(u.as_ptr(), velocity, n);
    Ok(report.status.info_code())
}

/// LMGC90 interface: solves in place with `solver_id` (Siconos defaults otherwise), W given as
/// `nb` column-major 3x3 blocks `W[9k..9k+9]` at 1-based block coordinates `(row[k], column[k])`.
/// `verbose`, `outputFile`, `freq_output` and `ndof` are accepted and ignored (no file output).
/// Returns as `fc3d_driver`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn fc3d_LmgcDriver(
    reaction: *mut c_double,
    velocity: *mut c_double,
    q: *mut c_double,
    mu: *mut c_double,
    W: *mut c_double,
    row: *mut c_uint,
    column: *mut c_uint,
    nc: c_uint,
    nb: c_uint,
    solver_id: c_int,
    tolerance: c_double,
    itermax: c_int,
    verbose: c_int,
    outputFile: c_int,
    freq_output: c_int,
    ndof: c_int,
) -> c_int {
    let _ = (verbose, outputFile, freq_output, ndof);
    ffi_guard(
        "fc3d_LmgcDriver",
        |c| c,
        || {
            lmgc_impl(
                reaction, velocity, q, mu, W, row, column, nc, nb, solver_id, tolerance, itermax,
            )
        },
    )
}
