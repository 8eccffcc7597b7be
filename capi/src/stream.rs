//! C strings and `FILE*` streams shared by the problem and matrix file functions.

use std::ffi::{c_char, CStr};

use super::{CError, CResult, FC3D_ERR_IO};

/// A file name argument as UTF-8.
pub(crate) unsafe fn c_filename<'a>(filename: *const c_char) -> CResult<&'a str> {
    if filename.is_null() {
        return Err(CError::null("filename"));
    }
    CStr::from_ptr(filename)
        .to_str()
        .map_err(|_| CError::new(FC3D_ERR_IO, "filename is not valid UTF-8"))
}

/// Everything left in a C stream, as bytes.
pub(crate) unsafe fn read_rest(file: *mut libc::FILE) -> CResult<Vec<u8>> {
    if file.is_null() {
        return Err(CError::null("file"));
    }
    let mut bytes = Vec::new();
    let mut buf = [0u8; 65536];
    loop {
        let got = libc::fread(buf.as_mut_ptr() as *mut libc::c_void, 1, buf.len(), file);
        bytes.extend_from_slice(&buf[..got]);
        if got < buf.len() {
            break;
        }
    }
    if libc::ferror(file) != 0 {
        return Err(CError::new(FC3D_ERR_IO, "read error on the stream"));
    }
    Ok(bytes)
}

/// Writes all of `text` to a C stream.
pub(crate) unsafe fn write_all(file: *mut libc::FILE, text: &[u8]) -> CResult<()> {
    if file.is_null() {
        return Err(CError::null("file"));
    }
    if libc::fwrite(text.as_ptr() as *const libc::c_void, 1, text.len(), file) != text.len() {
        return Err(CError::new(FC3D_ERR_IO, "write error on the stream"));
    }
    Ok(())
}
