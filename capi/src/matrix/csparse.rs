//! CSparse storage (`CSparseMatrix` as triplet, CSC or Siconos' CSR, inside a
//! `NumericsSparseMatrix`): validated conversion to the core's `CsrMatrix`, the C-allocated CSC
//! copy of a core matrix, empty structures, release and triplet growth.

use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::{c_slice, indices, nonneg, storage_err};
use super::{NSM_CSC, NSM_CSR, NSM_HALF_TRIPLET, NSM_TRIPLET, NSM_UNKNOWN};
use crate::alloc::{c_box, c_copy, c_free};
use crate::types::*;
use crate::{CError, CResult, FC3D_ERR_INVALID_SIZE};
use fc3d_core::matrix::CsrMatrix;

/// Core view of a CSparse matrix as `(rows, cols, triplets or compressed form)`, validated.
pub(super) unsafe fn csr_from_cs(
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

// ---------------------------------------------------------------------------------------------
// Building C matrices from core ones.

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

pub(super) fn empty_nsm() -> NumericsSparseMatrix {
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

// ---------------------------------------------------------------------------------------------
// Releasing.

pub(super) unsafe fn cs_free(cs: *mut CSparseMatrix) {
    if cs.is_null() {
        return;
    }
    c_free((*cs).p);
    c_free((*cs).i);
    c_free((*cs).x);
    c_free(cs);
}

pub(super) unsafe fn nsm_clear(s: *mut NumericsSparseMatrix) {
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

pub(super) unsafe fn triplet_push(
    t: &mut CSparseMatrix,
    i: usize,
    j: usize,
    v: f64,
) -> CResult<()> {
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
