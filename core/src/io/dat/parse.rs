//! The public readers: a problem file, a matrix (`NM_new_from_file`) and a sparse-block body
//! (`SBM_new_from_file`).

use std::path::Path;

use super::storage::{parse_matrix_body, parse_sparse_block};
use super::tokens::Reader;
use super::STORAGE_DENSE;
use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, Delassus};
use crate::problem::{FrictionProblem, DIMENSION};

/// Largest number of rows or columns (2^24) [`parse_matrix`] accepts for a sparse or sparse-block
/// matrix. Their sizes are not bounded by the number of values in the text (an empty
/// 10^12 x 10^12 sparse matrix is a few tokens), while reading them allocates per row: this keeps
/// a corrupt header from exhausting memory. 2^24 rows are 5.6 million contacts, far beyond any
/// fc3d problem.
const MAX_SPARSE_MATRIX_SIZE: usize = 1 << 24;

/// Parses the text of a `.dat` file. `file_label` names the input in error messages.
pub fn parse_dat(text: &str, file_label: &str) -> Result<FrictionProblem<'static>, Fc3dError> {
    let mut r = Reader::new(text, file_label, "W");

    let (dim_index, dim) = r.usize("the problem dimension")?;
    match dim {
        DIMENSION => {}
        2 => {
            return Err(Fc3dError::UnsupportedDimension {
                file: file_label.to_string(),
                dimension: 2,
            })
        }
        _ => return Err(r.error_at(dim_index, "the problem dimension must be 3")),
    }
    let (nc_index, nc) = r.usize("the number of contacts")?;
    let n = nc
        .checked_mul(DIMENSION)
        .ok_or_else(|| r.error_at(nc_index, "the number of contacts is too large"))?;

    let (storage_index, storage) = r.usize("the storage type of W")?;
    let (rows_index, rows) = r.usize("the number of rows of W")?;
    if rows != n {
        return Err(r.error_at(
            rows_index,
            format!("W must have 3 * {nc} = {n} rows, not {rows}"),
        ));
    }
    let (cols_index, cols) = r.usize("the number of columns of W")?;
    if cols != n {
        return Err(r.error_at(
            cols_index,
            format!("W must have 3 * {nc} = {n} columns, not {cols}"),
        ));
    }
    // q and mu follow the matrix: a size the rest of the file cannot hold fails here, before any
    // storage sized by it (a CSR row pointer array, say) is allocated.
    r.ensure_remaining(n.saturating_add(nc), "W, q and mu")?;
    // The solvers need the diagonal block of every contact: a sparse-block W must store them all.
    let w = parse_matrix_body(&mut r, storage_index, storage, n, n, true)?;

    let q = r.reals(n, "q")?;
    r.ensure_remaining(nc, "the friction coefficients mu")?;
    let mut mu = Vec::with_capacity(nc);
    for _ in 0..nc {
        let (index, m) = r.real("a friction coefficient")?;
        if m < 0.0 {
            return Err(r.error_at(index, "friction coefficients must be >= 0"));
        }
        mu.push(m);
    }
    // Everything `FrictionProblem::new` checks has been checked token by token above; this only
    // catches what slipped through, pointing at the matrix it concerns.
    FrictionProblem::new(w, q, mu)
        .map_err(|e| r.error_at(storage_index, format!("invalid problem: {e}")))
}

/// Reads and parses a `.dat` file; parse errors carry the path as `file`.
pub fn read_dat_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| Fc3dError::Io {
        file: label.clone(),
        message: format!("cannot read: {e}"),
    })?;
    // Bytes that are not UTF-8 can only matter where a number is expected, and there the
    // replacement character makes a clean parse error; elsewhere (the CSparse banner line, the
    // ignored tail) they are harmless, as they are to Siconos.
    let text = String::from_utf8_lossy(&bytes);
    parse_dat(&text, &label)
}

/// Parses a matrix as Siconos' `NM_write_in_file` writes it: `storageType size0 size1` and the
/// body of that storage (see the module documentation), of any shape. Whatever follows the
/// matrix is ignored. `label` names the input in error messages.
///
/// Differences from Siconos' `NM_new_from_file`, which accepts more than fc3d can represent:
/// * a sparse-block matrix must be made of 3x3 blocks (so its sizes are multiples of 3): other
///   block sizes give [`Fc3dError::Unsupported`] naming `label`, the block and the token;
/// * a sparse matrix with origin 4 (half triplet) gives [`Fc3dError::Unsupported`];
/// * sparse and sparse-block matrices have at most 2^24 rows and columns (their sizes are not
///   bounded by the values in the text, and reading allocates per row);
/// * values must be finite, block numbers in order, the dense body must repeat the declared sizes;
/// * a sparse-block matrix without blocks (Siconos writes a lone `0` after the header, and reads
///   it back as a matrix without storage) is the all-zero matrix of the declared size.
///
/// Every other defect is an [`Fc3dError::Parse`] naming the token at fault.
pub fn parse_matrix(text: &str, label: &str) -> Result<Delassus<'static>, Fc3dError> {
    parse_matrix_prefix(text, label).map(|(w, _)| w)
}

/// [`parse_matrix`], also returning the length in bytes of the matrix text and the whitespace
/// after it: `&text[len..]` starts at the first token after the matrix (or is empty).
pub fn parse_matrix_prefix(
    text: &str,
    label: &str,
) -> Result<(Delassus<'static>, usize), Fc3dError> {
    let mut r = Reader::new(text, label, "M");
    let (storage_index, storage) = r.usize("the storage type of the matrix")?;
    let (rows_index, rows) = r.usize("the number of rows of the matrix (size0)")?;
    let (cols_index, cols) = r.usize("the number of columns of the matrix (size1)")?;
    let limit = if storage == STORAGE_DENSE {
        // The values are in the text: the remaining-token checks bound what is allocated.
        i32::MAX as usize
    } else {
        MAX_SPARSE_MATRIX_SIZE
    };
    for (index, size) in [(rows_index, rows), (cols_index, cols)] {
        if size > limit {
            return Err(r.error_at(
                index,
                format!("the matrix size must be at most {limit} for this storage"),
            ));
        }
    }
    let w = parse_matrix_body(&mut r, storage_index, storage, rows, cols, false)?;
    Ok((w, r.consumed_bytes()))
}

/// Parses a sparse-block body without the `storageType size0 size1` header, as Siconos'
/// `SBM_write_in_file` writes it and `SBM_new_from_file` reads it. The size comes from the
/// cumulative block sizes; a lone `0` (no block) is the empty 0x0 matrix (Siconos'
/// `SBM_new_from_file` returns NULL there). Blocks must be 3x3: other block sizes give
/// [`Fc3dError::Unsupported`] naming `label`; other defects are [`Fc3dError::Parse`] errors.
/// Whatever follows the body is ignored.
pub fn parse_sbm(text: &str, label: &str) -> Result<BlockSparseMatrix, Fc3dError> {
    parse_sbm_prefix(text, label).map(|(m, _)| m)
}

/// [`parse_sbm`], also returning the length in bytes of the body and the whitespace after it.
pub fn parse_sbm_prefix(text: &str, label: &str) -> Result<(BlockSparseMatrix, usize), Fc3dError> {
    let mut r = Reader::new(text, label, "M");
    let m = parse_sparse_block(&mut r, None, false)?;
    Ok((m, r.consumed_bytes()))
}
