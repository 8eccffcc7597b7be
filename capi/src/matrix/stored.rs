//! Matrices of any shape and block sizes (the M and H of a global problem) between a host's
//! `NumericsMatrix` and the core's compressed rows with the storage they had
//! (`fc3d_core::io::dat::MatrixStorage`): a dense matrix (its non-zero entries), a
//! sparse-block matrix of blocks of any sizes (every value of its blocks, exact zeros
//! included, and its cumulative block sizes), a sparse one (its CSparse origin form).
//!
//! Every count and size of the host's structs is checked before an array is read with it (as
//! for a problem's W), every value checked finite and named (`M` or `H`).

use std::os::raw::{c_double, c_uint};
use std::ptr::null_mut;

use super::csparse::{csr_from_cs, empty_nsm, triplet_new};
use super::sbm::{check_block_sizes, empty_sbm, sbm_row_ptr};
use super::{
    c_size, c_slice, finish_matrix, matrix_dims, null_matrix, size_err, sparse_source, storage_err,
    CBuf, NM_DENSE, NM_SPARSE, NM_SPARSE_BLOCK, NSM_TRIPLET,
};
use crate::types::*;
use crate::{CError, CResult};
use fc3d_core::error::{check_finite, try_vec, Fc3dError};
use fc3d_core::io::dat::{block_cut, block_start, block_values, csr_of_dense, MatrixStorage};
use fc3d_core::matrix::CsrMatrix;

/// A core error about a matrix's values named after the matrix (the core's conversions call
/// every matrix W).
fn named(e: Fc3dError, name: &str) -> CError {
    match e {
        Fc3dError::NonFinite { index, .. } => Fc3dError::NonFinite {
            what: format!("{name} (entry {index})"),
            index,
        }
        .into(),
        e => CError::from(e),
    }
}

/// The compressed rows of a host matrix and the storage it has. `name` names it in errors.
pub(crate) unsafe fn stored_from_c(
    m: &NumericsMatrix,
    name: &str,
) -> CResult<(CsrMatrix, MatrixStorage)> {
    let (rows, cols) = matrix_dims(m)?;
    match m.storageType {
        NM_DENSE => {
            let n = rows
                .checked_mul(cols)
                .ok_or_else(|| size_err(format!("{name}: {rows}x{cols} overflows")))?;
            let what = format!("{name}: dense values (matrix0)");
            let values = c_slice(m.matrix0 as *const c_double, n, &what)?;
            check_finite(name, values)?;
            let csr = csr_of_dense(rows, cols, values).map_err(|e| named(e, name))?;
            Ok((csr, MatrixStorage::Dense))
        }
        NM_SPARSE_BLOCK => {
            if m.matrix1.is_null() {
                return Err(CError::null(&format!(
                    "{name}: sparse-block storage (matrix1)"
                )));
            }
            let (csr, row_sizes, col_sizes) = csr_from_any_sbm(&*m.matrix1, rows, cols, name)?;
            let storage = MatrixStorage::SparseBlock {
                row_sizes,
                col_sizes,
            };
            Ok((csr, storage))
        }
        NM_SPARSE => {
            if m.matrix2.is_null() {
                return Err(CError::null(&format!("{name}: sparse storage (matrix2)")));
            }
            let (cs, kind) = sparse_source(&*m.matrix2)?;
            let csr = csr_from_cs(cs, kind, rows, cols).map_err(|e| {
                CError::new(
                    e.code,
                    format!("{name}: {}", e.message.replace(" W", " matrix")),
                )
            })?;
            Ok((csr, MatrixStorage::Sparse))
        }
        other => Err(storage_err(format!(
            "{name}: unknown storage type {other} (0 dense, 1 sparse-block, 2 sparse)"
        ))),
    }
}

