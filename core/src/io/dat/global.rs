//! The `.dat` format of a global problem, as Siconos' `globalFrictionContact_printInFile` writes
//! it and `globalFrictionContact_newFromFile` reads it:
//!
//! ```text
//! dim nc
//! M        storageType size0 size1 and the body (NM_write_in_file), n x n
//! H        the same, n x (dim nc)
//! q[0] ... q[n-1]
//! b[0] ... b[dim nc - 1]
//! mu[0] ... mu[nc-1]
//! anything (ignored)
//! ```
//!
//! and of a global rolling problem (`globalRollingFrictionContact_printInFile`, dimension 5):
//! the same followed by `mu_r[0] ... mu_r[nc-1]`.
//!
//! M and H may be stored dense, sparse-block or sparse (a CSparse dump), as for a local problem
//! (see the module documentation), and the blocks of a sparse-block M or H have any sizes:
//! Siconos' files give M one diagonal block per body (two 27x27 blocks in
//! `GFC3D_TwoRods1.dat`) and H blocks of a body's unknowns by a contact's. Both are read into
//! compressed rows ([`GlobalProblem`] holds them so), and the storage each had is returned beside
//! the problem ([`GlobalStorage`]) so that [`write_global_dat`] writes them back as they were:
//! the blocks of a sparse-block matrix with their exact zeros, a dense matrix in full.
//!
//! The reader checks what Siconos' does not: M square, H with M's rows and `dim nc` columns, q,
//! b and mu of those sizes, `mu >= 0` (and `mu_r`), every value finite; each failure is an
//! [`Fc3dError::Parse`] naming the token. It reads in chunks and only as far as the problem
//! goes, with the bounds of the local readers (a declared size the input cannot hold fails
//! before it is allocated; sparse and sparse-block sizes at most 2^24). Dimensions 2 and 3 are
//! read ([`GlobalDatProblem`]: Siconos 4.5's gfc2d files are dimension 2), 5 by the rolling
//! reader.

use std::io::{self, Read, Write};
use std::path::Path;

use super::csparse::{parse_sparse, SparseEntries};
use super::storage::{parse_dense, parse_sparse_block_as_csr, BlockSizes};
use super::store::{OwnStore, ReadMatrix};
use super::tokens::{try_push, Reader};
use super::write::{write_path, write_reals_line, write_triplet_dump, write_usizes_line};
use super::{STORAGE_DENSE, STORAGE_SPARSE, STORAGE_SPARSE_BLOCK};
use crate::error::{try_vec, Fc3dError};
use crate::matrix::{transpose, CsrMatrix, Delassus};
use crate::problem::{GlobalProblem, GlobalRollingProblem};

/// Largest number of rows or columns of a sparse or sparse-block M or H (as for a matrix file:
/// their sizes are declared, not bounded by the values in the text).
const MAX_SPARSE_SIZE: usize = 1 << 24;

/// How a matrix of a global problem is stored in a file (and in a Siconos `NumericsMatrix`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum MatrixStorage {
    /// Every entry, column-major (`NM_DENSE`).
    Dense,
    /// Blocks of the given cumulative row and column sizes (`NM_SPARSE_BLOCK`): every block
    /// that holds a stored entry is written whole. Empty sizes: a matrix without blocks.
    SparseBlock {
        row_sizes: Vec<usize>,
        col_sizes: Vec<usize>,
    },
    /// A CSparse triplet dump (`NM_SPARSE`).
    #[default]
    Sparse,
}

impl MatrixStorage {
    /// Siconos' `NM_types` code of the storage.
    pub fn code(&self) -> usize {
        match self {
            MatrixStorage::Dense => STORAGE_DENSE,
            MatrixStorage::SparseBlock { .. } => STORAGE_SPARSE_BLOCK,
            MatrixStorage::Sparse => STORAGE_SPARSE,
        }
    }

    /// The storage's name in messages and displays.
    pub fn name(&self) -> &'static str {
        match self {
            MatrixStorage::Dense => "dense",
            MatrixStorage::SparseBlock { .. } => "sparse-block",
            MatrixStorage::Sparse => "sparse",
        }
    }
}

