//! The `NM_*` functions of Siconos' API on a `NumericsMatrix` (creation, filling, entries,
//! release, sparse copy).
//!
//! A matrix handed in by a host is checked where it is used: sizes, storage type, the counts
//! and index arrays of its storage (see `csparse` and `sbm`), never trusted. A function that
//! fails changes nothing and leaves a code and a message (`fc3d_last_error_message`).

use std::os::raw::{c_double, c_int, c_void};
use std::ptr::null_mut;

use super::csparse::{cs_free, csc_insert, empty_nsm, triplet_new, triplet_push, CsView};
use super::own_destructible;
use super::sbm::{empty_sbm, sbm_get};
use super::{byte_size, c_slice, check_clearable, delassus_from_c, matrix_dims, nm_clear_impl};
use super::{null_matrix, size_err, sparse_origin, sparse_source, storage_err, CBuf};
use super::{NM_DENSE, NM_SPARSE, NM_SPARSE_BLOCK, NSM_CSC, NSM_CSR, NSM_TRIPLET};
use crate::alloc::c_free;
use crate::types::*;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_OUT_OF_MEMORY};
use fc3d_core::error::Fc3dError;

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// A new empty matrix in Siconos' `NM_null` state (storage NM_UNKNOWN, sizes -1, its own
/// destructible matrix). Release with `NM_free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn NM_new() -> *mut NumericsMatrix {
    ffi_guard(
        "NM_new",
        |_| null_mut(),
        || {
            let p = boxed(null_matrix())?;
            // SAFETY: p is the fresh matrix.
            unsafe { own_destructible(p) };
            Ok(p)
        },
    )
}

/// A C-allocated struct holding `v`.
fn boxed<T>(v: T) -> CResult<*mut T> {
    let p = CBuf::<T>::zeroed(1, "struct")?.into_raw();
    // SAFETY: p is a fresh allocation for one T.
    unsafe { p.write(v) };
    Ok(p)
}

/// Resets every field of `A` as Siconos does (storage NM_UNKNOWN, sizes -1, NULL storage,
/// version 0, `destructible = A`); frees nothing.
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
            own_destructible(A);
            Ok(())
        },
    )
}

fn check_sizes(size0: c_int, size1: c_int) -> CResult<()> {
    if size0 < 0 || size1 < 0 {
        return Err(size_err(format!("size {size0}x{size1} is negative")));
    }
    Ok(())
}

fn unknown_storage(storage: c_int) -> CError {
    storage_err(format!(
        "unknown storage type {storage} (0 dense, 1 sparse-block, 2 sparse)"
    ))
}

fn storage_for(storageType: c_int, size0: c_int, size1: c_int) -> CResult<NumericsMatrix> {
    check_sizes(size0, size1)?;
    let mut m = null_matrix();
    m.storageType = storageType;
    m.size0 = size0;
    m.size1 = size1;
    match storageType {
        NM_DENSE => {
            let n = (size0 as usize) * (size1 as usize);
            if byte_size::<c_double>(n).is_none() {
                return Err(size_err(format!(
                    "a dense {size0}x{size1} matrix exceeds the address space"
                )));
            }
            m.matrix0 = CBuf::<c_double>::zeroed(n, "dense matrix")?.into_raw();
        }
        NM_SPARSE_BLOCK => {
            let mut sbm = empty_sbm();
            sbm.version.number = 1;
            m.matrix1 = boxed(sbm)?;
        }
        NM_SPARSE => m.matrix2 = boxed(empty_nsm())?,
        other => return Err(unknown_storage(other)),
    }
    if storageType == NM_DENSE {
        m.version.number = 1;
    }
    Ok(m)
}

/// A matrix of the given storage: dense is zero-filled, sparse-block and sparse are empty
/// structures to fill (e.g. with `NM_triplet_alloc` + `NM_entry`). Release with `NM_free`.
/// NULL with `FC3D_ERR_INVALID_SIZE` for negative sizes or a dense size beyond the address
/// space, `FC3D_ERR_OUT_OF_MEMORY`, `FC3D_ERR_INVALID_STORAGE` for an unknown storage type.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn NM_create(storageType: c_int, size0: c_int, size1: c_int) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_create",
        |_| null_mut(),
        || {
            // The struct first: storage_for allocates one thing, freed by nobody if this failed.
            let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
            let m = storage_for(storageType, size0, size1)?;
            let p = out.into_raw();
            // SAFETY: p is a fresh allocation for one NumericsMatrix.
            unsafe {
                p.write(m);
                own_destructible(p);
            }
            Ok(p)
        },
    )
}

