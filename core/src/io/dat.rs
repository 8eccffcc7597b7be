//! The Siconos Numerics `.dat` text format of a `FrictionContactProblem` (reduced form).
//!
//! The file is a sequence of whitespace-separated tokens (0-based indices everywhere):
//!
//! ```text
//! dim nc
//! storageType size0 size1   matrix body (see below)
//! q[0] ... q[size0-1]
//! mu[0] ... mu[nc-1]
//! anything (ignored)
//! ```
//!
//! Matrix bodies, as written by Siconos 4.4 (`NM_write_in_file`) and read by `NM_new_from_file`:
//!
//! * dense (0): `size0 size1` again, then `size0 * size1` values, column-major;
//! * sparse-block (1): `nbblocks`, `blocknumber0 blocknumber1`, the cumulative row then column
//!   block sizes, `filled1 filled2`, `index1_data` (block-row pointers, `filled1` of them),
//!   `index2_data` (block columns, `filled2` of them), then for each block row and each of its
//!   blocks the block number and its values column-major. A lone `0` (no block) ends the body;
//! * sparse (2): an origin (`1` triplet, `2` CSC, `3` CSR), then the CSparse dump of
//!   `CSparseMatrix_print_in_file`: a banner line `CSparse Version ...`, then either
//!   `m-by-n, nzmax: Z nnz: N, 1-norm: X` followed by `col j : locations a to b` and `i : value`
//!   lines, or `triplet: m-by-n, nzmax: Z nnz: N` followed by `N` lines `row col : value`.
//!
//! Siconos prints sparse values with `%g` (6 significant digits), so its own sparse files are lossy;
//! [`write_dat`] prints every value in the shortest form that reads back to the same `f64`
//! (Rust's `{:e}`, which C's `strtod` reads too), so our files round-trip bit for bit in all three
//! storages.
//!
//! Only dimension 3 is supported, sparse-block matrices must be made of 3x3 blocks, and every error
//! in the text is an [`Fc3dError::Parse`] naming the token at fault (or `<end of file>`). Declared
//! sizes are checked against the number of tokens left before anything is allocated, so a corrupt
//! header cannot make the reader allocate more than the file could describe.
//!
//! The matrix part alone (`storageType size0 size1` and the body, any shape) is what Siconos'
//! `NM_write_in_file` writes and `NM_new_from_file` reads: [`parse_matrix`] and [`write_matrix`].
//! The sparse-block body without that header is what `SBM_write_in_file` writes and
//! `SBM_new_from_file` reads: [`parse_sbm`] and [`write_sbm`]. The `_prefix` variants also say
//! where the matrix text ends, for readers that continue after it.

use std::io::{self, BufWriter, Write};
use std::path::Path;

use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::problem::{FrictionProblem, DIMENSION};

/// Siconos `NM_types` codes of the matrix storage.
const STORAGE_DENSE: usize = 0;
const STORAGE_SPARSE_BLOCK: usize = 1;
const STORAGE_SPARSE: usize = 2;

/// Siconos 4.4 `NumericsSparseOrigin` codes (`NSM_UNKNOWN, NSM_TRIPLET, NSM_CSC, NSM_CSR,
/// NSM_HALF_TRIPLET`).
const ORIGIN_TRIPLET: usize = 1;
const ORIGIN_CSC: usize = 2;
const ORIGIN_CSR: usize = 3;
const ORIGIN_HALF_TRIPLET: usize = 4;

/// The token text reported when the input ends too early.
const END_OF_FILE: &str = "<end of file>";

/// Tokens of a 3x3 block in the sparse-block body: its number and 9 values.
const TOKENS_PER_BLOCK: usize = 1 + 9;
/// Tokens of a `col j : locations a to b` line of a CSC dump.
const TOKENS_PER_CSC_COLUMN: usize = 7;
/// Tokens of an `i : value` line of a CSC dump.
const TOKENS_PER_CSC_ENTRY: usize = 3;
/// Tokens of a `row col : value` line of a triplet dump.
const TOKENS_PER_TRIPLET: usize = 4;

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
            return Err(Fc3dError::Unsupported(format!(
                "{file_label}: fc2d problems are not supported (the file has dimension 2, fc3d solves dimension 3)"
            )))
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

