//! The matrix-storage readers: the dispatch on the storage code, the dense body and the
//! sparse-block body (the sparse storage, a CSparse dump, is in `csparse`).

use super::csparse::{parse_sparse, SparseEntries};
use super::store::{BlockArray, DatStore, ReadArray, ReadMatrix};
use super::tokens::{reserve, token_count, try_push, Reader};
use super::{STORAGE_DENSE, STORAGE_SPARSE, STORAGE_SPARSE_BLOCK};
use crate::error::Fc3dError;
use crate::matrix::{CsrMatrix, Delassus};
use crate::problem::DIMENSION;

/// A matrix body as read: complete, or the entries of a sparse matrix whose compressed form
/// (one pointer per row) is built by [`MatrixBody::finish`]. A problem reader finishes it after
/// q has been read, so that the per-row storage is bounded by values the input holds.
pub(super) enum MatrixBody<S: DatStore> {
    Done(ReadMatrix<S>),
    Sparse(SparseEntries),
}

impl<S: DatStore> MatrixBody<S> {
    pub(super) fn finish(self, r: &Reader<'_>) -> Result<ReadMatrix<S>, Fc3dError> {
        match self {
            MatrixBody::Done(w) => Ok(w),
            MatrixBody::Sparse(entries) => entries.finish(r).map(ReadMatrix::Built),
        }
    }
}

/// The body of a `rows x cols` matrix of the given storage code (read at token `storage_index`,
/// which the caller has kept with `Reader::remember`).
/// `require_diagonal`: a sparse-block matrix must store every diagonal block (a problem's W).
/// `block`: the side of the sparse-block matrix's blocks, the contact dimension (3, or 2 for a
/// 2D problem, whose 2x2 blocks are stored as a general sparse W: the sparse-block storage of
/// the core holds 3x3 blocks).
pub(super) fn parse_matrix_body<S: DatStore>(
    r: &mut Reader<'_>,
    storage_index: usize,
    storage: usize,
    rows: usize,
    cols: usize,
    require_diagonal: bool,
    block: usize,
) -> Result<MatrixBody<S>, Fc3dError> {
    match storage {
        STORAGE_DENSE => parse_dense(r, rows, cols).map(MatrixBody::Done),
        STORAGE_SPARSE_BLOCK if block == DIMENSION => {
            parse_sparse_block(r, Some((rows, cols)), require_diagonal).map(MatrixBody::Done)
        }
        STORAGE_SPARSE_BLOCK => parse_sparse_block_as_csr(
            r,
            (rows, cols),
            require_diagonal,
            BlockSizes::Uniform(block),
        )
        .map(|(m, _)| MatrixBody::Done(ReadMatrix::Built(Delassus::Sparse(m)))),
        STORAGE_SPARSE => parse_sparse(r, rows, cols).map(MatrixBody::Sparse),
        _ => Err(r.error_at(
            storage_index,
            format!(
                "unknown storage type of {} (0 dense, 1 sparse-block, 2 sparse)",
                r.name
            ),
        )),
    }
}

pub(super) fn parse_dense<S: DatStore>(
    r: &mut Reader<'_>,
    rows: usize,
    cols: usize,
) -> Result<ReadMatrix<S>, Fc3dError> {
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
    let Some(len) = rows.checked_mul(cols) else {
        r.peek()?;
        return Err(r.error_at(start, format!("the dense {name} is too large")));
    };
    let values = r.reals(len, &format!("the dense {name}"))?;
    Ok(ReadMatrix::Dense { rows, cols, values })
}

/// The block sizes a sparse-block reader accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum BlockSizes {
    /// Every block `b x b` (the contact blocks of a problem's W).
    Uniform(usize),
    /// Any sizes (Siconos' general sparse-block matrices: the mass matrix of a global problem
    /// has one diagonal block per body, 27x27 in `GFC3D_TwoRods1.dat`, and H blocks of
    /// `body x contact` unknowns).
    Any,
}

