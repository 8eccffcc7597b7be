//! The public readers: a problem file, a matrix (`NM_new_from_file`) and a sparse-block body
//! (`SBM_new_from_file`), each from text in memory or from a stream read in chunks.

use std::io::Read;
use std::path::Path;

use super::storage::{parse_matrix_body, parse_sparse_block};
use super::store::{DatStore, OwnStore, ReadArray, ReadMatrix, ReadProblem};
use super::tokens::{try_push, Reader};
use super::STORAGE_DENSE;
use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, Delassus};
use crate::problem::{FrictionProblem, FrictionProblem2d, RollingProblem, DIMENSION};

/// A problem as read from a `.dat` file, of the dimension the file declares.
#[derive(Debug, Clone, PartialEq)]
pub enum DatProblem {
    /// Dimension 3.
    Spatial(FrictionProblem<'static>),
    /// Dimension 2 (Siconos' `fc2d` problems). A sparse-block W (2x2 blocks) is held as a
    /// general sparse matrix.
    Planar(FrictionProblem2d<'static>),
}

/// Largest number of rows or columns (2^24) [`parse_matrix`] accepts for a sparse or sparse-block
/// matrix. Their sizes are not bounded by the number of values in the text (an empty
/// 10^12 x 10^12 sparse matrix is a few tokens), while reading them allocates per row: this keeps
/// a corrupt header from exhausting memory. 2^24 rows are 5.6 million contacts, far beyond any
/// fc3d problem.
const MAX_SPARSE_MATRIX_SIZE: usize = 1 << 24;

/// Parses the text of a `.dat` file. `file_label` names the input in error messages.
pub fn parse_dat(text: &str, file_label: &str) -> Result<FrictionProblem<'static>, Fc3dError> {
    let mut r = Reader::new(text, file_label, "W");
    problem(&mut r)
}

/// Reads a `.dat` problem from a stream, in chunks, up to the last friction coefficient: what
/// follows is not read (but for the whitespace after mu and the first byte of the next token,
/// to find where the problem ends). `len`: the number of bytes the stream holds, when known (a
/// regular file), so that a declared size the stream cannot hold fails before it is read to its
/// end; without it values are stored as they arrive. Returns the problem and the number of bytes
/// it takes with the whitespace after it (where the next token starts, or the end).
///
/// A stream that never ends is rejected after a bounded amount of reading when it stops making
/// tokens (`/dev/zero`, endless blank lines: see the module documentation); memory grows only with
/// the values actually read and is allocated fallibly ([`Fc3dError::OutOfMemory`]).
pub fn read_dat<R: Read>(
    mut input: R,
    len: Option<u64>,
    file_label: &str,
) -> Result<(FrictionProblem<'static>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, file_label, "W");
    let p = problem(&mut r)?;
    Ok((p, r.consumed_bytes()))
}

/// [`parse_dat`] for a file of dimension 2 or 3.
pub fn parse_dat_any(text: &str, file_label: &str) -> Result<DatProblem, Fc3dError> {
    let mut r = Reader::new(text, file_label, "W");
    any_problem(&mut r)
}

/// [`read_dat`] for a stream of dimension 2 or 3.
pub fn read_dat_any<R: Read>(
    mut input: R,
    len: Option<u64>,
    file_label: &str,
) -> Result<(DatProblem, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, file_label, "W");
    let p = any_problem(&mut r)?;
    Ok((p, r.consumed_bytes()))
}

/// [`read_dat_file`] for a file of dimension 2 or 3.
pub fn read_dat_file_any(path: &Path) -> Result<DatProblem, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = open(path, &label)?;
    read_dat_any(file, len, &label).map(|(p, _)| p)
}

fn any_problem(r: &mut Reader<'_>) -> Result<DatProblem, Fc3dError> {
    let (dim_index, dim) = r.usize("the problem dimension")?;
    match dim {
        DIMENSION => problem_body::<3>(r).map(DatProblem::Spatial),
        2 => problem_body::<2>(r).map(DatProblem::Planar),
        _ => Err(r.error_at(dim_index, "the problem dimension must be 2 or 3")),
    }
}