/// Writes `problem` in the `.dat` format, W in the storage it has (a [`CsrMatrix`] as a CSparse
/// triplet dump, which Siconos reads as `NM_SPARSE` with origin `NSM_TRIPLET`). Values are printed
/// in their shortest exactly round-tripping form, so [`parse_dat`] gives back an equal problem.
pub fn write_dat<W: Write>(problem: &FrictionProblem<'_>, out: &mut W) -> io::Result<()> {
    writeln!(out, "{DIMENSION}")?;
    writeln!(out, "{}", problem.n_contacts())?;
    write_matrix(problem.w(), out)?;
    write_reals_line(out, problem.q())?;
    write_reals_line(out, problem.mu())
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
    for (k, block) in m.blocks().iter().enumerate() {
        writeln!(out, "{k}")?;
        for v in block {
            writeln!(out, "{v:e}")?;
        }
    }
    Ok(())
}

/// Writes `problem` to `path` (see [`write_dat`]).
pub fn write_dat_file(problem: &FrictionProblem<'_>, path: &Path) -> Result<(), Fc3dError> {
    let io_error = |e: io::Error| Fc3dError::Io {
        file: path.display().to_string(),
        message: format!("cannot write: {e}"),
    };
    let file = std::fs::File::create(path).map_err(io_error)?;
    let mut out = BufWriter::new(file);
    write_dat(problem, &mut out).map_err(io_error)?;
    out.flush().map_err(io_error)
}

// ---------------------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------------------

/// A whitespace-separated token and the line it sits on (the CSparse dump is partly line-based).
struct Token<'t> {
    text: &'t str,
    line: usize,
}

/// A cursor over the tokens of the whole input.
struct Reader<'t> {
    text: &'t str,
    file: &'t str,
    /// What the matrix is called in messages ("W" in a problem file, "M" alone).
    name: &'static str,
    tokens: Vec<Token<'t>>,
    pos: usize,
}

impl<'t> Reader<'t> {
    fn new(text: &'t str, file: &'t str, name: &'static str) -> Self {
        // Splitting lines on '\n' then each line on whitespace yields exactly the tokens of
        // `text.split_whitespace()`, so token indices are those of the whole text.
        let tokens = text
            .split('\n')
            .enumerate()
            .flat_map(|(line, l)| l.split_whitespace().map(move |text| Token { text, line }))
            .collect();
        Reader {
            text,
            file,
            name,
            tokens,
            pos: 0,
        }
    }

    /// The bytes of the text read so far and the whitespace after them: the offset of the first
    /// unread token, or the length of the text when every token has been read.
    fn consumed_bytes(&self) -> usize {
        self.tokens.get(self.pos).map_or(self.text.len(), |t| {
            // Tokens are slices of `text`.
            t.text.as_ptr() as usize - self.text.as_ptr() as usize
        })
    }

    /// A parse error at token `index` (the end of the input if there is no such token).
    fn error_at(&self, index: usize, message: impl Into<String>) -> Fc3dError {
        let token = self.tokens.get(index).map_or(END_OF_FILE, |t| t.text);
        Fc3dError::Parse {
            file: self.file.to_string(),
            token_index: index,
            token: token.to_string(),
            message: message.into(),
        }
    }