fn fill(
    m: &mut NumericsMatrix,
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut c_void,
) -> CResult<()> {
    check_sizes(size0, size1)?;
    let mut n = null_matrix();
    n.storageType = storageType;
    n.size0 = size0;
    n.size1 = size1;
    match storageType {
        NM_DENSE => n.matrix0 = data as *mut c_double,
        NM_SPARSE_BLOCK => n.matrix1 = data as *mut SparseBlockStructuredMatrix,
        NM_SPARSE => n.matrix2 = data as *mut NumericsSparseMatrix,
        other => return Err(unknown_storage(other)),
    }
    // Siconos counts the data's first version: 1 for a dense array, one past a sparse-block
    // structure's own version.
    if !data.is_null() {
        match storageType {
            NM_DENSE => n.version.number = 1,
            NM_SPARSE_BLOCK => {
                // SAFETY: the host hands over a SparseBlockStructuredMatrix for this storage.
                let v = unsafe { &mut (*n.matrix1).version.number };
                *v = v.saturating_add(1);
            }
            _ => {}
        }
    }
    *m = n;
    // SAFETY: m is a valid matrix (a reference).
    unsafe { own_destructible(m) };
    Ok(())
}

/// A matrix wrapping `data` without copying it (a `double*` for dense, a
/// `SparseBlockStructuredMatrix*` or a `NumericsSparseMatrix*`; NULL is kept as NULL). `NM_free`
/// will free `data`. The data is checked when the matrix is used, not here.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn NM_create_from_data(
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut c_void,
) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_create_from_data",
        |_| null_mut(),
        || {
            let mut m = null_matrix();
            fill(&mut m, storageType, size0, size1, data)?;
            let p = boxed(m)?;
            // SAFETY: p is the fresh matrix (fill pointed it at the local copy).
            unsafe { own_destructible(p) };
            Ok(p)
        },
    )
}

/// Sets `M` to wrap `data` (no copy); previous storage of `M` is not released. Negative sizes
/// and unknown storage types are refused and leave `M` unchanged.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_fill(
    M: *mut NumericsMatrix,
    storageType: c_int,
    size0: c_int,
    size1: c_int,
    data: *mut c_void,
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
    NM_create_from_data(NM_SPARSE_BLOCK, size0, size1, m1 as *mut c_void)
}

/// Frees the storage of `m` (not the struct itself) and resets its pointers. Refused, with
/// nothing freed (`FC3D_ERR_INVALID_STORAGE`), when a sparse-block storage's `nbblocks` exceeds
/// the heap block that holds its block pointers.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_clear(m: *mut NumericsMatrix) {
    ffi_guard(
        "NM_clear",
        |_| (),
        || {
            check_clearable(m)?;
            nm_clear_impl(m);
            Ok(())
        },
    )
}

/// Frees the storage of `m` and `m` itself; returns NULL (Siconos' idiom `M = NM_free(M)`).
/// When the storage cannot be freed safely (see `NM_clear`) nothing is freed: NULL is returned
/// all the same, with `fc3d_last_error_code()` set.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_free(m: *mut NumericsMatrix) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_free",
        |_| null_mut(),
        || {
            check_clearable(m)?;
            nm_clear_impl(m);
            c_free(m);
            Ok(null_mut())
        },
    )
}

/// Allocates a triplet of capacity `nzmax` as the sparse storage of `A` (origin: triplet),
/// replacing (and freeing) a previous triplet. All or nothing: a NULL `A`, negative sizes or
/// `nzmax`, a capacity beyond the address space (`FC3D_ERR_INVALID_SIZE`) or memory that cannot
/// be had (`FC3D_ERR_OUT_OF_MEMORY`) leave `A` unchanged.
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
            matrix_dims(a)?;
            let cap = super::nonneg(nzmax, "nzmax")?;
            install_triplet(a, cap).map(|_| ())
        },
    )
}

