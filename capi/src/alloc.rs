//! C-allocator helpers: everything a host may release with `free()` is allocated here.

use std::os::raw::c_void;

use super::{CError, CResult, FC3D_ERR_OUT_OF_MEMORY};

/// `calloc(n, size_of::<T>())`, zero-filled; an error (not a crash) if it fails.
/// `n == 0` still returns a valid, freeable pointer.
pub(crate) fn c_calloc<T>(n: usize) -> CResult<*mut T> {
    let size = std::mem::size_of::<T>().max(1);
    // SAFETY: calloc checks n * size for overflow itself.
    let p = unsafe { libc::calloc(n.max(1), size) } as *mut T;
    if p.is_null() {
        Err(CError::new(
            FC3D_ERR_OUT_OF_MEMORY,
            format!("cannot allocate {n} elements of {size} bytes"),
        ))
    } else {
        Ok(p)
    }
}

/// A C-allocated copy of `values`.
pub(crate) fn c_copy<T: Copy>(values: &[T]) -> CResult<*mut T> {
    let p = c_calloc::<T>(values.len())?;
    // SAFETY: p has room for values.len() elements and does not overlap `values`.
    unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), p, values.len()) };
    Ok(p)
}

/// A C-allocated struct holding `value`.
pub(crate) fn c_box<T>(value: T) -> CResult<*mut T> {
    let p = c_calloc::<T>(1)?;
    // SAFETY: p is valid for one T.
    unsafe { p.write(value) };
    Ok(p)
}

/// `free(p)` for any C-allocated pointer (NULL is fine).
pub(crate) unsafe fn c_free<T>(p: *mut T) {
    libc::free(p as *mut c_void);
}