    fn peek(&self) -> Option<&'t str> {
        self.tokens.get(self.pos).map(|t| t.text)
    }

    /// The next token and its index.
    fn next(&mut self, what: &str) -> Result<(usize, &'t str), Fc3dError> {
        let index = self.pos;
        match self.tokens.get(index) {
            Some(t) => {
                self.pos += 1;
                Ok((index, t.text))
            }
            None => Err(self.error_at(index, format!("the file ends where {what} is expected"))),
        }
    }

    /// Fails unless at least `needed` tokens are left: called with the token count a declared size
    /// implies, before allocating for it.
    fn ensure_remaining(&self, needed: usize, what: &str) -> Result<(), Fc3dError> {
        let left = self.tokens.len() - self.pos;
        if needed > left {
            return Err(self.error_at(
                self.tokens.len(),
                format!("{what} need {needed} more tokens but the file ends after {left}"),
            ));
        }
        Ok(())
    }

    fn usize(&mut self, what: &str) -> Result<(usize, usize), Fc3dError> {
        let (index, text) = self.next(what)?;
        text.parse::<usize>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (a non-negative integer)")))
    }

    fn integer(&mut self, what: &str) -> Result<(usize, i64), Fc3dError> {
        let (index, text) = self.next(what)?;
        text.parse::<i64>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (an integer)")))
    }

    /// A finite real number (NaN and infinities are rejected here, where the token is known).
    fn real(&mut self, what: &str) -> Result<(usize, f64), Fc3dError> {
        let (index, text) = self.next(what)?;
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((index, v)),
            Ok(_) => Err(self.error_at(index, format!("{what} must be finite"))),
            Err(_) => Err(self.error_at(index, format!("expected {what} (a real number)"))),
        }
    }

    /// `count` finite reals.
    fn reals(&mut self, count: usize, what: &str) -> Result<Vec<f64>, Fc3dError> {
        self.ensure_remaining(count, what)?;
        let mut values = Vec::with_capacity(count);
        for _ in 0..count {
            values.push(self.real(&format!("a value of {what}"))?.1);
        }
        Ok(values)
    }

    /// Consumes a token that must be exactly `literal`.
    fn literal(&mut self, literal: &str, context: &str) -> Result<usize, Fc3dError> {
        let (index, text) = self.next(&format!("'{literal}' ({context})"))?;
        if text != literal {
            return Err(self.error_at(index, format!("expected '{literal}' ({context})")));
        }
        Ok(index)
    }

    /// Skips the tokens that share the line of token `index` and follow the cursor.
    fn skip_rest_of_line(&mut self, index: usize) {
        if let Some(line) = self.tokens.get(index).map(|t| t.line) {
            while self.tokens.get(self.pos).is_some_and(|t| t.line == line) {
                self.pos += 1;
            }
        }
    }
}

/// `count * per_item` tokens, saturating: an absurd count must fail the remaining-token check,
/// not overflow.
fn token_count(count: usize, per_item: usize) -> usize {
    count.saturating_mul(per_item)
}

/// The body of a `rows x cols` matrix of the given storage code (read at token `storage_index`).
/// `require_diagonal`: a sparse-block matrix must store every diagonal block (a problem's W).
fn parse_matrix_body(
    r: &mut Reader<'_>,
    storage_index: usize,
    storage: usize,
    rows: usize,
    cols: usize,
    require_diagonal: bool,
) -> Result<Delassus<'static>, Fc3dError> {
    match storage {
        STORAGE_DENSE => parse_dense(r, rows, cols),
        STORAGE_SPARSE_BLOCK => {
            parse_sparse_block(r, Some((rows, cols)), require_diagonal).map(Delassus::SparseBlock)
        }
        STORAGE_SPARSE => parse_sparse(r, rows, cols),
        _ => Err(r.error_at(
            storage_index,
            format!(
                "unknown storage type of {} (0 dense, 1 sparse-block, 2 sparse)",
                r.name
            ),
        )),
    }
}

