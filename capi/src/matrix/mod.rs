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

use std::borrow::Cow;
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::alloc::{c_box, c_copy, c_free};
use super::types::*;
use super::{CError, CResult, FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_STORAGE};
use csparse::{csc_to_c, csr_from_cs, empty_nsm, nsm_clear};
use fc3d_core::matrix::{Delassus, DenseMatrix};
use sbm::{block_sparse_from_sbm, sbm_clear_impl, sbm_to_c};

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