fn problem(r: &mut Reader<'_>) -> Result<FrictionProblem<'static>, Fc3dError> {
    let (dim_index, dim) = r.usize("the problem dimension")?;
    match dim {
        DIMENSION => {}
        2 => {
            return Err(Fc3dError::UnsupportedDimension {
                file: r.file.to_string(),
                dimension: 2,
            })
        }
        _ => return Err(r.error_at(dim_index, "the problem dimension must be 3")),
    }
    problem_body::<3>(r)
}

/// The problem after its dimension token, for contacts of dimension `D`.
fn problem_body<const D: usize>(
    r: &mut Reader<'_>,
) -> Result<FrictionProblem<'static, D>, Fc3dError> {
    let (w, q, mu, storage_index) = problem_parts::<D, OwnStore>(r, 0)?;
    own_problem(r, w, q, mu, storage_index)
}

/// The problem of parts read into fc3d's own storage. Everything `FrictionProblem::new` checks
/// has been checked token by token; this only catches what slipped through, pointing at the
/// matrix it concerns.
fn own_problem<const D: usize>(
    r: &Reader<'_>,
    w: ReadMatrix<OwnStore>,
    q: Vec<f64>,
    mu: Vec<f64>,
    storage_index: usize,
) -> Result<FrictionProblem<'static, D>, Fc3dError> {
    w.into_delassus()
        .and_then(|w| FrictionProblem::<D>::from_parts(w, q, mu))
        .map_err(|e| r.error_at(storage_index, format!("invalid problem: {e}")))
}

/// [`read_dat_any`] into the caller's storage `S` (see [`DatStore`]): q, mu, a dense W's values
/// and a sparse-block W's index arrays and blocks are stored in `S`'s arrays as they are read,
/// so that nothing is held twice; a sparse W, or the sparse-block W of a 2D problem, comes as
/// fc3d's own matrix ([`ReadMatrix::Built`]). The same checks as [`read_dat_any`], token by
/// token; returns the problem and the number of bytes it takes (see [`read_dat`]).
pub fn read_dat_into<S: DatStore, R: Read>(
    mut input: R,
    len: Option<u64>,
    file_label: &str,
) -> Result<(ReadProblem<S>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, file_label, "W");
    let (dim_index, dim) = r.usize("the problem dimension")?;
    let (w, q, mu, _) = match dim {
        DIMENSION => problem_parts::<DIMENSION, S>(&mut r, 0)?,
        2 => problem_parts::<2, S>(&mut r, 0)?,
        _ => return Err(r.error_at(dim_index, "the problem dimension must be 2 or 3")),
    };
    let problem = ReadProblem {
        dimension: dim,
        w,
        q,
        mu,
    };
    Ok((problem, r.consumed_bytes()))
}

/// [`read_dat_into`] on a file (see [`read_dat_file`]).
pub fn read_dat_file_into<S: DatStore>(path: &Path) -> Result<ReadProblem<S>, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = open(path, &label)?;
    read_dat_into(file, len, &label).map(|(p, _)| p)
}

/// W, q and mu after the dimension token, for contacts of dimension `D`, and the index of W's
/// storage token; `more_per_contact` values per contact are still to come after mu (the rolling
/// coefficients), so a size the input cannot hold fails before anything is allocated.
#[allow(clippy::type_complexity)]
fn problem_parts<const D: usize, S: DatStore>(
    r: &mut Reader<'_>,
    more_per_contact: usize,
) -> Result<(ReadMatrix<S>, S::Reals, S::Reals, usize), Fc3dError> {
    let (nc_index, nc) = r.usize("the number of contacts")?;
    let n = nc
        .checked_mul(D)
        .ok_or_else(|| r.error_at(nc_index, "the number of contacts is too large"))?;

    let (storage_index, storage) = r.usize("the storage type of W")?;
    r.remember(storage_index);
    let (rows_index, rows) = r.usize("the number of rows of W")?;
    if rows != n {
        return Err(r.error_at(
            rows_index,
            format!("W must have {D} * {nc} = {n} rows, not {rows}"),
        ));
    }
    let (cols_index, cols) = r.usize("the number of columns of W")?;
    if cols != n {
        return Err(r.error_at(
            cols_index,
            format!("W must have {D} * {nc} = {n} columns, not {cols}"),
        ));
    }
    // q and mu follow the matrix: a size the rest of the input cannot hold fails here, before any
    // storage sized by it is allocated.
    r.ensure_remaining(
        n.saturating_add(nc.saturating_mul(1 + more_per_contact)),
        "W, q and mu",
    )?;
    // The solvers need the diagonal block of every contact: a sparse-block W must store them all.
    let body = parse_matrix_body::<S>(r, storage_index, storage, n, n, true, D)?;

    let q = r.reals::<S::Reals>(n, "q")?;
    r.ensure_remaining(nc, "the friction coefficients mu")?;
    let what = "the friction coefficients mu";
    let mut mu = S::Reals::with_capacity(r.capacity_for(nc, 1), what)?;
    for _ in 0..nc {
        let (index, m) = r.real("a friction coefficient")?;
        if m < 0.0 {
            return Err(r.error_at(index, "friction coefficients must be >= 0"));
        }
        mu.push(m, what)?;
    }
    // A sparse W is compressed now that q, one value per row, has been read: its row pointers
    // are bounded by the input even when its length is unknown.
    let w = body.finish(r)?;
    Ok((w, q, mu, storage_index))
}

