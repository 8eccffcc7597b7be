//! Sparse-block matrices (`SparseBlockStructuredMatrix`, `SparseBlockCoordinateMatrix`):
//! conversion to and from the core's `BlockSparseMatrix`, release, and the `SBM_*` / `SBCM_*`
//! functions of Siconos' API.

use std::os::raw::{c_double, c_uint};
use std::ptr::null_mut;

use super::{c_slice, storage_err};
use crate::alloc::{c_box, c_calloc, c_copy, c_free};
use crate::types::*;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::matrix::BlockSparseMatrix;

/// Validated block-sparse core copy of a Siconos SBM with uniform 3x3 blocks.
pub(super) unsafe fn block_sparse_from_sbm(
    s: &SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
) -> CResult<BlockSparseMatrix> {
    let (nbr, nbc) = (s.blocknumber0 as usize, s.blocknumber1 as usize);
    if 3 * nbr != rows || 3 * nbc != cols {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("sparse-block matrix has {nbr}x{nbc} blocks but the NumericsMatrix is {rows}x{cols} (fc3d needs 3x3 blocks)"),
        ));
    }
    let bs0 = c_slice(s.blocksize0, nbr, "SBM blocksize0")?;
    let bs1 = c_slice(s.blocksize1, nbc, "SBM blocksize1")?;
    for (k, &v) in bs0.iter().chain(bs1.iter()).enumerate() {
        let expected = 3 * ((if k < nbr { k } else { k - nbr }) + 1);
        if v as usize != expected {
            return Err(storage_err(format!(
                "sparse-block matrix blocks must all be 3x3 (cumulative sizes 3, 6, 9, ...): found {v} where {expected} was expected"
            )));
        }
    }
    if s.filled1 != nbr + 1 {
        return Err(storage_err(format!(
            "SBM filled1 = {} but blocknumber0 + 1 = {}",
            s.filled1,
            nbr + 1
        )));
    }
    let row_ptr = c_slice(s.index1_data, s.filled1, "SBM index1_data")?.to_vec();
    let nb = *row_ptr.last().unwrap_or(&0);
    if nb != s.filled2 || nb != s.nbblocks as usize {
        return Err(storage_err(format!(
            "SBM block counts disagree: index1_data ends at {nb}, filled2 = {}, nbblocks = {}",
            s.filled2, s.nbblocks
        )));
    }
    let col_idx = c_slice(s.index2_data, nb, "SBM index2_data")?.to_vec();
    let ptrs = c_slice(s.block as *const *mut c_double, nb, "SBM block array")?;
    let mut blocks = Vec::with_capacity(nb);
    for (k, &bp) in ptrs.iter().enumerate() {
        let b = c_slice(bp as *const c_double, 9, &format!("SBM block {k}"))?;
        let mut a = [0.0; 9];
        a.copy_from_slice(b);
        blocks.push(a);
    }
    Ok(BlockSparseMatrix::new(nbr, nbc, row_ptr, col_idx, blocks)?)
}

// ---------------------------------------------------------------------------------------------
// Building C matrices from core ones.

/// A C-allocated SBM copy of a core block-sparse matrix (blocks malloc'd one by one, as Siconos).
pub(crate) fn sbm_to_c(b: &BlockSparseMatrix) -> CResult<*mut SparseBlockStructuredMatrix> {
    let nb = b.n_blocks();
    let block = c_calloc::<*mut c_double>(nb)?;
    for (k, v) in b.blocks().iter().enumerate() {
        // SAFETY: block has nb slots.
        unsafe { *block.add(k) = c_copy(v)? };
    }
    let bs0: Vec<c_uint> = (1..=b.n_block_rows()).map(|i| 3 * i as c_uint).collect();
    let bs1: Vec<c_uint> = (1..=b.n_block_cols()).map(|i| 3 * i as c_uint).collect();
    let diag: Vec<c_uint> = (0..b.n_block_rows())
        .map(|i| {
            (b.row_ptr()[i]..b.row_ptr()[i + 1])
                .find(|&k| b.col_idx()[k] == i)
                .map_or(c_uint::MAX, |k| k as c_uint)
        })
        .collect();
    c_box(SparseBlockStructuredMatrix {
        nbblocks: nb as c_uint,
        block,
        blocknumber0: b.n_block_rows() as c_uint,
        blocknumber1: b.n_block_cols() as c_uint,
        blocksize0: c_copy(&bs0)?,
        blocksize1: c_copy(&bs1)?,
        filled1: b.n_block_rows() + 1,
        filled2: nb,
        index1_data: c_copy(b.row_ptr())?,
        index2_data: c_copy(b.col_idx())?,
        diagonal_blocks: c_copy(&diag)?,
        version: NumericsDataVersion::default(),
    })
}

