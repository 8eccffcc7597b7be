//! The exact one-contact solve of a 2D problem: FC(w, q, mu) with a 2x2 `w`, components
//! `(N, T)`, the cone `|r_T| <= mu r_N`. The law has four branches, each a linear problem with
//! a closed-form solution: take-off (`r = 0`), stick (`u = 0`), and sliding on either side of
//! the cone (`r_T = -+ mu r_N` with `u_N = 0` and `u_T` of the matching sign). The solve tries
//! them in that order and returns the first consistent one, so it is exact up to the rounding
//! of a 2x2 solve; nothing iterates and nothing allocates.

use crate::math::linalg::Block;
use crate::measure::contact_residual_sq_d;

/// The branch of the 2D Coulomb law a one-contact solution lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanarBranch {
    /// `r = 0`, `u_N >= 0`.
    TakeOff,
    /// `u = 0`, `|r_T| <= mu r_N`.
    Stick,
    /// `u_N = 0`, `u_T >= 0`, `r_T = -mu r_N`.
    SlidePositive,
    /// `u_N = 0`, `u_T <= 0`, `r_T = mu r_N`.
    SlideNegative,
}

/// The answer of [`solve_planar_contact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarSolution {
    pub r: [f64; 2],
    pub branch: PlanarBranch,
    /// The branch's conditions hold exactly. When no branch is consistent (a `w` far from
    /// positive definite, or a contact on the edge between two branches where rounding breaks
    /// both), the candidate with the smallest natural-map residual is returned with `false`.
    pub consistent: bool,
}