/// Gives `a` a new empty triplet of capacity `cap` as its sparse storage (a new sparse structure
/// when it has none); returns it. All or nothing.
unsafe fn install_triplet(a: &mut NumericsMatrix, cap: usize) -> CResult<*mut CSparseMatrix> {
    let nsm = if a.matrix2.is_null() {
        Some(CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage")?)
    } else {
        None
    };
    let t = triplet_new(a.size0 as CS_INT, a.size1 as CS_INT, cap)?;
    if let Some(b) = nsm {
        let p = b.into_raw();
        p.write(empty_nsm());
        a.matrix2 = p;
    }
    let s = &mut *a.matrix2;
    cs_free(s.triplet);
    s.triplet = t;
    s.origin = NSM_TRIPLET;
    a.storageType = NM_SPARSE;
    Ok(t)
}

fn outside(i: c_int, j: c_int, m: &NumericsMatrix) -> CError {
    size_err(format!(
        "entry ({i}, {j}) outside a {}x{} matrix",
        m.size0, m.size1
    ))
}

/// Sets entry (i, j) of a dense matrix, or adds it to a sparse one as Siconos does: appended to
/// the triplet (grown as needed; a sparse matrix without storage gets a triplet), or inserted
/// into the compressed columns of a CSC matrix (rebuilt, origin kept). Refused, with the matrix
/// unchanged: (i, j) outside the matrix, compressed-row and half-triplet storage, storage whose
/// counts or index arrays are inconsistent (negative `nz` or `nzmax`, `nz > nzmax`, pointers
/// that decrease or pass `nzmax`, indices out of range), and sparse-block storage.
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
                return Err(outside(i, j, m));
            }
            let (i, j) = (i as usize, j as usize);
            match m.storageType {
                NM_DENSE => {
                    let data = c_slice(
                        m.matrix0 as *const c_double,
                        m.size0 as usize * m.size1 as usize,
                        "dense matrix data (matrix0)",
                    )?;
                    let k = i + j * m.size0 as usize;
                    debug_assert!(k < data.len());
                    *m.matrix0.add(k) = val;
                    Ok(())
                }
                NM_SPARSE => {
                    let target = match m.matrix2.as_ref() {
                        Some(s) => sparse_origin(s)?,
                        None => None,
                    };
                    match target {
                        Some((t, NSM_TRIPLET)) => triplet_push(&mut *t, i, j, val),
                        Some((t, NSM_CSC)) => {
                            let (rows, cols) = matrix_dims(m)?;
                            csc_insert(&mut *t, rows, cols, i, j, val)
                        }
                        Some((_, kind)) => Err(storage_err(format!(
                            "NM_entry inserts into triplet and compressed-column storage, not into {} storage (origin {kind})",
                            if kind == NSM_CSR { "compressed-row" } else { "half-triplet" }
                        ))),
                        None => {
                            // No storage yet: a triplet of capacity 16 holding the entry.
                            let t = triplet_new(m.size0 as CS_INT, m.size1 as CS_INT, 16)?;
                            triplet_push(&mut *t, i, j, val)?;
                            let installed = (|| {
                                let nsm = if m.matrix2.is_null() {
                                    Some(CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage")?)
                                } else {
                                    None
                                };
                                if let Some(b) = nsm {
                                    let p = b.into_raw();
                                    p.write(empty_nsm());
                                    m.matrix2 = p;
                                }
                                Ok(())
                            })();
                            if let Err(e) = installed {
                                cs_free(t);
                                return Err(e);
                            }
                            let s = &mut *m.matrix2;
                            cs_free(s.triplet);
                            s.triplet = t;
                            s.origin = NSM_TRIPLET;
                            Ok(())
                        }
                    }
                }
                other => Err(storage_err(format!(
                    "NM_entry does not support storage type {other} (0 dense, 2 sparse)"
                ))),
            }
        },
    )
}

/// Entry (i, j) of `M` in any storage: the value stored there (NaN and infinities included),
/// the sum of the entries or blocks stored at (i, j) of a sparse or sparse-block matrix, 0 where
/// nothing is stored. NaN on invalid input, with a code: (i, j) outside the matrix
/// (`FC3D_ERR_INVALID_SIZE`), NULL storage, and an inconsistent storage where it is read
/// (block counts, cumulative block sizes, the pointers and indices of the line read).
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
                return Err(outside(i, j, m));
            }
            let (rows, cols) = matrix_dims(m)?;
            let (i, j) = (i as usize, j as usize);
            match m.storageType {
                NM_DENSE => {
                    let data = c_slice(
                        m.matrix0 as *const c_double,
                        rows * cols,
                        "dense matrix data (matrix0)",
                    )?;
                    Ok(data[i + j * rows])
                }
                NM_SPARSE_BLOCK => match m.matrix1.as_ref() {
                    Some(s) => sbm_get(s, i, j),
                    None => Err(CError::null("sparse-block storage (matrix1)")),
                },
                NM_SPARSE => match m.matrix2.as_ref() {
                    Some(s) => {
                        let (cs, kind) = sparse_source(s)?;
                        CsView::new(cs, kind, rows, cols)?.get(i, j)
                    }
                    None => Err(CError::null("sparse storage (matrix2)")),
                },
                other => Err(storage_err(format!(
                    "unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
                ))),
            }
        },
    )
}

