//! The discrete frictional contact problem FC(W, q, mu) in reduced (Delassus) form, dimension 3.

use std::borrow::Cow;

use crate::error::{check_finite, Fc3dError};
use crate::matrix::Delassus;

/// FC(W, q, mu): `nc` contacts, `W` of size `3nc x 3nc`, `q` of size `3nc`, `mu` of size `nc`.
/// Local frames put the normal component first: `r_c = (r_N, r_T1, r_T2)`.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionProblem<'a> {
    w: Delassus<'a>,
    q: Cow<'a, [f64]>,
    mu: Cow<'a, [f64]>,
}

/// The only dimension fc3d solves.
pub const DIMENSION: usize = 3;

impl<'a> FrictionProblem<'a> {
    /// Validates and assembles a problem: sizes agree, every value finite, `mu >= 0`, and (for a
    /// sparse-block W) every diagonal 3x3 block present.
    pub fn new(
        w: Delassus<'a>,
        q: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        let q = q.into();
        let mu = mu.into();
        let nc = mu.len();
        let n = DIMENSION * nc;
        if w.nrows() != n || w.ncols() != n {
            return Err(Fc3dError::dims(
                format!("W is {}x{} but {nc} contacts need", w.nrows(), w.ncols()),
                n,
                w.nrows().max(w.ncols()),
            ));
        }
        if q.len() != n {
            return Err(Fc3dError::dims("q", n, q.len()));
        }
        check_finite("q", &q)?;
        check_finite("mu", &mu)?;
        if let Some(c) = mu.iter().position(|&m| m < 0.0) {
            return Err(Fc3dError::NegativeFriction {
                contact: c,
                value: mu[c],
            });
        }
        if let Delassus::SparseBlock(s) = &w {
            if let Some(c) = (0..nc).find(|&c| s.diagonal_block(c).is_none()) {
                return Err(Fc3dError::MissingDiagonalBlock { contact: c });
            }
        }
        Ok(FrictionProblem { w, q, mu })
    }

    pub fn n_contacts(&self) -> usize {
        self.mu.len()
    }
    /// `3 * n_contacts`.
    pub fn size(&self) -> usize {
        DIMENSION * self.mu.len()
    }
    pub fn w(&self) -> &Delassus<'a> {
        &self.w
    }
    pub fn q(&self) -> &[f64] {
        &self.q
    }
    pub fn mu(&self) -> &[f64] {
        &self.mu
    }

    /// `u = W r + q`.
    pub fn velocity(&self, r: &[f64], u: &mut [f64]) {
        self.w.velocity(r, &self.q, u);
    }

    /// The same problem with W in another storage (used to cross-check storages).
    pub fn with_w(&self, w: Delassus<'static>) -> Result<FrictionProblem<'static>, Fc3dError> {
        FrictionProblem::new(w, self.q.to_vec(), self.mu.to_vec())
    }

    /// An owned copy that no longer borrows any host array.
    pub fn into_owned(self) -> FrictionProblem<'static> {
        let w = match self.w {
            Delassus::Dense(d) => Delassus::Dense(d.into_owned()),
            Delassus::SparseBlock(s) => Delassus::SparseBlock(s),
            Delassus::Sparse(s) => Delassus::Sparse(s),
        };
        FrictionProblem {
            w,
            q: Cow::Owned(self.q.into_owned()),
            mu: Cow::Owned(self.mu.into_owned()),
        }
    }
}
