//! The writers: a problem file, a matrix (`NM_write_in_file`) and a sparse-block body
//! (`SBM_write_in_file`).

use std::io::{self, BufWriter, Write};
use std::path::Path;

#[cfg(doc)]
use super::{parse_dat, parse_matrix};
use super::{ORIGIN_TRIPLET, STORAGE_DENSE, STORAGE_SPARSE, STORAGE_SPARSE_BLOCK};
use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::problem::{FrictionProblem, RollingProblem, DIMENSION};

/// Writes `problem` in the `.dat` format, W in the storage it has (a [`CsrMatrix`] as a CSparse
/// triplet dump, which Siconos reads as `NM_SPARSE` with origin `NSM_TRIPLET`). Values are printed
/// in their shortest exactly round-tripping form, so [`parse_dat`] (or, in 2D,
/// [`super::parse_dat_any`]) gives back an equal problem.
pub fn write_dat<W: Write, const D: usize>(
    problem: &FrictionProblem<'_, D>,
    out: &mut W,
) -> io::Result<()> {
    writeln!(out, "{D}")?;
    writeln!(out, "{}", problem.n_contacts())?;
    write_matrix(problem.w(), out)?;
    write_reals_line(out, problem.q())?;
    write_reals_line(out, problem.mu())
}

/// Writes a rolling `problem` in the `.dat` format of Siconos' `rollingFrictionContact_printInFile`
/// (dimension, contacts, W, q, mu, mu_r), values in their shortest exactly round-tripping form.
pub fn write_rolling_dat<W: Write, const D: usize>(
    problem: &RollingProblem<'_, D>,
    out: &mut W,
) -> io::Result<()> {
    write_dat(problem.base(), out)?;
    write_reals_line(out, problem.mu_r())
}

/// Writes `w` as Siconos' `NM_write_in_file` does (`storageType size0 size1` and the body), in the
/// storage it has; a [`CsrMatrix`] is written as a CSparse triplet dump (origin `NSM_TRIPLET`).
/// Values are printed in their shortest exactly round-tripping form: [`parse_matrix`] gives back
/// an equal matrix, bit for bit, and Siconos reads the same values.
pub fn write_matrix<W: Write>(w: &Delassus<'_>, out: &mut W) -> io::Result<()> {
    match w {
        Delassus::Dense(d) => write_dense(d, out),
        Delassus::SparseBlock(s) => {
            writeln!(out, "{STORAGE_SPARSE_BLOCK}\n{}\n{}", s.nrows(), s.ncols())?;
            write_sbm(s, out)
        }
        Delassus::Sparse(s) => write_triplet_dump(s, out),
    }
}

/// Writes the sparse-block body of `m` without the `storageType size0 size1` header, as Siconos'
/// `SBM_write_in_file` does (a lone `0` for a matrix without blocks).
pub fn write_sbm<W: Write>(m: &BlockSparseMatrix, out: &mut W) -> io::Result<()> {
    writeln!(out, "{}", m.n_blocks())?;
    if m.n_blocks() == 0 {
        return Ok(());
    }
    writeln!(out, "{}\n{}", m.n_block_rows(), m.n_block_cols())?;
    write_usizes_line(out, (1..=m.n_block_rows()).map(|k| DIMENSION * k))?;
    write_usizes_line(out, (1..=m.n_block_cols()).map(|k| DIMENSION * k))?;
    writeln!(out, "{}\n{}", m.row_ptr().len(), m.n_blocks())?;
    write_usizes_line(out, m.row_ptr().iter().copied())?;
    write_usizes_line(out, m.col_idx().iter().copied())?;
    // Blocks are stored in block-CSR order, so storage index k is the number Siconos expects.
    for (k, block) in m.blocks().enumerate() {
        writeln!(out, "{k}")?;
        for v in block {
            writeln!(out, "{v:e}")?;
        }
    }
    Ok(())
}

/// Writes `problem` to `path` (see [`write_dat`]).
pub fn write_dat_file<const D: usize>(
    problem: &FrictionProblem<'_, D>,
    path: &Path,
) -> Result<(), Fc3dError> {
    write_path(path, |out| write_dat(problem, out))
}

/// Creates (or truncates) `path` and writes to it with `write`, buffered; an I/O failure is an
/// [`Fc3dError::Io`] naming the file.
pub(super) fn write_path(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<std::fs::File>) -> io::Result<()>,
) -> Result<(), Fc3dError> {
    let io_error = |e: io::Error| Fc3dError::Io {
        file: path.display().to_string(),
        message: format!("cannot write: {e}"),
    };
    let file = std::fs::File::create(path).map_err(io_error)?;
    let mut out = BufWriter::new(file);
    write(&mut out).map_err(io_error)?;
    out.flush().map_err(io_error)
}

/// Values separated by spaces on one line, each in the shortest form that reads back exactly.
pub(super) fn write_reals_line<W: Write>(out: &mut W, values: &[f64]) -> io::Result<()> {
    for (k, v) in values.iter().enumerate() {
        if k > 0 {
            out.write_all(b" ")?;
        }
        write!(out, "{v:e}")?;
    }
    writeln!(out)
}

/// Integers separated (and ended) by tabs on one line, as Siconos prints index arrays.
pub(super) fn write_usizes_line<W: Write>(
    out: &mut W,
    values: impl Iterator<Item = usize>,
) -> io::Result<()> {
    for v in values {
        write!(out, "{v}\t")?;
    }
    writeln!(out)
}

fn write_dense<W: Write>(d: &DenseMatrix<'_>, out: &mut W) -> io::Result<()> {
    let (m, n) = (d.nrows(), d.ncols());
    writeln!(out, "{STORAGE_DENSE}\n{m}\n{n}\n{m}\t{n}")?;
    // The column-major values, size1 per line as Siconos prints them (one column per line when
    // the matrix is square).
    for line in d.values().chunks(n.max(1)) {
        write_reals_line(out, line)?;
    }
    Ok(())
}

pub(super) fn write_triplet_dump<W: Write>(s: &CsrMatrix, out: &mut W) -> io::Result<()> {
    let (m, n, nnz) = (s.nrows(), s.ncols(), s.nnz());
    writeln!(out, "{STORAGE_SPARSE}\n{m}\n{n}\n{ORIGIN_TRIPLET}")?;
    // Siconos skips this banner line unread; the header after it must keep single spaces because
    // Siconos splits it with strtok(" ").
    writeln!(out, "CSparse Version 3.2.0 triplet dump written by fc3d")?;
    writeln!(out, "triplet: {m}-by-{n}, nzmax: {nnz} nnz: {nnz}")?;
    let mut result = Ok(());
    s.for_each_entry(|i, j, v| {
        if result.is_ok() {
            result = writeln!(out, "    {i} {j} : {v:e}");
        }
    });
    result
}