/// The storages of M and H.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct GlobalStorage {
    pub m: MatrixStorage,
    pub h: MatrixStorage,
}

/// A global problem as read, of the dimension its file declares.
#[derive(Debug, Clone, PartialEq)]
pub enum GlobalDatProblem {
    /// Dimension 3 (`gfc3d`).
    Spatial(GlobalProblem<'static, 3>),
    /// Dimension 2 (Siconos 4.5's `gfc2d`).
    Planar(GlobalProblem<'static, 2>),
}

/// A problem read from a global `.dat` file and the storages its matrices had.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobalDat<P> {
    pub problem: P,
    pub storage: GlobalStorage,
}

/// Reads a global `.dat` problem from a stream, in chunks, up to the last friction coefficient
/// (see [`super::read_dat`] for `len` and what is read past the end). Returns the problem with
/// its storages and the number of bytes it takes.
pub fn read_global_dat<R: Read>(
    mut input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(GlobalDat<GlobalDatProblem>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, label, "M");
    let (dim_index, dim) = r.usize("the problem dimension")?;
    let dat = match dim {
        3 => global_body::<3>(&mut r)?.map(GlobalDatProblem::Spatial),
        2 => global_body::<2>(&mut r)?.map(GlobalDatProblem::Planar),
        5 => {
            return Err(r.error_at(
                dim_index,
                "dimension 5 is a global rolling problem: read it as one \
                 (globalRollingFrictionContact_new_from_filename)",
            ))
        }
        _ => {
            return Err(r.error_at(
                dim_index,
                "the dimension of a global problem must be 2 or 3",
            ))
        }
    };
    Ok((dat, r.consumed_bytes()))
}

/// [`read_global_dat`] on a file; errors carry the path.
pub fn read_global_dat_file(path: &Path) -> Result<GlobalDat<GlobalDatProblem>, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = super::parse::open(path, &label)?;
    read_global_dat(file, len, &label).map(|(p, _)| p)
}

/// [`read_global_dat`] on text in memory.
pub fn parse_global_dat(text: &str, label: &str) -> Result<GlobalDat<GlobalDatProblem>, Fc3dError> {
    read_global_dat(text.as_bytes(), Some(text.len() as u64), label).map(|(p, _)| p)
}

/// Reads a global rolling `.dat` problem (dimension 5, `mu_r` after `mu`) from a stream, as
/// [`read_global_dat`].
pub fn read_global_rolling_dat<R: Read>(
    mut input: R,
    len: Option<u64>,
    label: &str,
) -> Result<(GlobalDat<GlobalRollingProblem<'static>>, u64), Fc3dError> {
    let mut r = Reader::from_stream(&mut input, len, label, "M");
    let (dim_index, dim) = r.usize("the problem dimension")?;
    if dim != 5 {
        return Err(r.error_at(
            dim_index,
            "the dimension of a global rolling problem must be 5",
        ));
    }
    let (parts, storage) = global_parts::<5>(&mut r, 1)?;
    let nc = parts.mu.len();
    r.ensure_remaining(nc, "the rolling coefficients mu_r")?;
    let mu_r = coefficients(
        &mut r,
        nc,
        "rolling coefficient",
        "the rolling coefficients mu_r",
    )?;
    let at = parts.at;
    let base = parts.into_problem::<5>(&r)?;
    let problem = GlobalRollingProblem::new(base, mu_r)
        .map_err(|e| r.error_at(at, format!("invalid problem: {e}")))?;
    Ok((GlobalDat { problem, storage }, r.consumed_bytes()))
}

/// [`read_global_rolling_dat`] on a file.
pub fn read_global_rolling_dat_file(
    path: &Path,
) -> Result<GlobalDat<GlobalRollingProblem<'static>>, Fc3dError> {
    let label = path.display().to_string();
    let (file, len) = super::parse::open(path, &label)?;
    read_global_rolling_dat(file, len, &label).map(|(p, _)| p)
}

impl<P> GlobalDat<P> {
    fn map<Q>(self, f: impl FnOnce(P) -> Q) -> GlobalDat<Q> {
        GlobalDat {
            problem: f(self.problem),
            storage: self.storage,
        }
    }
}

