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
//!
//! Layout: this file holds the shared helpers and the conversions between a C `NumericsMatrix`
//! and the core's `Delassus` (used by the driver and the problem functions); `csparse` the
//! CSparse (triplet, CSC, CSR) storage; `nm` the `NM_*` functions; `sbm` the sparse-block
//! `SBM_*`/`SBCM_*` functions; `file` the matrix files and streams.

#![allow(non_snake_case)]

// cbindgen reads a module's own items, then its submodules in the order declared here, so this
// order (`NM_*`, then `SBM_*`/`SBCM_*`, then the file functions) is the order of include/fc3d.h.
// The blank lines keep rustfmt from sorting the declarations.
mod csparse;

mod nm;

mod sbm;

mod file;

mod stored;

use std::borrow::Cow;
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_calloc, c_free, CStore};
use super::types::*;
use super::{CError, CResult, FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_STORAGE};
use csparse::{csc_to_c, csr_from_cs, empty_nsm, nsm_clear};
use fc3d_core::io::dat::ReadMatrix;
use fc3d_core::matrix::{Delassus, DenseMatrix};
pub(crate) use file::read_from_stream;
use sbm::{
    block_sparse_from_sbm, check_sbm_clearable, csr_from_uniform_sbm, sbm_clear_impl, sbm_to_c,
};
pub(crate) use stored::{stored_from_c, stored_to_c};

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

fn size_err(msg: impl Into<String>) -> CError {
    CError::new(FC3D_ERR_INVALID_SIZE, msg)
}

fn nonneg(v: CS_INT, what: &str) -> CResult<usize> {
    usize::try_from(v).map_err(|_| size_err(format!("{what} = {v} is negative")))
}

/// The number of bytes of `len` values of `T`, if that many can exist in one allocation
/// (at most `isize::MAX` bytes, Rust's and C's limit for one object).
fn byte_size<T>(len: usize) -> Option<usize> {
    len.checked_mul(std::mem::size_of::<T>())
        .filter(|&b| b <= isize::MAX as usize)
}

/// Checks that `len` values of `T` at `p` could be one array: the byte size fits one object,
/// the array does not wrap around the address space, `p` is aligned for `T`.
fn check_extent<T>(p: *const T, len: usize, what: &str) -> CResult<()> {
    let fits = byte_size::<T>(len).is_some_and(|b| (p as usize).checked_add(b).is_some());
    if !fits {
        return Err(size_err(format!(
            "{what}: {len} elements of {} bytes exceed the address space",
            std::mem::size_of::<T>()
        )));
    }
    if !p.is_aligned() {
        return Err(storage_err(format!(
            "{what} is not aligned for its type (address {p:p})"
        )));
    }
    Ok(())
}

/// A slice view of a C array of `len` elements, as the host declares it; `len == 0` accepts
/// NULL. NULL for a non-empty array, a length no array can have and a misaligned pointer are
/// errors (the memory behind a valid pointer is the host's promise: it cannot be checked).
pub(crate) unsafe fn c_slice<'a, T>(p: *const T, len: usize, what: &str) -> CResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(CError::null(what));
    }
    check_extent(p, len, what)?;
    Ok(std::slice::from_raw_parts(p, len))
}

/// Memory the host may release with `free()` (an allocation of `malloc`/`calloc`/`realloc`):
/// the number of bytes usable in the heap block at `p`, where the C library can tell.
/// Used only on arrays fc3d is about to free or grow (they must be heap blocks anyway), so that
/// a count above what the block holds is refused instead of read past it.
unsafe fn heap_block_bytes<T>(p: *const T) -> Option<usize> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        Some(libc::malloc_usable_size(p as *mut libc::c_void))
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    {
        let _ = p;
        None
    }
}

/// Checks that the heap block at `p` (a host array fc3d will free or grow) holds at least
/// `len` values of `T`.
unsafe fn check_heap_len<T>(p: *const T, len: usize, what: &str) -> CResult<()> {
    if len == 0 || p.is_null() {
        return Ok(());
    }
    let need = byte_size::<T>(len).ok_or_else(|| {
        storage_err(format!(
            "{what} declares {len} elements: no array is that large"
        ))
    })?;
    match heap_block_bytes(p) {
        Some(have) if have < need => Err(storage_err(format!(
            "{what} declares {len} elements but its heap block holds {} bytes ({} elements)",
            have,
            have / std::mem::size_of::<T>().max(1)
        ))),
        _ => Ok(()),
    }
}

/// A C allocation owned until handed over with `into_raw`: partial results of a call that
/// fails half-way are freed, not leaked.
pub(crate) struct CBuf<T> {
    ptr: *mut T,
    len: usize,
}