/// A rolling-friction problem as read from a `.dat` file (Siconos'
/// `rollingFrictionContact_newFromFile`: dimension, contacts, W, q, mu, then mu_r), of the
/// dimension the file declares.
#[derive(Debug, Clone, PartialEq)]
pub enum RollingDatProblem {
    /// Dimension 5 (`rolling_fc3d`).
    Spatial(RollingProblem<'static, 5>),
    /// Dimension 3 (`rolling_fc2d`).
    Planar(RollingProblem<'static, 3>),
}

/// Reads a rolling `.dat` problem from a stream, in chunks, up to the last rolling coefficient
/// (as [`read_dat`]); returns the problem and the number of bytes it takes.
pub fn read_rolling_dat<R: Read>(
    mut input: R,
    len: Option<u64>,
    file_label: &str,
) -> Result<(RollingDatProblem, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, file_label, "W");
    let (dim_index, dim) = r.usize("the problem dimension")?;
    let p = match dim {
        5 => rolling_body::<5>(&mut r).map(RollingDatProblem::Spatial)?,
        3 => rolling_body::<3>(&mut r).map(RollingDatProblem::Planar)?,
        _ => {
            return Err(r.error_at(
                dim_index,
                "the dimension of a rolling problem must be 5 (3D) or 3 (2D)",
            ))
        }
    };
    Ok((p, r.consumed_bytes()))
}

/// [`read_rolling_dat`] on a file.
pub fn read_rolling_dat_file(path: &Path) -> Result<RollingDatProblem, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = open(path, &label)?;
    read_rolling_dat(file, len, &label).map(|(p, _)| p)
}

/// [`read_rolling_dat`] on text in memory.
pub fn parse_rolling_dat(text: &str, file_label: &str) -> Result<RollingDatProblem, Fc3dError> {
    read_rolling_dat(text.as_bytes(), Some(text.len() as u64), file_label).map(|(p, _)| p)
}

fn rolling_body<const D: usize>(
    r: &mut Reader<'_>,
) -> Result<RollingProblem<'static, D>, Fc3dError> {
    let (w, q, mu, storage_index) = problem_parts::<D, OwnStore>(r, 1)?;
    let w = w
        .into_delassus()
        .map_err(|e| r.error_at(storage_index, format!("invalid problem: {e}")))?;
    let nc = mu.len();
    r.ensure_remaining(nc, "the rolling coefficients mu_r")?;
    let mut mu_r = r.vec_for(nc, 1, "the rolling coefficients mu_r")?;
    for _ in 0..nc {
        let (index, m) = r.real("a rolling coefficient")?;
        if m < 0.0 {
            return Err(r.error_at(index, "rolling coefficients must be >= 0"));
        }
        try_push(&mut mu_r, m, "the rolling coefficients mu_r")?;
    }
    RollingProblem::<D>::new(w, q, mu, mu_r)
        .map_err(|e| r.error_at(storage_index, format!("invalid problem: {e}")))
}

/// Opens `path` for the streaming readers: the file and its length when it is a regular file
/// with a length (not a device, a pipe, or a `/proc` file that says 0).
pub(super) fn open(path: &Path, label: &str) -> Result<(std::fs::File, Option<u64>), Fc3dError> {
    let io_error = |e: std::io::Error| Fc3dError::Io {
        file: label.to_string(),
        message: format!("cannot read: {e}"),
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    let meta = file.metadata().map_err(io_error)?;
    let len = (meta.is_file() && meta.len() > 0).then_some(meta.len());
    Ok((file, len))
}

/// Reads and parses a `.dat` file, in chunks, up to the last friction coefficient (see
/// [`read_dat`]); parse errors carry the path as `file`. Bytes that are not UTF-8 are read as
/// U+FFFD: where a number is expected they make a parse error, elsewhere (the CSparse banner
/// line, the ignored tail) they are harmless, as they are to Siconos.
pub fn read_dat_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = open(path, &label)?;
    read_dat(file, len, &label).map(|(p, _)| p)
}

