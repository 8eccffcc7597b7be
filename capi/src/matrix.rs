//! NumericsMatrix / SparseBlockStructuredMatrix / CSparse conversions and the `NM_*`, `SBM_*`,
//! `SBCM_*` functions of Siconos' API that hosts use to build W.
//!
//! Matrix files: `NM_new_from_file`/`NM_new_from_filename`, `NM_write_in_file`/
//! `NM_write_in_filename` and `SBM_new_from_file` read and write the matrix part of the .dat
//! format (`fc3d_core::io::dat::parse_matrix`, `write_matrix`, `parse_sbm`).
//!
//! Ownership (as in Siconos): `NM_create*`/`NM_new*` return a matrix the caller releases with
//! `NM_free` (storage and struct) or `NM_clear` + `free` (storage, then struct).
//! `NM_create_from_data` and `NM_fill` keep the given storage pointer without copying: it then
//! belongs to the matrix and is released by `NM_clear`/`NM_free` with `free()`.

#![allow(non_snake_case)]

use std::borrow::Cow;
use std::ffi::c_char;
use std::os::raw::{c_double, c_int, c_uint};
use std::ptr::null_mut;

use super::alloc::{c_box, c_calloc, c_copy, c_free};
use super::stream::{c_filename, read_rest, write_all};
use super::types::*;
use super::{
    ffi_guard, CError, CResult, FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_STORAGE, FC3D_ERR_IO,
};
use fc3d_core::io::dat::{parse_matrix, parse_matrix_prefix, parse_sbm_prefix, write_matrix};
use fc3d_core::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};

pub(crate) const NM_DENSE: c_int = 0;
pub(crate) const NM_SPARSE_BLOCK: c_int = 1;
pub(crate) const NM_SPARSE: c_int = 2;
pub(crate) const NM_UNKNOWN: c_int = 3;

pub(crate) const NSM_UNKNOWN: c_int = 0;
pub(crate) const NSM_TRIPLET: c_int = 1;
pub(crate) const NSM_CSC: c_int = 2;
pub(crate) const NSM_CSR: c_int = 3;
pub(crate) const NSM_HALF_TRIPLET: c_int = 4;

fn storage_err(msg: impl Into<String>) -> CError {
    CError::new(FC3D_ERR_INVALID_STORAGE, msg)
}

fn nonneg(v: CS_INT, what: &str) -> CResult<usize> {
    usize::try_from(v)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, format!("{what} = {v} is negative")))
}

/// A slice view of a C array; `len == 0` accepts NULL.
pub(crate) unsafe fn c_slice<'a, T>(p: *const T, len: usize, what: &str) -> CResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(CError::null(what));
    }
    Ok(std::slice::from_raw_parts(p, len))
}

fn indices(v: &[CS_INT], what: &str) -> CResult<Vec<usize>> {
    v.iter().map(|&x| nonneg(x, what)).collect()
}