impl<T> CBuf<T> {
    /// `len` zeroed elements (`calloc`).
    pub(crate) fn zeroed(len: usize, what: &str) -> CResult<Self> {
        if byte_size::<T>(len).is_none() {
            return Err(size_err(format!(
                "{what}: {len} elements of {} bytes exceed the address space",
                std::mem::size_of::<T>()
            )));
        }
        Ok(CBuf {
            ptr: c_calloc::<T>(len)?,
            len,
        })
    }

    pub(crate) fn as_mut_slice(&mut self) -> &mut [T] {
        // SAFETY: ptr holds len zero-initialised elements of plain C data.
        unsafe { std::slice::from_raw_parts_mut(self.ptr, self.len) }
    }

    /// Hands the allocation over (to a struct the host will free).
    pub(crate) fn into_raw(self) -> *mut T {
        let p = self.ptr;
        std::mem::forget(self);
        p
    }
}

impl<T: Copy> CBuf<T> {
    /// A C-allocated copy of `values`.
    pub(crate) fn copy(values: &[T], what: &str) -> CResult<Self> {
        let mut b = Self::zeroed(values.len(), what)?;
        b.as_mut_slice().copy_from_slice(values);
        Ok(b)
    }
}

impl<T> Drop for CBuf<T> {
    fn drop(&mut self) {
        // SAFETY: ptr came from c_calloc and was not handed over.
        unsafe { c_free(self.ptr) };
    }
}

/// The CSparse matrix a `NumericsSparseMatrix` designates by its origin (for an unknown origin:
/// the CSC, else the triplet, else the CSR form), with its kind; `None` when that pointer is
/// NULL.
pub(crate) unsafe fn sparse_origin(
    s: &NumericsSparseMatrix,
) -> CResult<Option<(*mut CSparseMatrix, c_int)>> {
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
    match s.origin {
        NSM_UNKNOWN => Ok(pick(NSM_CSC)
            .or_else(|| pick(NSM_TRIPLET))
            .or_else(|| pick(NSM_CSR))),
        NSM_TRIPLET | NSM_CSC | NSM_CSR | NSM_HALF_TRIPLET => Ok(pick(s.origin)),
        other => Err(storage_err(format!(
            "unknown sparse origin {other} (0 unknown, 1 triplet, 2 CSC, 3 CSR, 4 half triplet)"
        ))),
    }
}

/// The CSparse matrix of a sparse NumericsMatrix, as `sparse_origin`, NULL being an error.
unsafe fn sparse_source(s: &NumericsSparseMatrix) -> CResult<(&CSparseMatrix, c_int)> {
    match sparse_origin(s)? {
        Some((cs, kind)) => Ok((&*cs, kind)),
        None if s.origin == NSM_HALF_TRIPLET || !s.half_triplet.is_null() => Err(storage_err(
            "half-triplet (symmetric half) storage is rejected: W is not symmetric in general",
        )),
        None => Err(CError::null(&format!(
            "the CSparse matrix of the sparse storage (origin {})",
            s.origin
        ))),
    }
}

/// The sizes of a NumericsMatrix as `usize`; negative sizes are an error.
fn matrix_dims(m: &NumericsMatrix) -> CResult<(usize, usize)> {
    if m.size0 < 0 || m.size1 < 0 {
        return Err(size_err(format!(
            "matrix size {}x{} is negative",
            m.size0, m.size1
        )));
    }
    Ok((m.size0 as usize, m.size1 as usize))
}

/// The core view of a NumericsMatrix (dense and sparse-block storage are borrowed, not copied),
/// every value checked finite. Every number of the host's structs is checked before an array
/// is read with it.
pub(crate) unsafe fn delassus_from_c<'a>(m: &'a NumericsMatrix) -> CResult<Delassus<'a>> {
    let w = delassus_from_c_blocks(m, 3)?;
    w.check_finite()?;
    Ok(w)
}

/// The W of a problem of contact dimension `block`, as [`delassus_from_c`] but, for a
/// sparse-block W of 3x3 blocks, a view of the host's blocks whose values are not read here
/// (see `Delassus::check_finite`); a sparse-block W of 2x2 blocks (a 2D problem) is copied into
/// a general sparse matrix.
pub(crate) unsafe fn delassus_from_c_blocks<'a>(
    m: &'a NumericsMatrix,
    block: usize,
) -> CResult<Delassus<'a>> {
    let (rows, cols) = matrix_dims(m)?;
    if m.storageType == NM_SPARSE_BLOCK && block != 3 {
        if m.matrix1.is_null() {
            return Err(CError::null("sparse-block storage (matrix1)"));
        }
        return Ok(Delassus::Sparse(csr_from_uniform_sbm(
            &*m.matrix1,
            rows,
            cols,
            block,
        )?));
    }
    match m.storageType {
        NM_DENSE => {
            let n = rows
                .checked_mul(cols)
                .ok_or_else(|| size_err("matrix size overflows"))?;
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
            let (cs, kind) = sparse_source(&*m.matrix2)?;
            Ok(Delassus::Sparse(csr_from_cs(cs, kind, rows, cols)?))
        }
        other => Err(storage_err(format!(
            "unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
        ))),
    }
}

