//! Accelerated first-order solvers of the convex sub-problems of the exact-Coulomb fixed points:
//!
//! `minimize f(r) = 1/2 r.W r + c.r over r ∈ S`, `S` a product of closed convex sets, one a
//! contact,
//!
//! which is the Tresca sub-problem of TFP (S the cylinders `R+ x D(mu_c s_c)`, c = q), PFP's
//! tangent problem (disks, the normal reactions frozen) and the SOCLCP of ACLMFP (S the Coulomb
//! cones, c = q plus the De Saxcé shift on the normal components). Projected gradient methods are
//! reliable there, unlike on Coulomb's law itself (a non-monotone problem, So-bogus' notes): the
//! outer loop turns their convex solutions into a Coulomb solution.
//!
//! * [`ApgdSettings`]: Nesterov's accelerated projected gradient (FISTA's momentum) with the
//!   backtracking of Mazhar, Heyn, Negrut and Tasora (2015) and the adaptive gradient-mapping
//!   restart of O'Donoghue and Candès (2015);
//! * [`SpgSettings`]: the spectral projected gradient of Birgin, Martínez and Raydan (2000): a
//!   projected step of Barzilai-Borwein length, then a non-monotone line search along it.
//!
//! Both spend one product with W per iteration (their backtracking is free or rare: along a
//! direction the quadratic is known once `W d` is), counted in [`FirstOrderWork::products`]; the
//! first step comes from a few Lanczos steps on W ([`crate::math::spectrum`]), once per solve.
//! They stop on the sub-problem's natural map, `||r - P_S(r - (W r + c))||`, relative to
//! `max(||q||, ||r||, ||W r + c||)` as the Coulomb error (133) is, and return the iterate with the
//! smallest such residual (neither method decreases it monotonically).
//!
//! The analysis assumes W symmetric positive semi-definite (`W = H M^-1 H^T`). For a
//! non-symmetric W the same iterations solve the VI `-(W r + c) ∈ N_S(r)` with the model
//! `1/2 d.W d` of the symmetric part along each step: no convergence guarantee, but the limits
//! hold and the best iterate is returned.

mod apgd;
mod settings;
mod spg;

pub use settings::{ApgdSettings, SpgSettings};

use std::time::Instant;

use crate::contract::deadline_passed;
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::norm;
use crate::math::spectrum::{euclidean, Lanczos};
use crate::matrix::BlockRows;

/// A closed convex set, a product over contacts, given by its projection.
pub(crate) trait ConvexSet {
    /// `x <- P(x)`.
    fn project(&self, x: &mut [f64]);
}

/// `min 1/2 r.W r + c.r` over `set`, W through its block rows.
pub(crate) struct ConvexSubproblem<'s, 'a, S> {
    pub rows: &'s BlockRows<'a>,
    /// The linear term c (the problem's q, shifted for the SOCLCP of ACLMFP).
    pub linear: &'s [f64],
    pub set: &'s S,
    /// `||q||` of the friction problem: the scale of the relative residual, as in (133).
    pub norm_q: f64,
}

/// The first-order method of a convex sub-problem, with its settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FirstOrderMethod {
    Apgd(ApgdSettings),
    Spg(SpgSettings),
}

impl FirstOrderMethod {
    fn spectral_steps(&self) -> usize {
        match self {
            FirstOrderMethod::Apgd(s) => s.spectral_steps,
            FirstOrderMethod::Spg(s) => s.spectral_steps,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        match self {
            FirstOrderMethod::Apgd(s) => s.validate(),
            FirstOrderMethod::Spg(s) => s.validate(),
        }
    }
}

/// Work space of the first-order solvers, allocated once per solve; the step state (APGD's L,
/// SPG's spectral step) is kept from one sub-problem to the next of the same outer loop.
pub(crate) struct FirstOrderWork {
    method: FirstOrderMethod,
    /// The gradient `W r + c` at the current iterate.
    g: Vec<f64>,
    /// APGD's extrapolated point and its gradient.
    y: Vec<f64>,
    g_y: Vec<f64>,
    /// The projected trial point and its gradient.
    trial: Vec<f64>,
    g_trial: Vec<f64>,
    /// The iterate of smallest residual so far.
    best: Vec<f64>,
    /// Work of the residual's projection.
    scratch: Vec<f64>,
    /// SPG's last values of f (relative to the first iterate), a ring of `memory` entries.
    history: Vec<f64>,
    /// Lanczos on W for the first step, run once (the first sub-problem) and then dropped.
    lanczos: Option<Lanczos>,
    /// Current Lipschitz estimate (APGD: L; SPG: 1 / its spectral step).
    curvature: Option<f64>,
    /// The largest eigenvalue estimate of W from Lanczos (the scale of SPG's step bounds).
    lambda_max: f64,
    /// Products with W done, spectral estimate included.
    pub products: usize,
}

impl FirstOrderWork {
    /// Work space for sub-problems of size `n`.
    pub fn new(n: usize, method: FirstOrderMethod) -> Result<Self, Fc3dError> {
        let memory = match method {
            FirstOrderMethod::Spg(s) => s.memory,
            FirstOrderMethod::Apgd(_) => 0,
        };
        let steps = method.spectral_steps();
        const WHAT: &str = "the accelerated solver's work arrays";
        let mut history = try_vec(memory, 0.0, WHAT)?;
        history.clear();
        Ok(FirstOrderWork {
            method,
            g: try_vec(n, 0.0, WHAT)?,
            y: try_vec(n, 0.0, WHAT)?,
            g_y: try_vec(n, 0.0, WHAT)?,
            trial: try_vec(n, 0.0, WHAT)?,
            g_trial: try_vec(n, 0.0, WHAT)?,
            best: try_vec(n, 0.0, WHAT)?,
            scratch: try_vec(n, 0.0, WHAT)?,
            history,
            lanczos: Some(Lanczos::new(n, steps)?),
            curvature: None,
            lambda_max: 1.0,
            products: 0,
        })
    }

