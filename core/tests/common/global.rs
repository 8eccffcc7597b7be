//! What every global result must satisfy, checked without the crate's own error code:
//! Siconos' `gfc3d_compute_error` recomputed entry by entry, `M v = q + H r` to round-off,
//! `u = H^T v + b`, and a status that agrees with the error.

use super::honesty::norm;
use fc3d_core::global::{solve_global, GlobalConfig, GlobalProblem, GlobalReport};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

/// A generated pile of `contacts` contacts in the global form (seed 7).
pub fn scene(contacts: usize, shape: PileShape) -> GlobalProblem<'static> {
    GeneratedScene {
        pile: PileSpec {
            contacts,
            piles: 1,
            seed: 7,
        },
        shape,
    }
    .generate_global()
    .unwrap()
}

/// Siconos' gfc3d_compute_error written out plainly (dense loops over the stored entries, the
/// cone projection by its three cases), independent of the library's measure; with `coulomb`
/// false, its convex variant (no De Saxcé term).
pub fn independent_error_of(p: &GlobalProblem, r: &[f64], v: &[f64], coulomb: bool) -> f64 {
    let n = p.ndof();
    let mut hr = vec![0.0; n];
    p.h().for_each_entry(|i, j, x| hr[i] += x * r[j]);
    let mut mv = vec![0.0; n];
    p.m().for_each_entry(|i, j, x| mv[i] += x * v[j]);
    let balance: Vec<f64> = (0..n).map(|i| p.q()[i] + hr[i] - mv[i]).collect();
    let scale1 = norm(p.q()).max(norm(&mv)).max(norm(&hr));
    let e1 = if scale1 > f64::EPSILON {
        norm(&balance) / scale1
    } else {
        norm(&balance)
    };
    let mut u = p.b().to_vec();
    p.h().for_each_entry(|i, j, x| u[j] += x * v[i]);
    let mut s = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let ut = if coulomb {
            (uc[1] * uc[1] + uc[2] * uc[2]).sqrt()
        } else {
            0.0
        };
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let xt = (x[1] * x[1] + x[2] * x[2]).sqrt();
        let proj = if x[0] >= 0.0 && xt <= mu * x[0] {
            x
        } else if mu * xt <= -x[0] {
            [0.0; 3]
        } else {
            let a = (x[0] + mu * xt) / (1.0 + mu * mu);
            [a, mu * a * x[1] / xt, mu * a * x[2] / xt]
        };
        s += (0..3).map(|k| (rc[k] - proj[k]).powi(2)).sum::<f64>();
    }
    let scale2 = norm(&u).max(norm(r));
    let e2 = if scale2 > f64::EPSILON {
        s.sqrt() / scale2
    } else {
        s.sqrt()
    };
    e1 + e2
}

/// The global (Coulomb) error, recomputed.
pub fn independent_error(p: &GlobalProblem, r: &[f64], v: &[f64]) -> f64 {
    independent_error_of(p, r, v, true)
}

/// Checks a returned triple and its report: the reported error is the recomputed one,
/// `M v = q + H r` to round-off, `u = H^T v + b`, and the status agrees with the tolerance.
pub fn check_triple(
    p: &GlobalProblem,
    config: &GlobalConfig,
    report: &GlobalReport,
    r: &[f64],
    u: &[f64],
    v: &[f64],
) {
    let expected = independent_error(p, r, v);
    assert!(
        (report.error - expected).abs() <= 1e-9 * expected.max(1e-300) + 1e-15,
        "{}: reported {:e}, recomputed {expected:e}",
        config.method.label(),
        report.error
    );
    let n = p.ndof();
    let mut residual: Vec<f64> = p.q().iter().map(|x| -x).collect();
    p.m().for_each_entry(|i, j, x| residual[i] += x * v[j]);
    p.h().for_each_entry(|i, j, x| residual[i] -= x * r[j]);
    let scale = norm(p.q()).max(1.0);
    assert!(
        norm(&residual) <= 1e-12 * scale * n as f64,
        "balance {:e}",
        norm(&residual)
    );
    let mut uu = p.b().to_vec();
    p.h().for_each_entry(|i, j, x| uu[j] += x * v[i]);
    for (a, b) in u.iter().zip(&uu) {
        assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()));
    }
    if report.converged() {
        assert!(report.error <= config.tolerance);
    } else {
        assert!(report.error > config.tolerance);
    }
}

/// Solves from zero and checks the triple and the report; returns the report and `(r, u, v)`.
pub fn solve_checked(
    p: &GlobalProblem,
    config: &GlobalConfig,
) -> (GlobalReport, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut r, mut u, mut v) = (
        vec![0.0; p.size()],
        vec![0.0; p.size()],
        vec![0.0; p.ndof()],
    );
    let report = solve_global(p, config, &mut r, &mut u, &mut v).unwrap();
    check_triple(p, config, &report, &r, &u, &v);
    (report, r, u, v)
}

/// [`solve_checked`]'s report.
pub fn check(p: &GlobalProblem, config: &GlobalConfig) -> GlobalReport {
    solve_checked(p, config).0
}
