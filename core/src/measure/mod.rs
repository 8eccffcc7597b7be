//! Error measures. The one every result is judged by is [`natural_map_error`], Siconos'
//! `fc3d_compute_error` (and, for 2D problems, `fc2d_compute_error`, the same formula with the 2D
//! cone): with `u = W r + q` and the De Saxcé velocity `ũ_c = (u_N + mu ||u_T||, u_T)`,
//!
//! `error = sqrt( sum_c || r_c - P_K(mu_c)(r_c - ũ_c) ||^2 ) / max(||q||, ||r||, ||u||)`
//!
//! (the normalisation falls back to 1 when all three norms are zero).

mod global;

pub use global::{
    global_error, global_error_with, global_error_with_norm_q, global_rolling_error, ContactLaw,
    ErrorWork,
};

use crate::math::cone::{
    modified_velocity, modified_velocity_d, project_on_cone, project_on_cone_d,
};
use crate::math::linalg::{contact_of, norm, norm_of, Vec3};
use crate::math::rolling::{part_norms, project_on_rolling_cone, rolling_residual_sq};
use crate::matrix::{BlockRows, Delassus};
use crate::problem::{FrictionProblem, RollingProblem};

/// Squared natural-map residual of one contact, `|| r - P_K(r - ũ) ||^2`.
#[inline]
pub fn contact_residual_sq(r: &Vec3, u: &Vec3, mu: f64) -> f64 {
    let ut = modified_velocity(u, mu);
    if !ut[0].is_finite() {
        // The De Saxcé velocity overflowed (|u| near the overflow threshold, large mu): no
        // residual is measurable at this scale; `relative_natural_map_error` rescales.
        return f64::INFINITY;
    }
    let p = project_on_cone(&[r[0] - ut[0], r[1] - ut[1], r[2] - ut[2]], mu);
    let d = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

/// [`contact_residual_sq`] for a contact of dimension `D` (2 or 3; the 3D case is that function).
#[inline]
pub fn contact_residual_sq_d<const D: usize>(r: &[f64; D], u: &[f64; D], mu: f64) -> f64 {
    if D == 3 {
        return contact_residual_sq(&[r[0], r[1], r[2]], &[u[0], u[1], u[2]], mu);
    }
    let ut = modified_velocity_d(u, mu);
    if !ut[0].is_finite() {
        return f64::INFINITY;
    }
    let mut x = *r;
    for (xk, uk) in x.iter_mut().zip(&ut) {
        *xk -= uk;
    }
    let p = project_on_cone_d(&x, mu);
    crate::math::linalg::distance_sq_d(r, &p)
}

/// Absolute natural-map residual `sqrt(sum_c ||r_c - P_K(r_c - ũ_c)||^2)` for given `r, u` (3D).
pub fn absolute_natural_map_residual(r: &[f64], u: &[f64], mu: &[f64]) -> f64 {
    absolute_natural_map_residual_d::<3>(r, u, mu)
}

/// [`absolute_natural_map_residual`] for contacts of dimension `D`.
pub fn absolute_natural_map_residual_d<const D: usize>(r: &[f64], u: &[f64], mu: &[f64]) -> f64 {
    let mut s = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        s += contact_residual_sq_d::<D>(&contact_of(r, c), &contact_of(u, c), m);
    }
    s.sqrt()
}

/// Siconos' normalisation `max(||q||, ||r||, ||u||)`, or 1 when that is zero.
pub fn relative_scale(norm_q: f64, r: &[f64], u: &[f64]) -> f64 {
    largest_norm(norm_q, norm(r), norm(u))
}

/// `max(norm_q, norm_r, norm_u)`, or 1 when that is zero.
fn largest_norm(norm_q: f64, norm_r: f64, norm_u: f64) -> f64 {
    let s = norm_q.max(norm_r).max(norm_u);
    if s > 0.0 {
        s
    } else {
        1.0
    }
}

/// The relative natural-map error `absolute residual / max(norm_q, ||r||, ||u||)` of a pair
/// `(r, u)` of a 3D problem, finite for any finite `r`, `u`: the error is invariant under a
/// common scaling of `(r, u, q)`, so when the squares overflow (entries near 1e155 and beyond, or
/// a De Saxcé velocity that overflows) it is measured on the pair scaled by its largest entry.
/// The result equals the plain formula whenever that is finite.
pub fn relative_natural_map_error(r: &[f64], u: &[f64], mu: &[f64], norm_q: f64) -> f64 {
    relative_natural_map_error_d::<3>(r, u, mu, norm_q)
}