// ---------------------------------------------------------------------------------------------
// Building C matrices from core ones.

/// Siconos' `NM_null` state: unknown storage, sizes -1, no storage. `destructible` must then be
/// set to the matrix's own address (`own_destructible`) once it has one.
fn null_matrix() -> NumericsMatrix {
    NumericsMatrix {
        storageType: NM_UNKNOWN,
        size0: -1,
        size1: -1,
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

/// The C NumericsMatrix of a matrix a reader stored in C arrays ([`CStore`]): a dense matrix's
/// values and a sparse-block matrix's index arrays and blocks become the matrix's storage as
/// they are (no copy); a matrix the reader built as fc3d's own (sparse) is copied. Everything
/// is freed on failure.
pub(crate) fn matrix_from_read(w: ReadMatrix<CStore>) -> CResult<*mut NumericsMatrix> {
    let mut m = null_matrix();
    match w {
        ReadMatrix::Built(w) => return matrix_to_c(&w),
        ReadMatrix::Dense { rows, cols, values } => {
            m.size0 = c_size(rows)?;
            m.size1 = c_size(cols)?;
            if rows.checked_mul(cols) != Some(values.len()) {
                return Err(size_err(format!(
                    "a dense {rows}x{cols} matrix read with {} values",
                    values.len()
                )));
            }
            let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
            m.storageType = NM_DENSE;
            m.matrix0 = values.into_raw();
            Ok(finish_matrix(out, m))
        }
        ReadMatrix::SparseBlock {
            block_rows,
            block_cols,
            row_ptr,
            col_idx,
            blocks,
        } => {
            m.size0 = c_size(block_rows.saturating_mul(3))?;
            m.size1 = c_size(block_cols.saturating_mul(3))?;
            let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
            m.storageType = NM_SPARSE_BLOCK;
            m.matrix1 = sbm::sbm_from_parts(block_rows, block_cols, row_ptr, col_idx, blocks)?;
            Ok(finish_matrix(out, m))
        }
    }
}

/// Writes `m` into `out` (a fresh allocation) and hands it over.
fn finish_matrix(out: CBuf<NumericsMatrix>, m: NumericsMatrix) -> *mut NumericsMatrix {
    let out = out.into_raw();
    // SAFETY: out is a fresh allocation for one NumericsMatrix.
    unsafe {
        out.write(m);
        own_destructible(out);
    }
    out
}

/// A C-allocated NumericsMatrix holding a copy of `w` in the same storage
/// (CSR becomes Siconos' CSC origin). Nothing is left allocated on failure.
pub(crate) fn matrix_to_c(w: &Delassus<'_>) -> CResult<*mut NumericsMatrix> {
    let mut m = null_matrix();
    m.size0 = c_size(w.nrows())?;
    m.size1 = c_size(w.ncols())?;
    let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
    match w {
        Delassus::Dense(d) => {
            m.storageType = NM_DENSE;
            m.matrix0 = CBuf::copy(d.values(), "dense matrix")?.into_raw();
        }
        Delassus::SparseBlock(b) => {
            m.storageType = NM_SPARSE_BLOCK;
            m.matrix1 = sbm_to_c(b)?;
        }
        Delassus::Sparse(s) => {
            m.storageType = NM_SPARSE;
            let csc = csc_to_c(s)?;
            let nsm = match CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage") {
                Ok(b) => b.into_raw(),
                Err(e) => {
                    // SAFETY: csc was made just above and is referenced nowhere else.
                    unsafe { csparse::cs_free(csc) };
                    return Err(e);
                }
            };
            let mut v = empty_nsm();
            v.csc = csc;
            v.origin = NSM_CSC;
            // SAFETY: nsm is a fresh allocation for one NumericsSparseMatrix.
            unsafe { nsm.write(v) };
            m.matrix2 = nsm;
        }
    }
    let out = out.into_raw();
    // SAFETY: out is a fresh allocation for one NumericsMatrix.
    unsafe {
        out.write(m);
        own_destructible(out);
    }
    Ok(out)
}

/// Siconos' default: a matrix is its own "destructible" matrix (`NM_destructible` is true).
pub(crate) unsafe fn own_destructible(m: *mut NumericsMatrix) {
    (*m).destructible = m;
}

// ---------------------------------------------------------------------------------------------
// Releasing.

/// Checks that `nm_clear_impl` can release `m` without reading past an array: a sparse-block
/// storage whose `nbblocks` exceeds the heap block holding its block pointers is refused.
pub(crate) unsafe fn check_clearable(m: *const NumericsMatrix) -> CResult<()> {
    if let Some(mm) = m.as_ref() {
        if let Some(s) = mm.matrix1.as_ref() {
            check_sbm_clearable(s)?;
        }
    }
    Ok(())
}

/// Frees the storage of `m` and resets its pointers, or nothing at all when it cannot be freed
/// safely (`check_clearable`: the error is then the caller's to report, or the memory leaks).
pub(crate) unsafe fn nm_clear_impl(m: *mut NumericsMatrix) {
    if m.is_null() || check_clearable(m).is_err() {
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
    // As Siconos' NM_clear: a matrix whose destructible copy is another matrix (made by
    // Siconos' NM_preserve) releases that copy's storage too, then is its own again.
    let other = mm.destructible;
    mm.destructible = m;
    if !other.is_null() && other != m && (*other).destructible == other {
        nm_clear_impl(other);
    }
}

// ---------------------------------------------------------------------------------------------
// Copying.

/// A deep C-allocated copy of a host NumericsMatrix in the same storage and layout, as Siconos'
/// `NM_copy` into a new matrix: the dense values, the sparse-block structure with its blocks, or
/// the sparse origin form (the other forms and the factorisation caches are not copied; a
/// sparse copy's `nzmax` is its entry count). Checked first as the solvers check it. Nothing is
/// left allocated on failure.
pub(crate) unsafe fn nm_duplicate(m: &NumericsMatrix) -> CResult<*mut NumericsMatrix> {
    delassus_from_c(m)?;
    let (rows, cols) = matrix_dims(m)?;
    let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
    let mut copy = null_matrix();
    copy.storageType = m.storageType;
    copy.size0 = m.size0;
    copy.size1 = m.size1;
    copy.version = m.version;
    match m.storageType {
        NM_DENSE => {
            let values = c_slice(m.matrix0 as *const c_double, rows * cols, "matrix0")?;
            copy.matrix0 = CBuf::copy(values, "dense matrix")?.into_raw();
        }
        NM_SPARSE_BLOCK => copy.matrix1 = sbm::sbm_duplicate(&*m.matrix1)?,
        _ => {
            let s = &*m.matrix2;
            let (cs, kind) = sparse_source(s)?;
            let nsm = CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage")?;
            let form = csparse::cs_duplicate(cs, kind, rows, cols)?;
            let mut v = empty_nsm();
            v.origin = kind;
            v.versions = s.versions;
            match kind {
                NSM_TRIPLET => v.triplet = form,
                NSM_CSR => v.csr = form,
                _ => v.csc = form,
            }
            let nsm = nsm.into_raw();
            nsm.write(v);
            copy.matrix2 = nsm;
        }
    }
    let out = out.into_raw();
    out.write(copy);
    own_destructible(out);
    Ok(out)
}

/// Scales a host NumericsMatrix in place by `factor`, as Siconos' `NM_scal`: the dense values or
/// every block, the version raised past the matrix's newest; a sparse matrix is scaled in its CSC
/// form, which becomes the origin (`csparse::nsm_scale_to_csc`). The matrix is checked first as
/// the solvers check it; nothing is changed on failure.
pub(crate) unsafe fn nm_scale_in_place(m: &mut NumericsMatrix, factor: f64) -> CResult<()> {
    delassus_from_c(m)?;
    let (rows, cols) = matrix_dims(m)?;
    match m.storageType {
        NM_DENSE => {
            if rows * cols > 0 {
                for v in std::slice::from_raw_parts_mut(m.matrix0, rows * cols) {
                    *v *= factor;
                }
            }
            m.version.number = m.version.number.saturating_add(1);
        }
        NM_SPARSE_BLOCK => {
            let s = &mut *m.matrix1;
            // Checked above: nbblocks 3x3 blocks behind non-NULL pointers.
            let ptrs = c_slice(
                s.block as *const *mut c_double,
                s.nbblocks as usize,
                "SBM block array",
            )?;
            for &b in ptrs {
                for v in std::slice::from_raw_parts_mut(b, 9) {
                    *v *= factor;
                }
            }
            s.version.number = s.version.number.saturating_add(1);
        }
        _ => csparse::nsm_scale_to_csc(&mut *m.matrix2, rows, cols, factor)?,
    }
    Ok(())
}