/// The entries of `a` with `|value| > threshold`, by rows (duplicates of a sparse storage summed,
/// in storage order); the whole storage checked as the driver checks it, and memory for the
/// entries only (not for the matrix's size).
unsafe fn sparse_entries(a: &NumericsMatrix, threshold: f64) -> CResult<Vec<(usize, usize, f64)>> {
    let oom = || {
        CError::new(
            FC3D_ERR_OUT_OF_MEMORY,
            "cannot allocate the entries of the copy",
        )
    };
    let mut t: Vec<(usize, usize, f64)> = Vec::new();
    if a.storageType == NM_SPARSE {
        let (rows, cols) = matrix_dims(a)?;
        let s = a
            .matrix2
            .as_ref()
            .ok_or_else(|| CError::null("sparse storage (matrix2)"))?;
        let (cs, kind) = sparse_source(s)?;
        let raw = CsView::new(cs, kind, rows, cols)?.triplets()?;
        if let Some(k) = raw.iter().position(|e| !e.2.is_finite()) {
            return Err(Fc3dError::NonFinite {
                what: "W".into(),
                index: k,
            }
            .into());
        }
        // Sort by (row, column), ties in storage order (no allocation), then sum duplicates.
        let mut order = fc3d_core::error::try_vec(raw.len(), 0usize, "entry order")?;
        order.iter_mut().enumerate().for_each(|(k, o)| *o = k);
        order.sort_unstable_by_key(|&k| (raw[k].0, raw[k].1, k));
        t.try_reserve_exact(raw.len()).map_err(|_| oom())?;
        for &k in &order {
            let (i, j, v) = raw[k];
            match t.last_mut() {
                Some(last) if (last.0, last.1) == (i, j) => last.2 += v,
                _ => t.push((i, j, v)),
            }
        }
        t.retain(|e| e.2.abs() > threshold);
    } else {
        let w = delassus_from_c(a)?;
        let mut failed = false;
        w.for_each_entry(|i, j, v| {
            if !failed && v.abs() > threshold {
                if t.try_reserve(1).is_err() {
                    failed = true;
                } else {
                    t.push((i, j, v));
                }
            }
        });
        if failed {
            return Err(oom());
        }
    }
    Ok(t)
}

/// Replaces the storage of `B` by a sparse (triplet) copy of `A`, keeping entries with
/// `|value| > threshold` (`A` and `B` may be the same matrix). All or nothing: `A` is checked as
/// the driver checks it (non-finite values are refused) and `B` is changed only on success.
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
            let t = sparse_entries(&*A, threshold)?;
            let (size0, size1) = ((*A).size0, (*A).size1);
            let nz = t.len();
            let mut p = CBuf::<CS_INT>::zeroed(nz, "triplet column indices")?;
            let mut i = CBuf::<CS_INT>::zeroed(nz, "triplet row indices")?;
            let mut x = CBuf::<c_double>::zeroed(nz, "triplet values")?;
            for (k, e) in t.iter().enumerate() {
                p.as_mut_slice()[k] = e.1 as CS_INT;
                i.as_mut_slice()[k] = e.0 as CS_INT;
                x.as_mut_slice()[k] = e.2;
            }
            let tri = CBuf::<CSparseMatrix>::zeroed(1, "triplet")?;
            let nsm = CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage")?;
            check_clearable(B)?;
            // Committed: nothing below can fail.
            let tri = tri.into_raw();
            tri.write(CSparseMatrix {
                nzmax: nz as CS_INT,
                m: size0 as CS_INT,
                n: size1 as CS_INT,
                p: p.into_raw(),
                i: i.into_raw(),
                x: x.into_raw(),
                nz: nz as CS_INT,
            });
            let nsm = nsm.into_raw();
            let mut v = empty_nsm();
            v.triplet = tri;
            v.origin = NSM_TRIPLET;
            nsm.write(v);
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