pub(super) fn empty_sbm() -> SparseBlockStructuredMatrix {
    SparseBlockStructuredMatrix {
        nbblocks: 0,
        block: null_mut(),
        blocknumber0: 0,
        blocknumber1: 0,
        blocksize0: null_mut(),
        blocksize1: null_mut(),
        filled1: 0,
        filled2: 0,
        index1_data: null_mut(),
        index2_data: null_mut(),
        diagonal_blocks: null_mut(),
        version: NumericsDataVersion::default(),
    }
}

// ---------------------------------------------------------------------------------------------
// Releasing.

pub(super) unsafe fn sbm_clear_impl(s: *mut SparseBlockStructuredMatrix, free_blocks: bool) {
    if s.is_null() {
        return;
    }
    let s = &mut *s;
    if !s.block.is_null() {
        if free_blocks {
            for k in 0..s.nbblocks as usize {
                c_free(*s.block.add(k));
            }
        }
        c_free(s.block);
    }
    c_free(s.blocksize0);
    c_free(s.blocksize1);
    c_free(s.index1_data);
    c_free(s.index2_data);
    c_free(s.diagonal_blocks);
    s.block = null_mut();
    s.blocksize0 = null_mut();
    s.blocksize1 = null_mut();
    s.index1_data = null_mut();
    s.index2_data = null_mut();
    s.diagonal_blocks = null_mut();
    s.nbblocks = 0;
    s.filled1 = 0;
    s.filled2 = 0;
}

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// A new empty sparse-block structure. Release with `SBM_clear` + `free`, or through `NM_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn SBM_new() -> *mut SparseBlockStructuredMatrix {
    ffi_guard("SBM_new", |_| null_mut(), || c_box(empty_sbm()))
}

/// Frees the blocks and index arrays of `blmat` (not the struct).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBM_clear(blmat: *mut SparseBlockStructuredMatrix) {
    ffi_guard(
        "SBM_clear",
        |_| (),
        || {
            sbm_clear_impl(blmat, true);
            Ok(())
        },
    )
}

/// Coordinate block matrix of `nbblocks` 3x3 blocks at 1-based block coordinates
/// `(row[k], column[k])`, values `block[9k..9k+9]` column-major. Keeps `row`, `column` and
/// `block` without copying (they stay the caller's); release with `SBCM_free_3x3`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBCM_new_3x3(
    m: c_uint,
    n: c_uint,
    nbblocks: c_uint,
    row: *mut c_uint,
    column: *mut c_uint,
    block: *mut c_double,
) -> *mut SparseBlockCoordinateMatrix {
    ffi_guard(
        "SBCM_new_3x3",
        |_| null_mut(),
        || {
            let nb = nbblocks as usize;
            let rows = c_slice(row, nb, "row")?;
            let cols = c_slice(column, nb, "column")?;
            c_slice(block, 9 * nb, "block")?;
            for k in 0..nb {
                if rows[k] == 0 || rows[k] > m || cols[k] == 0 || cols[k] > n {
                    return Err(CError::new(
                        FC3D_ERR_INVALID_SIZE,
                        format!(
                            "block {k} at 1-based ({}, {}) is outside {m}x{n} blocks",
                            rows[k], cols[k]
                        ),
                    ));
                }
            }
            let ptrs = c_calloc::<*mut c_double>(nb)?;
            for k in 0..nb {
                *ptrs.add(k) = block.add(9 * k);
            }
            let bs0: Vec<c_uint> = (1..=m).map(|i| 3 * i).collect();
            let bs1: Vec<c_uint> = (1..=n).map(|i| 3 * i).collect();
            c_box(SparseBlockCoordinateMatrix {
                nbblocks,
                blocknumber0: m,
                blocknumber1: n,
                block: ptrs,
                blocksize0: c_copy(&bs0)?,
                blocksize1: c_copy(&bs1)?,
                row,
                column,
            })
        },
    )
}

