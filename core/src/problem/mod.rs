//! The discrete frictional contact problem FC(W, q, mu) in reduced (Delassus) form, of contact
//! dimension `D`: 3 (normal and two tangential components, the default) or 2 (normal and one
//! tangential component, Siconos' `fc2d` problems). The dimension is a type parameter, so that
//! every 3D path keeps its fixed 3x3 kernels and a 2D problem cannot reach a 3D-only solver.

mod global;

pub use global::{GlobalProblem, GlobalRollingProblem};

use std::borrow::Cow;

use crate::error::{check_finite, try_copy, Fc3dError};
use crate::matrix::Delassus;

/// FC(W, q, mu): `nc` contacts, `W` of size `D nc x D nc`, `q` of size `D nc`, `mu` of size `nc`.
/// Local frames put the normal component first: `r_c = (r_N, r_T1, r_T2)` in 3D, `(r_N, r_T)` in
/// 2D, where the Coulomb cone is `|r_T| <= mu r_N`.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionProblem<'a, const D: usize = 3> {
    w: Delassus<'a>,
    q: Cow<'a, [f64]>,
    mu: Cow<'a, [f64]>,
}

/// A 2D problem (Siconos' `fc2d`): two components per contact.
pub type FrictionProblem2d<'a> = FrictionProblem<'a, 2>;

/// The dimension of the default (3D) problem.
pub const DIMENSION: usize = 3;

impl<'a> FrictionProblem<'a> {
    /// Validates and assembles a 3D problem: sizes agree, every value finite, `mu >= 0`, and (for
    /// a sparse-block W) every diagonal 3x3 block present.
    pub fn new(
        w: Delassus<'a>,
        q: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        Self::validated(w, q.into(), mu.into())
    }
}

impl<'a> FrictionProblem<'a, 2> {
    /// Validates and assembles a 2D problem: sizes agree (`W` is `2 nc x 2 nc`), every value
    /// finite, `mu >= 0`. W is dense or general sparse: the sparse-block storage holds 3x3 blocks
    /// only, so a 2x2-block W is handed over as a [`crate::CsrMatrix`].
    pub fn new_2d(
        w: Delassus<'a>,
        q: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        Self::validated(w, q.into(), mu.into())
    }
}

impl<'a, const D: usize> FrictionProblem<'a, D> {
    /// [`FrictionProblem::new`] or [`FrictionProblem::new_2d`] for a dimension `D` chosen by
    /// the caller's type (readers generic over the dimension).
    pub fn from_parts(
        w: Delassus<'a>,
        q: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        if D != 2 && D != 3 {
            return Err(Fc3dError::Unsupported(format!(
                "contacts of dimension {D} (2 or 3 only)"
            )));
        }
        Self::validated(w, q.into(), mu.into())
    }

    fn validated(
        w: Delassus<'a>,
        q: Cow<'a, [f64]>,
        mu: Cow<'a, [f64]>,
    ) -> Result<Self, Fc3dError> {
        if D != DIMENSION && matches!(w, Delassus::SparseBlock(_)) {
            return Err(Fc3dError::Unsupported(format!(
                "a problem of dimension {D} cannot hold W in 3x3 sparse-block storage (use a \
                 dense or CSR W)"
            )));
        }
        let nc = mu.len();
        let n = nc.checked_mul(D).ok_or_else(|| {
            Fc3dError::InvalidStructure(format!("{nc} contacts of dimension {D} overflow"))
        })?;
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
            if let Some(c) = (0..nc).find(|&c| !s.has_diagonal_block(c)) {
                return Err(Fc3dError::MissingDiagonalBlock { contact: c });
            }
        }
        Ok(FrictionProblem { w, q, mu })
    }

    /// The contact dimension `D` (2 or 3).
    pub const fn dimension(&self) -> usize {
        D
    }
    pub fn n_contacts(&self) -> usize {
        self.mu.len()
    }
    /// `D * n_contacts`.
    pub fn size(&self) -> usize {
        D * self.mu.len()
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
    pub fn with_w(&self, w: Delassus<'static>) -> Result<FrictionProblem<'static, D>, Fc3dError> {
        FrictionProblem::validated(
            w,
            Cow::Owned(try_copy(&self.q, "q")?),
            Cow::Owned(try_copy(&self.mu, "mu")?),
        )
    }

    /// W, q and mu, taken apart without a copy (what a converter that releases the problem as it
    /// goes needs).
    pub fn into_parts(self) -> (Delassus<'a>, Cow<'a, [f64]>, Cow<'a, [f64]>) {
        (self.w, self.q, self.mu)
    }

    /// An owned copy that no longer borrows any host array.
    pub fn into_owned(self) -> FrictionProblem<'static, D> {
        let w = match self.w {
            Delassus::Dense(d) => Delassus::Dense(d.into_owned()),
            Delassus::SparseBlock(s) => Delassus::SparseBlock(s.into_owned()),
            Delassus::Sparse(s) => Delassus::Sparse(s),
        };
        FrictionProblem {
            w,
            q: Cow::Owned(self.q.into_owned()),
            mu: Cow::Owned(self.mu.into_owned()),
        }
    }
}