fn parse_dense(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
) -> Result<Delassus<'static>, Fc3dError> {
    let name = r.name;
    // The dense body repeats the sizes (Siconos reads them again and trusts the second pair).
    for (what, n) in [("rows", rows), ("columns", cols)] {
        let (index, size) = r.usize(&format!("the number of {what} of the dense {name}"))?;
        if size != n {
            return Err(r.error_at(
                index,
                format!("the dense {name} must have {n} {what} as declared, not {size}"),
            ));
        }
    }
    let start = r.pos;
    let len = rows
        .checked_mul(cols)
        .ok_or_else(|| r.error_at(start, format!("the dense {name} is too large")))?;
    let values = r.reals(len, &format!("the dense {name}"))?;
    DenseMatrix::new(rows, cols, values)
        .map(Delassus::Dense)
        .map_err(|e| r.error_at(start, e.to_string()))
}

/// Reads `count` cumulative block sizes that must be 3, 6, 9, ..., up to `n` when it is given;
/// returns the last one (the number of rows or columns the blocks cover).
fn parse_block_sizes(
    r: &mut Reader<'_>,
    count: usize,
    count_index: usize,
    n: Option<usize>,
    what: &str,
) -> Result<usize, Fc3dError> {
    r.ensure_remaining(count, &format!("the cumulative {what} block sizes"))?;
    let mut previous = 0;
    let mut last_index = count_index;
    for k in 0..count {
        let (index, size) = r.usize(&format!("a cumulative {what} block size"))?;
        if size <= previous {
            return Err(r.error_at(
                index,
                format!("cumulative {what} block sizes must increase ({size} after {previous})"),
            ));
        }
        if size - previous != DIMENSION {
            return Err(Fc3dError::Unsupported(format!(
                "{}: sparse-block {} with a block {what} of size {} (block {what} {k}, token {index}); \
                 fc3d handles 3x3 blocks only",
                r.file,
                r.name,
                size - previous
            )));
        }
        previous = size;
        last_index = index;
    }
    match n {
        Some(n) if previous != n => Err(r.error_at(
            last_index,
            format!(
                "the {what} blocks cover {previous} {what}s but {} has {n}",
                r.name
            ),
        )),
        _ => Ok(previous),
    }
}