/// [`relative_natural_map_error`] of a 2D pair (Siconos' `fc2d_compute_error`).
pub fn relative_natural_map_error_2d(r: &[f64], u: &[f64], mu: &[f64], norm_q: f64) -> f64 {
    relative_natural_map_error_d::<2>(r, u, mu, norm_q)
}

/// [`relative_natural_map_error`] for contacts of dimension `D`.
pub fn relative_natural_map_error_d<const D: usize>(
    r: &[f64],
    u: &[f64],
    mu: &[f64],
    norm_q: f64,
) -> f64 {
    let e = absolute_natural_map_residual_d::<D>(r, u, mu) / relative_scale(norm_q, r, u);
    if e.is_finite() {
        return e;
    }
    let largest = r.iter().chain(u).fold(norm_q.abs(), |a, &v| a.max(v.abs()));
    if !(largest > 0.0 && largest.is_finite()) {
        return e;
    }
    // Rare path (overflow): the pair scaled by its largest entry, contact by contact (nothing
    // allocated: r and u may be as large as the problem).
    let scaled = |v: &[f64], c: usize| contact_of::<D>(v, c).map(|x| x / largest);
    let mut s = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        s += contact_residual_sq_d::<D>(&scaled(r, c), &scaled(u, c), m);
    }
    let norm_scaled = |v: &[f64]| norm_of(v.iter().map(|x| x / largest));
    s.sqrt() / largest_norm(norm_q / largest, norm_scaled(r), norm_scaled(u))
}

/// The relative natural-map error of `r` for `problem`: computes `u = W r + q` into `u` (as
/// Siconos' `fc3d_compute_error` and `fc2d_compute_error` do) and returns the error.
pub fn natural_map_error<const D: usize>(
    problem: &FrictionProblem<'_, D>,
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    problem.velocity(r, u);
    natural_map_error_of(problem, r, u)
}

/// [`natural_map_error`] with `u = W r + q` computed through the block rows of W (cheaper than
/// the host's storage when W is dense but sparsely coupled).
pub fn natural_map_error_by_rows<const D: usize>(
    problem: &FrictionProblem<'_, D>,
    rows: &BlockRows<D>,
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    rows.velocity(problem.q(), r, u);
    natural_map_error_of(problem, r, u)
}

/// Relative natural-map error of a pair `(r, u)` taken as given (u is not recomputed).
pub fn natural_map_error_of<const D: usize>(
    problem: &FrictionProblem<'_, D>,
    r: &[f64],
    u: &[f64],
) -> f64 {
    relative_natural_map_error_d::<D>(r, u, problem.mu(), norm(problem.q()))
}

/// The relative natural-map error of a rolling pair `(r, u)` taken as given, as Siconos'
/// `rolling_fc3d_compute_error` measures it: `sqrt(sum_c ||r_c - P_K(r_c - ũ_c)||^2)` with the
/// rolling cone and De Saxcé velocity ([`crate::math::rolling`]), divided by `max(norm, ||r||,
/// ||u||)` when that exceeds the machine epsilon (`norm` is `||q||` for the solvers).
pub fn relative_rolling_error<const D: usize>(
    r: &[f64],
    u: &[f64],
    mu: &[f64],
    mu_r: &[f64],
    norm: f64,
) -> f64 {
    let mut s = 0.0;
    for (c, (&m, &mr)) in mu.iter().zip(mu_r).enumerate() {
        s += rolling_residual_sq::<D>(&contact_of(r, c), &contact_of(u, c), m, mr);
    }
    let scale = norm
        .max(crate::math::linalg::norm(r))
        .max(crate::math::linalg::norm(u));
    if scale.abs() > f64::EPSILON {
        s.sqrt() / scale
    } else {
        s.sqrt()
    }
}

/// The relative natural-map error of `r` for a rolling problem: computes `u = W r + q` into `u`
/// and returns [`relative_rolling_error`] with `norm = ||q||`.
pub fn rolling_error<const D: usize>(
    problem: &RollingProblem<'_, D>,
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    problem.velocity(r, u);
    relative_rolling_error::<D>(r, u, problem.mu(), problem.mu_r(), norm(problem.q()))
}

