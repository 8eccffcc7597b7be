//! Fallible allocation for the readers and writers: every size here comes from a file or a
//! stream, so a failure is an [`Fc3dError::OutOfMemory`] naming what was being read, never an
//! abort (see also `crate::error::try_vec`).

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

/// The items of `items` (whose length is known) in a vector allocated fallibly.
#[cfg_attr(not(feature = "fclib"), allow(dead_code))]
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
/// code that allocates that much without a fallible path (`CsrMatrix::from_triplets`, faer's
/// dense matrices, the hdf5 crate's reads), for sizes that come from the input, so that an
/// address-space limit gives an error rather than an abort. The probe is released at once.
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
