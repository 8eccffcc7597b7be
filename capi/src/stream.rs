//! C strings and `FILE*` streams shared by the problem and matrix file functions.
//!
//! Readers pull a stream through [`CStream`] (`std::io::Read`) in chunks the core's `.dat`
//! readers hold on the heap, and only up to the end of what they parse: a stream that goes on
//! (a huge file, `/dev/zero`, a pipe) is never read to its end. Writers push text through
//! [`CStreamWriter`] (`std::io::Write`) as it is produced, never building it whole in memory.

use std::ffi::{c_char, CStr};
use std::io;

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

/// A C stream being read. On a stream that can seek (`ftell` works: files, `fmemopen`), bytes
/// are read in chunks with `fread` and [`CStream::finish`] repositions the stream just after
/// what the reader used (or back where it was on failure). On one that cannot (a pipe), bytes
/// are read one at a time with `fgetc`, so that the reader takes at most one byte past what it
/// used (the first byte of the next token), which `finish` pushes back with `ungetc`.
pub(crate) struct CStream {
    file: *mut libc::FILE,
    /// `ftell` when reading started, -1 when the stream cannot seek.
    start: libc::c_long,
    /// Bytes taken from the stream.
    taken: u64,
    /// The last byte taken by `fgetc` (EOF when none).
    last: libc::c_int,
}

impl CStream {
    /// # Safety
    /// `file` is NULL (an error) or an open C stream.
    pub(crate) unsafe fn new(file: *mut libc::FILE) -> CResult<Self> {
        if file.is_null() {
            return Err(CError::null("file"));
        }
        Ok(CStream {
            file,
            start: libc::ftell(file),
            taken: 0,
            last: libc::EOF,
        })
    }

    /// The bytes left in the stream when it is a regular file with a length (so that a
    /// declared size it cannot hold fails without reading it to its end); None otherwise.
    pub(crate) fn len_hint(&self) -> Option<u64> {
        if self.start < 0 {
            return None;
        }
        // SAFETY: `file` is an open stream; fileno is -1 for streams without a descriptor
        // (fmemopen), and fstat only writes into `st`.
        unsafe {
            let fd = libc::fileno(self.file);
            if fd < 0 {
                return None;
            }
            let mut st: libc::stat = std::mem::zeroed();
            if libc::fstat(fd, &mut st) != 0 || (st.st_mode & libc::S_IFMT) != libc::S_IFREG {
                return None;
            }
            let size = u64::try_from(st.st_size).ok().filter(|&s| s > 0)?;
            Some(size.saturating_sub(self.start as u64))
        }
    }

    /// Repositions the stream after a read: just after the `used` bytes (Some: success), or
    /// where it was (None: failure). On a stream that cannot seek, pushes back the byte taken
    /// past `used`, if any; a failed read leaves the stream where reading stopped.
    pub(crate) fn finish(self, used: Option<u64>) {
        // SAFETY: `file` is an open stream (checked in `new`).
        unsafe {
            if self.start >= 0 {
                let target = libc::c_long::try_from(used.unwrap_or(0))
                    .ok()
                    .and_then(|u| self.start.checked_add(u));
                if let Some(target) = target {
                    libc::fseek(self.file, target, libc::SEEK_SET);
                }
            } else if let Some(used) = used {
                if self.taken == used.saturating_add(1) && self.last != libc::EOF {
                    libc::ungetc(self.last, self.file);
                }
            }
        }
    }
}

impl io::Read for CStream {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        // SAFETY: `file` is an open stream; fread writes at most buf.len() bytes into buf.
        let got = unsafe {
            if self.start >= 0 {
                libc::fread(buf.as_mut_ptr().cast(), 1, buf.len(), self.file)
            } else {
                let c = libc::fgetc(self.file);
                if c == libc::EOF {
                    0
                } else {
                    self.last = c;
                    buf[0] = c as u8;
                    1
                }
            }
        };
        // SAFETY: as above.
        if got == 0 && unsafe { libc::ferror(self.file) } != 0 {
            return Err(io::Error::other("read error on the stream"));
        }
        self.taken += got as u64;
        Ok(got)
    }
}

/// A C stream written through `std::io::Write` (`fwrite`); wrap it in a `BufWriter`.
pub(crate) struct CStreamWriter(*mut libc::FILE);

impl CStreamWriter {
    /// # Safety
    /// `file` is NULL (an error) or a C stream open for writing.
    pub(crate) unsafe fn new(file: *mut libc::FILE) -> CResult<Self> {
        if file.is_null() {
            return Err(CError::null("file"));
        }
        Ok(CStreamWriter(file))
    }
}

impl io::Write for CStreamWriter {
    fn write(&mut self, text: &[u8]) -> io::Result<usize> {
        // SAFETY: the stream is open (checked in `new`); fwrite reads text.len() bytes.
        let put = unsafe { libc::fwrite(text.as_ptr().cast(), 1, text.len(), self.0) };
        if put == 0 && !text.is_empty() {
            return Err(io::Error::other("write error on the stream"));
        }
        Ok(put)
    }

    fn flush(&mut self) -> io::Result<()> {
        // Like Siconos' writers, leave the C stream's own buffer to the host (fclose, fflush).
        Ok(())
    }
}

/// Writes text produced by `write` to a C stream as it comes (a heap buffer of a few KiB).
pub(crate) unsafe fn write_stream(
    file: *mut libc::FILE,
    write: impl FnOnce(&mut dyn io::Write) -> io::Result<()>,
) -> CResult<()> {
    let mut out = io::BufWriter::new(CStreamWriter::new(file)?);
    write(&mut out)
        .and_then(|()| io::Write::flush(&mut out))
        .map_err(|e| CError::new(FC3D_ERR_IO, format!("write error on the stream: {e}")))
}

/// Creates (or truncates) `path` and writes text produced by `write` to it as it comes.
pub(crate) fn write_file(
    path: &str,
    write: impl FnOnce(&mut dyn io::Write) -> io::Result<()>,
) -> CResult<()> {
    let io_error = |e: io::Error| CError::new(FC3D_ERR_IO, format!("{path}: cannot write: {e}"));
    let file = std::fs::File::create(path).map_err(io_error)?;
    let mut out = io::BufWriter::new(file);
    write(&mut out)
        .and_then(|()| io::Write::flush(&mut out))
        .map_err(io_error)
}
