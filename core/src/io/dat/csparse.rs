//! The sparse storage (code 2): the CSparse triplet and compressed (CSC / CSR) dumps.

use super::tokens::{token_count, try_push, Reader};
use super::{ORIGIN_CSC, ORIGIN_CSR, ORIGIN_HALF_TRIPLET, ORIGIN_TRIPLET};
use crate::error::Fc3dError;
use crate::matrix::{CsrMatrix, Delassus};

/// A sparse matrix as read: its size and `(row, column, value)` entries, all checked in range
/// and finite; [`SparseEntries::finish`] compresses it.
pub(super) struct SparseEntries {
    rows: usize,
    cols: usize,
    entries: Vec<(usize, usize, f64)>,
    /// The token of the origin (kept by the reader), where an error about the matrix points.
    origin_index: usize,
}

impl SparseEntries {
    /// The compressed matrix (a pointer per declared row and a few arrays per entry, allocated
    /// fallibly: an impossible size is an out-of-memory error, any other refusal is placed in
    /// the file).
    pub(super) fn finish(self, r: &Reader<'_>) -> Result<Delassus<'static>, Fc3dError> {
        CsrMatrix::from_triplets(self.rows, self.cols, &self.entries)
            .map(Delassus::Sparse)
            .map_err(|e| match e {
                Fc3dError::OutOfMemory { what, bytes } => Fc3dError::OutOfMemory {
                    what: format!("{what} of {}", r.name),
                    bytes,
                },
                other => r.error_at(self.origin_index, other.to_string()),
            })
    }
}

/// Tokens of a `col j : locations a to b` line of a CSC dump.
const TOKENS_PER_CSC_COLUMN: usize = 7;
/// Tokens of an `i : value` line of a CSC dump.
const TOKENS_PER_CSC_ENTRY: usize = 3;
/// Tokens of a `row col : value` line of a triplet dump.
const TOKENS_PER_TRIPLET: usize = 4;

/// Parses the `m-by-n,` token of a CSparse header.
fn parse_csparse_dims(text: &str) -> Option<(usize, usize)> {
    let (m, n) = text.strip_suffix(',')?.split_once("-by-")?;
    Some((m.parse().ok()?, n.parse().ok()?))
}

/// Reads the `m-by-n,` token and checks it against the expected `m` and `n`.
fn csparse_dims(r: &mut Reader<'_>, m: usize, n: usize) -> Result<(), Fc3dError> {
    let index = r.next("the matrix size 'm-by-n,'")?;
    match parse_csparse_dims(r.text()) {
        Some(dims) if dims == (m, n) => Ok(()),
        Some((a, b)) => Err(r.error_at(
            index,
            format!("the CSparse matrix is {a}-by-{b} where {m}-by-{n} is expected"),
        )),
        None => Err(r.error_at(index, "expected the matrix size 'm-by-n,'")),
    }
}

/// The sparse body: the entries, checked; the caller compresses them with
/// [`SparseEntries::finish`].
pub(super) fn parse_sparse(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
) -> Result<SparseEntries, Fc3dError> {
    let (origin_index, origin) = r.usize("the sparse origin (1 triplet, 2 CSC, 3 CSR)")?;
    r.remember(origin_index);
    // Siconos reads what follows with fgets: the rest of the origin line, the CSparse banner line,
    // then the header line. The banner is free text, so it is skipped as a whole line.
    r.skip_rest_of_line(origin_index)?;
    let banner_index = r.next("the 'CSparse Version ...' line")?;
    if r.text() != "CSparse" {
        return Err(r.error_at(banner_index, "expected the 'CSparse Version ...' line"));
    }
    r.skip_rest_of_line(banner_index)?;

    let triplets = if r.peek()? == Some("triplet:") {
        match origin {
            ORIGIN_TRIPLET => {}
            ORIGIN_HALF_TRIPLET => {
                return Err(Fc3dError::Unsupported(format!(
                    "{}: half-triplet (symmetric half) storage of {} is not supported",
                    r.file, r.name
                )))
            }
            _ => {
                return Err(r.error_at(
                    origin_index,
                    "a triplet dump must have origin 1 (NSM_TRIPLET)",
                ))
            }
        }
        parse_triplet_dump(r, rows, cols)?
    } else {
        let rows_are_outer = match origin {
            ORIGIN_CSC => false,
            // Siconos keeps a CSR matrix as the CSparse struct of its transpose (m = columns,
            // n = rows) and prints it with the same code: rows are the "col" sections.
            ORIGIN_CSR => true,
            _ => {
                return Err(r.error_at(
                    origin_index,
                    "a compressed dump must have origin 2 (NSM_CSC) or 3 (NSM_CSR)",
                ))
            }
        };
        parse_compressed_dump(r, rows, cols, rows_are_outer)?
    };
    Ok(SparseEntries {
        rows,
        cols,
        entries: triplets,
        origin_index,
    })
}

/// `triplet: m-by-n, nzmax: Z nnz: N` then `N` lines `row col : value`.
fn parse_triplet_dump(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
) -> Result<Vec<(usize, usize, f64)>, Fc3dError> {
    let name = r.name;
    r.literal("triplet:", "the triplet header")?;
    csparse_dims(r, rows, cols)?;
    r.literal("nzmax:", "the triplet header")?;
    let (_, nzmax) = r.usize("nzmax")?;
    r.literal("nnz:", "the triplet header")?;
    let (nnz_index, nnz) = r.usize("nnz")?;
    if nnz > nzmax {
        return Err(r.error_at(nnz_index, format!("nnz exceeds nzmax {nzmax}")));
    }
    r.ensure_remaining(token_count(nnz, TOKENS_PER_TRIPLET), "the triplet entries")?;
    let mut triplets = r.vec_for(nnz, TOKENS_PER_TRIPLET, "the triplet entries")?;
    let value = format!("a value of {name}");
    for _ in 0..nnz {
        let (i_index, i) = r.usize("a row index")?;
        if i >= rows {
            return Err(r.error_at(
                i_index,
                format!("row index out of range ({name} has {rows} rows)"),
            ));
        }
        let (j_index, j) = r.usize("a column index")?;
        if j >= cols {
            return Err(r.error_at(
                j_index,
                format!("column index out of range ({name} has {cols} columns)"),
            ));
        }
        r.literal(":", "between the indices and the value of a triplet")?;
        let (_, v) = r.real(&value)?;
        try_push(&mut triplets, (i, j, v), "the triplet entries")?;
    }
    Ok(triplets)
}

/// `m-by-n, nzmax: Z nnz: N, 1-norm: X` then per section `col j : locations a to b` and `b - a + 1`
/// lines `i : value`. Sections are columns (CSC: `m` rows, `n` columns), or rows when
/// `rows_are_outer` (CSR: printed from the transposed struct, so `m` columns and `n` rows).
fn parse_compressed_dump(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
    rows_are_outer: bool,
) -> Result<Vec<(usize, usize, f64)>, Fc3dError> {
    let name = r.name;
    let (inner_count, outer_count) = if rows_are_outer {
        (cols, rows)
    } else {
        (rows, cols)
    };
    csparse_dims(r, inner_count, outer_count)?;
    r.literal("nzmax:", "the CSparse header")?;
    let (_, nzmax) = r.usize("nzmax")?;
    r.literal("nnz:", "the CSparse header")?;
    let nnz_index = r.next("nnz")?;
    r.remember(nnz_index);
    let nnz: usize = r
        .text()
        .strip_suffix(',')
        .and_then(|t| t.parse().ok())
        .ok_or_else(|| r.error_at(nnz_index, "expected nnz followed by a comma"))?;
    if nnz > nzmax {
        return Err(r.error_at(nnz_index, format!("nnz exceeds nzmax {nzmax}")));
    }
    r.literal("1-norm:", "the CSparse header")?;
    // The norm is informative only (and printed with %g): any token will do.
    r.next("the 1-norm")?;

    r.ensure_remaining(
        token_count(outer_count, TOKENS_PER_CSC_COLUMN)
            .saturating_add(token_count(nnz, TOKENS_PER_CSC_ENTRY)),
        "the compressed sections",
    )?;
    let mut triplets = r.vec_for(nnz, TOKENS_PER_CSC_ENTRY, "the stored entries")?;
    let value = format!("a value of {name}");
    for outer in 0..outer_count {
        r.literal("col", "a section header 'col j : locations a to b'")?;
        let (j_index, j) = r.usize("a section number")?;
        if j != outer {
            return Err(r.error_at(j_index, format!("expected section {outer}")));
        }
        r.literal(":", "a section header")?;
        r.literal("locations", "a section header")?;
        let (a_index, a) = r.integer("the first location of a section")?;
        if usize::try_from(a).ok() != Some(triplets.len()) {
            return Err(r.error_at(
                a_index,
                format!("section {outer} must start at location {}", triplets.len()),
            ));
        }
        r.literal("to", "a section header")?;
        // An empty section is printed "locations a to a-1" (so "0 to -1" for the first one).
        let (b_index, b) = r.integer("the last location of a section")?;
        let count = b
            .checked_add(1)
            .and_then(|end| end.checked_sub(a))
            .and_then(|c| usize::try_from(c).ok())
            .filter(|&c| c <= nnz - triplets.len())
            .ok_or_else(|| {
                r.error_at(
                    b_index,
                    format!("section {outer} ends outside the {nnz} stored entries"),
                )
            })?;
        for _ in 0..count {
            let (i_index, inner) = r.usize("an index of a stored entry")?;
            if inner >= inner_count {
                return Err(r.error_at(
                    i_index,
                    format!("index out of range ({name} is {rows}x{cols})"),
                ));
            }
            r.literal(":", "between the index and the value of an entry")?;
            let (_, v) = r.real(&value)?;
            let entry = if rows_are_outer {
                (outer, inner, v)
            } else {
                (inner, outer, v)
            };
            try_push(&mut triplets, entry, "the stored entries")?;
        }
    }
    if triplets.len() != nnz {
        return Err(r.error_at(
            nnz_index,
            format!("the sections hold {} entries, not nnz", triplets.len()),
        ));
    }
    Ok(triplets)
}
