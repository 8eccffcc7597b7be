//! Sparse-block matrices (`SparseBlockStructuredMatrix`, `SparseBlockCoordinateMatrix`): this
//! file reads a host's SBM (checked, then viewed as the core's `BlockSparseMatrix` or copied,
//! single entries); `owned` builds, duplicates and releases the SBMs fc3d allocates
//! (`SBM_new`, `SBM_clear`); `coordinate` holds the `SBCM_*` functions of Siconos' API.
//!
//! A host fills the counts (`nbblocks`, `blocknumber0/1`, `filled1/2`), the cumulative sizes and
//! the index arrays as plain integers: each is checked against the others before an array is
//! read with it. Declared lengths: `blocksize0`/`blocksize1` hold `blocknumber0`/`blocknumber1`
//! sizes, `index1_data` `filled1` pointers, `index2_data` and `block` `filled2` = `nbblocks`
//! entries.

// cbindgen reads a module's own items, then its submodules in the order declared here: the order
// of include/fc3d.h (`SBM_new`, `SBM_clear`, then the `SBCM_*` functions). The blank line keeps
// rustfmt from sorting the declarations.
mod owned;

mod coordinate;

pub(in crate::matrix) use owned::{check_sbm_clearable, empty_sbm, sbm_clear_impl, sbm_duplicate};
pub(crate) use owned::{sbm_from_parts, sbm_to_c};

use std::os::raw::{c_double, c_int, c_uint};

use super::{c_slice, size_err, storage_err};
use crate::types::*;
use crate::{CError, CResult};
use fc3d_core::error::try_vec;
use fc3d_core::matrix::{BlockSparseMatrix, CsrMatrix, Shared};

/// Checks cumulative block sizes: strictly increasing from a positive first size.
pub(in crate::matrix) fn check_block_sizes(bs: &[c_uint], what: &str) -> CResult<()> {
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
pub(in crate::matrix) unsafe fn sbm_row_ptr(
    s: &SparseBlockStructuredMatrix,
) -> CResult<Shared<'_, usize>> {
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