/// Core view of a CSparse matrix as `(rows, cols, triplets or compressed form)`, validated.
unsafe fn csr_from_cs(
    cs: &CSparseMatrix,
    kind: c_int,
    rows: usize,
    cols: usize,
) -> CResult<CsrMatrix> {
    match kind {
        NSM_TRIPLET => {
            if cs.nz < 0 {
                return Err(storage_err(format!(
                    "triplet matrix has nz = {} (< 0)",
                    cs.nz
                )));
            }
            check_dims(cs.m, cs.n, rows, cols)?;
            let nz = nonneg(cs.nz, "nz")?;
            if cs.nz > cs.nzmax {
                return Err(storage_err(format!(
                    "triplet nz = {} exceeds nzmax = {}",
                    cs.nz, cs.nzmax
                )));
            }
            let ri = indices(c_slice(cs.i, nz, "triplet row indices (i)")?, "row index")?;
            let cj = indices(
                c_slice(cs.p, nz, "triplet column indices (p)")?,
                "column index",
            )?;
            let x = c_slice(cs.x, nz, "triplet values (x)")?;
            let t: Vec<_> = (0..nz).map(|k| (ri[k], cj[k], x[k])).collect();
            Ok(CsrMatrix::from_triplets(rows, cols, &t)?)
        }
        NSM_CSC => {
            if cs.nz != -1 {
                return Err(storage_err(format!(
                    "CSC matrix must have nz = -1, got {}",
                    cs.nz
                )));
            }
            check_dims(cs.m, cs.n, rows, cols)?;
            let ptr = indices(
                c_slice(cs.p, cols + 1, "CSC column pointers (p)")?,
                "column pointer",
            )?;
            let nnz = ptr[cols];
            if nnz as CS_INT > cs.nzmax {
                return Err(storage_err(format!(
                    "CSC has {nnz} entries but nzmax = {}",
                    cs.nzmax
                )));
            }
            let ri = indices(c_slice(cs.i, nnz, "CSC row indices (i)")?, "row index")?;
            let x = c_slice(cs.x, nnz, "CSC values (x)")?;
            Ok(CsrMatrix::from_csc(rows, cols, &ptr, &ri, x)?)
        }
        NSM_CSR => {
            // Siconos stores a CSR matrix as the CSC of its transpose: n rows, m columns.
            if cs.nz != -2 && cs.nz != -1 {
                return Err(storage_err(format!(
                    "CSR matrix must have nz = -2, got {}",
                    cs.nz
                )));
            }
            check_dims(cs.n, cs.m, rows, cols)?;
            let ptr = indices(
                c_slice(cs.p, rows + 1, "CSR row pointers (p)")?,
                "row pointer",
            )?;
            let nnz = ptr[rows];
            if nnz as CS_INT > cs.nzmax {
                return Err(storage_err(format!(
                    "CSR has {nnz} entries but nzmax = {}",
                    cs.nzmax
                )));
            }
            let cj = indices(
                c_slice(cs.i, nnz, "CSR column indices (i)")?,
                "column index",
            )?;
            let x = c_slice(cs.x, nnz, "CSR values (x)")?;
            Ok(CsrMatrix::from_csr(rows, cols, &ptr, &cj, x)?)
        }
        NSM_HALF_TRIPLET => Err(storage_err(
            "half-triplet (symmetric half) storage is rejected: W is not symmetric in general",
        )),
        other => Err(storage_err(format!("unknown sparse origin {other}"))),
    }
}

fn check_dims(m: CS_INT, n: CS_INT, rows: usize, cols: usize) -> CResult<()> {
    if m != rows as CS_INT || n != cols as CS_INT {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("sparse matrix is {m}x{n} but the NumericsMatrix says {rows}x{cols}"),
        ));
    }
    Ok(())
}

/// Validated block-sparse core copy of a Siconos SBM with uniform 3x3 blocks.
unsafe fn block_sparse_from_sbm(
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

/// The core view of a NumericsMatrix (dense storage is borrowed, not copied).
pub(crate) unsafe fn delassus_from_c<'a>(m: &'a NumericsMatrix) -> CResult<Delassus<'a>> {
    if m.size0 < 0 || m.size1 < 0 {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("matrix size {}x{} is negative", m.size0, m.size1),
        ));
    }
    let (rows, cols) = (m.size0 as usize, m.size1 as usize);
    match m.storageType {
        NM_DENSE => {
            let n = rows
                .checked_mul(cols)
                .ok_or_else(|| CError::new(FC3D_ERR_INVALID_SIZE, "matrix size overflows"))?;
            let data = c_slice(
                m.matrix0 as *const c_double,
                n,
                "dense matrix data (matrix0)",
            )?;
            Ok(Delassus::Dense(DenseMatrix::new(
                rows,
                cols,
                Cow::Borrowed(data),
            )?))
        }
        NM_SPARSE_BLOCK => {
            if m.matrix1.is_null() {
                return Err(CError::null("sparse-block storage (matrix1)"));
            }
            Ok(Delassus::SparseBlock(block_sparse_from_sbm(
                &*m.matrix1,
                rows,
                cols,
            )?))
        }
        NM_SPARSE => {
            if m.matrix2.is_null() {
                return Err(CError::null("sparse storage (matrix2)"));
            }
            let s = &*m.matrix2;
            let pick = |origin: c_int| -> Option<(*mut CSparseMatrix, c_int)> {
                let p = match origin {
                    NSM_TRIPLET => s.triplet,
                    NSM_CSC => s.csc,
                    NSM_CSR => s.csr,
                    NSM_HALF_TRIPLET => s.half_triplet,
                    _ => null_mut(),
                };
                (!p.is_null()).then_some((p, origin))
            };
            let chosen = match s.origin {
                NSM_UNKNOWN => pick(NSM_CSC)
                    .or_else(|| pick(NSM_TRIPLET))
                    .or_else(|| pick(NSM_CSR)),
                NSM_TRIPLET | NSM_CSC | NSM_CSR | NSM_HALF_TRIPLET => pick(s.origin),
                other => return Err(storage_err(format!("unknown sparse origin {other}"))),
            };
            let Some((cs, kind)) = chosen else {
                if s.origin == NSM_HALF_TRIPLET || !s.half_triplet.is_null() {
                    return Err(storage_err("half-triplet (symmetric half) storage is rejected: W is not symmetric in general"));
                }
                return Err(CError::null(&format!(
                    "the sparse matrix of origin {} ",
                    s.origin
                )));
            };
            Ok(Delassus::Sparse(csr_from_cs(&*cs, kind, rows, cols)?))
        }
        other => Err(storage_err(format!(
            "unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
        ))),
    }
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

