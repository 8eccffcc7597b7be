//! Sparse-block matrices (`SparseBlockStructuredMatrix`, `SparseBlockCoordinateMatrix`):
//! conversion to and from the core's `BlockSparseMatrix`, single entries, release, and the
//! `SBM_*` / `SBCM_*` functions of Siconos' API.
//!
//! A host fills the counts (`nbblocks`, `blocknumber0/1`, `filled1/2`), the cumulative sizes and
//! the index arrays as plain integers: each is checked against the others before an array is
//! read with it. Declared lengths: `blocksize0`/`blocksize1` hold `blocknumber0`/`blocknumber1`
//! sizes, `index1_data` `filled1` pointers, `index2_data` and `block` `filled2` = `nbblocks`
//! entries.

use std::os::raw::{c_double, c_int, c_uint};
use std::ptr::null_mut;

use super::{c_slice, check_heap_len, size_err, storage_err, CBuf};
use crate::alloc::c_free;
use crate::types::*;
use crate::{ffi_guard, CError, CResult};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::matrix::{BlockSparseMatrix, CsrMatrix};

/// Checks cumulative block sizes: strictly increasing from a positive first size.
fn check_block_sizes(bs: &[c_uint], what: &str) -> CResult<()> {
    let mut prev = 0;
    for (k, &v) in bs.iter().enumerate() {
        if v <= prev {
            return Err(storage_err(format!(
                "{what} must be cumulative block sizes (strictly increasing from a positive size): entry {k} is {v} after {prev}"
            )));
        }
        prev = v;
    }
    Ok(())
}

/// A block count whose 3x3 blocks a NumericsMatrix can hold: 3 * count fits a C int.
fn check_block_count(count: c_uint, what: &str) -> CResult<()> {
    if count as u64 * 3 > c_int::MAX as u64 {
        return Err(size_err(format!(
            "{what} = {count} blocks of size 3 exceed the size of a matrix (a C int)"
        )));
    }
    Ok(())
}

/// The checked structure of a host SBM with uniform `b x b` blocks covering `rows x cols`: the
/// block row pointers, block columns and block pointers, read from the host's arrays.
struct UniformSbm<'a> {
    nbr: usize,
    nbc: usize,
    row_ptr: &'a [usize],
    col_idx: &'a [usize],
    blocks: &'a [*mut c_double],
}