fn global_body<const D: usize>(
    r: &mut Reader<'_>,
) -> Result<GlobalDat<GlobalProblem<'static, D>>, Fc3dError> {
    let (parts, storage) = global_parts::<D>(r, 0)?;
    let problem = parts.into_problem::<D>(r)?;
    Ok(GlobalDat { problem, storage })
}

/// What a global file holds before the problem is assembled.
struct Parts {
    m: Body,
    h: Body,
    q: Vec<f64>,
    b: Vec<f64>,
    mu: Vec<f64>,
    /// The token of M's storage, where an error about the whole problem points.
    at: usize,
}

impl Parts {
    /// The problem (M and H compressed now that the vectors bound their rows).
    fn into_problem<const D: usize>(
        self,
        r: &Reader<'_>,
    ) -> Result<GlobalProblem<'static, D>, Fc3dError> {
        let m = self.m.finish(r)?;
        let h = self.h.finish(r)?;
        GlobalProblem::new(m, h, self.q, self.b, self.mu)
            .map_err(|e| r.error_at(self.at, format!("invalid problem: {e}")))
    }
}

/// A matrix body as read: compressed, or the entries of a sparse one to compress.
enum Body {
    Done(CsrMatrix),
    Sparse(SparseEntries),
}

impl Body {
    fn finish(self, r: &Reader<'_>) -> Result<CsrMatrix, Fc3dError> {
        match self {
            Body::Done(m) => Ok(m),
            Body::Sparse(entries) => match entries.finish(r)? {
                Delassus::Sparse(m) => Ok(m),
                _ => unreachable!("a sparse body compresses to a sparse matrix"),
            },
        }
    }
}

/// The header `storageType size0 size1` of a matrix.
struct Header {
    storage_index: usize,
    storage: usize,
    rows_index: usize,
    rows: usize,
    cols_index: usize,
    cols: usize,
}

fn header(r: &mut Reader<'_>) -> Result<Header, Fc3dError> {
    let name = r.name;
    let (storage_index, storage) = r.usize(&format!("the storage type of {name}"))?;
    r.remember(storage_index);
    let (rows_index, rows) = r.usize(&format!("the number of rows of {name}"))?;
    r.remember(rows_index);
    let (cols_index, cols) = r.usize(&format!("the number of columns of {name}"))?;
    r.remember(cols_index);
    if storage != STORAGE_DENSE {
        for (index, size) in [(rows_index, rows), (cols_index, cols)] {
            if size > MAX_SPARSE_SIZE {
                return Err(r.error_at(
                    index,
                    format!("the size of a sparse or sparse-block {name} must be at most {MAX_SPARSE_SIZE}"),
                ));
            }
        }
    }
    Ok(Header {
        storage_index,
        storage,
        rows_index,
        rows,
        cols_index,
        cols,
    })
}

/// The body of a matrix of header `h`, and its storage.
fn body(r: &mut Reader<'_>, h: &Header) -> Result<(Body, MatrixStorage), Fc3dError> {
    match h.storage {
        STORAGE_DENSE => {
            let ReadMatrix::Dense { values, .. } = parse_dense::<OwnStore>(r, h.rows, h.cols)?
            else {
                unreachable!("the dense reader makes a dense matrix")
            };
            let m = csr_of_dense(h.rows, h.cols, &values)
                .map_err(|e| r.error_at(h.storage_index, e.to_string()))?;
            Ok((Body::Done(m), MatrixStorage::Dense))
        }
        STORAGE_SPARSE_BLOCK => {
            let (m, (row_sizes, col_sizes)) =
                parse_sparse_block_as_csr(r, (h.rows, h.cols), false, BlockSizes::Any)?;
            Ok((
                Body::Done(m),
                MatrixStorage::SparseBlock {
                    row_sizes,
                    col_sizes,
                },
            ))
        }
        STORAGE_SPARSE => Ok((
            Body::Sparse(parse_sparse(r, h.rows, h.cols)?),
            MatrixStorage::Sparse,
        )),
        _ => Err(r.error_at(
            h.storage_index,
            format!(
                "unknown storage type of {} (0 dense, 1 sparse-block, 2 sparse)",
                r.name
            ),
        )),
    }
}