/// Reads a matrix file (`NM_write_in_filename`'s, see [`parse_matrix`]) in chunks, up to the end
/// of the matrix; what follows is not read. Errors as [`parse_matrix`]'s, with the path as label.
pub fn read_matrix_file(path: &Path) -> Result<Delassus<'static>, Fc3dError> {
    read_matrix_file_into::<OwnStore>(path)?.into_delassus()
}

/// [`read_matrix_file`] into the caller's storage `S` (see [`read_dat_into`]).
pub fn read_matrix_file_into<S: DatStore>(path: &Path) -> Result<ReadMatrix<S>, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = open(path, &label)?;
    read_matrix_into(file, len, &label).map(|(w, _)| w)
}

/// [`parse_matrix_prefix`] on a stream read in chunks, stopping after the matrix (see
/// [`read_dat`] for `len` and what is read past the end). Returns the matrix and the number of
/// bytes of the matrix text and the whitespace after it.
pub fn read_matrix<R: Read>(
    input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(Delassus<'static>, u64), Fc3dError> {
    let (w, used) = read_matrix_into::<OwnStore, R>(input, len, label)?;
    Ok((w.into_delassus()?, used))
}

/// [`read_matrix`] into the caller's storage `S` (see [`read_dat_into`]).
pub fn read_matrix_into<S: DatStore, R: Read>(
    mut input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(ReadMatrix<S>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, label, "M");
    let w = matrix(&mut r)?;
    Ok((w, r.consumed_bytes()))
}

/// [`parse_sbm_prefix`] on a stream read in chunks, stopping after the body (see [`read_dat`]).
pub fn read_sbm<R: Read>(
    input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(BlockSparseMatrix<'static>, u64), Fc3dError> {
    let (m, used) = read_sbm_into::<OwnStore, R>(input, len, label)?;
    Ok((own_sbm(m)?, used))
}

fn own_sbm(m: ReadMatrix<OwnStore>) -> Result<BlockSparseMatrix<'static>, Fc3dError> {
    match m.into_delassus()? {
        Delassus::SparseBlock(m) => Ok(m),
        _ => unreachable!("the sparse-block reader makes a sparse-block matrix"),
    }
}

/// [`read_sbm`] into the caller's storage `S` (see [`read_dat_into`]): always a
/// [`ReadMatrix::SparseBlock`].
pub fn read_sbm_into<S: DatStore, R: Read>(
    mut input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(ReadMatrix<S>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, label, "M");
    let m = parse_sparse_block::<S>(&mut r, None, false)?;
    Ok((m, r.consumed_bytes()))
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
    let w = matrix::<OwnStore>(&mut r)?.into_delassus()?;
    Ok((w, byte_offset(r.consumed_bytes())))
}

fn byte_offset(consumed: u64) -> usize {
    // An offset into text in memory.
    usize::try_from(consumed).unwrap_or(usize::MAX)
}

fn matrix<S: DatStore>(r: &mut Reader<'_>) -> Result<ReadMatrix<S>, Fc3dError> {
    let (storage_index, storage) = r.usize("the storage type of the matrix")?;
    r.remember(storage_index);
    let (rows_index, rows) = r.usize("the number of rows of the matrix (size0)")?;
    r.remember(rows_index);
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
    parse_matrix_body(r, storage_index, storage, rows, cols, false, DIMENSION)?.finish(r)
}

/// Parses a sparse-block body without the `storageType size0 size1` header, as Siconos'
/// `SBM_write_in_file` writes it and `SBM_new_from_file` reads it. The size comes from the
/// cumulative block sizes; a lone `0` (no block) is the empty 0x0 matrix (Siconos'
/// `SBM_new_from_file` returns NULL there). Blocks must be 3x3: other block sizes give
/// [`Fc3dError::Unsupported`] naming `label`; other defects are [`Fc3dError::Parse`] errors.
/// Whatever follows the body is ignored.
pub fn parse_sbm(text: &str, label: &str) -> Result<BlockSparseMatrix<'static>, Fc3dError> {
    parse_sbm_prefix(text, label).map(|(m, _)| m)
}

/// [`parse_sbm`], also returning the length in bytes of the body and the whitespace after it.
pub fn parse_sbm_prefix(
    text: &str,
    label: &str,
) -> Result<(BlockSparseMatrix<'static>, usize), Fc3dError> {
    let mut r = Reader::new(text, label, "M");
    let m = own_sbm(parse_sparse_block::<OwnStore>(&mut r, None, false)?)?;
    Ok((m, byte_offset(r.consumed_bytes())))
}
