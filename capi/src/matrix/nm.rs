//! The `NM_*` functions of Siconos' API on a `NumericsMatrix` (creation, filling, entries,
//! release, sparse copy).

use std::os::raw::{c_double, c_int, c_uint};
use std::ptr::null_mut;

use super::csparse::{cs_free, empty_nsm, triplet_push};
use super::sbm::empty_sbm;
use super::{c_slice, delassus_from_c, nm_clear_impl, nonneg, null_matrix, storage_err};
use super::{NM_DENSE, NM_SPARSE, NM_SPARSE_BLOCK, NSM_TRIPLET};
use crate::alloc::{c_box, c_calloc, c_copy, c_free};
use crate::types::*;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_SIZE};

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// A new empty matrix (storage NM_UNKNOWN, sizes 0). Release with `NM_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn NM_new() -> *mut NumericsMatrix {
    ffi_guard("NM_new", |_| null_mut(), || c_box(null_matrix()))
}

/// Resets every field of `A` (frees nothing).
#[cfg(feature = "siconos-abi")]
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

/// A matrix of the given storage: dense is zero-filled, sparse-block and sparse are empty
/// structures to fill (e.g. with `NM_triplet_alloc` + `NM_entry`). Release with `NM_free`.
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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

/// Sets entry (i, j) of a dense matrix, or appends it to the triplet of a sparse one (growing
/// it as needed). Sparse-block matrices are not supported here.
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
#[cfg(feature = "siconos-abi")]
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
