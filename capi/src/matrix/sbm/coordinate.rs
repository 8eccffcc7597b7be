//! Siconos' coordinate block matrices (`SparseBlockCoordinateMatrix`): the `SBCM_*` functions
//! and the sparse-block matrix made from one (`SBCM_to_SBM`, `SBM_free_from_SBCM`).

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_uint};
use std::ptr::null_mut;

use super::super::{c_slice, size_err, CBuf};
use super::{check_block_count, check_block_sizes};
use crate::alloc::c_free;
use crate::types::*;
use crate::{ffi_guard, CError, CResult};
use fc3d_core::error::try_copy;

/// Coordinate block matrix of `nbblocks` 3x3 blocks at 1-based block coordinates
/// `(row[k], column[k])`, values `block[9k..9k+9]` column-major, in an `m` x `n` grid of blocks,
/// with Siconos' ownership: `row` and `column` are copied and made 0-based, the block pointers
/// point into `block` (the caller's values, not copied), and `blocksize0`/`blocksize1` are the
/// cumulative sizes 3, 6, 9, ... (at least `nbblocks` entries, as Siconos allocates them, and
/// at least `m`/`n`, so that the grid is always described). Release with `SBCM_free_3x3` (the
/// arrays) and then `free` (the struct). NULL with `FC3D_ERR_INVALID_SIZE` when `3 m` or `3 n`
/// exceeds a C int or a coordinate is outside `1..=m` x `1..=n`, `FC3D_ERR_NULL_POINTER` for a
/// NULL array.
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
            check_block_count(m, "m (block rows)")?;
            check_block_count(n, "n (block columns)")?;
            let nb = nbblocks as usize;
            let rows = c_slice(row, nb, "row")?;
            let cols = c_slice(column, nb, "column")?;
            c_slice(block, 9 * nb, "block")?;
            for k in 0..nb {
                if rows[k] == 0 || rows[k] > m || cols[k] == 0 || cols[k] > n {
                    return Err(size_err(format!(
                        "block {k} at 1-based ({}, {}) is outside {m}x{n} blocks",
                        rows[k], cols[k]
                    )));
                }
            }
            let zero_based = |v: &[c_uint], what: &str| -> CResult<CBuf<c_uint>> {
                let mut b = CBuf::<c_uint>::zeroed(nb, what)?;
                for (d, &s) in b.as_mut_slice().iter_mut().zip(v) {
                    *d = s - 1;
                }
                Ok(b)
            };
            let row0 = zero_based(rows, "row")?;
            let col0 = zero_based(cols, "column")?;
            let mut ptrs = CBuf::<*mut c_double>::zeroed(nb, "block pointers")?;
            for (k, p) in ptrs.as_mut_slice().iter_mut().enumerate() {
                *p = block.add(9 * k);
            }
            let cumulative = |count: usize, what: &str| -> CResult<CBuf<c_uint>> {
                let mut bs = CBuf::<c_uint>::zeroed(count, what)?;
                for (k, v) in bs.as_mut_slice().iter_mut().enumerate() {
                    // count <= max(nbblocks, m or n): 3 (k + 1) fits when it is a grid size;
                    // past the grid (more blocks than rows) the sizes only need to increase.
                    *v = (3 * (k as u64 + 1)).min(c_uint::MAX as u64) as c_uint;
                }
                Ok(bs)
            };
            let bs0 = cumulative(nb.max(m as usize), "blocksize0")?;
            let bs1 = cumulative(nb.max(n as usize), "blocksize1")?;
            let out =
                CBuf::<SparseBlockCoordinateMatrix>::zeroed(1, "coordinate matrix")?.into_raw();
            out.write(SparseBlockCoordinateMatrix {
                nbblocks,
                blocknumber0: m,
                blocknumber1: n,
                block: ptrs.into_raw(),
                blocksize0: bs0.into_raw(),
                blocksize1: bs1.into_raw(),
                row: row0.into_raw(),
                column: col0.into_raw(),
            });
            Ok(out)
        },
    )
}

/// Frees the arrays `SBCM_new_3x3` allocated (`block`, `blocksize0`, `blocksize1`, `row`,
/// `column`), not the struct itself (the caller frees it, as in Siconos) nor the block values.
/// An SBM made by `SBCM_to_SBM` shares `blocksize0`/`blocksize1`: release it first. NULL is a
/// no-op.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBCM_free_3x3(MC: *mut SparseBlockCoordinateMatrix) {
    ffi_guard(
        "SBCM_free_3x3",
        |_| (),
        || {
            if let Some(mc) = MC.as_mut() {
                c_free(mc.block);
                c_free(mc.blocksize0);
                c_free(mc.blocksize1);
                c_free(mc.row);
                c_free(mc.column);
                mc.block = null_mut();
                mc.blocksize0 = null_mut();
                mc.blocksize1 = null_mut();
                mc.row = null_mut();
                mc.column = null_mut();
            }
            Ok(())
        },
    )
}