/// Reads `count` cumulative block sizes: for [`BlockSizes::Uniform`]`(b)` they must be `b`,
/// `2 b`, `3 b`, ...; for [`BlockSizes::Any`] they must increase, and are appended to `kept`.
/// They must end at `n` when it is given; returns the last one (the number of rows or columns
/// the blocks cover).
fn parse_block_sizes(
    r: &mut Reader<'_>,
    count: usize,
    count_index: usize,
    n: Option<usize>,
    what: &str,
    sizes: BlockSizes,
    kept: &mut Vec<usize>,
) -> Result<usize, Fc3dError> {
    r.ensure_remaining(count, &format!("the cumulative {what} block sizes"))?;
    if sizes == BlockSizes::Any {
        // `count` tokens are left (checked above for inputs of known size).
        reserve(
            kept,
            r.capacity_for(count, 1),
            &format!("the {what} block sizes"),
        )?;
    }
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
        match sizes {
            BlockSizes::Uniform(block) if size - previous != block => {
                return Err(Fc3dError::Unsupported(format!(
                    "{}: sparse-block {} with a block {what} of size {} (block {what} {k}, token {index}); \
                     fc3d handles {block}x{block} blocks only here",
                    r.file,
                    r.name,
                    size - previous
                )));
            }
            BlockSizes::Uniform(_) => {}
            BlockSizes::Any => try_push(kept, size, &format!("the {what} block sizes"))?,
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

/// A sparse-block body of 3x3 blocks, stored in `S`. `shape`: the declared `(rows, cols)`
/// (None: the block sizes tell). `require_diagonal`: every diagonal block must be stored (the W
/// of a problem).
pub(super) fn parse_sparse_block<S: DatStore>(
    r: &mut Reader<'_>,
    shape: Option<(usize, usize)>,
    require_diagonal: bool,
) -> Result<ReadMatrix<S>, Fc3dError> {
    let mut blocks: Option<S::Blocks> = None;
    let layout = parse_sparse_block_with::<S::Indices>(
        r,
        shape,
        require_diagonal,
        BlockSizes::Uniform(DIMENSION),
        |r, values, _| {
            let blocks = match &mut blocks {
                Some(b) => b,
                None => {
                    let what = format!("the blocks of {}", r.name);
                    blocks.insert(S::Blocks::with_capacity(
                        r.capacity_for(values.count, 1 + 9),
                        &what,
                    )?)
                }
            };
            let mut block = [0.0; 9];
            block.copy_from_slice(values.block);
            blocks.push(&block, "the blocks")
        },
    )?;
    let blocks = match blocks {
        Some(b) => b,
        None => S::Blocks::with_capacity(0, "the blocks")?,
    };
    Ok(ReadMatrix::SparseBlock {
        block_rows: layout.block_rows,
        block_cols: layout.block_cols,
        row_ptr: layout.row_ptr,
        col_idx: layout.col_idx,
        blocks,
    })
}

/// The cumulative row and column block sizes of a sparse-block matrix.
pub(super) type CumulativeSizes = (Vec<usize>, Vec<usize>);

/// A sparse-block body as a general sparse matrix of the declared `shape`: the `b x b` blocks
/// of a 2D problem's W ([`BlockSizes::Uniform`]), or blocks of any sizes ([`BlockSizes::Any`]:
/// the matrices of a global problem). Exact zeros inside stored blocks are kept, so that the
/// blocks can be written back as they were read. Returns the matrix and, for
/// [`BlockSizes::Any`], the cumulative row and column block sizes (empty without blocks).
pub(super) fn parse_sparse_block_as_csr(
    r: &mut Reader<'_>,
    shape: (usize, usize),
    require_diagonal: bool,
    sizes: BlockSizes,
) -> Result<(CsrMatrix, CumulativeSizes), Fc3dError> {
    let mut triplets: Vec<(usize, usize, f64)> = Vec::new();
    let layout = parse_sparse_block_with::<Vec<usize>>(
        r,
        Some(shape),
        require_diagonal,
        sizes,
        |r, values, place| {
            if triplets.capacity() == 0 {
                let what = format!("the entries of {}", r.name);
                triplets = r.vec_for(
                    token_count(values.count, token_count(place.rows, place.cols)),
                    1,
                    &what,
                )?;
            }
            // Column-major within a block.
            for (k, &v) in values.block.iter().enumerate() {
                let (i, j) = (k % place.rows, k / place.rows);
                try_push(
                    &mut triplets,
                    (place.first_row + i, place.first_col + j, v),
                    "the entries of a sparse-block matrix",
                )?;
            }
            Ok(())
        },
    )?;
    let m = CsrMatrix::from_triplets(shape.0, shape.1, &triplets)
        .map_err(|e| r.error_at(layout.nbblocks_index, e.to_string()))?;
    Ok((m, (layout.row_sizes, layout.col_sizes)))
}

/// The values of one block as read (column-major), and the number of blocks of the matrix.
pub(super) struct BlockValues<'v> {
    block: &'v [f64],
    /// The number of blocks of the matrix.
    count: usize,
}

/// Where a block lies: its first row and column and its size.
#[derive(Debug, Clone, Copy)]
struct BlockPlace {
    first_row: usize,
    first_col: usize,
    rows: usize,
    cols: usize,
}

/// The offset and size of block `k` of cumulative sizes `cumulative` (uniform `b`: `b k`, `b`).
fn block_span(sizes: BlockSizes, cumulative: &[usize], k: usize) -> (usize, usize) {
    match sizes {
        BlockSizes::Uniform(b) => (b * k, b),
        BlockSizes::Any => {
            let start = if k == 0 { 0 } else { cumulative[k - 1] };
            (start, cumulative[k] - start)
        }
    }
}

/// The block structure of a sparse-block body.
struct BlockLayout<I> {
    nbblocks_index: usize,
    block_rows: usize,
    block_cols: usize,
    row_ptr: I,
    col_idx: I,
    /// The cumulative row and column block sizes, for [`BlockSizes::Any`] (empty otherwise).
    row_sizes: Vec<usize>,
    col_sizes: Vec<usize>,
}

/// Reads a sparse-block body of blocks of the given sizes, handing each block's values
/// (column-major) and place to `on_block` in file order; returns the structure.
fn parse_sparse_block_with<I: ReadArray<usize>>(
    r: &mut Reader<'_>,
    shape: Option<(usize, usize)>,
    require_diagonal: bool,
    sizes: BlockSizes,
    mut on_block: impl FnMut(&Reader<'_>, BlockValues<'_>, BlockPlace) -> Result<(), Fc3dError>,
) -> Result<BlockLayout<I>, Fc3dError> {
    let name = r.name;
    let (nbblocks_index, nbblocks) = r.usize(&format!("the number of blocks of {name}"))?;
    r.remember(nbblocks_index);
    if nbblocks == 0 {
        let BlockSizes::Uniform(block) = sizes else {
            // Blocks of any sizes: without blocks there are no block rows nor columns.
            let mut row_ptr = I::with_capacity(1, "the block-row pointers")?;
            row_ptr.push(0, "the block-row pointers")?;
            return Ok(BlockLayout {
                nbblocks_index,
                block_rows: 0,
                block_cols: 0,
                row_ptr,
                col_idx: I::with_capacity(0, "the block columns")?,
                row_sizes: Vec::new(),
                col_sizes: Vec::new(),
            });
        };
        // Siconos writes a lone 0 for a matrix without blocks and stops there.
        let (rows, cols) = shape.unwrap_or((0, 0));
        if require_diagonal && rows > 0 {
            return Err(r.error_at(
                nbblocks_index,
                format!(
                    "a sparse-block {name} without blocks lacks the diagonal blocks of {} contacts",
                    rows / block
                ),
            ));
        }
        if rows % block != 0 || cols % block != 0 {
            return Err(Fc3dError::Unsupported(format!(
                "{}: a sparse-block {name} of size {rows}x{cols} cannot be made of \
                 {block}x{block} blocks (fc3d handles {block}x{block} blocks only here)",
                r.file
            )));
        }
        // The size is declared, not given by values: the row pointers are allocated fallibly.
        let what = "the block-row pointers";
        let mut row_ptr = I::with_capacity(rows / block + 1, what)?;
        for _ in 0..=rows / block {
            row_ptr.push(0, what)?;
        }
        return Ok(BlockLayout {
            nbblocks_index,
            block_rows: rows / block,
            block_cols: cols / block,
            row_ptr,
            col_idx: I::with_capacity(0, "the block columns")?,
            row_sizes: Vec::new(),
            col_sizes: Vec::new(),
        });
    }
    let (rows_index, block_rows) = r.usize("the number of block rows")?;
    r.remember(rows_index);
    let (cols_index, block_cols) = r.usize("the number of block columns")?;
    r.remember(cols_index);
    let (mut row_sizes, mut col_sizes) = (Vec::new(), Vec::new());
    let rows = shape.map(|s| s.0);
    parse_block_sizes(
        r,
        block_rows,
        rows_index,
        rows,
        "row",
        sizes,
        &mut row_sizes,
    )?;
    let cols = shape.map(|s| s.1);
    parse_block_sizes(
        r,
        block_cols,
        cols_index,
        cols,
        "column",
        sizes,
        &mut col_sizes,
    )?;
    // From here on the matrix is block_rows x block_cols blocks (and block_rows tokens
    // have been read, so allocating per block row is bounded by the text).

    let (filled1_index, filled1) = r.usize("filled1 (the length of index1_data)")?;
    r.remember(filled1_index);
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
    // block_rows + 1 >= filled1 entries; block_rows cumulative sizes have been read.
    let mut row_ptr = I::with_capacity(block_rows + 1, "the block-row pointers")?;
    // The texts of index1_data not written as their value prints (a sign, leading zeros), for a
    // message about a missing diagonal block.
    let mut unusual_texts = Vec::new();
    for k in 0..filled1 {
        let (index, p) = r.usize("a block-row pointer (index1_data)")?;
        let previous = row_ptr.last().copied().unwrap_or(0);
        if (k == 0 && p != 0) || p < previous || p > filled2 {
            return Err(r.error_at(
                index,
                format!("index1_data must start at 0 and not decrease up to the {filled2} blocks"),
            ));
        }
        if r.text() != p.to_string() {
            unusual_texts.push((k, r.text().to_string()));
        }
        row_ptr.push(p, "the block-row pointers")?;
    }
    if row_ptr.last() != Some(&filled2) {
        return Err(r.error_at(
            index1_start + filled1 - 1,
            format!("index1_data must end at the number of blocks {filled2}"),
        ));
    }
    // Siconos may stop index1_data after the last non-empty block row; the rows after it are empty.
    for _ in filled1..block_rows + 1 {
        row_ptr.push(filled2, "the block-row pointers")?;
    }

    let mut col_idx = I::with_capacity(
        r.capacity_for(filled2, 1),
        "the block columns (index2_data)",
    )?;
    for _ in 0..filled2 {
        let (index, c) = r.usize("a block column (index2_data)")?;
        if c >= block_cols {
            return Err(r.error_at(
                index,
                format!("block column {c} is out of range ({name} has {block_cols} block columns)"),
            ));
        }
        col_idx.push(c, "the block columns (index2_data)")?;
    }
    if require_diagonal {
        // The diagonal block of every contact is needed by the solvers: name the row that lacks it.
        for c in 0..block_rows {
            if !col_idx[row_ptr[c]..row_ptr[c + 1]].contains(&c) {
                let message = match sizes {
                    BlockSizes::Uniform(b) => {
                        format!("the diagonal {b}x{b} block of contact {c} is missing from {name}")
                    }
                    BlockSizes::Any => format!("the diagonal block {c} is missing from {name}"),
                };
                if c >= filled1 {
                    return Err(r.error_at(filled1_index, message));
                }
                let text = unusual_texts
                    .iter()
                    .find(|(k, _)| *k == c)
                    .map_or_else(|| row_ptr[c].to_string(), |(_, t)| t.clone());
                return Err(r.error_with_token(index1_start + c, &text, message));
            }
        }
    }

    // Tokens of a block: its number and its values.
    let mut tokens = 0usize;
    for row in 0..block_rows {
        let rows = block_span(sizes, &row_sizes, row).1;
        for &col in &col_idx[row_ptr[row]..row_ptr[row + 1]] {
            let cols = block_span(sizes, &col_sizes, col).1;
            tokens = tokens.saturating_add(token_count(rows, cols).saturating_add(1));
        }
    }
    r.ensure_remaining(tokens, &format!("the blocks of {name}"))?;
    let mut values: Vec<f64> = Vec::new();
    for row in 0..block_rows {
        let (first_row, rows) = block_span(sizes, &row_sizes, row);
        for k in row_ptr[row]..row_ptr[row + 1] {
            let (first_col, cols) = block_span(sizes, &col_sizes, col_idx[k]);
            let (index, number) = r.usize("a block number")?;
            // Siconos only warns about a wrong number (it stores blocks in file order anyway); a
            // wrong number means the file is corrupt, so it is an error here.
            if number != k {
                return Err(r.error_at(
                    index,
                    format!("block number {number} where block {k} is expected"),
                ));
            }
            // Grown as values arrive: a block's declared size is not bounded by the input of a
            // stream of unknown length.
            values.clear();
            for _ in 0..token_count(rows, cols) {
                try_push(&mut values, r.real("a block value")?.1, "a block's values")?;
            }
            let place = BlockPlace {
                first_row,
                first_col,
                rows,
                cols,
            };
            on_block(
                r,
                BlockValues {
                    block: &values,
                    count: filled2,
                },
                place,
            )?;
        }
    }
    Ok(BlockLayout {
        nbblocks_index,
        block_rows,
        block_cols,
        row_ptr,
        col_idx,
        row_sizes,
        col_sizes,
    })
}
