//! Matrix files and streams: `NM_new_from_file`/`NM_new_from_filename`, `NM_write_in_file`/
//! `NM_write_in_filename` and `SBM_new_from_file`.

use std::ffi::c_char;
use std::os::raw::c_int;
use std::ptr::null_mut;

use super::sbm::sbm_from_parts;
use super::{delassus_from_c, matrix_from_read, storage_err, NM_SPARSE_BLOCK};
use crate::alloc::CStore;
use crate::stream::{c_filename, write_file, write_stream, CStream};
use crate::types::*;
use crate::{ffi_guard, CError, CResult};
use fc3d_core::io::dat::{
    read_matrix_file_into, read_matrix_into, read_sbm_into, write_matrix, ReadMatrix,
};
use fc3d_core::matrix::Delassus;

// ---------------------------------------------------------------------------------------------
// Matrix files: the matrix part of the .dat format (see `fc3d_core::io::dat`).

/// The label of a stream in error messages.
const STREAM_LABEL: &str = "<FILE stream>";

/// Reads a value from `file` with `read` (which pulls the stream in chunks and returns the value
/// and the number of bytes it used), then makes the host's structure of it with `to_c`. The
/// stream is read only up to the end of the value (never to the end of a stream that goes on),
/// then left just after it on success and put back where it was on failure (see `CStream`).
pub(crate) unsafe fn read_from_stream<T, U>(
    file: *mut libc::FILE,
    read: impl FnOnce(&mut CStream, Option<u64>) -> Result<(T, u64), fc3d_core::error::Fc3dError>,
    to_c: impl FnOnce(T) -> CResult<U>,
) -> CResult<U> {
    let mut stream = CStream::new(file)?;
    let len = stream.len_hint();
    let result = read(&mut stream, len)
        .map_err(CError::from)
        .and_then(|(value, used)| to_c(value).map(|c| (c, used)));
    match result {
        Ok((c, used)) => {
            stream.finish(Some(used));
            Ok(c)
        }
        Err(e) => {
            stream.finish(None);
            Err(e)
        }
    }
}

/// A matrix read from an open stream, as written by `NM_write_in_file` (`storageType size0
/// size1` and the body; the matrix part of a Siconos .dat file). Release with `NM_free`.
///
/// Only the matrix is read, in chunks (never the rest of a stream that goes on): on success a
/// stream that can seek (a regular file) is left at the first token after the matrix (as
/// Siconos' reader leaves it, but for the whitespace after a CSC dump, which Siconos leaves
/// unread), so a host may read what follows, and one that cannot (a pipe) just after the
/// whitespace that follows the matrix; on failure a stream that can seek is put back where it
/// was.
///
/// NULL on failure: `FC3D_ERR_PARSE` for malformed or truncated text (`fc3d_last_error_message`
/// names the token), a declared size the stream cannot hold, or a stream that stops making
/// tokens (`/dev/zero`); `FC3D_ERR_INVALID_STORAGE` for what fc3d does not represent (a
/// sparse-block matrix whose blocks are not all 3x3, a half-triplet sparse matrix);
/// `FC3D_ERR_OUT_OF_MEMORY` when the values given cannot be allocated; `FC3D_ERR_NULL_POINTER`,
/// `FC3D_ERR_IO`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_new_from_file(file: *mut libc::FILE) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_new_from_file",
        |_| null_mut(),
        || {
            read_from_stream(
                file,
                |stream, len| read_matrix_into::<CStore, _>(stream, len, STREAM_LABEL),
                matrix_from_read,
            )
        },
    )
}

/// A matrix read from the file `filename` (see `NM_new_from_file`). Release with `NM_free`.
/// NULL on failure (`FC3D_ERR_IO` when the file cannot be read).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_new_from_filename(filename: *const c_char) -> *mut NumericsMatrix {
    ffi_guard(
        "NM_new_from_filename",
        |_| null_mut(),
        || {
            let path = c_filename(filename)?;
            matrix_from_read(read_matrix_file_into::<CStore>(std::path::Path::new(path))?)
        },
    )
}

/// What `NM_write_in_file` writes: the core view of a matrix, checked whole before anything is
/// written, or the header of a sparse-block matrix without blocks.
enum ToWrite<'a> {
    Matrix(Delassus<'a>),
    /// `NM_create(NM_SPARSE_BLOCK, ..)` not filled yet: the zero matrix of its size, written as
    /// Siconos does (a lone 0 after the header) without building anything of that size.
    NoBlocks {
        rows: c_int,
        cols: c_int,
    },
}

