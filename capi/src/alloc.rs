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

fn out_of_memory<T>(count: usize, what: &str) -> fc3d_core::error::Fc3dError {
    fc3d_core::error::Fc3dError::OutOfMemory {
        what: what.to_string(),
        bytes: count.saturating_mul(std::mem::size_of::<T>()),
    }
}

/// A growable array allocated with `malloc`/`realloc`, owned until handed over with
/// [`CArray::into_raw`] (to a struct the host releases with `free()`), freed on drop: what the
/// readers fill as they read (q, mu, a dense matrix's values, a sparse-block matrix's index
/// arrays), so that a read holds each array once, where the host will own it.
pub(crate) struct CArray<T: Copy> {
    ptr: *mut T,
    len: usize,
    cap: usize,
}

impl<T: Copy> CArray<T> {
    /// An empty array with room for `capacity` values; an out-of-memory error when it cannot be
    /// allocated.
    pub(crate) fn with_capacity(
        capacity: usize,
        what: &str,
    ) -> Result<Self, fc3d_core::error::Fc3dError> {
        let ptr = Self::realloc(std::ptr::null_mut(), capacity)
            .ok_or_else(|| out_of_memory::<T>(capacity, what))?;
        Ok(CArray {
            ptr,
            len: 0,
            cap: capacity,
        })
    }

    /// A C-allocated copy of `values`.
    pub(crate) fn copy(values: &[T], what: &str) -> Result<Self, fc3d_core::error::Fc3dError> {
        let mut a = Self::with_capacity(values.len(), what)?;
        // SAFETY: a has room for values.len() elements and does not overlap `values`.
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), a.ptr, values.len()) };
        a.len = values.len();
        Ok(a)
    }

    /// `realloc(ptr, count * size_of::<T>())` (at least one byte, so that the result is a
    /// pointer `free()` takes); None when it fails or the size overflows (`ptr` is then kept).
    fn realloc(ptr: *mut T, count: usize) -> Option<*mut T> {
        let bytes = count.checked_mul(std::mem::size_of::<T>())?.max(1);
        // SAFETY: ptr is NULL or a live allocation of this array.
        let p = unsafe { libc::realloc(ptr as *mut c_void, bytes) } as *mut T;
        (!p.is_null()).then_some(p)
    }

    /// Appends `value`, doubling the capacity when the array is full.
    pub(crate) fn push(&mut self, value: T, what: &str) -> Result<(), fc3d_core::error::Fc3dError> {
        if self.len == self.cap {
            let cap = self.cap.saturating_mul(2).max(16);
            self.ptr = Self::realloc(self.ptr, cap).ok_or_else(|| out_of_memory::<T>(cap, what))?;
            self.cap = cap;
        }
        // SAFETY: len < cap after the growth above.
        unsafe { self.ptr.add(self.len).write(value) };
        self.len += 1;
        Ok(())
    }

    /// Hands the allocation over; unused capacity (a stream whose length was unknown) is given
    /// back first when the C library can.
    pub(crate) fn into_raw(self) -> *mut T {
        let mut ptr = self.ptr;
        if self.len < self.cap {
            ptr = Self::realloc(ptr, self.len).unwrap_or(ptr);
        }
        std::mem::forget(self);
        ptr
    }
}

impl<T: Copy> std::ops::Deref for CArray<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        // SAFETY: ptr holds len initialised values.
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

impl<T: Copy> Drop for CArray<T> {
    fn drop(&mut self) {
        // SAFETY: ptr came from realloc and was not handed over.
        unsafe { c_free(self.ptr) };
    }
}

/// The blocks of a sparse-block matrix as Siconos holds them: one `malloc`ed array of 9 values
/// per block (the host's `SBM_clear` frees each), and the array of their pointers; all freed on
/// drop until handed over with [`CBlocks::into_raw`].
pub(crate) struct CBlocks {
    pointers: CArray<*mut f64>,
}

impl CBlocks {
    pub(crate) fn with_capacity(
        capacity: usize,
        what: &str,
    ) -> Result<Self, fc3d_core::error::Fc3dError> {
        Ok(CBlocks {
            pointers: CArray::with_capacity(capacity, what)?,
        })
    }

    pub(crate) fn push(
        &mut self,
        block: &[f64; 9],
        what: &str,
    ) -> Result<(), fc3d_core::error::Fc3dError> {
        // SAFETY: a fresh allocation of 9 doubles, filled at once.
        let p = unsafe { libc::malloc(std::mem::size_of::<[f64; 9]>()) } as *mut f64;
        if p.is_null() {
            return Err(out_of_memory::<[f64; 9]>(1, what));
        }
        unsafe { std::ptr::copy_nonoverlapping(block.as_ptr(), p, 9) };
        self.pointers
            .push(p, what)
            .inspect_err(|_| unsafe { c_free(p) })
    }

    pub(crate) fn len(&self) -> usize {
        self.pointers.len()
    }

    /// Hands the pointer array (and the blocks it points to) over.
    pub(crate) fn into_raw(self) -> *mut *mut f64 {
        let this = std::mem::ManuallyDrop::new(self);
        // SAFETY: `this` is not dropped: the array is moved out once.
        unsafe { std::ptr::read(&this.pointers) }.into_raw()
    }
}

impl Drop for CBlocks {
    fn drop(&mut self) {
        for &p in self.pointers.iter() {
            // SAFETY: each pointer is a block malloc'd by push, not handed over.
            unsafe { c_free(p) };
        }
    }
}

/// The readers' storage for C: the arrays and blocks a host's structures own.
pub(crate) struct CStore;

impl fc3d_core::io::dat::DatStore for CStore {
    type Reals = CArray<f64>;
    type Indices = CArray<usize>;
    type Blocks = CBlocks;
}

impl<T: Copy> fc3d_core::io::dat::ReadArray<T> for CArray<T> {
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, fc3d_core::error::Fc3dError> {
        CArray::with_capacity(capacity, what)
    }

    fn push(&mut self, value: T, what: &str) -> Result<(), fc3d_core::error::Fc3dError> {
        CArray::push(self, value, what)
    }
}

impl fc3d_core::io::dat::BlockArray for CBlocks {
    fn with_capacity(capacity: usize, what: &str) -> Result<Self, fc3d_core::error::Fc3dError> {
        CBlocks::with_capacity(capacity, what)
    }

    fn push(&mut self, block: &[f64; 9], what: &str) -> Result<(), fc3d_core::error::Fc3dError> {
        CBlocks::push(self, block, what)
    }
}