    /// Solves the sub-problem from `r` (projected on the set first) to the relative residual
    /// `tol`, within `max_iter` iterations and the deadline; leaves the best iterate in `r`
    /// and returns the iterations done.
    pub fn solve<S: ConvexSet>(
        &mut self,
        sub: &ConvexSubproblem<'_, '_, S>,
        tol: f64,
        max_iter: usize,
        deadline: Option<Instant>,
        r: &mut [f64],
    ) -> usize {
        if self.curvature.is_none() {
            self.estimate_curvature(sub.rows, deadline);
        }
        match self.method {
            FirstOrderMethod::Apgd(s) => self.apgd(&s, sub, tol, max_iter, deadline, r),
            FirstOrderMethod::Spg(s) => self.spg(&s, sub, tol, max_iter, deadline, r),
        }
    }

    /// The largest eigenvalue of W by a few Lanczos steps (a lower bound, within a few per cent
    /// on the piles after 10 steps; the methods' step control absorbs the rest).
    fn estimate_curvature(&mut self, rows: &BlockRows<'_>, deadline: Option<Instant>) {
        let mut estimate = None;
        if let Some(mut lanczos) = self.lanczos.take() {
            Lanczos::default_start(&mut self.trial);
            let zero = &mut self.scratch;
            zero.iter_mut().for_each(|v| *v = 0.0);
            if lanczos.start(&self.trial, euclidean) {
                for _ in 0..self.method.spectral_steps() {
                    if deadline_passed(deadline) {
                        break;
                    }
                    self.products += 1;
                    if !lanczos.step(|x, y| rows.velocity(zero, x, y), euclidean) {
                        break;
                    }
                }
            }
            estimate = lanczos.extremes().map(|(_, hi)| hi);
        }
        let lambda = estimate
            .filter(|l| *l > 0.0 && l.is_finite())
            .unwrap_or(1.0);
        self.lambda_max = lambda;
        self.curvature = Some(lambda);
    }

    /// The relative natural map of the sub-problem at `x` with gradient `g`.
    fn residual<S: ConvexSet>(
        scratch: &mut [f64],
        sub: &ConvexSubproblem<'_, '_, S>,
        x: &[f64],
        g: &[f64],
    ) -> f64 {
        for ((s, xi), gi) in scratch.iter_mut().zip(x).zip(g) {
            *s = xi - gi;
        }
        sub.set.project(scratch);
        let sum: f64 = scratch
            .iter()
            .zip(x)
            .map(|(p, xi)| (xi - p) * (xi - p))
            .sum();
        let scale = sub.norm_q.max(norm(x)).max(norm(g));
        sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
    }
}

/// The smallest residual seen and the iterate that had it.
struct Best {
    residual: f64,
}

impl Best {
    /// Records `x` when its residual is the smallest so far.
    fn offer(&mut self, residual: f64, x: &[f64], store: &mut [f64]) {
        if residual < self.residual {
            self.residual = residual;
            store.copy_from_slice(x);
        }
    }

    /// Puts the best iterate back in `r` when the last one is worse (or not finite).
    fn restore(&self, last_residual: f64, store: &[f64], r: &mut [f64]) {
        if self.residual.is_finite() && (last_residual.is_nan() || last_residual > self.residual) {
            r.copy_from_slice(store);
        }
    }
}

#[cfg(test)]
mod tests;