/// A sparse-block matrix (block-CSR) built from the coordinate matrix as Siconos builds it:
/// blocks grouped by block row in their coordinate order (columns are not sorted within a row),
/// `blocksize0`/`blocksize1` and the block pointers shared with `MC` (nothing copied),
/// `index1_data` (`blocknumber0 + 1` entries), `index2_data` and the block-pointer array
/// allocated, `filled1` one past the last block row that holds a block (at least 2), no
/// `diagonal_blocks`. Release with `SBM_free_from_SBCM` (or `free` of `index1_data`,
/// `index2_data`, `block` and the struct) before `SBCM_free_3x3`. Checks what a host may have
/// changed in `MC`: NULL arrays and block pointers, cumulative sizes that do not increase,
/// 0-based coordinates outside the grid (NULL and a code).
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
            let (nbr, nbc) = (mc.blocknumber0 as usize, mc.blocknumber1 as usize);
            let rows = c_slice(mc.row, nb, "row")?;
            let cols = c_slice(mc.column, nb, "column")?;
            let ptrs = c_slice(mc.block as *const *mut c_double, nb, "block")?;
            check_block_sizes(c_slice(mc.blocksize0, nbr, "blocksize0")?, "blocksize0")?;
            check_block_sizes(c_slice(mc.blocksize1, nbc, "blocksize1")?, "blocksize1")?;
            for k in 0..nb {
                let (r, c) = (rows[k] as usize, cols[k] as usize);
                if r >= nbr || c >= nbc {
                    return Err(size_err(format!(
                        "block {k} at 0-based ({r}, {c}) is outside {nbr}x{nbc} blocks"
                    )));
                }
                if ptrs[k].is_null() {
                    return Err(CError::null(&format!("block {k}")));
                }
            }
            // Counting sort by block row: stable, so a row keeps its blocks in coordinate order.
            let mut row_ptr = CBuf::<usize>::zeroed(nbr + 1, "index1_data")?;
            let rp = row_ptr.as_mut_slice();
            for &r in rows {
                rp[r as usize + 1] += 1;
            }
            for i in 0..nbr {
                rp[i + 1] += rp[i];
            }
            let mut next = try_copy(&rp[..nbr], "block row cursors")?;
            let mut col_idx = CBuf::<usize>::zeroed(nb, "index2_data")?;
            let mut grouped = CBuf::<*mut c_double>::zeroed(nb, "block array")?;
            let (ci, gb) = (col_idx.as_mut_slice(), grouped.as_mut_slice());
            for k in 0..nb {
                let dest = &mut next[rows[k] as usize];
                ci[*dest] = cols[k] as usize;
                gb[*dest] = ptrs[k];
                *dest += 1;
            }
            let filled1 = rows
                .iter()
                .map(|&r| r as usize + 2)
                .max()
                .unwrap_or(2)
                .max(2);
            let out = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "SBM")?.into_raw();
            out.write(SparseBlockStructuredMatrix {
                nbblocks: mc.nbblocks,
                block: grouped.into_raw(),
                blocknumber0: mc.blocknumber0,
                blocknumber1: mc.blocknumber1,
                blocksize0: mc.blocksize0,
                blocksize1: mc.blocksize1,
                filled1,
                filled2: nb,
                index1_data: row_ptr.into_raw(),
                index2_data: col_idx.into_raw(),
                diagonal_blocks: null_mut(),
                version: NumericsDataVersion::default(),
            });
            Ok(out)
        },
    )
}

/// Frees an SBM made by `SBCM_to_SBM`: its `index1_data`, `index2_data`, block-pointer array
/// and the struct, not what it shares with the coordinate matrix (`blocksize0`, `blocksize1`,
/// the block values). NULL is a no-op.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBM_free_from_SBCM(M: *mut SparseBlockStructuredMatrix) {
    ffi_guard(
        "SBM_free_from_SBCM",
        |_| (),
        || {
            if let Some(m) = M.as_mut() {
                c_free(m.index1_data);
                c_free(m.index2_data);
                c_free(m.block);
                c_free(M);
            }
            Ok(())
        },
    )
}
