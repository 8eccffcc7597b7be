//! The global frictional contact problem (Siconos' `GlobalFrictionContactProblem`): find the
//! global velocity `v` (`ndof`), the local velocity `u` and the reaction `r` (`D nc` each) with
//!
//! `M v = q + H r`, `u = H^T v + b`, and the contact law between `u` and `r` per contact
//! (Coulomb's for `D = 3`; [`GlobalRollingProblem`] adds rolling resistance, `D = 5`).
//!
//! Eliminating v gives the local problem FC(W, q_loc, mu) with `W = H^T M^-1 H` and
//! `q_loc = H^T M^-1 q + b` ([`GlobalProblem::reduce`]); the [`HForm`] operator does that
//! without a dense inverse.

use std::borrow::Cow;

use super::{FrictionProblem, RollingProblem};
use crate::error::{check_finite, Fc3dError};
use crate::matrix::{CsrMatrix, HForm};

/// `M` (`ndof x ndof`, invertible), `H` (`ndof x D nc`), `q` (`ndof`), `b` (`D nc`), `mu` (`nc`).
/// M and H are the host's values in compressed rows (whatever storage the host gave); the
/// error of a result is always measured on them.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobalProblem<'a, const D: usize = 3> {
    m: CsrMatrix,
    h: CsrMatrix,
    q: Cow<'a, [f64]>,
    b: Cow<'a, [f64]>,
    mu: Cow<'a, [f64]>,
}

impl<'a, const D: usize> GlobalProblem<'a, D> {
    /// Validates and assembles a global problem: sizes agree, every value finite (M's and H's
    /// are checked when they are built), `mu >= 0`. M's invertibility is checked when it is
    /// factored ([`GlobalProblem::operator`]).
    pub fn new(
        m: CsrMatrix,
        h: CsrMatrix,
        q: impl Into<Cow<'a, [f64]>>,
        b: impl Into<Cow<'a, [f64]>>,
        mu: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
        if !(2..=5).contains(&D) {
            return Err(Fc3dError::Unsupported(format!(
                "global contacts of dimension {D} (2 to 5 only)"
            )));
        }
        let (q, b, mu) = (q.into(), b.into(), mu.into());
        let ndof = m.nrows();
        if m.ncols() != ndof {
            return Err(Fc3dError::dims(
                format!("M is {}x{}: columns of M", m.nrows(), m.ncols()),
                ndof,
                m.ncols(),
            ));
        }
        if h.nrows() != ndof {
            return Err(Fc3dError::dims(
                "rows of H (the size of M)",
                ndof,
                h.nrows(),
            ));
        }
        let nc = mu.len();
        let size = nc.checked_mul(D).ok_or_else(|| {
            Fc3dError::InvalidStructure(format!("{nc} contacts of dimension {D} overflow"))
        })?;
        if h.ncols() != size {
            return Err(Fc3dError::dims(
                format!("columns of H ({nc} contacts of dimension {D})"),
                size,
                h.ncols(),
            ));
        }
        if q.len() != ndof {
            return Err(Fc3dError::dims("q (the size of M)", ndof, q.len()));
        }
        if b.len() != size {
            return Err(Fc3dError::dims("b (the columns of H)", size, b.len()));
        }
        check_finite("q", &q)?;
        check_finite("b", &b)?;
        check_finite("mu", &mu)?;
        if let Some(c) = mu.iter().position(|&m| m < 0.0) {
            return Err(Fc3dError::NegativeFriction {
                contact: c,
                value: mu[c],
            });
        }
        Ok(GlobalProblem { m, h, q, b, mu })
    }

    pub const fn dimension(&self) -> usize {
        D
    }
    pub fn n_contacts(&self) -> usize {
        self.mu.len()
    }
    /// `D * n_contacts`: the size of `r`, `u` and `b`.
    pub fn size(&self) -> usize {
        D * self.mu.len()
    }
    /// The size of M, `q` and `v`.
    pub fn ndof(&self) -> usize {
        self.m.nrows()
    }
    pub fn m(&self) -> &CsrMatrix {
        &self.m
    }
    pub fn h(&self) -> &CsrMatrix {
        &self.h
    }
    pub fn q(&self) -> &[f64] {
        &self.q
    }
    pub fn b(&self) -> &[f64] {
        &self.b
    }
    pub fn mu(&self) -> &[f64] {
        &self.mu
    }

    /// `W = H^T M^-1 H` as an operator: M factored (block by block when it is block diagonal).
    pub fn operator(&self) -> Result<HForm, Fc3dError> {
        HForm::new(&self.m, self.h.try_clone()?)
    }

    /// The local problem FC(W, q_loc, mu), W assembled from the operator.
    pub fn reduce(&self, operator: &mut HForm) -> Result<FrictionProblem<'static, D>, Fc3dError> {
        let w = operator.assemble::<D>()?;
        let q_local = operator.local_q(&self.q, &self.b)?;
        FrictionProblem::from_parts(w, q_local, self.mu.to_vec())
    }

    /// An owned copy that no longer borrows any host array.
    pub fn into_owned(self) -> GlobalProblem<'static, D> {
        GlobalProblem {
            m: self.m,
            h: self.h,
            q: Cow::Owned(self.q.into_owned()),
            b: Cow::Owned(self.b.into_owned()),
            mu: Cow::Owned(self.mu.into_owned()),
        }
    }
}

/// A global rolling-friction problem (Siconos' `GlobalRollingFrictionContactProblem`,
/// contacts of dimension 5): a [`GlobalProblem`] with a rolling coefficient `mu_r` per contact.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobalRollingProblem<'a> {
    base: GlobalProblem<'a, 5>,
    mu_r: Cow<'a, [f64]>,
}

impl<'a> GlobalRollingProblem<'a> {
    pub fn new(
        base: GlobalProblem<'a, 5>,
        mu_r: impl Into<Cow<'a, [f64]>>,
    ) -> Result<Self, Fc3dError> {
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
        Ok(GlobalRollingProblem { base, mu_r })
    }

    pub fn base(&self) -> &GlobalProblem<'a, 5> {
        &self.base
    }
    pub fn mu_r(&self) -> &[f64] {
        &self.mu_r
    }

    /// The local rolling problem (W, q_loc, mu, mu_r).
    pub fn reduce(&self, operator: &mut HForm) -> Result<RollingProblem<'static, 5>, Fc3dError> {
        // Built as a rolling problem directly: a friction problem of dimension 5 does not exist.
        let w = operator.assemble::<5>()?;
        let q = operator.local_q(self.base.q(), self.base.b())?;
        RollingProblem::new(w, q, self.base.mu().to_vec(), self.mu_r.to_vec())
    }
}
