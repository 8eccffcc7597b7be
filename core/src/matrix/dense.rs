use std::borrow::Cow;

use crate::alloc::try_collect;
use crate::error::{check_finite, Fc3dError};

/// Dense column-major matrix; borrows the host's array when created from a slice.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseMatrix<'a> {
    nrows: usize,
    ncols: usize,
    data: Cow<'a, [f64]>,
}

impl<'a> DenseMatrix<'a> {
    /// Takes `data` (column-major, `nrows * ncols` values), owned or borrowed.
    pub fn new(
        nrows: usize,
        ncols: usize,
        data: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        let data = data.into();
        let expected = nrows
            .checked_mul(ncols)
            .ok_or_else(|| Fc3dError::InvalidStructure("matrix size overflows".into()))?;
        if data.len() != expected {
            return Err(Fc3dError::dims("dense matrix values", expected, data.len()));
        }
        check_finite("W", &data)?;
        Ok(DenseMatrix { nrows, ncols, data })
    }

    pub fn nrows(&self) -> usize {
        self.nrows
    }
    pub fn ncols(&self) -> usize {
        self.ncols
    }
    /// Column-major values.
    pub fn values(&self) -> &[f64] {
        &self.data
    }

    /// True when the values are the host's array, not a copy.
    pub fn is_borrowed(&self) -> bool {
        matches!(self.data, Cow::Borrowed(_))
    }

    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.data[i + j * self.nrows]
    }

    /// `y <- y + A x`, column by column (contiguous reads of A).
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        let m = self.nrows;
        for (j, &xj) in x.iter().enumerate().take(self.ncols) {
            if xj == 0.0 {
                continue;
            }
            let col = &self.data[j * m..(j + 1) * m];
            for (yi, &a) in y.iter_mut().zip(col) {
                *yi += a * xj;
            }
        }
    }

    pub fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        for j in 0..self.ncols {
            for i in 0..self.nrows {
                f(i, j, self.data[i + j * self.nrows]);
            }
        }
    }

    /// An owned copy that no longer borrows the host.
    /// `alpha * self`, owned.
    pub fn scaled(&self, alpha: f64) -> Result<DenseMatrix<'static>, Fc3dError> {
        Ok(DenseMatrix {
            nrows: self.nrows,
            ncols: self.ncols,
            data: Cow::Owned(try_collect(
                self.data.iter().map(|v| alpha * v),
                "a rescaled W",
            )?),
        })
    }

    pub fn into_owned(self) -> DenseMatrix<'static> {
        DenseMatrix {
            nrows: self.nrows,
            ncols: self.ncols,
            data: Cow::Owned(self.data.into_owned()),
        }
    }
}
