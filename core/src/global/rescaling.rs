//! Siconos' rescalings of a global problem (`iparam[3]` of 607 and 613), as exact
//! reformulations: with positive diagonal `D` (`ndof`) and `E` (`D nc`, one value per contact, so
//! that each cone is kept) and positive scalars `alpha`, `beta`,
//!
//! `M' = alpha D M D`, `q' = alpha D q`, `H' = beta D H E`, `b' = beta E b`
//!
//! is a global problem whose solutions are those of the original one through
//! `v = D v'`, `r = (beta / alpha) E r'`, `u = u' / (beta E)`: `M v = q + H r` holds exactly when
//! `M' v' = q' + H' r'` does, `u' = H'^T v' + b'`, and `r'` is in a contact's cone exactly when
//! `r` is, with `u'` a positive multiple of `u` (De Saxcé's term included).
//!
//! Siconos' choices, kept: *scalar* (`alpha = 1 / ||M||_inf`, `beta = 1 / ||H||_inf`, D = E = I);
//! *balancing of M* (Ruiz's equilibration of M in the max norm, D on both sides, E = I); *balancing
//! of `[[M, H], [H^T, 0]]`* (Ruiz's equilibration of that matrix, each contact's E taken from its
//! normal row). Siconos scales M by `D1 M D2` and H by `D2 H`, which is a reformulation only when
//! `D1 = D2` (a symmetric M); fc3d equilibrates rows and columns together (`D M D`), the same
//! scaling for a symmetric M and still exact for any other.

use crate::error::{try_vec, Fc3dError};
use crate::matrix::CsrMatrix;
use crate::problem::GlobalProblem;

/// A rescaling of a global problem before it is solved (Siconos' `iparam[3]` for 607 and 613).
/// The error reported is always measured on the original problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GlobalRescaling {
    /// The problem as given (Siconos' `RESCALING_NO`, the default).
    #[default]
    None,
    /// M and q divided by `||M||_inf`, H and b by `||H||_inf` (Siconos' `RESCALING_SCALAR`).
    Scalar,
    /// M equilibrated by Ruiz's method (Siconos' `RESCALING_BALANCING_M`).
    BalancingM,
    /// `[[M, H], [H^T, 0]]` equilibrated by Ruiz's method, one scale per contact
    /// (Siconos' `RESCALING_BALANCING_MHHT`).
    BalancingMhht,
}

/// Ruiz's iterations on M: Siconos' 5 at tolerance 1e-2, then up to 100 more at 1e-3 (its
/// `gfc3d_balancing_M` equilibrates again what `gfc3d_balancing_problem` equilibrated).
const BALANCING_M: (f64, usize) = (1e-3, 105);
/// Ruiz's iterations on `[[M, H], [H^T, 0]]`: Siconos' 5 at tolerance 1e-2.
const BALANCING_MHHT: (f64, usize) = (1e-2, 5);

/// The factors of a rescaling (see the module's documentation).
pub(super) struct Scaling {
    alpha: f64,
    beta: f64,
    d: Vec<f64>,
    e: Vec<f64>,
}

impl Scaling {
    pub(super) fn of<const D: usize>(
        problem: &GlobalProblem<'_, D>,
        rescaling: GlobalRescaling,
    ) -> Result<Scaling, Fc3dError> {
        let (m, h) = (problem.m(), problem.h());
        let mut d = try_vec(problem.ndof(), 1.0, "the rescaling of the global velocity")?;
        let mut e = try_vec(problem.size(), 1.0, "the rescaling of the reaction")?;
        let (mut alpha, mut beta) = (1.0, 1.0);
        match rescaling {
            GlobalRescaling::None => {}
            GlobalRescaling::Scalar => {
                alpha = positive_inverse(inf_norm(m));
                beta = positive_inverse(inf_norm(h));
            }
            GlobalRescaling::BalancingM => {
                let (tolerance, iterations) = BALANCING_M;
                let mut row_max = try_vec(problem.ndof(), 0.0, "the balancing of M")?;
                for _ in 0..iterations {
                    row_max.iter_mut().for_each(|x| *x = 0.0);
                    scaled_max(m, &d, &d, &mut row_max, None);
                    if equilibrate(&mut d, &row_max) <= tolerance {
                        break;
                    }
                }
            }
            GlobalRescaling::BalancingMhht => {
                let (tolerance, iterations) = BALANCING_MHHT;
                let mut row_max = try_vec(problem.ndof(), 0.0, "the balancing of M and H")?;
                let mut col_max = try_vec(problem.size(), 0.0, "the balancing of M and H")?;
                for _ in 0..iterations {
                    row_max.iter_mut().for_each(|x| *x = 0.0);
                    col_max.iter_mut().for_each(|x| *x = 0.0);
                    scaled_max(m, &d, &d, &mut row_max, None);
                    scaled_max(h, &d, &e, &mut row_max, Some(&mut col_max));
                    let error = equilibrate(&mut d, &row_max).max(equilibrate(&mut e, &col_max));
                    if error <= tolerance {
                        break;
                    }
                }
                // One scale per contact, its normal row's, so that each cone is kept.
                for contact in e.chunks_exact_mut(D) {
                    let normal = contact[0];
                    contact.iter_mut().for_each(|x| *x = normal);
                }
            }
        }
        Ok(Scaling { alpha, beta, d, e })
    }