/// Dumont's criterion (37) for the rolling law: as [`dumont_criterion_d`] with the rolling cone
/// and the bi-potential `|u·r + (mu ||u_T|| + mu_r ||u_R||) r_N|`, which vanishes on every branch
/// of the rolling law for an `r` in its cone.
pub fn rolling_dumont_criterion<const D: usize>(
    r: &[f64],
    u: &[f64],
    u_solved: &[f64],
    mu: &[f64],
    mu_r: &[f64],
) -> f64 {
    let nc = mu.len();
    if nc == 0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for (c, (&m, &mr)) in mu.iter().zip(mu_r).enumerate() {
        let rc: [f64; D] = contact_of(r, c);
        let uc: [f64; D] = contact_of(u, c);
        let us: [f64; D] = contact_of(u_solved, c);
        let motion = crate::math::linalg::distance_sq_d(&us, &uc).sqrt();
        let p = project_on_rolling_cone(&rc, m, mr);
        let proj = crate::math::linalg::distance_sq_d(&rc, &p).sqrt();
        let (nt, nr) = part_norms(&uc);
        let mut ur = 0.0;
        for k in 0..D {
            ur += uc[k] * rc[k];
        }
        let bipotential = (ur + (m * nt + mr * nr) * rc[0]).abs();
        sum += motion + proj + bipotential + (-uc[0]).max(0.0);
    }
    sum / nc as f64
}

/// A problem the Gauss-Seidel main loop can sweep and measure: a friction problem (Coulomb cone)
/// or a rolling one (rolling cone), of contact dimension `D`.
pub trait SweptProblem<const D: usize> {
    fn q(&self) -> &[f64];
    /// The friction coefficients the sweep hands its one-contact step.
    fn mu(&self) -> &[f64];
    fn n_contacts(&self) -> usize;
    /// W, in the storage the problem holds.
    fn w(&self) -> &Delassus<'_>;
    /// The problem's relative natural-map error of `r`, `u = W r + q` computed on W's storage.
    fn error(&self, r: &[f64], u: &mut [f64]) -> f64;
    /// The problem's relative natural-map error of the pair `(r, u)` as given.
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64;
    /// [`SweptProblem::error`] with `u` computed through the block rows of W.
    fn error_by_rows(&self, rows: &BlockRows<D>, r: &[f64], u: &mut [f64]) -> f64 {
        rows.velocity(self.q(), r, u);
        self.error_of(r, u)
    }
    /// Dumont's criterion with the problem's cone (`u` receives `W r + q`).
    fn dumont_by_rows(
        &self,
        rows: &BlockRows<D>,
        r: &[f64],
        u: &mut [f64],
        u_solved: &[f64],
    ) -> f64;
}

impl<const D: usize> SweptProblem<D> for FrictionProblem<'_, D> {
    fn q(&self) -> &[f64] {
        FrictionProblem::q(self)
    }
    fn mu(&self) -> &[f64] {
        FrictionProblem::mu(self)
    }
    fn n_contacts(&self) -> usize {
        FrictionProblem::n_contacts(self)
    }
    fn w(&self) -> &Delassus<'_> {
        FrictionProblem::w(self)
    }
    fn error(&self, r: &[f64], u: &mut [f64]) -> f64 {
        natural_map_error(self, r, u)
    }
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64 {
        natural_map_error_of(self, r, u)
    }
    fn dumont_by_rows(
        &self,
        rows: &BlockRows<D>,
        r: &[f64],
        u: &mut [f64],
        u_solved: &[f64],
    ) -> f64 {
        rows.velocity(self.q(), r, u);
        dumont_criterion_d::<D>(r, u, u_solved, self.mu())
    }
}

impl<const D: usize> SweptProblem<D> for RollingProblem<'_, D> {
    fn q(&self) -> &[f64] {
        RollingProblem::q(self)
    }
    fn mu(&self) -> &[f64] {
        RollingProblem::mu(self)
    }
    fn n_contacts(&self) -> usize {
        RollingProblem::n_contacts(self)
    }
    fn w(&self) -> &Delassus<'_> {
        RollingProblem::w(self)
    }
    fn error(&self, r: &[f64], u: &mut [f64]) -> f64 {
        rolling_error(self, r, u)
    }
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64 {
        relative_rolling_error::<D>(r, u, self.mu(), self.mu_r(), norm(self.q()))
    }
    fn dumont_by_rows(
        &self,
        rows: &BlockRows<D>,
        r: &[f64],
        u: &mut [f64],
        u_solved: &[f64],
    ) -> f64 {
        rows.velocity(self.q(), r, u);
        rolling_dumont_criterion::<D>(r, u, u_solved, self.mu(), self.mu_r())
    }
}