/// Frees what `SBCM_new_3x3` allocated (not the caller's row, column and block arrays).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBCM_free_3x3(MC: *mut SparseBlockCoordinateMatrix) {
    ffi_guard(
        "SBCM_free_3x3",
        |_| (),
        || {
            if !MC.is_null() {
                c_free((*MC).block);
                c_free((*MC).blocksize0);
                c_free((*MC).blocksize1);
                c_free(MC);
            }
            Ok(())
        },
    )
}

/// A sparse-block matrix (block-CSR, sorted) whose blocks point into the coordinate matrix's
/// values (no copy). Release with `SBM_free_from_SBCM` before the coordinate data goes away.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBCM_to_SBM(
    MC: *mut SparseBlockCoordinateMatrix,
) -> *mut SparseBlockStructuredMatrix {
    ffi_guard(
        "SBCM_to_SBM",
        |_| null_mut(),
        || {
            if MC.is_null() {
                return Err(CError::null("MC"));
            }
            let mc = &*MC;
            let nb = mc.nbblocks as usize;
            let rows = c_slice(mc.row, nb, "row")?;
            let cols = c_slice(mc.column, nb, "column")?;
            let ptrs = c_slice(mc.block as *const *mut c_double, nb, "block")?;
            let mut order: Vec<usize> = (0..nb).collect();
            order.sort_by_key(|&k| (rows[k], cols[k]));
            let nbr = mc.blocknumber0 as usize;
            let mut row_ptr = vec![0usize; nbr + 1];
            for &k in &order {
                let r = rows[k] as usize;
                if r == 0 || r > nbr {
                    return Err(CError::new(
                        FC3D_ERR_INVALID_SIZE,
                        format!("block row {r} outside 1..={nbr}"),
                    ));
                }
                row_ptr[r] += 1;
            }
            for i in 0..nbr {
                row_ptr[i + 1] += row_ptr[i];
            }
            let col_idx: Vec<usize> = order.iter().map(|&k| cols[k] as usize - 1).collect();
            let sorted: Vec<*mut c_double> = order.iter().map(|&k| ptrs[k]).collect();
            let diag: Vec<c_uint> = (0..nbr)
                .map(|i| {
                    (row_ptr[i]..row_ptr[i + 1])
                        .find(|&k| col_idx[k] == i)
                        .map_or(c_uint::MAX, |k| k as c_uint)
                })
                .collect();
            c_box(SparseBlockStructuredMatrix {
                nbblocks: mc.nbblocks,
                block: c_copy(&sorted)?,
                blocknumber0: mc.blocknumber0,
                blocknumber1: mc.blocknumber1,
                blocksize0: c_copy(c_slice(mc.blocksize0, nbr, "blocksize0")?)?,
                blocksize1: c_copy(c_slice(
                    mc.blocksize1,
                    mc.blocknumber1 as usize,
                    "blocksize1",
                )?)?,
                filled1: nbr + 1,
                filled2: nb,
                index1_data: c_copy(&row_ptr)?,
                index2_data: c_copy(&col_idx)?,
                diagonal_blocks: c_copy(&diag)?,
                version: NumericsDataVersion::default(),
            })
        },
    )
}

/// Frees an SBM made by `SBCM_to_SBM` (structure and struct, not the block values).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBM_free_from_SBCM(M: *mut SparseBlockStructuredMatrix) {
    ffi_guard(
        "SBM_free_from_SBCM",
        |_| (),
        || {
            sbm_clear_impl(M, false);
            c_free(M);
            Ok(())
        },
    )
}