/// Solves the 2D one-contact problem `u = w r + q`, `K* ∋ (u_N + mu |u_T|, u_T) ⟂ r ∈ K`.
/// `None` when no branch gives a finite candidate (a singular `w` with `W_NN -+ mu W_NT <= 0`).
pub fn solve_planar_contact(w: &Block<2>, q: &[f64; 2], mu: f64) -> Option<PlanarSolution> {
    let [[wnn, wnt], [wtn, wtt]] = *w;
    let (qn, qt) = (q[0], q[1]);
    if qn >= 0.0 {
        return Some(PlanarSolution {
            r: [0.0, 0.0],
            branch: PlanarBranch::TakeOff,
            consistent: true,
        });
    }
    let mut best: Option<(f64, PlanarSolution)> = None;
    let mut offer =
        |r: [f64; 2], branch: PlanarBranch, consistent: bool| -> Option<PlanarSolution> {
            if !(r[0].is_finite() && r[1].is_finite()) {
                return None;
            }
            let s = PlanarSolution {
                r,
                branch,
                consistent,
            };
            if consistent {
                return Some(s);
            }
            let u = [wnn * r[0] + wnt * r[1] + qn, wtn * r[0] + wtt * r[1] + qt];
            let res = contact_residual_sq_d::<2>(&r, &u, mu);
            if best.is_none_or(|(b, _)| res < b) {
                best = Some((res, s));
            }
            None
        };

    // Stick: w r = -q.
    let det = wnn * wtt - wnt * wtn;
    if det != 0.0 {
        let rn = (wnt * qt - wtt * qn) / det;
        let rt = (wtn * qn - wnn * qt) / det;
        let ok = rn >= 0.0 && rt.abs() <= mu * rn;
        if let Some(s) = offer([rn, rt], PlanarBranch::Stick, ok) {
            return Some(s);
        }
    }
    // Sliding with u_T >= 0: r_T = -mu r_N, u_N = 0.
    let den = wnn - mu * wnt;
    if den > 0.0 {
        let rn = -qn / den;
        let ut = qt + (wtn - mu * wtt) * rn;
        if let Some(s) = offer([rn, -mu * rn], PlanarBranch::SlidePositive, ut >= 0.0) {
            return Some(s);
        }
    }
    // Sliding with u_T <= 0: r_T = mu r_N, u_N = 0.
    let den = wnn + mu * wnt;
    if den > 0.0 {
        let rn = -qn / den;
        let ut = qt + (wtn + mu * wtt) * rn;
        if let Some(s) = offer([rn, mu * rn], PlanarBranch::SlideNegative, ut <= 0.0) {
            return Some(s);
        }
    }
    best.map(|(_, s)| s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::linalg::block_vec_add;
    use proptest::prelude::*;

    fn residual(w: &Block<2>, q: &[f64; 2], mu: f64, r: &[f64; 2]) -> f64 {
        contact_residual_sq_d::<2>(r, &block_vec_add(w, r, q), mu).sqrt()
    }

    #[test]
    fn the_four_branches() {
        let w = [[2.0, 0.5], [0.5, 1.0]];
        let mu = 0.5;
        // q_N >= 0: take-off.
        let s = solve_planar_contact(&w, &[1.0, -3.0], mu).unwrap();
        assert_eq!(
            (s.r, s.branch, s.consistent),
            ([0.0, 0.0], PlanarBranch::TakeOff, true)
        );
        // Stick: w r = -q with r = (1, 0.2) inside the cone.
        let r = [1.0, 0.2];
        let q = [-(2.0 * r[0] + 0.5 * r[1]), -(0.5 * r[0] + r[1])];
        let s = solve_planar_contact(&w, &q, mu).unwrap();
        assert_eq!(s.branch, PlanarBranch::Stick);
        assert!((s.r[0] - 1.0).abs() < 1e-15 && (s.r[1] - 0.2).abs() < 1e-15);
        // A large positive q_T pushes the contact to slide forward: r_T = -mu r_N.
        let s = solve_planar_contact(&w, &[-1.0, 5.0], mu).unwrap();
        assert_eq!(s.branch, PlanarBranch::SlidePositive);
        assert!(s.consistent);
        // r_N = 1 / (2 - 0.25), r_T = -r_N / 2.
        assert!((s.r[0] - 1.0 / 1.75).abs() < 1e-15);
        assert_eq!(s.r[1], -0.5 * s.r[0]);
        let s = solve_planar_contact(&w, &[-1.0, -5.0], mu).unwrap();
        assert_eq!(s.branch, PlanarBranch::SlideNegative);
        assert!((s.r[0] - 1.0 / 2.25).abs() < 1e-15);
        assert_eq!(s.r[1], 0.5 * s.r[0]);
        for q in [[-1.0, 5.0], [-1.0, -5.0], q, [1.0, -3.0]] {
            let s = solve_planar_contact(&w, &q, mu).unwrap();
            assert!(residual(&w, &q, mu, &s.r) < 1e-15);
        }
    }

    #[test]
    fn frictionless_and_singular_blocks() {
        // mu = 0: r_T = 0 and u_N = 0.
        let w = [[4.0, 1.0], [1.0, 3.0]];
        let s = solve_planar_contact(&w, &[-2.0, 1.0], 0.0).unwrap();
        assert_eq!(s.r, [0.5, 0.0]);
        // A rank-one block (two coupled constraints of one body): the stick system is
        // singular, the slides are not.
        let w = [[1.0, 1.0], [1.0, 1.0]];
        let s = solve_planar_contact(&w, &[-1.0, 0.0], 0.3).unwrap();
        assert!(s.consistent);
        assert!(residual(&w, &[-1.0, 0.0], 0.3, &s.r) < 1e-15);
        // No finite candidate at all.
        assert!(solve_planar_contact(&[[0.0, 0.0], [0.0, 0.0]], &[-1.0, 0.0], 0.3).is_none());
    }

    proptest! {
        /// On positive-definite (not necessarily symmetric) blocks a consistent branch exists
        /// for mu < 1, and its natural-map residual is rounding.
        #[test]
        fn exact_on_positive_definite_blocks(
            a in 0.1f64..10.0, d in 0.1f64..10.0, b in -1.0f64..1.0, skew in -0.5f64..0.5,
            qn in -10.0f64..10.0, qt in -10.0f64..10.0, mu in 0.0f64..1.0,
        ) {
            let off = b * (a * d).sqrt() * 0.9;
            let w = [[a, off + skew * a.min(d) * 0.1], [off - skew * a.min(d) * 0.1, d]];
            let q = [qn, qt];
            let s = solve_planar_contact(&w, &q, mu).unwrap();
            let scale = 1.0 + qn.abs() + qt.abs();
            prop_assert!(residual(&w, &q, mu, &s.r) <= 1e-12 * scale, "{:?}", s);
        }
    }
}