/// A C-allocated CSparse compressed-column copy.
pub(crate) fn csc_to_c(m: &CsrMatrix) -> CResult<*mut CSparseMatrix> {
    // Transpose the CSR structure into CSC.
    let (rows, cols) = (m.nrows(), m.ncols());
    let mut count = vec![0usize; cols + 1];
    for &j in m.col_idx() {
        count[j + 1] += 1;
    }
    for j in 0..cols {
        count[j + 1] += count[j];
    }
    let nnz = m.nnz();
    let mut next = count.clone();
    let mut ri = vec![0 as CS_INT; nnz];
    let mut x = vec![0.0; nnz];
    for i in 0..rows {
        for k in m.row_ptr()[i]..m.row_ptr()[i + 1] {
            let j = m.col_idx()[k];
            ri[next[j]] = i as CS_INT;
            x[next[j]] = m.values()[k];
            next[j] += 1;
        }
    }
    let p: Vec<CS_INT> = count.iter().map(|&v| v as CS_INT).collect();
    c_box(CSparseMatrix {
        nzmax: nnz as CS_INT,
        m: rows as CS_INT,
        n: cols as CS_INT,
        p: c_copy(&p)?,
        i: c_copy(&ri)?,
        x: c_copy(&x)?,
        nz: -1,
    })
}

fn empty_nsm() -> NumericsSparseMatrix {
    NumericsSparseMatrix {
        triplet: null_mut(),
        half_triplet: null_mut(),
        csc: null_mut(),
        trans_csc: null_mut(),
        csr: null_mut(),
        diag_indx: null_mut(),
        origin: NSM_UNKNOWN,
        linearSolverParams: null_mut(),
        versions: [NumericsDataVersion::default(); 5],
    }
}

fn null_matrix() -> NumericsMatrix {
    NumericsMatrix {
        storageType: NM_UNKNOWN,
        size0: 0,
        size1: 0,
        matrix0: null_mut(),
        matrix1: null_mut(),
        matrix2: null_mut(),
        internalData: null_mut(),
        version: NumericsDataVersion::default(),
        destructible: null_mut(),
    }
}

fn c_size(n: usize) -> CResult<c_int> {
    c_int::try_from(n).map_err(|_| {
        CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("size {n} does not fit a C int"),
        )
    })
}

/// A C-allocated NumericsMatrix holding a copy of `w` in the same storage
/// (CSR becomes Siconos' CSC origin).
pub(crate) fn matrix_to_c(w: &Delassus<'_>) -> CResult<*mut NumericsMatrix> {
    let mut m = null_matrix();
    m.size0 = c_size(w.nrows())?;
    m.size1 = c_size(w.ncols())?;
    match w {
        Delassus::Dense(d) => {
            m.storageType = NM_DENSE;
            m.matrix0 = c_copy(d.values())?;
        }
        Delassus::SparseBlock(b) => {
            m.storageType = NM_SPARSE_BLOCK;
            m.matrix1 = sbm_to_c(b)?;
        }
        Delassus::Sparse(s) => {
            m.storageType = NM_SPARSE;
            let mut nsm = empty_nsm();
            nsm.csc = csc_to_c(s)?;
            nsm.origin = NSM_CSC;
            m.matrix2 = c_box(nsm)?;
        }
    }
    c_box(m)
}

// ---------------------------------------------------------------------------------------------
// Releasing.

unsafe fn cs_free(cs: *mut CSparseMatrix) {
    if cs.is_null() {
        return;
    }
    c_free((*cs).p);
    c_free((*cs).i);
    c_free((*cs).x);
    c_free(cs);
}