/// A host SBM of blocks of any sizes covering `rows x cols`, as compressed rows (every value of
/// its blocks, duplicates summed) and its cumulative row and column block sizes.
unsafe fn csr_from_any_sbm(
    s: &SparseBlockStructuredMatrix,
    rows: usize,
    cols: usize,
    name: &str,
) -> CResult<(CsrMatrix, Vec<usize>, Vec<usize>)> {
    let (nbr, nbc, nb) = (
        s.blocknumber0 as usize,
        s.blocknumber1 as usize,
        s.nbblocks as usize,
    );
    if nb != s.filled2 {
        return Err(storage_err(format!(
            "{name}: SBM nbblocks = {nb} but filled2 = {}",
            s.filled2
        )));
    }
    if nb == 0 && (nbr == 0 || nbc == 0) {
        // A matrix without blocks (as Siconos reads a lone 0): all zeros.
        return Ok((
            CsrMatrix::from_triplets(rows, cols, &[])?,
            Vec::new(),
            Vec::new(),
        ));
    }
    let sizes = |p: *const c_uint, n: usize, total: usize, what: &str| -> CResult<Vec<usize>> {
        let what = format!("{name}: SBM {what}");
        let bs = c_slice(p, n, &what)?;
        check_block_sizes(bs, &what)?;
        if bs.last().map_or(0, |&v| v as usize) != total {
            return Err(size_err(format!(
                "{what}: the blocks cover {} but the NumericsMatrix has {total}",
                bs.last().copied().unwrap_or(0)
            )));
        }
        let mut out = try_vec(n, 0usize, &what)?;
        out.iter_mut().zip(bs).for_each(|(o, &v)| *o = v as usize);
        Ok(out)
    };
    let row_sizes = sizes(s.blocksize0, nbr, rows, "blocksize0")?;
    let col_sizes = sizes(s.blocksize1, nbc, cols, "blocksize1")?;
    let row_ptr = sbm_row_ptr(s)?;
    if let Some(w) = row_ptr.windows(2).find(|w| w[0] > w[1]) {
        return Err(storage_err(format!(
            "{name}: SBM index1_data decreases ({} then {})",
            w[0], w[1]
        )));
    }
    if row_ptr[0] != 0 || row_ptr[nbr] != nb {
        return Err(storage_err(format!(
            "{name}: SBM index1_data must run from 0 to the {nb} blocks"
        )));
    }
    let block_cols = c_slice(s.index2_data, nb, &format!("{name}: SBM index2_data"))?;
    let pointers = c_slice(
        s.block as *const *mut c_double,
        nb,
        &format!("{name}: SBM block array"),
    )?;
    // Every block's values: at most rows * cols each (checked against the address space by
    // c_slice), the total grown fallibly.
    let mut triplets: Vec<(usize, usize, f64)> = Vec::new();
    for bi in 0..nbr {
        let (r0, r1) = (block_start(&row_sizes, bi), row_sizes[bi]);
        for k in row_ptr[bi]..row_ptr[bi + 1] {
            let bj = block_cols[k];
            if bj >= nbc {
                return Err(storage_err(format!(
                    "{name}: SBM block {k} is in block column {bj}, past {nbc} (index2_data)"
                )));
            }
            let (c0, c1) = (block_start(&col_sizes, bj), col_sizes[bj]);
            let what = format!("{name}: SBM block {k}");
            let values = c_slice(pointers[k] as *const c_double, (r1 - r0) * (c1 - c0), &what)?;
            check_finite(&what, values)?;
            triplets.try_reserve(values.len()).map_err(|_| {
                CError::from(Fc3dError::OutOfMemory {
                    what: format!("the entries of {name}"),
                    bytes: values.len().saturating_mul(24),
                })
            })?;
            // Column-major blocks.
            for (p, &v) in values.iter().enumerate() {
                triplets.push((r0 + p % (r1 - r0), c0 + p / (r1 - r0), v));
            }
        }
    }
    let csr = CsrMatrix::from_triplets(rows, cols, &triplets).map_err(|e| named(e, name))?;
    Ok((csr, row_sizes, col_sizes))
}

/// A C-allocated NumericsMatrix holding `m` in `storage`: dense (column-major, every entry),
/// sparse-block (every block holding a stored entry, whole, blocks malloc'd one by one as
/// Siconos does) or sparse (a triplet origin, as Siconos' global readers give). Nothing is left
/// allocated on failure.
pub(crate) fn stored_to_c(m: &CsrMatrix, storage: &MatrixStorage) -> CResult<*mut NumericsMatrix> {
    let mut nm = null_matrix();
    nm.size0 = c_size(m.nrows())?;
    nm.size1 = c_size(m.ncols())?;
    let out = CBuf::<NumericsMatrix>::zeroed(1, "matrix")?;
    match storage {
        MatrixStorage::Dense => {
            let (rows, cols) = (m.nrows(), m.ncols());
            let n = rows
                .checked_mul(cols)
                .ok_or_else(|| size_err(format!("a dense {rows}x{cols} matrix overflows")))?;
            let mut values = CBuf::<c_double>::zeroed(n, "dense matrix")?;
            let v = values.as_mut_slice();
            m.for_each_entry(|i, j, x| v[i + j * rows] = x);
            nm.storageType = NM_DENSE;
            nm.matrix0 = values.into_raw();
        }
        MatrixStorage::SparseBlock {
            row_sizes,
            col_sizes,
        } => {
            nm.storageType = NM_SPARSE_BLOCK;
            nm.matrix1 = sbm_of_csr(m, row_sizes, col_sizes)?;
        }
        MatrixStorage::Sparse => {
            nm.storageType = NM_SPARSE;
            nm.matrix2 = triplet_nsm(m)?;
        }
    }
    Ok(finish_matrix(out, nm))
}

