//! The bench's own error measurement, independent of the solver's claim and of `fc3d_core::measure`:
//! `u = W r + q` with `Delassus::mul_add`, then the relative natural-map error (eq. 133 of
//! Acary-Brémond-Huber with Siconos' normalisation) from a projection written here.

use fc3d_core::problem::GlobalProblem;
use fc3d_core::FrictionProblem;

/// Projection on the Coulomb cone `{ x : ||x_T|| <= mu x_N }` (components `N, T1, T2`).
fn project_cone(x: [f64; 3], mu: f64) -> [f64; 3] {
    let (n, t) = (x[0], (x[1] * x[1] + x[2] * x[2]).sqrt());
    if n >= 0.0 && t <= mu * n {
        x // inside the cone
    } else if mu * t <= -n {
        [0.0; 3] // inside the polar cone
    } else {
        // Onto the boundary ray along x_T (t > 0 here).
        let pn = (n + mu * t) / (1.0 + mu * mu);
        let s = mu * pn / t;
        [pn, s * x[1], s * x[2]]
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Relative natural-map error of reaction `r`:
/// `||r - P_K(r - ũ)|| / max(||q||, ||r||, ||u||)` with `u = W r + q`,
/// `ũ_c = (u_N + mu_c ||u_T||, u_T)`; the denominator falls back to 1 when it is 0.
pub fn independent_error(problem: &FrictionProblem<'_>, r: &[f64]) -> f64 {
    let mut u = problem.q().to_vec();
    problem.w().mul_add(r, &mut u);
    let mut sum = 0.0;
    for (c, &mu) in problem.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let ut = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let p = project_cone(x, mu);
        sum += (0..3).map(|k| (rc[k] - p[k]).powi(2)).sum::<f64>();
    }
    let scale = norm(problem.q()).max(norm(r)).max(norm(&u));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// `y += A x` (`transpose`: `y += A^T x`) from A's compressed rows, written here.
fn csr_mul_add(a: &fc3d_core::CsrMatrix, x: &[f64], y: &mut [f64], transpose: bool) {
    let (ptr, idx, val) = (a.row_ptr(), a.col_idx(), a.values());
    for i in 0..a.nrows() {
        for k in ptr[i]..ptr[i + 1] {
            if transpose {
                y[idx[k]] += val[k] * x[i];
            } else {
                y[i] += val[k] * x[idx[k]];
            }
        }
    }
}

/// `x / scale`, or x itself when the scale is (about) zero, as Siconos normalises.
fn relative(x: f64, scale: f64) -> f64 {
    if scale > f64::EPSILON {
        x / scale
    } else {
        x
    }
}

/// Siconos' global error (`gfc3d_compute_error`) of `(r, v)`, recomputed here:
/// `||q + H r - M v|| / max(||q||, ||M v||, ||H r||)` plus the natural-map residual of
/// `(r, u)`, `u = H^T v + b`, over `max(||u||, ||r||)`.
pub fn independent_global_error(problem: &GlobalProblem<'_>, r: &[f64], v: &[f64]) -> f64 {
    let n = problem.ndof();
    let (mut hr, mut mv) = (vec![0.0; n], vec![0.0; n]);
    csr_mul_add(problem.h(), r, &mut hr, false);
    csr_mul_add(problem.m(), v, &mut mv, false);
    let balance: Vec<f64> = (0..n).map(|i| problem.q()[i] + hr[i] - mv[i]).collect();
    let balance_scale = norm(problem.q()).max(norm(&mv)).max(norm(&hr));
    let mut u = problem.b().to_vec();
    csr_mul_add(problem.h(), v, &mut u, true);
    let mut sum = 0.0;
    for (c, &mu) in problem.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let ut = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let p = project_cone(x, mu);
        sum += (0..3).map(|k| (rc[k] - p[k]).powi(2)).sum::<f64>();
    }
    relative(norm(&balance), balance_scale) + relative(sum.sqrt(), norm(&u).max(norm(r)))
}

/// Whether two measurements of the same error agree "within rounding": relative difference at
/// most 1e-6, or both at the rounding level of the normalised residual (below 1e-13 apart).
pub fn errors_agree(a: f64, b: f64) -> bool {
    if a.is_nan() || b.is_nan() {
        return false;
    }
    let d = (a - b).abs();
    d <= 1e-13 || d <= 1e-6 * a.abs().max(b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc3d_core::{natural_map_error, scenes::default_scenes, solve, NsgsOptions, SolverConfig};

    #[test]
    fn projection_cases() {
        assert_eq!(project_cone([1.0, 0.3, 0.4], 0.5), [1.0, 0.3, 0.4]);
        assert_eq!(project_cone([-1.0, 0.3, 0.4], 0.5), [0.0; 3]);
        // mu = 0: the cone is the half line R+ e_N.
        assert_eq!(project_cone([-1.0, 0.0, 0.0], 0.0), [0.0; 3]);
        assert_eq!(project_cone([2.0, 1.0, 0.0], 0.0), [2.0, 0.0, 0.0]);
        // Boundary: (0, 2, 0), mu = 1 -> ((0 + 2) / 2, 1, 0).
        let p = project_cone([0.0, 2.0, 0.0], 1.0);
        assert!((p[0] - 1.0).abs() < 1e-15 && (p[1] - 1.0).abs() < 1e-15 && p[2] == 0.0);
    }

    #[test]
    fn agrees_with_the_library_on_the_scenes() {
        for scene in default_scenes() {
            let p = &scene.problem;
            let n = p.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            // Both at the start (r = 0) and at a solution.
            let e0 = natural_map_error(p, &r, &mut u);
            assert!(errors_agree(independent_error(p, &r), e0), "{}", scene.name);
            let config = SolverConfig::new(NsgsOptions::default())
                .with_tolerance(1e-10)
                .with_max_iter(10_000);
            let report = solve(p, &config, &mut r, &mut u).unwrap();
            let e = independent_error(p, &r);
            assert!(
                errors_agree(e, report.error),
                "{}: {e} vs {}",
                scene.name,
                report.error
            );
        }
    }

    #[test]
    fn agreement_rule() {
        assert!(errors_agree(1e-8, 1e-8 * (1.0 + 1e-9)));
        assert!(errors_agree(1e-15, 3e-15));
        assert!(!errors_agree(1e-8, 2e-8));
        assert!(!errors_agree(1e-3, 1e-3 + 1e-8));
        assert!(!errors_agree(f64::NAN, 1.0));
    }
}