unsafe fn nsm_clear(s: *mut NumericsSparseMatrix) {
    if s.is_null() {
        return;
    }
    let s = &mut *s;
    for cs in [
        &mut s.triplet,
        &mut s.half_triplet,
        &mut s.csc,
        &mut s.trans_csc,
        &mut s.csr,
    ] {
        cs_free(*cs);
        *cs = null_mut();
    }
    c_free(s.diag_indx);
    s.diag_indx = null_mut();
    c_free(s.linearSolverParams);
    s.linearSolverParams = null_mut();
    s.origin = NSM_UNKNOWN;
}

unsafe fn sbm_clear_impl(s: *mut SparseBlockStructuredMatrix, free_blocks: bool) {
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

pub(crate) unsafe fn nm_clear_impl(m: *mut NumericsMatrix) {
    if m.is_null() {
        return;
    }
    let mm = &mut *m;
    c_free(mm.matrix0);
    mm.matrix0 = null_mut();
    if !mm.matrix1.is_null() {
        sbm_clear_impl(mm.matrix1, true);
        c_free(mm.matrix1);
        mm.matrix1 = null_mut();
    }
    if !mm.matrix2.is_null() {
        nsm_clear(mm.matrix2);
        c_free(mm.matrix2);
        mm.matrix2 = null_mut();
    }
    if !mm.internalData.is_null() {
        c_free((*mm.internalData).iWork);
        c_free((*mm.internalData).dWork);
        c_free(mm.internalData);
        mm.internalData = null_mut();
    }
    mm.destructible = null_mut();
}

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// A new empty matrix (storage NM_UNKNOWN, sizes 0). Release with `NM_free`.
#[no_mangle]
pub extern "C" fn NM_new() -> *mut NumericsMatrix {
    ffi_guard("NM_new", |_| null_mut(), || c_box(null_matrix()))
}

/// Resets every field of `A` (frees nothing).
#[no_mangle]
pub unsafe extern "C" fn NM_null(A: *mut NumericsMatrix) {
    ffi_guard(
        "NM_null",
        |_| (),
        || {
            if A.is_null() {
                return Err(CError::null("A"));
            }
            *A = null_matrix();
            Ok(())
        },
    )
}

fn storage_for(storageType: c_int, size0: c_int, size1: c_int) -> CResult<NumericsMatrix> {
    if size0 < 0 || size1 < 0 {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("size {size0}x{size1} is negative"),
        ));
    }
    let mut m = null_matrix();
    m.storageType = storageType;
    m.size0 = size0;
    m.size1 = size1;
    match storageType {
        NM_DENSE => {
            m.matrix0 = c_calloc::<c_double>(
                (size0 as usize)
                    .checked_mul(size1 as usize)
                    .ok_or_else(|| CError::new(FC3D_ERR_INVALID_SIZE, "size overflows"))?,
            )?
        }
        NM_SPARSE_BLOCK => m.matrix1 = c_box(empty_sbm())?,
        NM_SPARSE => m.matrix2 = c_box(empty_nsm())?,
        other => {
            return Err(storage_err(format!(
                "unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
            )))
        }
    }
    Ok(m)
}

fn empty_sbm() -> SparseBlockStructuredMatrix {
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

/// A matrix of the given storage: dense is zero-filled, sparse-block and sparse are empty
/// structures to fill (e.g. with `NM_triplet_alloc` + `NM_entry`). Release with `NM_free`.
#[no_mangle]
pub extern "C" fn NM_create(storageType: c_int, size0: c_int, size1: c_int) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_create",
        |_| null_mut(),
        || c_box(storage_for(storageType, size0, size1)?),
    )
}

fn fill(
    m: &mut NumericsMatrix,
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut std::os::raw::c_void,
) -> CResult<()> {
    if size0 < 0 || size1 < 0 {
        return Err(CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("size {size0}x{size1} is negative"),
        ));
    }
    let mut n = null_matrix();
    n.storageType = storageType;
    n.size0 = size0;
    n.size1 = size1;
    match storageType {
        NM_DENSE => n.matrix0 = data as *mut c_double,
        NM_SPARSE_BLOCK => n.matrix1 = data as *mut SparseBlockStructuredMatrix,
        NM_SPARSE => n.matrix2 = data as *mut NumericsSparseMatrix,
        other => {
            return Err(storage_err(format!(
                "unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
            )))
        }
    }
    *m = n;
    Ok(())
}

/// A matrix wrapping `data` without copying it (a `double*` for dense, a
/// `SparseBlockStructuredMatrix*` or a `NumericsSparseMatrix*`). `NM_free` will free `data`.
#[no_mangle]
pub extern "C" fn NM_create_from_data(
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut std::os::raw::c_void,
) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_create_from_data",
        |_| null_mut(),
        || {
            let mut m = null_matrix();
            fill(&mut m, storageType, size0, size1, data)?;
            c_box(m)
        },
    )
}