/// A sparse-block body. `shape`: the declared `(rows, cols)` (None: the block sizes tell).
/// `require_diagonal`: every diagonal block must be stored (the W of a problem).
fn parse_sparse_block(
    r: &mut Reader<'_>,
    shape: Option<(usize, usize)>,
    require_diagonal: bool,
) -> Result<BlockSparseMatrix, Fc3dError> {
    let name = r.name;
    let (nbblocks_index, nbblocks) = r.usize(&format!("the number of blocks of {name}"))?;
    if nbblocks == 0 {
        // Siconos writes a lone 0 for a matrix without blocks and stops there.
        let (rows, cols) = shape.unwrap_or((0, 0));
        if require_diagonal && rows > 0 {
            return Err(r.error_at(
                nbblocks_index,
                format!(
                    "a sparse-block {name} without blocks lacks the diagonal blocks of {} contacts",
                    rows / DIMENSION
                ),
            ));
        }
        if rows % DIMENSION != 0 || cols % DIMENSION != 0 {
            return Err(Fc3dError::Unsupported(format!(
                "{}: a sparse-block {name} of size {rows}x{cols} cannot be made of 3x3 blocks \
                 (fc3d handles 3x3 blocks only)",
                r.file
            )));
        }
        let empty = BlockSparseMatrix::new(
            rows / DIMENSION,
            cols / DIMENSION,
            vec![0; rows / DIMENSION + 1],
            Vec::new(),
            Vec::new(),
        )
        .map_err(|e| r.error_at(nbblocks_index, e.to_string()))?;
        return Ok(empty);
    }
    let (rows_index, block_rows) = r.usize("the number of block rows")?;
    let (cols_index, block_cols) = r.usize("the number of block columns")?;
    parse_block_sizes(r, block_rows, rows_index, shape.map(|s| s.0), "row")?;
    parse_block_sizes(r, block_cols, cols_index, shape.map(|s| s.1), "column")?;
    // From here on the matrix is block_rows x block_cols blocks of 3x3 (and block_rows tokens
    // have been read, so allocating per block row is bounded by the text).

    let (filled1_index, filled1) = r.usize("filled1 (the length of index1_data)")?;
    if filled1 == 0 || filled1 > block_rows + 1 {
        return Err(r.error_at(
            filled1_index,
            format!(
                "filled1 must be between 1 and {} (block rows + 1)",
                block_rows + 1
            ),
        ));
    }
    let (filled2_index, filled2) = r.usize("filled2 (the number of stored blocks)")?;
    if filled2 != nbblocks {
        return Err(r.error_at(
            filled2_index,
            format!("filled2 must equal the number of blocks {nbblocks}"),
        ));
    }
    r.ensure_remaining(
        filled1.saturating_add(filled2),
        "index1_data and index2_data",
    )?;

    let index1_start = r.pos;
    let mut row_ptr = Vec::with_capacity(block_rows + 1);
    for k in 0..filled1 {
        let (index, p) = r.usize("a block-row pointer (index1_data)")?;
        let previous = row_ptr.last().copied().unwrap_or(0);
        if (k == 0 && p != 0) || p < previous || p > filled2 {
            return Err(r.error_at(
                index,
                format!("index1_data must start at 0 and not decrease up to the {filled2} blocks"),
            ));
        }
        row_ptr.push(p);
    }
    if row_ptr.last() != Some(&filled2) {
        return Err(r.error_at(
            index1_start + filled1 - 1,
            format!("index1_data must end at the number of blocks {filled2}"),
        ));
    }
    // Siconos may stop index1_data after the last non-empty block row; the rows after it are empty.
    row_ptr.resize(block_rows + 1, filled2);

    let mut col_idx = Vec::with_capacity(filled2);
    for _ in 0..filled2 {
        let (index, c) = r.usize("a block column (index2_data)")?;
        if c >= block_cols {
            return Err(r.error_at(
                index,
                format!("block column {c} is out of range ({name} has {block_cols} block columns)"),
            ));
        }
        col_idx.push(c);
    }
    if require_diagonal {
        // The diagonal block of every contact is needed by the solvers: name the row that lacks it.
        for c in 0..block_rows {
            if !col_idx[row_ptr[c]..row_ptr[c + 1]].contains(&c) {
                let index = if c < filled1 {
                    index1_start + c
                } else {
                    filled1_index
                };
                return Err(r.error_at(
                    index,
                    format!("the diagonal 3x3 block of contact {c} is missing from {name}"),
                ));
            }
        }
    }

    r.ensure_remaining(
        token_count(filled2, TOKENS_PER_BLOCK),
        &format!("the blocks of {name}"),
    )?;
    let mut blocks = Vec::with_capacity(filled2);
    for row in 0..block_rows {
        for k in row_ptr[row]..row_ptr[row + 1] {
            let (index, number) = r.usize("a block number")?;
            // Siconos only warns about a wrong number (it stores blocks in file order anyway); a
            // wrong number means the file is corrupt, so it is an error here.
            if number != k {
                return Err(r.error_at(
                    index,
                    format!("block number {number} where block {k} is expected"),
                ));
            }
            let mut block = [0.0; 9];
            for v in block.iter_mut() {
                *v = r.real("a block value")?.1;
            }
            blocks.push(block);
        }
    }
    BlockSparseMatrix::new(block_rows, block_cols, row_ptr, col_idx, blocks)
        .map_err(|e| r.error_at(nbblocks_index, e.to_string()))
}

/// Parses the `m-by-n,` token of a CSparse header.
fn parse_csparse_dims(text: &str) -> Option<(usize, usize)> {
    let (m, n) = text.strip_suffix(',')?.split_once("-by-")?;
    Some((m.parse().ok()?, n.parse().ok()?))
}