/// A C-allocated sparse storage whose origin is a triplet copy of `m`.
fn triplet_nsm(m: &CsrMatrix) -> CResult<*mut NumericsSparseMatrix> {
    let nsm = CBuf::<NumericsSparseMatrix>::zeroed(1, "sparse storage")?;
    let t = triplet_new(m.nrows() as CS_INT, m.ncols() as CS_INT, m.nnz())?;
    // SAFETY: t is a fresh triplet with room for nnz entries.
    unsafe {
        let (p, i, x) = ((*t).p, (*t).i, (*t).x);
        let mut k = 0;
        m.for_each_entry(|r, c, v| {
            *i.add(k) = r as CS_INT;
            *p.add(k) = c as CS_INT;
            *x.add(k) = v;
            k += 1;
        });
        (*t).nz = k as CS_INT;
    }
    let mut v = empty_nsm();
    v.triplet = t;
    v.origin = NSM_TRIPLET;
    let nsm = nsm.into_raw();
    // SAFETY: nsm is a fresh allocation for one NumericsSparseMatrix.
    unsafe { nsm.write(v) };
    Ok(nsm)
}

/// A C-allocated SBM of `m` cut by the cumulative sizes: every block holding a stored entry,
/// whole. Nothing is left allocated on failure.
fn sbm_of_csr(
    m: &CsrMatrix,
    row_sizes: &[usize],
    col_sizes: &[usize],
) -> CResult<*mut SparseBlockStructuredMatrix> {
    let out = CBuf::<SparseBlockStructuredMatrix>::zeroed(1, "sparse-block matrix")?;
    if row_sizes.is_empty() && col_sizes.is_empty() && m.nnz() == 0 {
        let out = out.into_raw();
        // SAFETY: a fresh allocation for one SBM.
        unsafe { out.write(empty_sbm()) };
        return Ok(out);
    }
    let cut = block_cut(m, row_sizes, col_sizes)?;
    let uint = |v: usize, what: &str| {
        c_uint::try_from(v).map_err(|_| size_err(format!("{what} {v} does not fit a C unsigned")))
    };
    let nb = cut.col_idx.len();
    let mut bs0 = CBuf::<c_uint>::zeroed(row_sizes.len(), "SBM blocksize0")?;
    for (d, &v) in bs0.as_mut_slice().iter_mut().zip(row_sizes) {
        *d = uint(v, "a block size")?;
    }
    let mut bs1 = CBuf::<c_uint>::zeroed(col_sizes.len(), "SBM blocksize1")?;
    for (d, &v) in bs1.as_mut_slice().iter_mut().zip(col_sizes) {
        *d = uint(v, "a block size")?;
    }
    let index1 = CBuf::copy(&cut.row_ptr, "SBM index1_data")?;
    let index2 = CBuf::copy(&cut.col_idx, "SBM index2_data")?;
    // The blocks, owned until handed over (freed on an error below).
    let mut blocks: Vec<CBuf<c_double>> = Vec::new();
    blocks
        .try_reserve_exact(nb)
        .map_err(|_| size_err(format!("cannot hold {nb} blocks")))?;
    let mut values = Vec::new();
    for bi in 0..row_sizes.len() {
        let rows = block_start(row_sizes, bi)..row_sizes[bi];
        for &bj in &cut.col_idx[cut.row_ptr[bi]..cut.row_ptr[bi + 1]] {
            block_values(
                m,
                rows.clone(),
                block_start(col_sizes, bj)..col_sizes[bj],
                &mut values,
            );
            blocks.push(CBuf::copy(&values, "an SBM block")?);
        }
    }
    let mut block_array = CBuf::<*mut c_double>::zeroed(nb, "SBM block array")?;
    let (nbr, nbc, nb_u) = (
        uint(row_sizes.len(), "block rows")?,
        uint(col_sizes.len(), "block columns")?,
        uint(nb, "blocks")?,
    );
    // Nothing can fail from here on.
    for (slot, b) in block_array.as_mut_slice().iter_mut().zip(blocks) {
        *slot = b.into_raw();
    }
    let s = SparseBlockStructuredMatrix {
        nbblocks: nb_u,
        block: block_array.into_raw(),
        blocknumber0: nbr,
        blocknumber1: nbc,
        blocksize0: bs0.into_raw(),
        blocksize1: bs1.into_raw(),
        filled1: row_sizes.len() + 1,
        filled2: nb,
        index1_data: index1.into_raw(),
        index2_data: index2.into_raw(),
        diagonal_blocks: null_mut(),
        version: NumericsDataVersion::default(),
    };
    let out = out.into_raw();
    // SAFETY: a fresh allocation for one SBM.
    unsafe { out.write(s) };
    Ok(out)
}
