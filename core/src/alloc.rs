//! Fallible allocation for memory whose size comes from the input (a file, a stream, a host's
//! matrix): the readers and writers and the conversions between storages of W. A failure is an
//! [`Fc3dError::OutOfMemory`] naming what was being built, never an abort (see also
//! `crate::error::try_vec` and `try_copy`).

use crate::error::Fc3dError;

fn out_of_memory<T>(what: &str, items: usize) -> Fc3dError {
    Fc3dError::OutOfMemory {
        what: what.to_string(),
        bytes: items.saturating_mul(std::mem::size_of::<T>()),
    }
}

/// Reserves room for exactly `additional` more items, fallibly.
pub(crate) fn reserve<T>(v: &mut Vec<T>, additional: usize, what: &str) -> Result<(), Fc3dError> {
    v.try_reserve_exact(additional)
        .map_err(|_| out_of_memory::<T>(what, v.len().saturating_add(additional)))
}

/// Pushes `value`, growing `v` fallibly (amortized doubling).
pub(crate) fn try_push<T>(v: &mut Vec<T>, value: T, what: &str) -> Result<(), Fc3dError> {
    if v.len() == v.capacity() {
        v.try_reserve(1)
            .map_err(|_| out_of_memory::<T>(what, v.len().saturating_mul(2)))?;
    }
    v.push(value);
    Ok(())
}

/// Appends `values`, growing `v` fallibly (amortized doubling).
pub(crate) fn try_extend<T: Clone>(
    v: &mut Vec<T>,
    values: &[T],
    what: &str,
) -> Result<(), Fc3dError> {
    v.try_reserve(values.len())
        .map_err(|_| out_of_memory::<T>(what, v.len().saturating_add(values.len())))?;
    v.extend_from_slice(values);
    Ok(())
}

/// The items of `items` (whose length is known) in a vector allocated fallibly.
pub(crate) fn try_collect<T>(
    items: impl ExactSizeIterator<Item = T>,
    what: &str,
) -> Result<Vec<T>, Fc3dError> {
    let mut v = Vec::new();
    reserve(&mut v, items.len(), what)?;
    v.extend(items);
    Ok(v)
}

/// Fails with [`Fc3dError::OutOfMemory`] unless `bytes` can be allocated now: a probe before
/// code that allocates that much without a fallible path (faer's dense matrices, the hdf5
/// crate's reads), for sizes that come from the input, so that an address-space limit gives an
/// error rather than an abort. The probe is released at once.
#[cfg_attr(not(feature = "fclib"), allow(dead_code))]
pub(crate) fn ensure_headroom(bytes: usize, what: &str) -> Result<(), Fc3dError> {
    let mut probe: Vec<u8> = Vec::new();
    probe
        .try_reserve_exact(bytes)
        .map_err(|_| Fc3dError::OutOfMemory {
            what: what.to_string(),
            bytes,
        })
}

/// `count * size` bytes, saturating (a saturated size fails [`ensure_headroom`]).
#[cfg_attr(not(feature = "fclib"), allow(dead_code))]
pub(crate) fn bytes_of(count: usize, size: usize) -> usize {
    count.saturating_mul(size)
}