/// A rolling-friction problem (Siconos' `RollingFrictionContactProblem`): FC(W, q, mu) with a
/// rolling resistance coefficient `mu_r` per contact and contacts of dimension `D`: 5 (normal,
/// two tangential, two rolling components; Siconos' `rolling_fc3d`, the default) or 3 (normal,
/// tangential, rolling; `rolling_fc2d`). Each contact's cone is
/// `K = { ||r_T|| <= mu r_N, ||r_R|| <= mu_r r_N }` (see [`crate::math::rolling`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RollingProblem<'a, const D: usize = 5> {
    base: FrictionProblem<'a, D>,
    mu_r: Cow<'a, [f64]>,
}

/// A 2D rolling problem (Siconos' `rolling_fc2d`): three components per contact.
pub type RollingProblem2d<'a> = RollingProblem<'a, 3>;

impl<'a, const D: usize> RollingProblem<'a, D> {
    /// Validates and assembles a rolling problem: `W` is `D nc x D nc` (dense or general sparse;
    /// sparse-block in 2D only, where its 3x3 blocks are the contacts' blocks), `q` of size
    /// `D nc`, `mu` and `mu_r` of size `nc`, every value finite, both coefficients `>= 0`.
    pub fn new(
        w: Delassus<'a>,
        q: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
        mu_r: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        if D != 5 && D != 3 {
            return Err(Fc3dError::Unsupported(format!(
                "rolling contacts of dimension {D} (5 or 3 only)"
            )));
        }
        let base = FrictionProblem::validated(w, q.into(), mu.into())?;
        let mu_r = mu_r.into();
        if mu_r.len() != base.n_contacts() {
            return Err(Fc3dError::dims("mu_r", base.n_contacts(), mu_r.len()));
        }
        check_finite("mu_r", &mu_r)?;
        if let Some(c) = mu_r.iter().position(|&m| m < 0.0) {
            return Err(Fc3dError::NegativeFriction {
                contact: c,
                value: mu_r[c],
            });
        }
        Ok(RollingProblem { base, mu_r })
    }

    /// The same W, q and mu as a friction problem of dimension `D` (what the generic sweep and
    /// storages work on; its cone is not the rolling one).
    pub fn base(&self) -> &FrictionProblem<'a, D> {
        &self.base
    }
    pub const fn dimension(&self) -> usize {
        D
    }
    pub fn n_contacts(&self) -> usize {
        self.base.n_contacts()
    }
    /// `D * n_contacts`.
    pub fn size(&self) -> usize {
        self.base.size()
    }
    pub fn w(&self) -> &Delassus<'a> {
        self.base.w()
    }
    pub fn q(&self) -> &[f64] {
        self.base.q()
    }
    pub fn mu(&self) -> &[f64] {
        self.base.mu()
    }
    pub fn mu_r(&self) -> &[f64] {
        &self.mu_r
    }
    /// `u = W r + q`.
    pub fn velocity(&self, r: &[f64], u: &mut [f64]) {
        self.base.velocity(r, u);
    }

    /// An owned copy that no longer borrows any host array.
    pub fn into_owned(self) -> RollingProblem<'static, D> {
        RollingProblem {
            base: self.base.into_owned(),
            mu_r: Cow::Owned(self.mu_r.into_owned()),
        }
    }
}