    /// The rescaled problem.
    pub(super) fn apply<const D: usize>(
        &self,
        problem: &GlobalProblem<'_, D>,
    ) -> Result<GlobalProblem<'static, D>, Fc3dError> {
        let mut m = problem.m().try_clone()?;
        m.scale_entries(|i, j, x| self.alpha * self.d[i] * x * self.d[j]);
        let mut h = problem.h().try_clone()?;
        h.scale_entries(|i, k, x| self.beta * self.d[i] * x * self.e[k]);
        let mut q = try_vec(problem.ndof(), 0.0, "the rescaled q")?;
        for ((q, &qi), &di) in q.iter_mut().zip(problem.q()).zip(&self.d) {
            *q = self.alpha * di * qi;
        }
        let mut b = try_vec(problem.size(), 0.0, "the rescaled b")?;
        for ((b, &bi), &ei) in b.iter_mut().zip(problem.b()).zip(&self.e) {
            *b = self.beta * ei * bi;
        }
        let mut mu = try_vec(problem.n_contacts(), 0.0, "the coefficients of friction")?;
        mu.copy_from_slice(problem.mu());
        GlobalProblem::new(m, h, q, b, mu)
    }

    /// `(r', u', v')` of the rescaled problem from `(r, u, v)`.
    pub(super) fn to_rescaled(
        &self,
        (r, u, v): (&[f64], &[f64], &[f64]),
        (rs, us, vs): (&mut [f64], &mut [f64], &mut [f64]),
    ) {
        let ratio = self.alpha / self.beta;
        for (((rs, us), (&r, &u)), &e) in rs
            .iter_mut()
            .zip(us.iter_mut())
            .zip(r.iter().zip(u))
            .zip(&self.e)
        {
            *rs = ratio * r / e;
            *us = self.beta * e * u;
        }
        for ((vs, &v), &d) in vs.iter_mut().zip(v).zip(&self.d) {
            *vs = v / d;
        }
    }

    /// `(r, u, v)` of the original problem from `(r', u', v')`.
    pub(super) fn to_original(
        &self,
        (rs, us, vs): (&[f64], &[f64], &[f64]),
        (r, u, v): (&mut [f64], &mut [f64], &mut [f64]),
    ) {
        let ratio = self.beta / self.alpha;
        for (((r, u), (&rs, &us)), &e) in r
            .iter_mut()
            .zip(u.iter_mut())
            .zip(rs.iter().zip(us))
            .zip(&self.e)
        {
            *r = ratio * e * rs;
            *u = us / (self.beta * e);
        }
        for ((v, &vs), &d) in v.iter_mut().zip(vs).zip(&self.d) {
            *v = d * vs;
        }
    }
}

/// `1 / x`, or 1 for a zero norm (a matrix without entries is left as it is).
fn positive_inverse(x: f64) -> f64 {
    if x > 0.0 {
        1.0 / x
    } else {
        1.0
    }
}