/// Sets `M` to wrap `data` (no copy); previous storage of `M` is not released.
#[no_mangle]
pub unsafe extern "C" fn NM_fill(
    M: *mut NumericsMatrix,
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut std::os::raw::c_void,
) {
    ffi_guard(
        "NM_fill",
        |_| (),
        || {
            if M.is_null() {
                return Err(CError::null("M"));
            }
            fill(&mut *M, storageType, size0, size1, data)
        },
    )
}

/// A sparse-block matrix wrapping `m1` (no copy).
#[no_mangle]
pub extern "C" fn NM_new_SBM(
    size0: c_int,
    size1: c_int,
    m1: *mut SparseBlockStructuredMatrix,
) -> *mut NumericsMatrix {
    NM_create_from_data(
        NM_SPARSE_BLOCK,
        size0,
        size1,
        m1 as *mut std::os::raw::c_void,
    )
}

/// Frees the storage of `m` (not the struct itself) and resets its pointers.
#[no_mangle]
pub unsafe extern "C" fn NM_clear(m: *mut NumericsMatrix) {
    ffi_guard(
        "NM_clear",
        |_| (),
        || {
            nm_clear_impl(m);
            Ok(())
        },
    )
}

/// Frees the storage of `m` and `m` itself; returns NULL (Siconos' idiom `M = NM_free(M)`).
#[no_mangle]
pub unsafe extern "C" fn NM_free(m: *mut NumericsMatrix) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_free",
        |_| null_mut(),
        || {
            nm_clear_impl(m);
            c_free(m);
            Ok(null_mut())
        },
    )
}

/// Allocates a triplet of capacity `nzmax` as the sparse storage of `A` (origin: triplet).
#[no_mangle]
pub unsafe extern "C" fn NM_triplet_alloc(A: *mut NumericsMatrix, nzmax: CS_INT) {
    ffi_guard(
        "NM_triplet_alloc",
        |_| (),
        || {
            if A.is_null() {
                return Err(CError::null("A"));
            }
            let a = &mut *A;
            let cap = nonneg(nzmax, "nzmax")?;
            if a.matrix2.is_null() {
                a.matrix2 = c_box(empty_nsm())?;
            }
            let t = c_box(CSparseMatrix {
                nzmax: cap as CS_INT,
                m: a.size0 as CS_INT,
                n: a.size1 as CS_INT,
                p: c_calloc::<CS_INT>(cap)?,
                i: c_calloc::<CS_INT>(cap)?,
                x: c_calloc::<c_double>(cap)?,
                nz: 0,
            })?;
            let s = &mut *a.matrix2;
            cs_free(s.triplet);
            s.triplet = t;
            s.origin = NSM_TRIPLET;
            a.storageType = NM_SPARSE;
            Ok(())
        },
    )
}

unsafe fn triplet_push(t: &mut CSparseMatrix, i: usize, j: usize, v: f64) -> CResult<()> {
    if t.nz >= t.nzmax {
        let cap = (2 * t.nzmax.max(1)) as usize;
        let grow =
            |p: *mut std::os::raw::c_void, elt: usize| -> CResult<*mut std::os::raw::c_void> {
                let q = libc::realloc(p, cap * elt);
                if q.is_null() {
                    Err(CError::new(
                        FC3D_ERR_INVALID_SIZE,
                        "cannot grow the triplet",
                    ))
                } else {
                    Ok(q)
                }
            };
        t.p = grow(t.p as _, std::mem::size_of::<CS_INT>())? as _;
        t.i = grow(t.i as _, std::mem::size_of::<CS_INT>())? as _;
        t.x = grow(t.x as _, std::mem::size_of::<c_double>())? as _;
        t.nzmax = cap as CS_INT;
    }
    let k = t.nz as usize;
    *t.i.add(k) = i as CS_INT;
    *t.p.add(k) = j as CS_INT;
    *t.x.add(k) = v;
    t.nz += 1;
    Ok(())
}

