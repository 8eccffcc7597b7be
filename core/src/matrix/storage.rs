//! Where the arrays of a sparse-block W live: owned by fc3d (reference-counted, so that views
//! share them) or borrowed from the host for the length of a call (zero copy).
//!
//! The products and the Gauss-Seidel sweep read blocks through [`BlockAt`], one generic
//! implementation monomorphised per storage: a call dispatches once on [`BlockValues`] and the
//! loop inside runs on the concrete storage, with no per-block branch.

use std::ops::Deref;
use std::sync::Arc;

use crate::error::{try_copy, Fc3dError};

/// An array owned by fc3d and shared between W and its views, or borrowed for `'a`.
#[derive(Debug)]
pub enum Shared<'a, T> {
    Owned(Arc<Vec<T>>),
    Borrowed(&'a [T]),
}

impl<T> Clone for Shared<'_, T> {
    fn clone(&self) -> Self {
        match self {
            Shared::Owned(a) => Shared::Owned(Arc::clone(a)),
            Shared::Borrowed(s) => Shared::Borrowed(s),
        }
    }
}

impl<T> Deref for Shared<'_, T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        match self {
            Shared::Owned(a) => a,
            Shared::Borrowed(s) => s,
        }
    }
}

impl<T> From<Vec<T>> for Shared<'_, T> {
    fn from(v: Vec<T>) -> Self {
        Shared::Owned(Arc::new(v))
    }
}

impl<'a, T: Clone> Shared<'a, T> {
    /// The same values, owned (a borrowed array is copied; an owned one is shared).
    pub fn into_owned(self) -> Shared<'static, T>
    where
        T: 'static,
    {
        match self {
            Shared::Owned(a) => Shared::Owned(a),
            Shared::Borrowed(s) => Shared::Owned(Arc::new(s.to_vec())),
        }
    }

    /// [`Shared::into_owned`], the copy of a borrowed array allocated fallibly.
    pub fn try_into_owned(self, what: &str) -> Result<Shared<'static, T>, Fc3dError>
    where
        T: 'static,
    {
        Ok(match self {
            Shared::Owned(a) => Shared::Owned(a),
            Shared::Borrowed(s) => Shared::Owned(Arc::new(try_copy(s, what)?)),
        })
    }

    /// The values as a vector, without a copy when this is the only owner.
    pub fn into_vec(self) -> Vec<T> {
        match self {
            Shared::Owned(a) => Arc::try_unwrap(a).unwrap_or_else(|a| (*a).clone()),
            Shared::Borrowed(s) => s.to_vec(),
        }
    }

    pub fn is_borrowed(&self) -> bool {
        matches!(self, Shared::Borrowed(_))
    }
}

/// The values of the blocks of a sparse-block W, column-major, in storage order.
#[derive(Debug, Clone)]
pub enum BlockValues<'a> {
    /// `n * n` values per block, one block after the other (fc3d's own storage).
    Packed(Arc<Vec<f64>>),
    /// One reference per 3x3 block (a host's blocks, each where the host allocated it: Siconos'
    /// `double **block`, read in place).
    Table(Shared<'a, &'a [f64; 9]>),
}

impl BlockValues<'_> {
    /// Whether the blocks are the host's (borrowed, not copied).
    pub fn is_borrowed(&self) -> bool {
        matches!(self, BlockValues::Table(_))
    }
}

/// Read access to block `k` (its values column-major) of one storage; see the module doc.
pub(crate) trait BlockAt {
    fn at(&self, k: usize) -> &[f64];
    /// Blocks `range`, in order (one bounds check for the range, none a block).
    fn blocks(&self, range: std::ops::Range<usize>) -> impl Iterator<Item = &[f64]>;
}

/// Packed storage of `len`-value blocks.
#[derive(Clone, Copy)]
pub(crate) struct Packed<'s> {
    pub values: &'s [f64],
    pub len: usize,
}

impl BlockAt for Packed<'_> {
    #[inline(always)]
    fn at(&self, k: usize) -> &[f64] {
        &self.values[self.len * k..self.len * (k + 1)]
    }
    #[inline(always)]
    fn blocks(&self, range: std::ops::Range<usize>) -> impl Iterator<Item = &[f64]> {
        self.values[self.len * range.start..self.len * range.end].chunks_exact(self.len)
    }
}

/// A table of references to 3x3 blocks.
#[derive(Clone, Copy)]
pub(crate) struct Table<'s, 'a>(pub &'s [&'a [f64; 9]]);

impl BlockAt for Table<'_, '_> {
    #[inline(always)]
    fn at(&self, k: usize) -> &[f64] {
        self.0[k]
    }
    #[inline(always)]
    fn blocks(&self, range: std::ops::Range<usize>) -> impl Iterator<Item = &[f64]> {
        self.0[range].iter().map(|b| &b[..])
    }
}

/// Runs `$body` with `$s` bound to the concrete [`BlockAt`] storage of `$values` (blocks of
/// `$len` values when packed): one dispatch, then monomorphised code.
macro_rules! with_blocks {
    ($values:expr, $len:expr, |$s:ident| $body:expr) => {
        match $values {
            $crate::matrix::storage::BlockValues::Packed(v) => {
                let $s = $crate::matrix::storage::Packed {
                    values: v.as_slice(),
                    len: $len,
                };
                $body
            }
            $crate::matrix::storage::BlockValues::Table(t) => {
                let $s = $crate::matrix::storage::Table(&t[..]);
                $body
            }
        }
    };
}
pub(crate) use with_blocks;