/// The largest row sum of absolute values.
fn inf_norm(a: &CsrMatrix) -> f64 {
    let (ptr, values) = (a.row_ptr(), a.values());
    ptr.windows(2)
        .map(|w| values[w[0]..w[1]].iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The largest `|left_i a_ij right_j|` of each row into `row_max` and of each column into
/// `col_max` when given, else (a square matrix equilibrated on both sides) into `row_max` too.
fn scaled_max(
    a: &CsrMatrix,
    left: &[f64],
    right: &[f64],
    row_max: &mut [f64],
    mut col_max: Option<&mut [f64]>,
) {
    let (ptr, cols, values) = (a.row_ptr(), a.col_idx(), a.values());
    for i in 0..a.nrows() {
        for k in ptr[i]..ptr[i + 1] {
            let j = cols[k];
            let x = (left[i] * values[k] * right[j]).abs();
            row_max[i] = row_max[i].max(x);
            match col_max.as_deref_mut() {
                Some(col) => col[j] = col[j].max(x),
                None => row_max[j] = row_max[j].max(x),
            }
        }
    }
}

/// One step of Ruiz's method: each scale divided by the square root of its row's largest
/// entry (rows without entries keep theirs). Returns `max |1 - largest entry|` before the step.
fn equilibrate(scale: &mut [f64], largest: &[f64]) -> f64 {
    let mut error: f64 = 0.0;
    for (s, &l) in scale.iter_mut().zip(largest) {
        if l > 0.0 {
            error = error.max((1.0 - l).abs());
            *s /= l.sqrt();
        }
    }
    error
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{global_error, ContactLaw};

    /// Two bodies of 3 dofs with badly scaled masses, two contacts.
    fn problem() -> GlobalProblem<'static> {
        let m = CsrMatrix::from_triplets(
            6,
            6,
            &[
                (0, 0, 1e4),
                (1, 1, 1e4),
                (2, 2, 2e4),
                (2, 5, 5.0),
                (5, 2, 5.0),
                (3, 3, 1e-2),
                (4, 4, 3e-2),
                (5, 5, 1e-2),
            ],
        )
        .unwrap();
        let h = CsrMatrix::from_triplets(
            6,
            6,
            &[
                (2, 0, 1.0),
                (0, 1, 1.0),
                (1, 2, 1.0),
                (5, 3, 1.0),
                (2, 3, -1.0),
                (3, 4, 1.0),
                (4, 5, 1.0),
            ],
        )
        .unwrap();
        GlobalProblem::new(
            m,
            h,
            vec![1.0, -2.0, -3e4, 0.5, 0.2, -1.0],
            vec![0.0, 0.1, 0.0, 0.01, 0.0, 0.2],
            vec![0.3, 0.5],
        )
        .unwrap()
    }

    /// Every rescaling maps a triple of the original problem to one of the rescaled problem
    /// with the same residuals up to the scaling: `M v - q - H r` is `D^-1 / alpha` times
    /// `M' v' - q' - H' r'`, u' = H'^T v' + b', and the error of a solution is kept.
    #[test]
    fn every_rescaling_is_an_exact_reformulation() {
        let p = problem();
        let r = [0.5, 0.1, -0.1, 2.0, 0.3, 0.2];
        for rescaling in [
            GlobalRescaling::None,
            GlobalRescaling::Scalar,
            GlobalRescaling::BalancingM,
            GlobalRescaling::BalancingMhht,
        ] {
            let s = Scaling::of(&p, rescaling).unwrap();
            let scaled = s.apply(&p).unwrap();
            // v solving the balance for r, in both problems.
            let mut operator = p.operator().unwrap();
            let mut v = vec![0.0; 6];
            operator.global_velocity(p.q(), &r, &mut v);
            let mut u = vec![0.0; 6];
            let error = global_error(&p, ContactLaw::Coulomb, &r, &mut u, &v);
            let (mut rs, mut us, mut vs) = (vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]);
            s.to_rescaled((&r, &u, &v), (&mut rs, &mut us, &mut vs));
            let mut scaled_operator = scaled.operator().unwrap();
            let mut v_check = vec![0.0; 6];
            scaled_operator.global_velocity(scaled.q(), &rs, &mut v_check);
            for (a, b) in v_check.iter().zip(&vs) {
                assert!(
                    (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "{rescaling:?}: {a} vs {b}"
                );
            }
            let mut u_check = vec![0.0; 6];
            global_error(&scaled, ContactLaw::Coulomb, &rs, &mut u_check, &vs);
            for (a, b) in u_check.iter().zip(&us) {
                assert!(
                    (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "{rescaling:?}: {a} vs {b}"
                );
            }
            // And back.
            let (mut r2, mut u2, mut v2) = (vec![0.0; 6], vec![0.0; 6], vec![0.0; 6]);
            s.to_original((&rs, &us, &vs), (&mut r2, &mut u2, &mut v2));
            for (a, b) in r2
                .iter()
                .zip(&r)
                .chain(v2.iter().zip(&v))
                .chain(u2.iter().zip(&u))
            {
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                    "{rescaling:?}: {a} vs {b}"
                );
            }
            assert!(error.is_finite());
        }
    }

    /// Balancing brings M's largest entries per row to 1 and keeps one scale per contact.
    #[test]
    fn balancing_equilibrates_and_keeps_the_cones() {
        let p = problem();
        let s = Scaling::of(&p, GlobalRescaling::BalancingM).unwrap();
        let scaled = s.apply(&p).unwrap();
        let mut row_max = vec![0.0; 6];
        scaled_max(scaled.m(), &[1.0; 6], &[1.0; 6], &mut row_max, None);
        assert!(
            row_max.iter().all(|x| (x - 1.0).abs() <= 1e-3),
            "{row_max:?}"
        );
        let s = Scaling::of(&p, GlobalRescaling::BalancingMhht).unwrap();
        for contact in s.e.chunks_exact(3) {
            assert!(contact.iter().all(|&x| x == contact[0] && x > 0.0));
        }
        assert!(s.d.iter().all(|&x| x > 0.0 && x.is_finite()));
    }
}