/// Sets entry (i, j) of a dense matrix, or appends it to the triplet of a sparse one (growing
/// it as needed). Sparse-block matrices are not supported here.
#[no_mangle]
pub unsafe extern "C" fn NM_entry(M: *mut NumericsMatrix, i: c_int, j: c_int, val: c_double) {
    ffi_guard(
        "NM_entry",
        |_| (),
        || {
            if M.is_null() {
                return Err(CError::null("M"));
            }
            let m = &mut *M;
            if i < 0 || j < 0 || i >= m.size0 || j >= m.size1 {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("entry ({i}, {j}) outside a {}x{} matrix", m.size0, m.size1),
                ));
            }
            match m.storageType {
                NM_DENSE => {
                    if m.matrix0.is_null() {
                        return Err(CError::null("dense matrix data (matrix0)"));
                    }
                    *m.matrix0.add(i as usize + j as usize * m.size0 as usize) = val;
                    Ok(())
                }
                NM_SPARSE => {
                    if m.matrix2.is_null() || (*m.matrix2).triplet.is_null() {
                        NM_triplet_alloc(M, 16);
                    }
                    if m.matrix2.is_null() || (*m.matrix2).triplet.is_null() {
                        return Err(CError::null("triplet storage"));
                    }
                    triplet_push(&mut *(*m.matrix2).triplet, i as usize, j as usize, val)
                }
                other => Err(storage_err(format!(
                    "NM_entry does not support storage type {other}"
                ))),
            }
        },
    )
}

/// Entry (i, j) of `M` in any storage (0 where nothing is stored); NaN on invalid input.
#[no_mangle]
pub unsafe extern "C" fn NM_get_value(M: *const NumericsMatrix, i: c_int, j: c_int) -> c_double {
    ffi_guard(
        "NM_get_value",
        |_| f64::NAN,
        || {
            if M.is_null() {
                return Err(CError::null("M"));
            }
            let m = &*M;
            if i < 0 || j < 0 || i >= m.size0 || j >= m.size1 {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("entry ({i}, {j}) outside a {}x{} matrix", m.size0, m.size1),
                ));
            }
            if m.storageType == NM_SPARSE_BLOCK {
                // Look the block up directly: a general SBM need not have 3x3 blocks.
                if m.matrix1.is_null() {
                    return Err(CError::null("sparse-block storage (matrix1)"));
                }
                let s = &*m.matrix1;
                let bs0 = c_slice(s.blocksize0, s.blocknumber0 as usize, "blocksize0")?;
                let bs1 = c_slice(s.blocksize1, s.blocknumber1 as usize, "blocksize1")?;
                let find = |bs: &[c_uint], x: c_int| bs.iter().position(|&c| (x as c_uint) < c);
                let (Some(bi), Some(bj)) = (find(bs0, i), find(bs1, j)) else {
                    return Err(storage_err("index outside the block structure"));
                };
                let r0 = if bi == 0 { 0 } else { bs0[bi - 1] } as usize;
                let c0 = if bj == 0 { 0 } else { bs1[bj - 1] } as usize;
                let nrows = bs0[bi] as usize - r0;
                let ptr = c_slice(s.index1_data, s.filled1, "index1_data")?;
                let cols = c_slice(s.index2_data, s.filled2, "index2_data")?;
                for k in ptr[bi]..ptr[bi + 1] {
                    if cols[k] == bj {
                        let b = *s.block.add(k);
                        return Ok(*b.add((i as usize - r0) + (j as usize - c0) * nrows));
                    }
                }
                return Ok(0.0);
            }
            Ok(delassus_from_c(m)?.get(i as usize, j as usize))
        },
    )
}

/// Replaces the storage of `B` by a sparse (triplet) copy of `A`, keeping entries with
/// `|value| > threshold`.
#[no_mangle]
pub unsafe extern "C" fn NM_copy_to_sparse(
    A: *const NumericsMatrix,
    B: *mut NumericsMatrix,
    threshold: c_double,
) {
    ffi_guard(
        "NM_copy_to_sparse",
        |_| (),
        || {
            if A.is_null() {
                return Err(CError::null("A"));
            }
            if B.is_null() {
                return Err(CError::null("B"));
            }
            let w = delassus_from_c(&*A)?;
            let mut t = Vec::new();
            w.for_each_entry(|i, j, v| {
                if v.abs() > threshold {
                    t.push((i, j, v))
                }
            });
            let (size0, size1) = ((*A).size0, (*A).size1);
            let tri = c_box(CSparseMatrix {
                nzmax: t.len() as CS_INT,
                m: size0 as CS_INT,
                n: size1 as CS_INT,
                p: c_copy(&t.iter().map(|e| e.1 as CS_INT).collect::<Vec<_>>())?,
                i: c_copy(&t.iter().map(|e| e.0 as CS_INT).collect::<Vec<_>>())?,
                x: c_copy(&t.iter().map(|e| e.2).collect::<Vec<_>>())?,
                nz: t.len() as CS_INT,
            })?;
            let mut nsm = empty_nsm();
            nsm.triplet = tri;
            nsm.origin = NSM_TRIPLET;
            let nsm = c_box(nsm)?;
            nm_clear_impl(B);
            let b = &mut *B;
            b.storageType = NM_SPARSE;
            b.size0 = size0;
            b.size1 = size1;
            b.matrix2 = nsm;
            Ok(())
        },
    )
}

