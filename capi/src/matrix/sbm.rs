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
use crate::alloc::{c_free, CArray, CBlocks};
use crate::types::*;
use crate::{ffi_guard, CError, CResult};
use fc3d_core::error::{try_copy, try_vec};
use fc3d_core::matrix::{BlockSparseMatrix, CsrMatrix, Shared};

/// Checks cumulative block sizes: strictly increasing from a positive first size.
pub(super) fn check_block_sizes(bs: &[c_uint], what: &str) -> CResult<()> {
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

/// The `blocknumber0 + 1` block-row pointers of a host SBM. Siconos' `filled1` counts the
/// pointers up to the last block row that holds a block (`SBCM_to_SBM` sets it so, and to 2 for
/// a grid without rows): the rows past it are empty.
pub(super) unsafe fn sbm_row_ptr(s: &SparseBlockStructuredMatrix) -> CResult<Shared<'_, usize>> {
    let nbr = s.blocknumber0 as usize;
    let given = s.filled1.min(nbr + 1);
    if s.filled1 > nbr + 1 && nbr > 0 || given == 0 && s.nbblocks != 0 {
        return Err(storage_err(format!(
            "SBM filled1 = {} but blocknumber0 + 1 = {} (and {} blocks)",
            s.filled1,
            nbr + 1,
            s.nbblocks
        )));
    }
    let declared: &[usize] = c_slice(s.index1_data, given, "SBM index1_data")?;
    let last = declared.last().copied().unwrap_or(0);
    // The rows up to filled1 - 1 hold every block.
    if last != s.filled2 {
        return Err(storage_err(format!(
            "SBM index1_data[filled1 - 1 = {}] = {last} but filled2 = {} blocks",
            given.saturating_sub(1),
            s.filled2
        )));
    }
    if given == nbr + 1 {
        return Ok(Shared::Borrowed(declared));
    }
    let mut ptr = try_vec(nbr + 1, 0usize, "SBM block row pointers")?;
    ptr[..given].copy_from_slice(declared);
    ptr[given..].iter_mut().for_each(|p| *p = last);
    Ok(ptr.into())
}

/// The checked structure of a host SBM with uniform `b x b` blocks covering `rows x cols`: block
/// row pointers, and the block columns and block pointers of each row sorted by column.
struct UniformSbm<'a> {
    nbr: usize,
    nbc: usize,
    /// The host's arrays when they can be used as they are (always for the column indices
    /// of rows sorted by column), else fc3d's copies.
    row_ptr: Shared<'a, usize>,
    col_idx: Shared<'a, usize>,
    /// The host's block pointers, in its order.
    pointers: &'a [*mut c_double],
    /// Where block `k` (sorted order) is among `pointers`; `None` when the host's rows are
    /// already sorted (the usual case: no permutation is built).
    order: Option<Vec<usize>>,
}

impl UniformSbm<'_> {
    fn n_blocks(&self) -> usize {
        self.col_idx.len()
    }

    /// The host's pointer to block `k` of the sorted order.
    fn block(&self, k: usize) -> *const c_double {
        block_pointer(self.pointers, self.order.as_deref(), k)
    }
}

fn block_pointer(pointers: &[*mut c_double], order: Option<&[usize]>, k: usize) -> *const c_double {
    pointers[order.map_or(k, |o| o[k])] as *const c_double
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
    let row_ptr = sbm_row_ptr(s)?;
    let nb = row_ptr[nbr];
    if nb != s.filled2 || nb != s.nbblocks as usize {
        return Err(storage_err(format!(
            "SBM block counts disagree: index1_data ends at {nb}, filled2 = {}, nbblocks = {}",
            s.filled2, s.nbblocks
        )));
    }
    if let Some(w) = row_ptr.windows(2).find(|w| w[0] > w[1]) {
        return Err(storage_err(format!(
            "SBM index1_data decreases ({} then {})",
            w[0], w[1]
        )));
    }
    let given_cols: &[usize] = c_slice(s.index2_data, nb, "SBM index2_data")?;
    let ptrs = c_slice(s.block as *const *mut c_double, nb, "SBM block array")?;
    // A Siconos SBM need not sort the blocks of a row (SBCM_to_SBM keeps their coordinate
    // order): the copy sorts them (stably), so that products sum in the same order whatever the
    // input order. Sorted rows, the usual case, need no permutation.
    let sorted = (0..nbr).all(|i| {
        given_cols[row_ptr[i]..row_ptr[i + 1]]
            .windows(2)
            .all(|w| w[0] <= w[1])
    });
    let (col_idx, order) = if sorted {
        (Shared::Borrowed(given_cols), None)
    } else {
        let mut order = try_vec(nb, 0usize, "SBM block order")?;
        order.iter_mut().enumerate().for_each(|(k, o)| *o = k);
        for i in 0..nbr {
            order[row_ptr[i]..row_ptr[i + 1]].sort_by_key(|&k| given_cols[k]);
        }
        let mut col_idx = try_vec(nb, 0usize, "SBM block columns")?;
        for (&k, c) in order.iter().zip(col_idx.iter_mut()) {
            *c = given_cols[k];
        }
        (col_idx.into(), Some(order))
    };
    Ok(UniformSbm {
        nbr,
        nbc,
        row_ptr,
        col_idx,
        pointers: ptrs,
        order,
    })
}