unsafe fn uniform_sbm<'a>(
    s: &'a SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
    b: usize,
) -> CResult<UniformSbm<'a>> {
    let (nbr, nbc) = (s.blocknumber0 as usize, s.blocknumber1 as usize);
    if b * nbr != rows || b * nbc != cols {
        return Err(size_err(format!(
            "sparse-block matrix has {nbr}x{nbc} blocks but the NumericsMatrix is {rows}x{cols} (fc3d needs {b}x{b} blocks)"
        )));
    }
    let bs0 = c_slice(s.blocksize0, nbr, "SBM blocksize0")?;
    let bs1 = c_slice(s.blocksize1, nbc, "SBM blocksize1")?;
    for (k, &v) in bs0.iter().chain(bs1.iter()).enumerate() {
        let expected = b * ((if k < nbr { k } else { k - nbr }) + 1);
        if v as usize != expected {
            return Err(storage_err(format!(
                "sparse-block matrix blocks must all be {b}x{b} (cumulative sizes {b}, {}, {}, ...): found {v} where {expected} was expected",
                2 * b,
                3 * b
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
    let row_ptr = c_slice(s.index1_data, s.filled1, "SBM index1_data")?;
    let nb = row_ptr[nbr];
    if nb != s.filled2 || nb != s.nbblocks as usize {
        return Err(storage_err(format!(
            "SBM block counts disagree: index1_data ends at {nb}, filled2 = {}, nbblocks = {}",
            s.filled2, s.nbblocks
        )));
    }
    Ok(UniformSbm {
        nbr,
        nbc,
        row_ptr,
        col_idx: c_slice(s.index2_data, nb, "SBM index2_data")?,
        blocks: c_slice(s.block as *const *mut c_double, nb, "SBM block array")?,
    })
}

/// Validated block-sparse core copy of a Siconos SBM with uniform 3x3 blocks.
pub(super) unsafe fn block_sparse_from_sbm(
    s: &SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
) -> CResult<BlockSparseMatrix> {
    let u = uniform_sbm(s, rows, cols, 3)?;
    let row_ptr = try_copy(u.row_ptr, "SBM block row pointers")?;
    let col_idx = try_copy(u.col_idx, "SBM block columns")?;
    let mut blocks = try_vec(u.blocks.len(), [0.0; 9], "SBM blocks")?;
    for (k, (&bp, a)) in u.blocks.iter().zip(blocks.iter_mut()).enumerate() {
        a.copy_from_slice(c_slice(
            bp as *const c_double,
            9,
            &format!("SBM block {k}"),
        )?);
    }
    Ok(BlockSparseMatrix::new(
        u.nbr, u.nbc, row_ptr, col_idx, blocks,
    )?)
}

/// Validated general sparse copy of a Siconos SBM with uniform `b x b` blocks (the 2x2 blocks of
/// a 2D problem's W; the core's sparse-block storage holds 3x3 blocks only).
pub(super) unsafe fn csr_from_uniform_sbm(
    s: &SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
    b: usize,
) -> CResult<CsrMatrix> {
    let u = uniform_sbm(s, rows, cols, b)?;
    if u.row_ptr[0] != 0 {
        return Err(storage_err(format!(
            "SBM index1_data must start at 0, not {}",
            u.row_ptr[0]
        )));
    }
    let mut triplets = try_vec(
        u.blocks.len().saturating_mul(b * b),
        (0usize, 0usize, 0.0),
        "SBM entries",
    )?;
    let mut k = 0;
    for row in 0..u.nbr {
        let (start, end) = (u.row_ptr[row], u.row_ptr[row + 1]);
        if start > end || end > u.blocks.len() {
            return Err(storage_err(format!(
                "SBM index1_data must not decrease: block row {row} spans {start}..{end}"
            )));
        }
        for slot in start..end {
            let col = u.col_idx[slot];
            if col >= u.nbc {
                return Err(storage_err(format!(
                    "SBM block column {col} out of range ({} block columns)",
                    u.nbc
                )));
            }
            let values = c_slice(
                u.blocks[slot] as *const c_double,
                b * b,
                &format!("SBM block {slot}"),
            )?;
            // Column-major blocks.
            for j in 0..b {
                for i in 0..b {
                    triplets[k] = (b * row + i, b * col + j, values[i + b * j]);
                    k += 1;
                }
            }
        }
    }
    triplets.truncate(k);
    Ok(CsrMatrix::from_triplets(rows, cols, &triplets)?)
}

/// Entry (i, j) of a host SBM of any block sizes (the sum of the blocks stored at its place, 0
/// if none), `i`, `j` inside the NumericsMatrix. Checks the counts, the cumulative sizes and the
/// block row it reads; an SBM with no block row or column (as `NM_create` makes it) holds zeros.
pub(super) unsafe fn sbm_get(s: &SparseBlockStructuredMatrix, i: usize, j: usize) -> CResult<f64> {
    let (nbr, nbc, nb) = (s.blocknumber0 as usize, s.blocknumber1 as usize, s.filled2);
    if nb != s.nbblocks as usize {
        return Err(storage_err(format!(
            "SBM block counts disagree: filled2 = {nb}, nbblocks = {}",
            s.nbblocks
        )));
    }
    if nbr == 0 || nbc == 0 {
        if nb == 0 {
            return Ok(0.0);
        }
        return Err(storage_err(format!(
            "SBM has {nb} blocks but {nbr}x{nbc} block rows and columns"
        )));
    }
    let bs0 = c_slice(s.blocksize0, nbr, "SBM blocksize0")?;
    let bs1 = c_slice(s.blocksize1, nbc, "SBM blocksize1")?;
    check_block_sizes(bs0, "SBM blocksize0")?;
    check_block_sizes(bs1, "SBM blocksize1")?;
    // The block row of i: the first cumulative size above it.
    let bi = bs0.partition_point(|&c| c as usize <= i);
    let bj = bs1.partition_point(|&c| c as usize <= j);
    if bi == nbr || bj == nbc {
        return Err(storage_err(format!(
            "entry ({i}, {j}) is outside the blocks, which cover {}x{}",
            bs0[nbr - 1],
            bs1[nbc - 1]
        )));
    }
    let r0 = if bi == 0 { 0 } else { bs0[bi - 1] as usize };
    let c0 = if bj == 0 { 0 } else { bs1[bj - 1] as usize };
    let (nrows, ncols) = (bs0[bi] as usize - r0, bs1[bj] as usize - c0);
    if s.filled1 != nbr + 1 {
        return Err(storage_err(format!(
            "SBM filled1 = {} but blocknumber0 + 1 = {}",
            s.filled1,
            nbr + 1
        )));
    }
    let ptr = c_slice(s.index1_data, s.filled1, "SBM index1_data")?;
    let (a, z) = (ptr[bi], ptr[bi + 1]);
    if a > z || z > nb {
        return Err(storage_err(format!(
            "SBM block row {bi} spans blocks {a}..{z} of {nb} (index1_data)"
        )));
    }
    let cols = c_slice(s.index2_data, nb, "SBM index2_data")?;
    let blocks = c_slice(s.block as *const *mut c_double, nb, "SBM block array")?;
    let mut v = 0.0;
    for k in a..z {
        if cols[k] >= nbc {
            return Err(storage_err(format!(
                "SBM block {k} is in block column {}, past {nbc} (index2_data)",
                cols[k]
            )));
        }
        if cols[k] == bj {
            let b = c_slice(
                blocks[k] as *const c_double,
                nrows * ncols,
                &format!("SBM block {k}"),
            )?;
            v += b[(i - r0) + (j - c0) * nrows];
        }
    }
    Ok(v)
}

// ---------------------------------------------------------------------------------------------
// Building C matrices from core ones.

/// A C-allocated SBM copy of a core block-sparse matrix (blocks malloc'd one by one, as
/// Siconos); nothing is left allocated on failure.
pub(crate) fn sbm_to_c(b: &BlockSparseMatrix) -> CResult<*mut SparseBlockStructuredMatrix> {
    let (nbr, nbc, nb) = (b.n_block_rows(), b.n_block_cols(), b.n_blocks());
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
    let mut s = empty_sbm();
    let filled = (|| -> CResult<()> {
        s.block = CBuf::<*mut c_double>::zeroed(nb, "SBM block array")?.into_raw();
        for (k, v) in b.blocks().iter().enumerate() {
            // SAFETY: s.block has nb slots; nbblocks counts the blocks allocated so far.
            unsafe { *s.block.add(k) = CBuf::copy(v, "SBM block")?.into_raw() };
            s.nbblocks = k as c_uint + 1;
        }
        s.nbblocks = nb_u;
        s.blocknumber0 = nbr_u;
        s.blocknumber1 = nbc_u;
        let mut bs0 = CBuf::<c_uint>::zeroed(nbr, "SBM blocksize0")?;
        for (k, v) in bs0.as_mut_slice().iter_mut().enumerate() {
            *v = 3 * (k as c_uint + 1);
        }
        s.blocksize0 = bs0.into_raw();
        let mut bs1 = CBuf::<c_uint>::zeroed(nbc, "SBM blocksize1")?;
        for (k, v) in bs1.as_mut_slice().iter_mut().enumerate() {
            *v = 3 * (k as c_uint + 1);
        }
        s.blocksize1 = bs1.into_raw();
        s.index1_data = CBuf::copy(b.row_ptr(), "SBM index1_data")?.into_raw();
        s.filled1 = nbr + 1;
        s.index2_data = CBuf::copy(b.col_idx(), "SBM index2_data")?.into_raw();
        s.filled2 = nb;
        let mut diag = CBuf::<c_uint>::zeroed(nbr, "SBM diagonal_blocks")?;
        for (i, d) in diag.as_mut_slice().iter_mut().enumerate() {
            *d = (b.row_ptr()[i]..b.row_ptr()[i + 1])
                .find(|&k| b.col_idx()[k] == i)
                .map_or(c_uint::MAX, |k| k as c_uint);
        }
        s.diagonal_blocks = diag.into_raw();
        Ok(())
    })();
    match filled {
        Ok(()) => {
            let out = out.into_raw();
            // SAFETY: out is a fresh allocation for one SBM.
            unsafe { out.write(s) };
            Ok(out)
        }
        Err(e) => {
            // SAFETY: s holds only what was allocated above (nbblocks blocks so far).
            unsafe { sbm_clear_impl(&mut s, true) };
            Err(e)
        }
    }
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

/// Checks that `sbm_clear_impl(s, true)` reads no block pointer past the heap block holding the
/// block array (`nbblocks` larger than the array is refused).
pub(super) unsafe fn check_sbm_clearable(s: &SparseBlockStructuredMatrix) -> CResult<()> {
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

/// Coordinate block matrix of `nbblocks` 3x3 blocks at 1-based block coordinates
/// `(row[k], column[k])`, values `block[9k..9k+9]` column-major, in an `m` x `n` grid of blocks.
/// Keeps `row`, `column` and `block` without copying (they stay the caller's); release with
/// `SBCM_free_3x3`. NULL with `FC3D_ERR_INVALID_SIZE` when `3 m` or `3 n` exceeds a C int or a
/// coordinate is outside `1..=m` x `1..=n`, `FC3D_ERR_NULL_POINTER` for a NULL array.
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
            let mut ptrs = CBuf::<*mut c_double>::zeroed(nb, "block pointers")?;
            for (k, p) in ptrs.as_mut_slice().iter_mut().enumerate() {
                *p = block.add(9 * k);
            }
            let cumulative = |count: c_uint, what: &str| -> CResult<CBuf<c_uint>> {
                let mut bs = CBuf::<c_uint>::zeroed(count as usize, what)?;
                for (k, v) in bs.as_mut_slice().iter_mut().enumerate() {
                    *v = 3 * (k as c_uint + 1);
                }
                Ok(bs)
            };
            let bs0 = cumulative(m, "blocksize0")?;
            let bs1 = cumulative(n, "blocksize1")?;
            let out =
                CBuf::<SparseBlockCoordinateMatrix>::zeroed(1, "coordinate matrix")?.into_raw();
            out.write(SparseBlockCoordinateMatrix {
                nbblocks,
                blocknumber0: m,
                blocknumber1: n,
                block: ptrs.into_raw(),
                blocksize0: bs0.into_raw(),
                blocksize1: bs1.into_raw(),
                row,
                column,
            });
            Ok(out)
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
/// Checks what a host may have filled: NULL arrays and block pointers, cumulative sizes that do
/// not increase, coordinates outside `1..=blocknumber0` x `1..=blocknumber1` (NULL and a code).
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
            let bs0 = c_slice(mc.blocksize0, nbr, "blocksize0")?;
            let bs1 = c_slice(mc.blocksize1, nbc, "blocksize1")?;
            check_block_sizes(bs0, "blocksize0")?;
            check_block_sizes(bs1, "blocksize1")?;
            for k in 0..nb {
                let (r, c) = (rows[k] as usize, cols[k] as usize);
                if r == 0 || r > nbr || c == 0 || c > nbc {
                    return Err(size_err(format!(
                        "block {k} at 1-based ({r}, {c}) is outside {nbr}x{nbc} blocks"
                    )));
                }
                if ptrs[k].is_null() {
                    return Err(CError::null(&format!("block {k}")));
                }
            }
            // Sorted by (row, column), ties in the given order.
            let mut order = try_vec(nb, 0usize, "block order")?;
            order.iter_mut().enumerate().for_each(|(k, o)| *o = k);
            order.sort_unstable_by_key(|&k| (rows[k], cols[k], k));
            let mut row_ptr = CBuf::<usize>::zeroed(nbr + 1, "index1_data")?;
            let rp = row_ptr.as_mut_slice();
            for &k in &order {
                rp[rows[k] as usize] += 1;
            }
            for i in 0..nbr {
                rp[i + 1] += rp[i];
            }
            let mut col_idx = CBuf::<usize>::zeroed(nb, "index2_data")?;
            let mut sorted = CBuf::<*mut c_double>::zeroed(nb, "block array")?;
            for ((c, b), &k) in col_idx
                .as_mut_slice()
                .iter_mut()
                .zip(sorted.as_mut_slice().iter_mut())
                .zip(&order)
            {
                *c = cols[k] as usize - 1;
                *b = ptrs[k];
            }
            let mut diag = CBuf::<c_uint>::zeroed(nbr, "diagonal_blocks")?;
            let (rp, ci) = (row_ptr.as_mut_slice(), col_idx.as_mut_slice());
            for (i, d) in diag.as_mut_slice().iter_mut().enumerate() {
                *d = (rp[i]..rp[i + 1])
                    .find(|&k| ci[k] == i)
                    .map_or(c_uint::MAX, |k| k as c_uint);
            }
            let bs0 = CBuf::copy(bs0, "blocksize0")?;
            let bs1 = CBuf::copy(bs1, "blocksize1")?;
            let out = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "SBM")?.into_raw();
            out.write(SparseBlockStructuredMatrix {
                nbblocks: mc.nbblocks,
                block: sorted.into_raw(),
                blocknumber0: mc.blocknumber0,
                blocknumber1: mc.blocknumber1,
                blocksize0: bs0.into_raw(),
                blocksize1: bs1.into_raw(),
                filled1: nbr + 1,
                filled2: nb,
                index1_data: row_ptr.into_raw(),
                index2_data: col_idx.into_raw(),
                diagonal_blocks: diag.into_raw(),
                version: NumericsDataVersion::default(),
            });
            Ok(out)
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