/// A new empty sparse-block structure. Release with `SBM_clear` + `free`, or through `NM_free`.
#[no_mangle]
pub extern "C" fn SBM_new() -> *mut SparseBlockStructuredMatrix {
    ffi_guard("SBM_new", |_| null_mut(), || c_box(empty_sbm()))
}

/// Frees the blocks and index arrays of `blmat` (not the struct).
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

// ---------------------------------------------------------------------------------------------
// Matrix files: the matrix part of the .dat format (see `fc3d_core::io::dat`).

/// The label of a stream in error messages.
const STREAM_LABEL: &str = "<FILE stream>";

/// Reads a matrix from `file` with `parse`, which returns the value and the number of bytes it
/// used, then convert it with `to_c`. The whole rest of the stream is read, then, when the stream
/// is seekable (`ftell` works), it is repositioned just after what was used on success (the next
/// token), and back where it was on failure. On a non-seekable stream (a pipe) the rest of the
/// stream is consumed either way.
unsafe fn read_from_stream<T, U>(
    file: *mut libc::FILE,
    parse: impl FnOnce(&str) -> Result<(T, usize), fc3d_core::error::Fc3dError>,
    to_c: impl FnOnce(&T) -> CResult<U>,
) -> CResult<U> {
    if file.is_null() {
        return Err(CError::null("file"));
    }
    let start = libc::ftell(file);
    let result = match read_rest(file) {
        Err(e) => Err(e),
        Ok(bytes) => {
            // Matrix text is ASCII: a byte that is not UTF-8 can only end it (data after the matrix),
            // so only the valid prefix is parsed; byte offsets stay those of the stream.
            let (text, bad_byte) = match std::str::from_utf8(&bytes) {
                Ok(t) => (t, None),
                Err(e) => (
                    std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or(""),
                    Some(e.valid_up_to()),
                ),
            };
            match parse(text) {
                Ok((value, used)) => to_c(&value).map(|c| (c, used)),
                Err(e) => {
                    let mut err = CError::from(e);
                    if let Some(at) = bad_byte {
                        err.message += &format!(" (the stream holds a byte that is not text at offset {at} from where reading started)");
                    }
                    Err(err)
                }
            }
        }
    };
    if start >= 0 {
        let target = match &result {
            Ok((_, used)) => start + *used as libc::c_long,
            Err(_) => start,
        };
        libc::fseek(file, target, libc::SEEK_SET);
    }
    result.map(|(c, _)| c)
}

/// A matrix read from an open stream, as written by `NM_write_in_file` (`storageType size0
/// size1` and the body; see `fc3d_core::io::dat`). Release with `NM_free`.
///
/// On a seekable stream (a regular file) only the matrix is consumed: on success the stream is
/// left at the first token after the matrix (as Siconos' reader leaves it, but for the whitespace
/// after a CSC dump, which Siconos leaves unread), so a host may read what follows; on failure it
/// is put back where it was. On a stream that cannot seek (a pipe) the rest of the stream is read.
///
/// NULL on failure: `FC3D_ERR_PARSE` for malformed text (`fc3d_last_error_message` names the
/// token), `FC3D_ERR_INVALID_STORAGE` for what fc3d does not represent (a sparse-block matrix
/// whose blocks are not all 3x3, a half-triplet sparse matrix), `FC3D_ERR_NULL_POINTER`,
/// `FC3D_ERR_IO`.
#[no_mangle]
pub unsafe extern "C" fn NM_new_from_file(file: *mut libc::FILE) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_new_from_file",
        |_| null_mut(),
        || {
            read_from_stream(
                file,
                |text| parse_matrix_prefix(text, STREAM_LABEL),
                |w| matrix_to_c(w),
            )
        },
    )
}