fn matrix_to_write<'a>(M: *const NumericsMatrix) -> CResult<ToWrite<'a>> {
    if M.is_null() {
        return Err(CError::null("M"));
    }
    // SAFETY: checked non-NULL; the caller passes a valid matrix.
    let m = unsafe { &*M };
    let no_blocks = m.storageType == NM_SPARSE_BLOCK
        && !m.matrix1.is_null()
        && unsafe { (*m.matrix1).nbblocks } == 0
        && m.size0 >= 0
        && m.size1 >= 0
        && m.size0 % 3 == 0
        && m.size1 % 3 == 0;
    if no_blocks {
        Ok(ToWrite::NoBlocks {
            rows: m.size0,
            cols: m.size1,
        })
    } else {
        Ok(ToWrite::Matrix(unsafe { delassus_from_c(m)? }))
    }
}

/// Writes `w` with `out`, as the text is produced.
fn write_matrix_to(w: &ToWrite<'_>, mut out: &mut dyn std::io::Write) -> std::io::Result<()> {
    match w {
        ToWrite::Matrix(w) => write_matrix(w, &mut out),
        // What `write_matrix` writes for a sparse-block matrix without blocks.
        ToWrite::NoBlocks { rows, cols } => writeln!(out, "{NM_SPARSE_BLOCK}\n{rows}\n{cols}\n0"),
    }
}

/// Writes `M` to an open stream as Siconos does (`storageType size0 size1` and the body), values
/// in their shortest exactly round-tripping form (Siconos' own writer prints sparse values with
/// `%g`). Sparse matrices are written as a CSparse triplet dump (origin `NSM_TRIPLET`), whatever
/// their origin. Both Siconos' `NM_new_from_file` and fc3d's read it back.
///
/// Nothing is written when `M` cannot be represented by fc3d (a sparse-block matrix whose blocks
/// are not all 3x3, non-finite values, an inconsistent structure): see `fc3d_last_error_code`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_write_in_file(M: *const NumericsMatrix, file: *mut libc::FILE) {
    ffi_guard(
        "NM_write_in_file",
        |_| (),
        || {
            let w = matrix_to_write(M)?;
            write_stream(file, |out| write_matrix_to(&w, out))
        },
    )
}

/// Writes `M` to the file `filename`, created or truncated (see `NM_write_in_file`). The file is
/// not touched when `M` cannot be written.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn NM_write_in_filename(M: *const NumericsMatrix, filename: *const c_char) {
    ffi_guard(
        "NM_write_in_filename",
        |_| (),
        || {
            let w = matrix_to_write(M)?;
            let path = c_filename(filename)?;
            write_file(path, |out| write_matrix_to(&w, out))
        },
    )
}

/// A sparse-block matrix read from an open stream, as written by Siconos' `SBM_write_in_file`:
/// the sparse-block body without the `storageType size0 size1` header (`nbblocks`, then the block
/// structure and the blocks). The size comes from the cumulative block sizes. Blocks must all be
/// 3x3 (`FC3D_ERR_INVALID_STORAGE` otherwise); a lone `0` gives an empty 0x0 matrix (Siconos
/// returns NULL there). The stream is consumed as by `NM_new_from_file`.
/// Release with `SBM_clear` + `free` (or through `NM_free` once wrapped by `NM_new_SBM`).
/// NULL on failure (`FC3D_ERR_PARSE` for malformed text).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn SBM_new_from_file(
    file: *mut libc::FILE,
) -> *mut SparseBlockStructuredMatrix {
    ffi_guard(
        "SBM_new_from_file",
        |_| null_mut(),
        || {
            read_from_stream(
                file,
                |stream, len| read_sbm_into::<CStore, _>(stream, len, STREAM_LABEL),
                |m| match m {
                    ReadMatrix::SparseBlock {
                        block_rows,
                        block_cols,
                        row_ptr,
                        col_idx,
                        blocks,
                    } => sbm_from_parts(block_rows, block_cols, row_ptr, col_idx, blocks),
                    _ => Err(storage_err("the sparse-block reader made another storage")),
                },
            )
        },
    )
}