/// The non-zero entries of a dense column-major matrix in compressed rows.
pub fn csr_of_dense(rows: usize, cols: usize, values: &[f64]) -> Result<CsrMatrix, Fc3dError> {
    let nonzeros = values.iter().filter(|v| **v != 0.0).count();
    let mut triplets = Vec::new();
    crate::alloc::reserve(&mut triplets, nonzeros, "the entries of a dense matrix")?;
    for (k, &v) in values.iter().enumerate() {
        if v != 0.0 {
            triplets.push((k % rows.max(1), k / rows.max(1), v));
        }
    }
    CsrMatrix::from_triplets(rows, cols, &triplets)
}

/// M, H, q, b and mu after the dimension token, for contacts of dimension `D`, and the
/// storages; `more_per_contact` values per contact follow mu (the rolling coefficients).
fn global_parts<const D: usize>(
    r: &mut Reader<'_>,
    more_per_contact: usize,
) -> Result<(Parts, GlobalStorage), Fc3dError> {
    let (nc_index, nc) = r.usize("the number of contacts")?;
    let size = nc
        .checked_mul(D)
        .filter(|&s| s <= MAX_SPARSE_SIZE)
        .ok_or_else(|| r.error_at(nc_index, "the number of contacts is too large"))?;

    r.name = "M";
    let mh = header(r)?;
    if mh.cols != mh.rows {
        return Err(r.error_at(
            mh.cols_index,
            format!("M must be square: {} rows, {} columns", mh.rows, mh.cols),
        ));
    }
    let n = mh.rows;
    // H, q, b and mu follow M: a size the rest of the input cannot hold fails here.
    let vectors = n
        .saturating_add(size)
        .saturating_add(nc.saturating_mul(1 + more_per_contact));
    r.ensure_remaining(vectors, "M, H, q, b and mu")?;
    let (m, m_storage) = body(r, &mh)?;

    r.name = "H";
    let hh = header(r)?;
    if hh.rows != n {
        return Err(r.error_at(
            hh.rows_index,
            format!("H must have the {n} rows of M, not {}", hh.rows),
        ));
    }
    if hh.cols != size {
        return Err(r.error_at(
            hh.cols_index,
            format!("H must have {D} * {nc} = {size} columns, not {}", hh.cols),
        ));
    }
    let (h, h_storage) = body(r, &hh)?;

    let q = r.reals::<Vec<f64>>(n, "q")?;
    let b = r.reals::<Vec<f64>>(size, "b")?;
    r.ensure_remaining(nc, "the friction coefficients mu")?;
    let mu = coefficients(
        r,
        nc,
        "friction coefficient",
        "the friction coefficients mu",
    )?;
    let parts = Parts {
        m,
        h,
        q,
        b,
        mu,
        at: mh.storage_index,
    };
    let storage = GlobalStorage {
        m: m_storage,
        h: h_storage,
    };
    Ok((parts, storage))
}

/// `nc` coefficients `>= 0`.
fn coefficients(
    r: &mut Reader<'_>,
    nc: usize,
    item: &str,
    what: &str,
) -> Result<Vec<f64>, Fc3dError> {
    let mut values = r.vec_for(nc, 1, what)?;
    for _ in 0..nc {
        let (index, v) = r.real(&format!("a {item}"))?;
        if v < 0.0 {
            return Err(r.error_at(index, format!("{item}s must be >= 0")));
        }
        try_push(&mut values, v, what)?;
    }
    Ok(values)
}

// ---------------------------------------------------------------------------------------------
// Writing.