/// A matrix read from the file `filename` (see `NM_new_from_file`). Release with `NM_free`.
/// NULL on failure (`FC3D_ERR_IO` when the file cannot be read).
#[no_mangle]
pub unsafe extern "C" fn NM_new_from_filename(filename: *const c_char) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_new_from_filename",
        |_| null_mut(),
        || {
            let path = c_filename(filename)?;
            let bytes = std::fs::read(path)
                .map_err(|e| CError::new(FC3D_ERR_IO, format!("{path}: cannot read: {e}")))?;
            let w = parse_matrix(&String::from_utf8_lossy(&bytes), path)?;
            matrix_to_c(&w)
        },
    )
}

fn matrix_text(M: *const NumericsMatrix) -> CResult<Vec<u8>> {
    if M.is_null() {
        return Err(CError::null("M"));
    }
    // SAFETY: checked non-NULL; the caller passes a valid matrix.
    let m = unsafe { &*M };
    // A sparse-block matrix without blocks (`NM_create(NM_SPARSE_BLOCK, ..)` not filled yet) is
    // the zero matrix of its size, written as Siconos does (a lone 0 after the header).
    let no_blocks = m.storageType == NM_SPARSE_BLOCK
        && !m.matrix1.is_null()
        && unsafe { (*m.matrix1).nbblocks } == 0
        && m.size0 >= 0
        && m.size1 >= 0
        && m.size0 % 3 == 0
        && m.size1 % 3 == 0;
    let w = if no_blocks {
        let (nbr, nbc) = (m.size0 as usize / 3, m.size1 as usize / 3);
        Delassus::SparseBlock(BlockSparseMatrix::new(
            nbr,
            nbc,
            vec![0; nbr + 1],
            Vec::new(),
            Vec::new(),
        )?)
    } else {
        unsafe { delassus_from_c(m)? }
    };
    let mut out = Vec::new();
    write_matrix(&w, &mut out).map_err(|e| CError::new(FC3D_ERR_IO, e.to_string()))?;
    Ok(out)
}

/// Writes `M` to an open stream as Siconos does (`storageType size0 size1` and the body), values
/// in their shortest exactly round-tripping form (Siconos' own writer prints sparse values with
/// `%g`). Sparse matrices are written as a CSparse triplet dump (origin `NSM_TRIPLET`), whatever
/// their origin. Both Siconos' `NM_new_from_file` and fc3d's read it back.
///
/// Nothing is written when `M` cannot be represented by fc3d (a sparse-block matrix whose blocks
/// are not all 3x3, non-finite values, an inconsistent structure): see `fc3d_last_error_code`.
#[no_mangle]
pub unsafe extern "C" fn NM_write_in_file(M: *const NumericsMatrix, file: *mut libc::FILE) {
    ffi_guard(
        "NM_write_in_file",
        |_| (),
        || {
            let text = matrix_text(M)?;
            if file.is_null() {
                return Err(CError::null("file"));
            }
            write_all(file, &text)
        },
    )
}

/// Writes `M` to the file `filename`, created or truncated (see `NM_write_in_file`). The file is
/// not touched when `M` cannot be written.
#[no_mangle]
pub unsafe extern "C" fn NM_write_in_filename(M: *const NumericsMatrix, filename: *const c_char) {
    ffi_guard(
        "NM_write_in_filename",
        |_| (),
        || {
            let text = matrix_text(M)?;
            let path = c_filename(filename)?;
            std::fs::write(path, text)
                .map_err(|e| CError::new(FC3D_ERR_IO, format!("{path}: cannot write: {e}")))
        },
    )
}

/// A sparse-block matrix read from an open stream, as written by Siconos' `SBM_write_in_file`:
/// the sparse-block body without the `storageType size0 size1` header (`nbblocks`, then the block
/// structure and the blocks). The size comes from the cumulative block sizes. Blocks must all be
/// 3x3 (`FC3D_ERR_INVALID_STORAGE` otherwise); a lone `0` gives an empty 0x0 matrix (Siconos
/// returns NULL there). The stream is consumed as by `NM_new_from_file`.
/// Release with `SBM_clear` + `free` (or through `NM_free` once wrapped by `NM_new_SBM`).
/// NULL on failure (`FC3D_ERR_PARSE` for malformed text).
#[no_mangle]
pub unsafe extern "C" fn SBM_new_from_file(
    file: *mut libc::FILE,
) -> *mut SparseBlockStructuredMatrix {
    ffi_guard(
        "SBM_new_from_file",
        |_| null_mut(),
        || read_from_stream(file, |text| parse_sbm_prefix(text, STREAM_LABEL), sbm_to_c),
    )
}