/// A validated block-sparse core view of a Siconos SBM with uniform 3x3 blocks, reading the
/// host's blocks in place: nothing is copied but the row pointers a short `filled1` leaves
/// implicit, and, when a row is not sorted by column, the column indices and block references
/// in sorted order. The checks read the index arrays and the table of block pointers only (each
/// pointer non-NULL, aligned, its 9 doubles within the address space); the values themselves are
/// read by the solve (see `Delassus::check_finite`).
///
/// Siconos and the core store a 3x3 block the same way (9 doubles, column-major), so a block
/// pointer is used as it is, never transposed.
pub(super) unsafe fn block_sparse_from_sbm<'a>(
    s: &'a SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
) -> CResult<BlockSparseMatrix<'a>> {
    let UniformSbm {
        nbr,
        nbc,
        row_ptr,
        col_idx,
        pointers,
        order,
    } = uniform_sbm(s, rows, cols, 3)?;
    for (k, &p) in pointers.iter().enumerate() {
        if p.is_null() || !p.is_aligned() || (p as usize).checked_add(72).is_none() {
            return Err(match c_slice(p as *const c_double, 9, "SBM block") {
                Err(e) => CError::new(e.code, format!("{} (block {k})", e.message)),
                Ok(_) => storage_err(format!("SBM block {k} cannot be read")),
            });
        }
    }
    let table: Shared<'a, &'a [f64; 9]> = match order {
        // SAFETY: every pointer of `pointers` was checked above to be non-NULL, aligned for f64
        // and followed by 9 doubles within the address space; that they are readable and left
        // unchanged while the call lasts (`'a`, the borrow of the host's matrix) is the host's
        // promise, as for every array it hands over. A `&[f64; 9]` is a thin pointer, laid out
        // as the `*mut c_double` it is read from, so the table is the host's, reinterpreted.
        None => Shared::Borrowed(std::slice::from_raw_parts(
            pointers.as_ptr() as *const &'a [f64; 9],
            pointers.len(),
        )),
        Some(order) => {
            let mut t: Vec<&'a [f64; 9]> = Vec::new();
            t.try_reserve_exact(order.len()).map_err(|_| {
                fc3d_core::error::Fc3dError::OutOfMemory {
                    what: "sorted SBM block table".into(),
                    bytes: order.len().saturating_mul(8),
                }
            })?;
            // SAFETY: as above, pointer by pointer.
            t.extend(order.iter().map(|&k| &*(pointers[k] as *const [f64; 9])));
            t.into()
        }
    };
    Ok(BlockSparseMatrix::from_block_table(
        nbr, nbc, row_ptr, col_idx, table,
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
        u.n_blocks().saturating_mul(b * b),
        (0usize, 0usize, 0.0),
        "SBM entries",
    )?;
    let mut k = 0;
    for row in 0..u.nbr {
        let (start, end) = (u.row_ptr[row], u.row_ptr[row + 1]);
        if start > end || end > u.n_blocks() {
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
            let values = c_slice(u.block(slot), b * b, "SBM block")
                .map_err(|e| CError::new(e.code, format!("{} (block {slot})", e.message)))?;
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
    let ptr = sbm_row_ptr(s)?;
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

/// A deep C-allocated copy of a host SBM that `block_sparse_from_sbm` accepted (3x3 blocks), as
/// Siconos' `SBM_copy` with blocks: the same counts, sizes, `filled1`/`filled2` entries of the
/// index arrays and block order, every block copied, `diagonal_blocks` (one entry per block
/// row) when the source has one, the version. Nothing is left allocated on failure.
pub(super) unsafe fn sbm_duplicate(
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
