//! What every returned result must satisfy, checked without the crate's own error code: the
//! natural-map error recomputed entry by entry (De Saxcé velocity, the projection on the cone
//! written from its dot-product form).

use fc3d_core::{FrictionProblem, SolveReport};

pub fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

pub fn cone_projection(x: [f64; 3], mu: f64) -> [f64; 3] {
    let nt = (x[1] * x[1] + x[2] * x[2]).sqrt();
    if x[0] >= 0.0 && nt <= mu * x[0] {
        return x;
    }
    if mu * nt <= -x[0] {
        return [0.0; 3];
    }
    let s = 1.0 / (1.0 + mu * mu).sqrt();
    let d = [s, s * mu * x[1] / nt, s * mu * x[2] / nt];
    let t = x[0] * d[0] + x[1] * d[1] + x[2] * d[2];
    [t * d[0], t * d[1], t * d[2]]
}

/// The natural-map error of `r` and `u = W r + q`, both recomputed here.
pub fn independent_error(p: &FrictionProblem<'_>, r: &[f64]) -> (f64, Vec<f64>) {
    let mut u = p.q().to_vec();
    p.w().for_each_entry(|i, j, v| u[i] += v * r[j]);
    let mut sum = 0.0;
    for (c, &mu) in p.mu().iter().enumerate() {
        let (rc, uc) = (&r[3 * c..3 * c + 3], &u[3 * c..3 * c + 3]);
        let ut = (uc[1] * uc[1] + uc[2] * uc[2]).sqrt();
        let x = [rc[0] - (uc[0] + mu * ut), rc[1] - uc[1], rc[2] - uc[2]];
        let pr = cone_projection(x, mu);
        sum += (0..3).map(|i| (rc[i] - pr[i]).powi(2)).sum::<f64>();
    }
    let scale = norm(p.q()).max(norm(r)).max(norm(&u));
    (sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }, u)
}

/// r and u finite, u = W r + q, the reported error is the recomputed one, status agrees.
pub fn check_report(
    name: &str,
    p: &FrictionProblem<'_>,
    tol: f64,
    rep: &SolveReport,
    r: &[f64],
    u: &[f64],
) {
    assert!(
        r.iter().chain(u).all(|v| v.is_finite()),
        "{name}: non-finite r or u"
    );
    let (e, u_ref) = independent_error(p, r);
    let su = norm(&u_ref).max(norm(p.q())).max(1e-300);
    for (a, b) in u.iter().zip(&u_ref) {
        assert!((a - b).abs() <= 1e-12 * su, "{name}: u {a} vs {b}");
    }
    assert!(
        (rep.error - e).abs() <= 1e-9 * e + 1e-14,
        "{name}: reported {:e}, recomputed {e:e}",
        rep.error
    );
    assert_eq!(rep.converged(), rep.error <= tol, "{name}");
}
