//! What every Siconos problem struct does the same way, written once: `_new`, `_free`,
//! `_display`, `_printInFile`, `_printInFilename`, `_newFromFile` and `_new_from_filename` of
//! `FrictionContactProblem`, `RollingFrictionContactProblem`, `GlobalFrictionContactProblem`
//! and `GlobalRollingFrictionContactProblem`. Each struct kind says, through [`HostProblem`],
//! how it is checked into a core view, written, displayed, read and released; the exported
//! functions of each kind are one call to the generic functions here.
//!
//! Ownership (as in Siconos): a problem struct owns its matrices (released with `NM_clear` and
//! `free`) and arrays (`free`); problems read from files are allocated the same way.

use std::ffi::c_char;
use std::io;
use std::os::raw::c_int;
use std::path::Path;
use std::ptr::null_mut;

use super::alloc::{c_box, c_free};
use super::matrix::{nm_clear_impl, read_from_stream};
use super::stream::{c_filename, write_file, write_stream};
use super::types::NumericsMatrix;
use super::{CError, CResult};
use fc3d_core::error::Fc3dError;

/// A Siconos problem struct as the C layer handles it.
pub(crate) trait HostProblem: Sized {
    /// The checked core view of a struct (borrowing the host's arrays where it can).
    type View<'a>
    where
        Self: 'a;
    /// What the `.dat` reader of the kind returns, before it becomes a C struct.
    type Read;

    /// The struct `..._new()` returns: no data, dimension 0, NULL pointers.
    fn empty() -> Self;
    /// Releases what the struct owns (not the struct itself) and leaves NULL pointers.
    ///
    /// # Safety
    /// The pointers are NULL or the struct's own allocations.
    unsafe fn release(&mut self);
    /// The core view, every size and pointer checked.
    ///
    /// # Safety
    /// The struct's pointers are NULL or point to arrays of the sizes it declares.
    unsafe fn view(&self) -> CResult<Self::View<'_>>;
    /// Writes the view in the kind's `.dat` format.
    fn write(view: &Self::View<'_>, out: &mut dyn io::Write) -> io::Result<()>;
    /// Prints a summary of the view to stdout.
    fn display(view: &Self::View<'_>);
    /// Reads the kind's `.dat` format from a stream, in chunks, up to the end of the problem;
    /// returns what was read and the number of bytes it takes.
    fn read(
        stream: &mut dyn io::Read,
        len: Option<u64>,
        label: &str,
    ) -> Result<(Self::Read, u64), Fc3dError>;
    /// A C-allocated struct of what was read.
    fn to_c(read: Self::Read) -> CResult<*mut Self>;
    /// Reads the file `path`: the `.dat` format, unless the kind also reads FCLIB files.
    fn read_file(path: &str) -> CResult<*mut Self> {
        read_dat_file(path)
    }
}

/// Reads the `.dat` file `path` of the kind `P`.
pub(crate) fn read_dat_file<P: HostProblem>(path: &str) -> CResult<*mut P> {
    let (mut file, len) = open(path)?;
    let (read, _) = P::read(&mut file, len, path)?;
    P::to_c(read)
}

/// Opens `path` for reading, with its length when it is a regular file.
fn open(path: &str) -> CResult<(std::fs::File, Option<u64>)> {
    let io_error = |e: io::Error| {
        CError::from(Fc3dError::Io {
            file: path.to_string(),
            message: format!("cannot read: {e}"),
        })
    };
    let file = std::fs::File::open(Path::new(path)).map_err(io_error)?;
    let meta = file.metadata().map_err(io_error)?;
    let len = (meta.is_file() && meta.len() > 0).then_some(meta.len());
    Ok((file, len))
}

/// `..._new()`: an empty struct (release it with `..._free`).
pub(crate) fn new<P: HostProblem>() -> CResult<*mut P> {
    c_box(P::empty())
}

/// `..._free(problem)`: releases what the struct owns and the struct; NULL is a no-op.
pub(crate) unsafe fn free<P: HostProblem>(problem: *mut P) -> CResult<()> {
    if let Some(p) = problem.as_mut() {
        p.release();
        c_free(problem);
    }
    Ok(())
}

/// `..._display(problem)`: a summary on stdout.
pub(crate) unsafe fn display<P: HostProblem>(problem: *mut P) -> CResult<()> {
    let view = checked(problem)?.view()?;
    P::display(&view);
    Ok(())
}

/// `..._printInFile(problem, file)`: the `.dat` format on an open stream; 0 on success.
pub(crate) unsafe fn print_in_file<P: HostProblem>(
    problem: *mut P,
    file: *mut libc::FILE,
) -> CResult<c_int> {
    let view = checked(problem)?.view()?;
    write_stream(file, |out| P::write(&view, out))?;
    Ok(0)
}

/// `..._printInFilename(problem, filename)`: the `.dat` format in a file (created or
/// truncated); 0 on success.
pub(crate) unsafe fn print_in_filename<P: HostProblem>(
    problem: *mut P,
    filename: *const c_char,
) -> CResult<c_int> {
    let view = checked(problem)?.view()?;
    let path = c_filename(filename)?;
    write_file(path, |out| P::write(&view, out))?;
    Ok(0)
}

/// `..._newFromFile(file)`: the `.dat` format read from an open stream, up to the end of the
/// problem (a stream that can seek is left at the next token, or put back on failure).
pub(crate) unsafe fn new_from_file<P: HostProblem>(file: *mut libc::FILE) -> CResult<*mut P> {
    read_from_stream(
        file,
        |stream, len| P::read(stream, len, "<FILE stream>"),
        P::to_c,
    )
}

/// `..._new_from_filename(filename)`: the file read ([`HostProblem::read_file`]).
pub(crate) unsafe fn new_from_filename<P: HostProblem>(filename: *const c_char) -> CResult<*mut P> {
    P::read_file(c_filename(filename)?)
}

/// The struct behind a pointer, NULL refused.
unsafe fn checked<'a, P>(problem: *mut P) -> CResult<&'a P> {
    problem.as_ref().ok_or_else(|| CError::null("problem"))
}

/// Releases a matrix a problem owns (its storage, then the struct) and clears the pointer.
pub(crate) unsafe fn release_matrix(m: &mut *mut NumericsMatrix) {
    nm_clear_impl(*m);
    c_free(*m);
    *m = null_mut();
}

/// Frees an array a problem owns and clears the pointer.
pub(crate) unsafe fn release_array<T>(a: &mut *mut T) {
    c_free(*a);
    *a = null_mut();
}