/// Reads the `m-by-n,` token and checks it against the expected `m` and `n`.
fn csparse_dims(r: &mut Reader<'_>, m: usize, n: usize) -> Result<(), Fc3dError> {
    let (index, text) = r.next("the matrix size 'm-by-n,'")?;
    match parse_csparse_dims(text) {
        Some(dims) if dims == (m, n) => Ok(()),
        Some((a, b)) => Err(r.error_at(
            index,
            format!("the CSparse matrix is {a}-by-{b} where {m}-by-{n} is expected"),
        )),
        None => Err(r.error_at(index, "expected the matrix size 'm-by-n,'")),
    }
}

fn parse_sparse(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
) -> Result<Delassus<'static>, Fc3dError> {
    let (origin_index, origin) = r.usize("the sparse origin (1 triplet, 2 CSC, 3 CSR)")?;
    // Siconos reads what follows with fgets: the rest of the origin line, the CSparse banner line,
    // then the header line. The banner is free text, so it is skipped as a whole line.
    r.skip_rest_of_line(origin_index);
    let (banner_index, banner) = r.next("the 'CSparse Version ...' line")?;
    if banner != "CSparse" {
        return Err(r.error_at(banner_index, "expected the 'CSparse Version ...' line"));
    }
    r.skip_rest_of_line(banner_index);

    let triplets = if r.peek() == Some("triplet:") {
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
    CsrMatrix::from_triplets(rows, cols, &triplets)
        .map(Delassus::Sparse)
        .map_err(|e| r.error_at(origin_index, e.to_string()))
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
    let mut triplets = Vec::with_capacity(nnz);
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
        let (_, v) = r.real(&format!("a value of {name}"))?;
        triplets.push((i, j, v));
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
    let (nnz_index, nnz_text) = r.next("nnz")?;
    let nnz: usize = nnz_text
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
    let mut triplets = Vec::with_capacity(nnz);
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
            let (_, v) = r.real(&format!("a value of {name}"))?;
            triplets.push(if rows_are_outer {
                (outer, inner, v)
            } else {
                (inner, outer, v)
            });
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

// ---------------------------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------------------------

/// Values separated by spaces on one line, each in the shortest form that reads back exactly.
fn write_reals_line<W: Write>(out: &mut W, values: &[f64]) -> io::Result<()> {
    for (k, v) in values.iter().enumerate() {
        if k > 0 {
            out.write_all(b" ")?;
        }
        write!(out, "{v:e}")?;
    }
    writeln!(out)
}

/// Integers separated (and ended) by tabs on one line, as Siconos prints index arrays.
fn write_usizes_line<W: Write>(out: &mut W, values: impl Iterator<Item = usize>) -> io::Result<()> {
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

fn write_triplet_dump<W: Write>(s: &CsrMatrix, out: &mut W) -> io::Result<()> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn data_file(name: &str) -> String {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
        std::fs::read_to_string(format!("{path}{name}")).expect("shared data file")
    }

    /// `FrictionContact3D_1c.dat` re-written by Siconos 4.4 (`frictionContact_printInFilename`)
    /// with W converted to CSC (`NM_csc`): same lines and tokens, indentation not kept.
    const SICONOS_CSC_1C: &str = "3\n1\n2\n3\n3\n2\n\
CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
3-by-3, nzmax: 9 nnz: 9, 1-norm: 19\n\
    col 0 : locations 0 to 2\n      0 : 15\n      1 : -1\n      2 : -2\n\
    col 1 : locations 3 to 5\n      0 : -1\n      1 : 14\n      2 : 1\n\
    col 2 : locations 6 to 8\n      0 : -2\n      1 : 1\n      2 : 16\n \
-1.000000000000000000000000e+00   2.000000000000000000000000e+00   3.000000000000000000000000e+00 \n  \
1.000000000000000055511151e-01 \n";

    /// The same problem with W converted to triplets (`NM_triplet`), verbatim.
    const SICONOS_TRIPLET_1C: &str = "3\n1\n2\n3\n3\n1\n\
CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
triplet: 3-by-3, nzmax: 16 nnz: 9\n\
    0 0 : 15\n    0 1 : -1\n    0 2 : -2\n    1 0 : -1\n    1 1 : 14\n    1 2 : 1\n\
    2 0 : -2\n    2 1 : 1\n    2 2 : 16\n \
-1.000000000000000000000000e+00   2.000000000000000000000000e+00   3.000000000000000000000000e+00 \n  \
1.000000000000000055511151e-01 \n";

    #[test]
    fn siconos_sparse_dumps_read_like_the_dense_original() {
        let dense = parse_dat(&data_file("FrictionContact3D_1c.dat"), "1c").unwrap();
        for (label, text) in [("csc", SICONOS_CSC_1C), ("triplet", SICONOS_TRIPLET_1C)] {
            let p = parse_dat(text, label).unwrap();
            assert!(matches!(p.w(), Delassus::Sparse(_)), "{label}");
            assert_eq!(p.w().to_dense(), dense.w().to_dense(), "{label}");
            assert_eq!(p.q(), dense.q());
            assert_eq!(p.mu(), dense.mu());
        }
    }

    #[test]
    fn csr_origin_reads_sections_as_rows() {
        // An upper-triangular W makes the orientation visible.
        let text = "3\n1\n2\n3\n3\n3\nCSparse Version x\n3-by-3, nzmax: 4 nnz: 4, 1-norm: 3\n\
            col 0 : locations 0 to 1\n 0 : 1\n 2 : 5\n col 1 : locations 2 to 2\n 1 : 1\n\
            col 2 : locations 3 to 3\n 2 : 1\n 0 0 0\n 0.5\n";
        let p = parse_dat(text, "csr").unwrap();
        assert_eq!(p.w().get(0, 2), 5.0);
        assert_eq!(p.w().get(2, 0), 0.0);
    }

    /// Parses the W of a (2D) file whose header is `dim nc storage n n`, to exercise the CSparse
    /// readers on the real dumps Siconos wrote.
    fn matrix_of(text: &str) -> Delassus<'static> {
        let mut r = Reader::new(text, "2d", "W");
        let header: Vec<usize> = (0..5).map(|_| r.usize("header").unwrap().1).collect();
        assert_eq!(header[2], STORAGE_SPARSE);
        parse_sparse(&mut r, header[3], header[4]).unwrap()
    }

    #[test]
    fn real_csc_dump_of_a_2d_file() {
        let w = matrix_of(&data_file("fc2d_granularflowonwall_00667_00000.dat"));
        let Delassus::Sparse(s) = &w else {
            panic!("expected a sparse W")
        };
        assert_eq!((s.nrows(), s.nnz()), (1334, 3822));
        assert_eq!(w.get(0, 0), 856.713);
        assert_eq!(w.get(649, 0), -454.43);
        assert_eq!(w.get(648, 1), 454.43);
    }

    #[test]
    fn real_triplet_dump_of_a_2d_file() {
        let w = matrix_of(&data_file("gfc2d_granularflowonwall_00069_00350.dat"));
        let Delassus::Sparse(s) = &w else {
            panic!("expected a sparse W")
        };
        assert_eq!((s.nrows(), s.nnz()), (900, 900));
        assert_eq!(w.get(2, 2), 1.46527e-10);
        assert_eq!(w.get(3, 3), 0.00149261);
    }

    #[test]
    fn empty_problem_round_trips_in_every_storage() {
        let dense = DenseMatrix::new(0, 0, Vec::new()).unwrap();
        let sbm = BlockSparseMatrix::new(0, 0, vec![0], Vec::new(), Vec::new()).unwrap();
        let csr = CsrMatrix::from_triplets(0, 0, &[]).unwrap();
        for w in [
            Delassus::Dense(dense),
            Delassus::SparseBlock(sbm),
            Delassus::Sparse(csr),
        ] {
            let p = FrictionProblem::new(w, Vec::new(), Vec::new()).unwrap();
            let mut text = Vec::new();
            write_dat(&p, &mut text).unwrap();
            let back = parse_dat(std::str::from_utf8(&text).unwrap(), "empty").unwrap();
            assert_eq!(back, p);
        }
    }

    #[test]
    fn extreme_values_round_trip_bit_for_bit() {
        let values = [
            f64::MIN_POSITIVE,
            5e-324,
            -f64::MAX,
            f64::MAX,
            -0.0,
            0.1,
            1.0 / 3.0,
            -2.5e-308,
            123_456_789.123_456_79,
        ];
        let w = DenseMatrix::new(3, 3, values.to_vec()).unwrap();
        let p = FrictionProblem::new(Delassus::Dense(w), vec![-0.0, 1e300, -1e-300], vec![0.0])
            .unwrap();
        let mut text = Vec::new();
        write_dat(&p, &mut text).unwrap();
        let back = parse_dat(std::str::from_utf8(&text).unwrap(), "x").unwrap();
        let Delassus::Dense(d) = back.w() else {
            panic!("expected a dense W")
        };
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(d.values()), bits(&values));
        assert_eq!(bits(back.q()), bits(p.q()));
    }

    #[test]
    fn errors_name_the_offending_token() {
        let err = parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 0 x", "f.dat").unwrap_err();
        assert_eq!(
            err,
            Fc3dError::Parse {
                file: "f.dat".into(),
                token_index: 15,
                token: "x".into(),
                message: "expected a value of the dense W (a real number)".into(),
            }
        );
        let Fc3dError::Parse {
            token, token_index, ..
        } = parse_dat("3 1 0 3 3 3 3 1 0", "f.dat").unwrap_err()
        else {
            panic!("expected a parse error")
        };
        assert_eq!((token.as_str(), token_index), (END_OF_FILE, 9));
        let Fc3dError::Parse { token, .. } =
            parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 0 1 0 0 0 -0.5", "f.dat").unwrap_err()
        else {
            panic!("expected a parse error")
        };
        assert_eq!(token, "-0.5");
        let Fc3dError::Parse { token, message, .. } =
            parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 inf 1", "f.dat").unwrap_err()
        else {
            panic!("expected a parse error")
        };
        assert_eq!(token, "inf");
        assert!(message.contains("finite"), "{message}");
    }

    #[test]
    fn huge_declared_sizes_fail_before_allocating() {
        for text in [
            "3 6148914691236517205 0 18446744073709551615 18446744073709551615",
            "3 1000000000 0 3000000000 3000000000 3000000000 3000000000 1",
            "3 1000000 1 3000000 3000000 1000000000000",
            "3 1 2 3 3 1\nCSparse\ntriplet: 3-by-3, nzmax: 99999999999 nnz: 99999999999\n",
            "3 1 2 3 3 2\nCSparse\n3-by-3, nzmax: 999999999999 nnz: 999999999999, 1-norm: 0\n",
            "3 1000000000000 2 3000000000000 3000000000000 1\nCSparse\n\
             triplet: 3000000000000-by-3000000000000, nzmax: 0 nnz: 0\n",
        ] {
            assert!(
                matches!(parse_dat(text, "big"), Err(Fc3dError::Parse { .. })),
                "{text}"
            );
        }
    }

    #[test]
    fn non_3x3_blocks_and_2d_files_are_unsupported() {
        let text = "3 2 1 6 6 1 1 1 6 6 2 1 0 1 0 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 \
                    19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 0 0 0 0 0 0 1 1";
        match parse_dat(text, "six.dat") {
            Err(Fc3dError::Unsupported(m)) => assert!(m.contains("six.dat") && m.contains("3x3")),
            other => panic!("{other:?}"),
        }
        match parse_dat("2 1 0 2 2 2 2 1 0 0 1 0 0 0.5", "flat.dat") {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(m.contains("flat.dat") && m.contains("fc2d problems are not supported"))
            }
            other => panic!("{other:?}"),
        }
    }
}