/// Cheap error (134) from the accumulated squared increment of a sweep.
pub fn cheap_error(increment_sq: f64, r: &[f64]) -> f64 {
    let nr = norm(r);
    if nr > 0.0 {
        increment_sq.sqrt() / nr
    } else {
        increment_sq.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::{Delassus, DenseMatrix};
    use approx::assert_relative_eq;

    fn one_contact(w: [f64; 9], q: [f64; 3], mu: f64) -> FrictionProblem<'static> {
        let d = DenseMatrix::new(3, 3, w.to_vec()).unwrap();
        FrictionProblem::new(Delassus::Dense(d), q.to_vec(), vec![mu]).unwrap()
    }

    #[test]
    fn exact_solutions_have_zero_error() {
        // Identity W, q = (-1, 0, 0): stick solution r = (1, 0, 0), u = 0.
        let p = one_contact([1., 0., 0., 0., 1., 0., 0., 0., 1.], [-1., 0., 0.], 0.5);
        let mut u = [0.0; 3];
        assert_eq!(natural_map_error(&p, &[1.0, 0.0, 0.0], &mut u), 0.0);
        // Take-off: q_N > 0, r = 0.
        let p = one_contact([1., 0., 0., 0., 1., 0., 0., 0., 1.], [1., 2., 0.], 0.5);
        assert_eq!(natural_map_error(&p, &[0.0; 3], &mut u), 0.0);
    }

    #[test]
    fn error_of_zero_reaction_on_penetrating_contact() {
        // r = 0, u = q = (-1, 0, 0): r - ũ = (1, 0, 0) is in K, so the residual is 1 and
        // the scale max(||q||, 0, ||u||) = 1.
        let p = one_contact([1., 0., 0., 0., 1., 0., 0., 0., 1.], [-1., 0., 0.], 0.5);
        let mut u = [0.0; 3];
        assert_relative_eq!(
            natural_map_error(&p, &[0.0; 3], &mut u),
            1.0,
            epsilon = 1e-15
        );
        assert_eq!(u, [-1.0, 0.0, 0.0]);
    }
}

/// Dumont's global criterion (37) of `(r, u)`, `u = W r + q`, with `u_solved` the velocities the
/// contacts were solved with during the sweep:
/// `(1/nc) sum_c ( ||u_solved_c - u_c|| + ||r_c - P_K(r_c)|| + |u_c·r_c + mu r_N ||u_T||| + max(0, -u_N) )`.
///
/// The paper's `ũ` is the velocity the contact law acts on, our `u` (not the De Saxcé velocity,
/// with which the friction work would be counted twice): `u·r + mu r_N ||u_T||` vanishes exactly
/// on the three branches of Coulomb's law for an `r` in its cone. Absolute, not normalised.
pub fn dumont_criterion(r: &[f64], u: &[f64], u_solved: &[f64], mu: &[f64]) -> f64 {
    dumont_criterion_d::<3>(r, u, u_solved, mu)
}

/// [`dumont_criterion`] for contacts of dimension `D` (`||u_T||` is `|u_T|` in 2D).
pub fn dumont_criterion_d<const D: usize>(
    r: &[f64],
    u: &[f64],
    u_solved: &[f64],
    mu: &[f64],
) -> f64 {
    let nc = mu.len();
    if nc == 0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        let rc: [f64; D] = contact_of(r, c);
        let uc: [f64; D] = contact_of(u, c);
        let us: [f64; D] = contact_of(u_solved, c);
        let motion = crate::math::linalg::distance_sq_d(&us, &uc).sqrt();
        let p = project_on_cone_d(&rc, m);
        let proj = crate::math::linalg::distance_sq_d(&rc, &p).sqrt();
        let ut_norm = if D == 3 {
            crate::math::linalg::norm2(uc[1], uc[2])
        } else {
            uc[1].abs()
        };
        let mut ur = 0.0;
        for k in 0..D {
            ur += uc[k] * rc[k];
        }
        let bipotential = (ur + m * rc[0] * ut_norm).abs();
        let penetration = (-uc[0]).max(0.0);
        sum += motion + proj + bipotential + penetration;
    }
    sum / nc as f64
}
