//! Sparse-block matrices fc3d allocates with the C allocator: built from the core's
//! `BlockSparseMatrix` or from a reader's arrays, duplicated, released; Siconos' `SBM_new` and
//! `SBM_clear`.

#![allow(non_snake_case)]

use std::os::raw::{c_double, c_uint};
use std::ptr::null_mut;

use super::super::{c_slice, check_heap_len, size_err, storage_err, CBuf};
use crate::alloc::{c_free, CArray, CBlocks};
use crate::types::*;
use crate::{ffi_guard, CResult};
use fc3d_core::matrix::BlockSparseMatrix;

// ---------------------------------------------------------------------------------------------
// Building C matrices from core ones.

/// A C-allocated SBM copy of a core block-sparse matrix (blocks malloc'd one by one, as
/// Siconos); nothing is left allocated on failure.
pub(crate) fn sbm_to_c(b: &BlockSparseMatrix) -> CResult<*mut SparseBlockStructuredMatrix> {
    let row_ptr = CArray::copy(b.row_ptr(), "SBM index1_data")?;
    let col_idx = CArray::copy(b.col_idx(), "SBM index2_data")?;
    let mut blocks = CBlocks::with_capacity(b.n_blocks(), "SBM blocks")?;
    for v in b.blocks() {
        blocks.push(v, "SBM blocks")?;
    }
    sbm_from_parts(b.n_block_rows(), b.n_block_cols(), row_ptr, col_idx, blocks)
}

/// The C SBM of `nbr x nbc` 3x3 blocks made of the given arrays, handed over to it as they are
/// (no copy: a reader fills them where the host will own them); the block sizes are added. The structure must be consistent (`row_ptr`: `nbr + 1` non-decreasing
/// entries from 0 to the number of blocks, block columns below `nbc`). On failure everything
/// given is freed.
pub(crate) fn sbm_from_parts(
    nbr: usize,
    nbc: usize,
    row_ptr: CArray<usize>,
    col_idx: CArray<usize>,
    blocks: CBlocks,
) -> CResult<*mut SparseBlockStructuredMatrix> {
    let nb = col_idx.len();
    if row_ptr.len() != nbr + 1 || row_ptr.last() != Some(&nb) || blocks.len() != nb {
        return Err(storage_err(format!(
            "inconsistent sparse-block structure: {} row pointers for {nbr} block rows, {nb} \
             block columns, {} blocks",
            row_ptr.len(),
            blocks.len()
        )));
    }
    let count = |n: usize, what: &str| -> CResult<c_uint> {
        c_uint::try_from(n.saturating_mul(3))
            .map(|_| n as c_uint)
            .map_err(|_| size_err(format!("{n} {what} do not fit a C unsigned int")))
    };
    let (nbr_u, nbc_u, nb_u) = (
        count(nbr, "block rows")?,
        count(nbc, "block columns")?,
        c_uint::try_from(nb)
            .map_err(|_| size_err(format!("{nb} blocks do not fit a C unsigned int")))?,
    );
    let out = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "sparse-block matrix")?;
    let mut bs0 = CBuf::<c_uint>::zeroed(nbr, "SBM blocksize0")?;
    for (k, v) in bs0.as_mut_slice().iter_mut().enumerate() {
        *v = 3 * (k as c_uint + 1);
    }
    let mut bs1 = CBuf::<c_uint>::zeroed(nbc, "SBM blocksize1")?;
    for (k, v) in bs1.as_mut_slice().iter_mut().enumerate() {
        *v = 3 * (k as c_uint + 1);
    }
    // Nothing can fail from here on.
    let s = SparseBlockStructuredMatrix {
        nbblocks: nb_u,
        block: blocks.into_raw(),
        blocknumber0: nbr_u,
        blocknumber1: nbc_u,
        blocksize0: bs0.into_raw(),
        blocksize1: bs1.into_raw(),
        filled1: nbr + 1,
        filled2: nb,
        index1_data: row_ptr.into_raw(),
        index2_data: col_idx.into_raw(),
        // As Siconos' readers leave it: computed on demand by its `SBM_diagonal_block_indices`
        // (fc3d's solvers find the diagonal blocks themselves), so a read holds no more.
        diagonal_blocks: null_mut(),
        version: NumericsDataVersion::default(),
    };
    let out = out.into_raw();
    // SAFETY: out is a fresh allocation for one SBM.
    unsafe { out.write(s) };
    Ok(out)
}

