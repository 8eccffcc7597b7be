//! Per-contact diagnostics of an iterate `(r, u = W r + q)`: what each contact is doing, how much
//! of the error it carries, and which contacts carry most of it, so that a host can see why a
//! step did not converge (a frictionless contact with `W_NN = 0` that q pushes in, a contact of an
//! over-constrained cluster that never settles, ...).
//!
//! # Status rules
//!
//! With `tau` the status tolerance ([`DiagnosticOptions::tolerance`]), the velocity scale of the
//! problem `U = max_c ||q_c||` and, for each contact, the stiffness `a_c = max_i |(W_cc)_ii|`
//! (the largest over all contacts when `W_cc` has a zero diagonal) that turns a reaction into a
//! velocity, contact `c` is *without force* when `a_c ||r_c|| <= tau max(U, ||u_c||)` (its
//! reaction moves it by a negligible velocity; a scale per contact, so that a reaction
//! growing without bound elsewhere does not hide this one), and with `eps_u = tau U` it is
//!
//! * [`ContactStatus::TakeOff`] when without force and `u_N > eps_u` (separating);
//! * [`ContactStatus::Apex`] when without force and `u_N <= eps_u`: no force and no
//!   separation, the reaction at the apex of the cone (a grazing contact, possibly sliding
//!   tangentially: then the De Saxcé velocity is on the boundary of the dual cone). A `u_N`
//!   below `-eps_u` here is a violated contact (penetrating without reaction): its error
//!   contribution says so;
//! * [`ContactStatus::Stick`] when with force and `||u_T|| <= eps_u` (this includes a
//!   reaction on the cone's boundary with no slip yet);
//! * [`ContactStatus::Slide`] when with force and `||u_T|| > eps_u`.
//!
//! The rules classify any iterate, converged or not; at a solution they are Coulomb's cases.
//!
//! # Error contribution
//!
//! Contact `c` contributes `e_c = ||r_c - P_K(r_c - ũ_c)|| / max(||q||, ||r||, ||u||)`, so that
//! `sqrt(sum_c e_c^2)` is the relative natural-map error of the iterate (the error every solve
//! reports).

use crate::error::Fc3dError;
use crate::math::linalg::norm;
use crate::measure::{contact_residual_sq, relative_scale};
use crate::problem::FrictionProblem;

/// What a contact does at an iterate (see the module documentation for the rules).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ContactStatus {
    /// No reaction, separating (`u_N > 0`).
    TakeOff,
    /// Reaction inside or on the cone, no tangential slip.
    Stick,
    /// Reaction with tangential slip (on the cone's boundary at a solution).
    Slide,
    /// No reaction and no separation: the reaction at the apex of the cone.
    Apex,
}

impl ContactStatus {
    /// Short name for tables (`take-off`, `stick`, `slide`, `apex`).
    pub fn name(self) -> &'static str {
        match self {
            ContactStatus::TakeOff => "take-off",
            ContactStatus::Stick => "stick",
            ContactStatus::Slide => "slide",
            ContactStatus::Apex => "apex",
        }
    }
}

/// Settings of [`diagnose`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiagnosticOptions {
    /// Relative tolerance `tau` of the status rules (finite, >= 0). Default 1e-6: a contact whose
    /// reaction changes its velocity by less than a millionth of the problem's velocity scale
    /// counts as without force. For an iterate
    /// solved to a tolerance above that, pass a larger one (about 10 times the error reached).
    pub tolerance: f64,
}

impl Default for DiagnosticOptions {
    fn default() -> Self {
        DiagnosticOptions { tolerance: 1e-6 }
    }
}

/// One contact's diagnostics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactDiagnostic {
    pub status: ContactStatus,
    /// `e_c`: this contact's part of the relative natural-map error.
    pub error_contribution: f64,
    /// `u_N`: negative when the contact penetrates (approaches) at the end of the step.
    pub normal_velocity: f64,
    /// `||u_T||`: the slip velocity.
    pub tangential_velocity: f64,
    /// `r_N`.
    pub normal_reaction: f64,
}

/// The diagnostics of every contact of an iterate.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostics {
    pub contacts: Vec<ContactDiagnostic>,
    /// The relative natural-map error of the iterate (`sqrt(sum_c e_c^2)`).
    pub error: f64,
}

impl Diagnostics {
    /// The indices of the `k` contacts with the largest error contributions, largest first
    /// (ties by index; fewer when there are fewer contacts).
    pub fn worst(&self, k: usize) -> Vec<usize> {
        worst_contacts(self.contacts.iter().map(|c| c.error_contribution), k)
    }

