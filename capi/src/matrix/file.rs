//! Matrix files and streams: `NM_new_from_file`/`NM_new_from_filename`, `NM_write_in_file`/
//! `NM_write_in_filename` and `SBM_new_from_file`.

use std::ffi::c_char;
use std::ptr::null_mut;

use super::sbm::sbm_to_c;
use super::{delassus_from_c, matrix_to_c, NM_SPARSE_BLOCK};
use crate::stream::{c_filename, read_rest, write_all};
use crate::types::*;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_IO};
use fc3d_core::io::dat::{parse_matrix, parse_matrix_prefix, parse_sbm_prefix, write_matrix};
use fc3d_core::matrix::{BlockSparseMatrix, Delassus};

// ---------------------------------------------------------------------------------------------
// Matrix files: the matrix part of the .dat format (see `fc3d_core::io::dat`).

/// The label of a stream in error messages.
const STREAM_LABEL: &str = "<FILE stream>";

/// Reads a matrix from `file` with `parse`, which returns the value and the number of bytes it
/// used, then convert it with `to_c`. The whole rest of the stream is read, then, when the stream
/// is seekable (`ftell` works), it is repositioned just after what was used on success (the next
/// token), and back where it was on failure. On a non-seekable stream (a pipe) the rest of the
/// stream is consumed either way.
unsafe fn read_from_stream<T, U>(
    file: *mut libc::FILE,
    parse: impl FnOnce(&str) -> Result<(T, usize), fc3d_core::error::Fc3dError>,
    to_c: impl FnOnce(&T) -> CResult<U>,
) -> CResult<U> {
    if file.is_null() {
        return Err(CError::null("file"));
    }
    let start = libc::ftell(file);
    let result = match read_rest(file) {
        Err(e) => Err(e),
        Ok(bytes) => {
            // Matrix text is ASCII: a byte that is not UTF-8 can only end it (data after the matrix),
            // so only the valid prefix is parsed; byte offsets stay those of the stream.
            let (text, bad_byte) = match std::str::from_utf8(&bytes) {
                Ok(t) => (t, None),
                Err(e) => (
                    std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or(""),
                    Some(e.valid_up_to()),
                ),
            };
            match parse(text) {
                Ok((value, used)) => to_c(&value).map(|c| (c, used)),
                Err(e) => {
                    let mut err = CError::from(e);
                    if let Some(at) = bad_byte {
                        err.message += &format!(" (the stream holds a byte that is not text at offset {at} from where reading started)");
                    }
                    Err(err)
                }
            }
        }
    };
    if start >= 0 {
        let target = match &result {
            Ok((_, used)) => start + *used as libc::c_long,
            Err(_) => start,
        };
        libc::fseek(file, target, libc::SEEK_SET);
    }
    result.map(|(c, _)| c)
}

/// A matrix read from an open stream, as written by `NM_write_in_file` (`storageType size0
/// size1` and the body; the matrix part of a Siconos .dat file). Release with `NM_free`.
///
/// On a seekable stream (a regular file) only the matrix is consumed: on success the stream is
/// left at the first token after the matrix (as Siconos' reader leaves it, but for the whitespace
/// after a CSC dump, which Siconos leaves unread), so a host may read what follows; on failure it
/// is put back where it was. On a stream that cannot seek (a pipe) the rest of the stream is read.
///
/// NULL on failure: `FC3D_ERR_PARSE` for malformed text (`fc3d_last_error_message` names the
/// token), `FC3D_ERR_INVALID_STORAGE` for what fc3d does not represent (a sparse-block matrix
/// whose blocks are not all 3x3, a half-triplet sparse matrix), `FC3D_ERR_NULL_POINTER`,
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
                |text| parse_matrix_prefix(text, STREAM_LABEL),
                |w| matrix_to_c(w),
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
            let bytes = std::fs::read(path)
                .map_err(|e| CError::new(FC3D_ERR_IO, format!("{path}: cannot read: {e}")))?;
            let w = parse_matrix(&String::from_utf8_lossy(&bytes), path)?;
            matrix_to_c(&w)
        },
    )
}

fn matrix_text(M: *const NumericsMatrix) -> CResult<Vec<u8>> {
    if M.is_null() {
        return Err(CError::null("M"));
    }
    // SAFETY: checked non-NULL; the caller passes a valid matrix.
    let m = unsafe { &*M };
    // A sparse-block matrix without blocks (`NM_create(NM_SPARSE_BLOCK, ..)` not filled yet) is
    // the zero matrix of its size, written as Siconos does (a lone 0 after the header).
    let no_blocks = m.storageType == NM_SPARSE_BLOCK
        && !m.matrix1.is_null()
        && unsafe { (*m.matrix1).nbblocks } == 0
        && m.size0 >= 0
        && m.size1 >= 0
        && m.size0 % 3 == 0
        && m.size1 % 3 == 0;
    let w = if no_blocks {
        let (nbr, nbc) = (m.size0 as usize / 3, m.size1 as usize / 3);
        Delassus::SparseBlock(BlockSparseMatrix::new(
            nbr,
            nbc,
            vec![0; nbr + 1],
            Vec::new(),
            Vec::new(),
        )?)
    } else {
        unsafe { delassus_from_c(m)? }
    };
    let mut out = Vec::new();
    write_matrix(&w, &mut out).map_err(|e| CError::new(FC3D_ERR_IO, e.to_string()))?;
    Ok(out)
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
            let text = matrix_text(M)?;
            if file.is_null() {
                return Err(CError::null("file"));
            }
            write_all(file, &text)
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
            let text = matrix_text(M)?;
            let path = c_filename(filename)?;
            std::fs::write(path, text)
                .map_err(|e| CError::new(FC3D_ERR_IO, format!("{path}: cannot write: {e}")))
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
        || read_from_stream(file, |text| parse_sbm_prefix(text, STREAM_LABEL), sbm_to_c),
    )
}