pub(in crate::matrix) fn empty_sbm() -> SparseBlockStructuredMatrix {
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

/// A deep C-allocated copy of a host SBM that `block_sparse_from_sbm` accepted (3x3 blocks), as
/// Siconos' `SBM_copy` with blocks: the same counts, sizes, `filled1`/`filled2` entries of the
/// index arrays and block order, every block copied, `diagonal_blocks` (one entry per block
/// row) when the source has one, the version. Nothing is left allocated on failure.
pub(in crate::matrix) unsafe fn sbm_duplicate(
    s: &SparseBlockStructuredMatrix,
) -> CResult<*mut SparseBlockStructuredMatrix> {
    let (nbr, nbc, nb) = (
        s.blocknumber0 as usize,
        s.blocknumber1 as usize,
        s.nbblocks as usize,
    );
    let copy = |p: *const c_uint, n: usize, what: &str| -> CResult<CBuf<c_uint>> {
        CBuf::copy(c_slice(p, n, what)?, what)
    };
    let bs0 = copy(s.blocksize0, nbr, "SBM blocksize0")?;
    let bs1 = copy(s.blocksize1, nbc, "SBM blocksize1")?;
    let i1 = CBuf::copy(
        c_slice(s.index1_data, s.filled1, "SBM index1_data")?,
        "SBM index1_data",
    )?;
    let i2 = CBuf::copy(
        c_slice(s.index2_data, s.filled2, "SBM index2_data")?,
        "SBM index2_data",
    )?;
    let diag = if s.diagonal_blocks.is_null() {
        None
    } else {
        Some(copy(s.diagonal_blocks, nbr, "SBM diagonal_blocks")?)
    };
    let ptrs = c_slice(s.block as *const *mut c_double, nb, "SBM block array")?;
    let mut blocks = Vec::new();
    blocks
        .try_reserve_exact(nb)
        .map_err(|_| size_err(format!("cannot hold {nb} block copies")))?;
    for (k, &b) in ptrs.iter().enumerate() {
        let what = format!("SBM block {k}");
        blocks.push(CBuf::copy(c_slice(b as *const c_double, 9, &what)?, &what)?);
    }
    let mut block_array = CBuf::<*mut c_double>::zeroed(nb, "SBM block array")?;
    let out = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "SBM")?.into_raw();
    for (slot, b) in block_array.as_mut_slice().iter_mut().zip(blocks) {
        *slot = b.into_raw();
    }
    out.write(SparseBlockStructuredMatrix {
        nbblocks: s.nbblocks,
        block: block_array.into_raw(),
        blocknumber0: s.blocknumber0,
        blocknumber1: s.blocknumber1,
        blocksize0: bs0.into_raw(),
        blocksize1: bs1.into_raw(),
        filled1: s.filled1,
        filled2: s.filled2,
        index1_data: i1.into_raw(),
        index2_data: i2.into_raw(),
        diagonal_blocks: diag.map_or(null_mut(), CBuf::into_raw),
        version: s.version,
    });
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Releasing.

/// Checks that `sbm_clear_impl(s, true)` reads no block pointer past the heap block holding the
/// block array (`nbblocks` larger than the array is refused).
pub(in crate::matrix) unsafe fn check_sbm_clearable(
    s: &SparseBlockStructuredMatrix,
) -> CResult<()> {
    if !s.block.is_null() {
        check_heap_len(
            s.block as *const *mut c_double,
            s.nbblocks as usize,
            "SBM block array (nbblocks)",
        )?;
    }
    Ok(())
}

/// Frees the arrays of `s` (and its `nbblocks` blocks with `free_blocks`); callers check
/// `check_sbm_clearable` first when `s` comes from the host.
pub(in crate::matrix) unsafe fn sbm_clear_impl(
    s: *mut SparseBlockStructuredMatrix,
    free_blocks: bool,
) {
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
    // Siconos lets a square SBM share one array of block sizes.
    if s.blocksize1 != s.blocksize0 {
        c_free(s.blocksize1);
    }
    c_free(s.blocksize0);
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
    s.blocknumber0 = 0;
    s.blocknumber1 = 0;
    s.filled1 = 0;
    s.filled2 = 0;
}

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// A new empty sparse-block structure. Release with `SBM_clear` + `free`, or through `NM_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn SBM_new() -> *mut SparseBlockStructuredMatrix {
    ffi_guard(
        "SBM_new",
        |_| null_mut(),
        || {
            let p = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "SBM")?.into_raw();
            // SAFETY: p is a fresh allocation for one SBM.
            unsafe { p.write(empty_sbm()) };
            Ok(p)
        },
    )
}

/// Frees the `nbblocks` blocks and the index arrays of `blmat` (not the struct); NULL is a
/// no-op. Refused (`FC3D_ERR_INVALID_STORAGE`, nothing freed) when `nbblocks` exceeds the heap
/// block holding the block array.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBM_clear(blmat: *mut SparseBlockStructuredMatrix) {
    ffi_guard(
        "SBM_clear",
        |_| (),
        || {
            if let Some(s) = blmat.as_ref() {
                check_sbm_clearable(s)?;
            }
            sbm_clear_impl(blmat, true);
            Ok(())
        },
    )
}