/// Writes `problem` in the global `.dat` format, M and H in the given storages, values in
/// their shortest exactly round-tripping form: [`read_global_dat`] gives back an equal problem
/// and the same storages. A sparse-block storage whose sizes do not cover the matrix is an
/// [`io::ErrorKind::InvalidInput`] error.
pub fn write_global_dat<W: Write, const D: usize>(
    problem: &GlobalProblem<'_, D>,
    storage: &GlobalStorage,
    out: &mut W,
) -> io::Result<()> {
    writeln!(out, "{D}")?;
    writeln!(out, "{}", problem.n_contacts())?;
    write_stored_matrix(problem.m(), &storage.m, out)?;
    write_stored_matrix(problem.h(), &storage.h, out)?;
    write_reals_line(out, problem.q())?;
    write_reals_line(out, problem.b())?;
    write_reals_line(out, problem.mu())
}

/// Writes a global rolling `problem` (the global format, then `mu_r`).
pub fn write_global_rolling_dat<W: Write>(
    problem: &GlobalRollingProblem<'_>,
    storage: &GlobalStorage,
    out: &mut W,
) -> io::Result<()> {
    write_global_dat(problem.base(), storage, out)?;
    write_reals_line(out, problem.mu_r())
}

/// [`write_global_dat`] to the file `path` (created or truncated).
pub fn write_global_dat_file<const D: usize>(
    problem: &GlobalProblem<'_, D>,
    storage: &GlobalStorage,
    path: &Path,
) -> Result<(), Fc3dError> {
    write_path(path, |out| write_global_dat(problem, storage, out))
}

/// Writes `m` as Siconos' `NM_write_in_file` does, in `storage`.
pub fn write_stored_matrix<W: Write>(
    m: &CsrMatrix,
    storage: &MatrixStorage,
    out: &mut W,
) -> io::Result<()> {
    match storage {
        MatrixStorage::Dense => write_dense_csr(m, out),
        MatrixStorage::SparseBlock {
            row_sizes,
            col_sizes,
        } => write_blocks(m, row_sizes, col_sizes, out),
        MatrixStorage::Sparse => write_triplet_dump(m, out),
    }
}

fn out_of_memory(e: Fc3dError) -> io::Error {
    io::Error::new(io::ErrorKind::OutOfMemory, e.to_string())
}

fn write_dense_csr<W: Write>(m: &CsrMatrix, out: &mut W) -> io::Result<()> {
    let (rows, cols) = (m.nrows(), m.ncols());
    writeln!(out, "{STORAGE_DENSE}\n{rows}\n{cols}\n{rows}\t{cols}")?;
    // Column by column: the rows of the transpose.
    let t = transpose(m).map_err(out_of_memory)?;
    let mut column = try_vec(rows, 0.0, "a column of a dense matrix").map_err(out_of_memory)?;
    let mut line = Vec::new();
    // As Siconos prints it: the column-major values, `cols` per line.
    for j in 0..cols {
        column.iter_mut().for_each(|v| *v = 0.0);
        for k in t.row_ptr()[j]..t.row_ptr()[j + 1] {
            column[t.col_idx()[k]] = t.values()[k];
        }
        for &v in &column {
            line.push(v);
            if line.len() == cols {
                write_reals_line(out, &line)?;
                line.clear();
            }
        }
    }
    if !line.is_empty() {
        write_reals_line(out, &line)?;
    }
    Ok(())
}

/// Checks cumulative block sizes against the size they must cover.
fn check_cumulative(sizes: &[usize], n: usize, what: &str) -> Result<(), Fc3dError> {
    let increasing = sizes.windows(2).all(|w| w[0] < w[1]) && sizes.first().is_none_or(|&s| s > 0);
    if !increasing || sizes.last().copied().unwrap_or(0) != n {
        return Err(Fc3dError::InvalidStructure(format!(
            "sparse-block {what} sizes {sizes:?} do not cover the {n} {what}s of the matrix"
        )));
    }
    Ok(())
}

/// The blocks of a matrix cut by cumulative row and column sizes (Siconos' sparse-block
/// storage of it): `row_ptr` (one more than the block rows) and `col_idx` (in order within a
/// block row) of every block holding a stored entry of the matrix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BlockCut {
    pub row_ptr: Vec<usize>,
    pub col_idx: Vec<usize>,
}