    /// How many contacts have each status: `(take-off, stick, slide, apex)`.
    pub fn counts(&self) -> (usize, usize, usize, usize) {
        let mut n = (0, 0, 0, 0);
        for c in &self.contacts {
            match c.status {
                ContactStatus::TakeOff => n.0 += 1,
                ContactStatus::Stick => n.1 += 1,
                ContactStatus::Slide => n.2 += 1,
                ContactStatus::Apex => n.3 += 1,
            }
        }
        n
    }
}

/// The indices of the `k` largest of `values`, largest first, ties by index (NaN counts as the
/// largest: a contact whose residual is not measurable is the first to look at).
pub fn worst_contacts(values: impl Iterator<Item = f64>, k: usize) -> Vec<usize> {
    let v: Vec<f64> = values.collect();
    let mut idx: Vec<usize> = (0..v.len()).collect();
    let key = |x: f64| if x.is_nan() { f64::INFINITY } else { x };
    idx.sort_by(|&a, &b| key(v[b]).total_cmp(&key(v[a])).then(a.cmp(&b)));
    idx.truncate(k);
    idx
}

/// Diagnoses the iterate `r` of `problem` (`u = W r + q` is computed). Fails when `r` has the
/// wrong size or a non-finite entry, or the tolerance is out of range.
pub fn diagnose(
    problem: &FrictionProblem<'_>,
    r: &[f64],
    options: &DiagnosticOptions,
) -> Result<Diagnostics, Fc3dError> {
    let n = problem.size();
    if r.len() != n {
        return Err(Fc3dError::dims("reaction", n, r.len()));
    }
    crate::error::check_finite("reaction", r)?;
    let t = options.tolerance;
    crate::error::require_setting(t >= 0.0 && t.is_finite(), "tolerance", t, "finite and >= 0")?;
    let mut u = crate::error::try_vec(n, 0.0, "velocity")?;
    problem.velocity(r, &mut u);
    let mut contacts = Vec::new();
    contacts
        .try_reserve_exact(problem.n_contacts())
        .map_err(|_| Fc3dError::OutOfMemory {
            what: "contact diagnostics".into(),
            bytes: problem.n_contacts() * std::mem::size_of::<ContactDiagnostic>(),
        })?;
    let (q, mu) = (problem.q(), problem.mu());
    let scale = relative_scale(norm(q), r, &u);
    let n_contacts = problem.n_contacts();
    let stiffness = |c: usize| {
        problem
            .w()
            .diagonal_block(c)
            .map_or(0.0, |b| b[0][0].abs().max(b[1][1].abs()).max(b[2][2].abs()))
    };
    let mut u_scale = 0.0_f64;
    let mut a_max = 0.0_f64;
    for c in 0..n_contacts {
        u_scale = u_scale.max(norm(&q[3 * c..3 * c + 3]));
        a_max = a_max.max(stiffness(c));
    }
    let a_default = if a_max > 0.0 && a_max.is_finite() {
        a_max
    } else {
        1.0
    };
    let eps_u = t * u_scale;
    let mut sum_sq = 0.0;
    for c in 0..n_contacts {
        let rc = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let uc = [u[3 * c], u[3 * c + 1], u[3 * c + 2]];
        let e = contact_residual_sq(&rc, &uc, mu[c]).sqrt() / scale;
        sum_sq += e * e;
        let slip = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let a = match stiffness(c) {
            a if a > 0.0 && a.is_finite() => a,
            _ => a_default,
        };
        let without_force = a * norm(&rc) <= t * u_scale.max(norm(&uc));
        let status = if without_force {
            if uc[0] > eps_u {
                ContactStatus::TakeOff
            } else {
                ContactStatus::Apex
            }
        } else if slip <= eps_u {
            ContactStatus::Stick
        } else {
            ContactStatus::Slide
        };
        contacts.push(ContactDiagnostic {
            status,
            error_contribution: e,
            normal_velocity: uc[0],
            tangential_velocity: slip,
            normal_reaction: rc[0],
        });
    }
    Ok(Diagnostics {
        contacts,
        error: sum_sq.sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::{Delassus, DenseMatrix};

    fn one_contact(w: [f64; 3], q: [f64; 3], mu: f64) -> FrictionProblem<'static> {
        let data = vec![w[0], 0.0, 0.0, 0.0, w[1], 0.0, 0.0, 0.0, w[2]];
        let w = Delassus::Dense(DenseMatrix::new(3, 3, data).unwrap());
        FrictionProblem::new(w, q.to_vec(), vec![mu]).unwrap()
    }

    fn status_of(p: &FrictionProblem<'_>, r: [f64; 3]) -> ContactDiagnostic {
        let d = diagnose(p, &r, &DiagnosticOptions::default()).unwrap();
        assert!(
            d.error < 1e-14,
            "the iterate is a solution: error {}",
            d.error
        );
        d.contacts[0]
    }

    #[test]
    fn stick_take_off_slide_apex_on_single_contacts() {
        // W = diag(1, 3.5, 3.5) (a sphere on a plane). Pushed down, no tangential velocity:
        // r = (1, 0, 0), u = 0, stick.
        let p = one_contact([1.0, 3.5, 3.5], [-1.0, 0.0, 0.0], 0.5);
        let d = status_of(&p, [1.0, 0.0, 0.0]);
        assert_eq!(d.status, ContactStatus::Stick);
        assert_eq!(d.normal_velocity, 0.0);
        // Tangential q small enough for the cone: q_T = (-0.7, 0) needs r_T = 0.2 <= 0.5 r_N.
        let p = one_contact([1.0, 3.5, 3.5], [-1.0, -0.7, 0.0], 0.5);
        assert_eq!(status_of(&p, [1.0, 0.2, 0.0]).status, ContactStatus::Stick);
        // Too large for the cone: r = (1, 0.5, 0) on the boundary, u_T = 3.5 * 0.5 - 7 < 0.
        let p = one_contact([1.0, 3.5, 3.5], [-1.0, -7.0, 0.0], 0.5);
        let d = status_of(&p, [1.0, 0.5, 0.0]);
        assert_eq!(d.status, ContactStatus::Slide);
        assert!((d.tangential_velocity - 5.25).abs() < 1e-14);
        // Pulled away: r = 0, u = q with u_N = 2 > 0.
        let p = one_contact([1.0, 3.5, 3.5], [2.0, 0.3, 0.0], 0.5);
        let d = status_of(&p, [0.0; 3]);
        assert_eq!(d.status, ContactStatus::TakeOff);
        assert_eq!(d.normal_velocity, 2.0);
        // Grazing while slipping: u = (0, 0.5, 0), r = 0 (û = (0.25, 0.5, 0) on the dual cone's
        // boundary): apex.
        let p = one_contact([1.0, 3.5, 3.5], [0.0, 0.5, 0.0], 0.5);
        assert_eq!(status_of(&p, [0.0; 3]).status, ContactStatus::Apex);
        // Frictionless and pushed: slides (r_T = 0 whatever u_T).
        let p = one_contact([2.0, 1.0, 1.0], [-1.0, 0.4, 0.0], 0.0);
        assert_eq!(status_of(&p, [0.5, 0.0, 0.0]).status, ContactStatus::Slide);
    }

    #[test]
    fn tolerance_decides_near_zero() {
        // A reaction of 1e-9 next to one of 1: without force at tau = 1e-6, with force at 0.
        let data = vec![
            1.0, 0.0, 0.0, 0.0, 0.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 0.0, 1.0, 0.0, //
            0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ];
        let w = Delassus::Dense(DenseMatrix::new(6, 6, data).unwrap());
        let p =
            FrictionProblem::new(w, vec![-1.0, 0.0, 0.0, -1e-9, 0.0, 0.0], vec![0.5, 0.5]).unwrap();
        let r = [1.0, 0.0, 0.0, 1e-9, 0.0, 0.0];
        let d = diagnose(&p, &r, &DiagnosticOptions::default()).unwrap();
        assert_eq!(d.contacts[1].status, ContactStatus::Apex);
        let d = diagnose(&p, &r, &DiagnosticOptions { tolerance: 0.0 }).unwrap();
        assert_eq!(d.contacts[1].status, ContactStatus::Stick);
        assert!(diagnose(&p, &r, &DiagnosticOptions { tolerance: -1.0 }).is_err());
        assert!(diagnose(&p, &r[..3], &DiagnosticOptions::default()).is_err());
    }

    #[test]
    fn contributions_add_up_to_the_error() {
        let p = crate::scenes::default_scenes()
            .into_iter()
            .find(|s| s.name == "box_stack")
            .unwrap()
            .problem;
        let r: Vec<f64> = (0..p.size())
            .map(|i| 0.01 * (i % 3) as f64 + 0.02)
            .collect();
        let d = diagnose(&p, &r, &DiagnosticOptions::default()).unwrap();
        let mut u = vec![0.0; p.size()];
        let e = crate::measure::natural_map_error(&p, &r, &mut u);
        assert!(
            (d.error - e).abs() <= 1e-14 * e.max(1.0),
            "{} vs {e}",
            d.error
        );
        let worst = d.worst(3);
        assert_eq!(worst.len(), 3);
        let top = d.contacts[worst[0]].error_contribution;
        assert!(d.contacts.iter().all(|c| c.error_contribution <= top));
    }

    #[test]
    fn worst_orders_by_value_then_index_nan_first() {
        let v = [0.1, 0.5, f64::NAN, 0.5, 0.0];
        assert_eq!(worst_contacts(v.into_iter(), 3), vec![2, 1, 3]);
        assert_eq!(worst_contacts(v.into_iter(), 10).len(), 5);
    }
}