/// The [`BlockCut`] of `m` for the cumulative sizes `row_sizes` and `col_sizes`, which must
/// increase and end at the rows and columns of `m` ([`Fc3dError::InvalidStructure`]
/// otherwise). Allocated fallibly.
pub fn block_cut(
    m: &CsrMatrix,
    row_sizes: &[usize],
    col_sizes: &[usize],
) -> Result<BlockCut, Fc3dError> {
    check_cumulative(row_sizes, m.nrows(), "row")?;
    check_cumulative(col_sizes, m.ncols(), "column")?;
    let mut row_ptr = Vec::new();
    crate::alloc::reserve(&mut row_ptr, row_sizes.len() + 1, "the block rows")?;
    row_ptr.push(0);
    let mut col_idx = Vec::new();
    let mut seen = try_vec(col_sizes.len(), usize::MAX, "the block columns")?;
    let mut first_row = 0;
    for (bi, &end) in row_sizes.iter().enumerate() {
        let first = col_idx.len();
        for i in first_row..end {
            for &j in &m.col_idx()[m.row_ptr()[i]..m.row_ptr()[i + 1]] {
                let bj = col_sizes.partition_point(|&c| c <= j);
                if seen[bj] != bi {
                    seen[bj] = bi;
                    try_push(&mut col_idx, bj, "the block columns")?;
                }
            }
        }
        col_idx[first..].sort_unstable();
        row_ptr.push(col_idx.len());
        first_row = end;
    }
    Ok(BlockCut { row_ptr, col_idx })
}

/// The block of `m` over `rows` x `cols`, column-major into `out` (cleared first; zeros where
/// `m` stores nothing, stored values as they are).
pub fn block_values(
    m: &CsrMatrix,
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
    out: &mut Vec<f64>,
) {
    out.clear();
    for j in cols {
        out.extend(rows.clone().map(|i| m.get(i, j)));
    }
}

/// The first row (or column) of block `k` of cumulative sizes `sizes`.
pub fn block_start(sizes: &[usize], k: usize) -> usize {
    if k == 0 {
        0
    } else {
        sizes[k - 1]
    }
}

/// The sparse-block body of `m` for the given cumulative block sizes: every block holding a
/// stored entry, whole (zeros where `m` stores nothing).
fn write_blocks<W: Write>(
    m: &CsrMatrix,
    row_sizes: &[usize],
    col_sizes: &[usize],
    out: &mut W,
) -> io::Result<()> {
    let (rows, cols) = (m.nrows(), m.ncols());
    writeln!(out, "{STORAGE_SPARSE_BLOCK}\n{rows}\n{cols}")?;
    if row_sizes.is_empty() && col_sizes.is_empty() && m.nnz() == 0 {
        // Siconos' matrix without blocks.
        return writeln!(out, "0");
    }
    let cut = block_cut(m, row_sizes, col_sizes).map_err(|e| match e {
        Fc3dError::OutOfMemory { .. } => out_of_memory(e),
        e => io::Error::new(io::ErrorKind::InvalidInput, e.to_string()),
    })?;
    let (row_ptr, col_idx) = (&cut.row_ptr, &cut.col_idx);
    writeln!(out, "{}", col_idx.len())?;
    writeln!(out, "{}\n{}", row_sizes.len(), col_sizes.len())?;
    write_usizes_line(out, row_sizes.iter().copied())?;
    write_usizes_line(out, col_sizes.iter().copied())?;
    writeln!(out, "{}\n{}", row_ptr.len(), col_idx.len())?;
    write_usizes_line(out, row_ptr.iter().copied())?;
    write_usizes_line(out, col_idx.iter().copied())?;
    let mut values = Vec::new();
    for bi in 0..row_sizes.len() {
        let rows = block_start(row_sizes, bi)..row_sizes[bi];
        for (k, &bj) in col_idx
            .iter()
            .enumerate()
            .take(row_ptr[bi + 1])
            .skip(row_ptr[bi])
        {
            // Blocks are numbered in storage order.
            writeln!(out, "{k}")?;
            block_values(
                m,
                rows.clone(),
                block_start(col_sizes, bj)..col_sizes[bj],
                &mut values,
            );
            // One value a line, as Siconos prints blocks.
            for v in &values {
                writeln!(out, "{v:e}")?;
            }
        }
    }
    Ok(())
}
