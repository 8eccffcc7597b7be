//! Extreme eigenvalues of a symmetric operator given only by its products: the Lanczos
//! recurrence (no reorthogonalization) and the extreme eigenvalues of its tridiagonal matrix by
//! Sturm-sequence bisection.
//!
//! Without reorthogonalization the Lanczos vectors lose orthogonality once a Ritz value has
//! converged, which only repeats converged Ritz values ("ghosts"); the extreme Ritz values stay
//! within rounding of `[lambda_min, lambda_max]` (Paige) and move monotonically towards the
//! extreme eigenvalues, so they are what this module reports: the largest Ritz value is a lower
//! bound of the largest eigenvalue after a few steps, the smallest an upper bound of the smallest
//! that needs about `sqrt(condition number)` steps to settle. The operator may be self-adjoint in
//! an inner product other than the Euclidean one (`M`-products for `M^-1 A`), given as a closure.

use crate::error::{try_vec, Fc3dError};

/// The Lanczos recurrence on an operator of size `n`, one step at a time. The vectors are
/// allocated once, at construction; a step allocates only when its coefficient lists grow past
/// the capacity asked for.
#[derive(Debug, Clone)]
pub struct Lanczos {
    alpha: Vec<f64>,
    beta: Vec<f64>,
    v_prev: Vec<f64>,
    v: Vec<f64>,
    w: Vec<f64>,
    /// The Krylov space is invariant (the last `beta` is zero to rounding): no further step.
    exhausted: bool,
}

impl Lanczos {
    /// A recurrence of size `n` with room for `steps` steps, not started.
    pub fn new(n: usize, steps: usize) -> Result<Self, Fc3dError> {
        const WHAT: &str = "the Lanczos vectors";
        let mut alpha = try_vec(steps, 0.0, WHAT)?;
        let mut beta = try_vec(steps, 0.0, WHAT)?;
        alpha.clear();
        beta.clear();
        Ok(Lanczos {
            alpha,
            beta,
            v_prev: try_vec(n, 0.0, WHAT)?,
            v: try_vec(n, 0.0, WHAT)?,
            w: try_vec(n, 0.0, WHAT)?,
            exhausted: false,
        })
    }

    /// Starts (again) from `start` (normalized in `inner`; not zero). Returns false when
    /// `start` has no positive finite norm.
    pub fn start(&mut self, start: &[f64], inner: impl Fn(&[f64], &[f64]) -> f64) -> bool {
        self.alpha.clear();
        self.beta.clear();
        self.v_prev.iter_mut().for_each(|x| *x = 0.0);
        let norm = inner(start, start).sqrt();
        self.exhausted = !(norm > 0.0 && norm.is_finite());
        if !self.exhausted {
            for (v, s) in self.v.iter_mut().zip(start) {
                *v = s / norm;
            }
        }
        !self.exhausted
    }

    /// The start vector of the Lanczos iteration on `n` unknowns used by the solvers: fixed (so
    /// that results are reproducible) and without structure a pile could align with.
    pub fn default_start(out: &mut [f64]) {
        for (i, x) in out.iter_mut().enumerate() {
            // A low-discrepancy sequence in [0.5, 1.5): all components positive, none equal.
            *x = 0.5 + ((i as f64 + 1.0) * 0.618_033_988_749_894_9).fract();
        }
    }

    /// One step: `w = A v - alpha v - beta v_prev` with `apply(v, w)` writing `A v` into `w`
    /// (overwritten). Returns false (and does nothing) once the Krylov space is invariant or a
    /// product is not finite.
    pub fn step(
        &mut self,
        mut apply: impl FnMut(&[f64], &mut [f64]),
        inner: impl Fn(&[f64], &[f64]) -> f64,
    ) -> bool {
        if self.exhausted {
            return false;
        }
        apply(&self.v, &mut self.w);
        let alpha = inner(&self.w, &self.v);
        let beta_prev = self.beta.last().copied().unwrap_or(0.0);
        for ((w, v), p) in self.w.iter_mut().zip(&self.v).zip(&self.v_prev) {
            *w -= alpha * v + beta_prev * p;
        }
        let beta = inner(&self.w, &self.w).max(0.0).sqrt();
        if !(alpha.is_finite() && beta.is_finite()) {
            self.exhausted = true;
            return false;
        }
        self.alpha.push(alpha);
        self.beta.push(beta);
        // An invariant subspace: the Ritz values are eigenvalues.
        if beta <= 1e-14 * (alpha.abs() + beta_prev) {
            self.exhausted = true;
            return true;
        }
        std::mem::swap(&mut self.v_prev, &mut self.v);
        for (v, w) in self.v.iter_mut().zip(&self.w) {
            *v = w / beta;
        }
        true
    }

    /// Steps done.
    pub fn steps(&self) -> usize {
        self.alpha.len()
    }

    /// The smallest and largest Ritz values (eigenvalues of the tridiagonal matrix of the steps
    /// done); `None` before the first step.
    pub fn extremes(&self) -> Option<(f64, f64)> {
        let k = self.alpha.len();
        (k > 0).then(|| {
            let off = &self.beta[..k - 1];
            (
                tridiagonal_eigenvalue(&self.alpha, off, 0),
                tridiagonal_eigenvalue(&self.alpha, off, k - 1),
            )
        })
    }

    /// The last `beta`: the norm of the part of `A v` outside the Krylov space.
    pub fn residual(&self) -> f64 {
        self.beta.last().copied().unwrap_or(0.0)
    }
}

/// The number of eigenvalues below `x` of the symmetric tridiagonal matrix with diagonal `diag`
/// and off-diagonal `off` (Sturm sequence: the negative pivots of `T - x I = L D L^T`).
fn count_below(diag: &[f64], off: &[f64], x: f64) -> usize {
    let mut count = 0;
    let mut d = 1.0;
    for (i, &a) in diag.iter().enumerate() {
        let b2 = if i > 0 { off[i - 1] * off[i - 1] } else { 0.0 };
        d = a - x - if i > 0 { b2 / d } else { 0.0 };
        if d == 0.0 {
            // Perturb an exact zero pivot: the count is that of a nearby x.
            d = -f64::EPSILON * (a.abs() + x.abs()).max(f64::MIN_POSITIVE);
        }
        if d < 0.0 {
            count += 1;
        }
    }
    count
}

/// Eigenvalue `index` (0 the smallest) of the symmetric tridiagonal matrix with diagonal `diag`
/// and off-diagonal `off` (`diag.len() - 1` entries), by bisection on the Sturm count inside the
/// Gershgorin interval, to the last bits.
pub fn tridiagonal_eigenvalue(diag: &[f64], off: &[f64], index: usize) -> f64 {
    let k = diag.len();
    assert!(
        index < k && off.len() + 1 == k,
        "tridiagonal_eigenvalue: sizes"
    );
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for i in 0..k {
        let radius =
            if i > 0 { off[i - 1].abs() } else { 0.0 } + if i + 1 < k { off[i].abs() } else { 0.0 };
        lo = lo.min(diag[i] - radius);
        hi = hi.max(diag[i] + radius);
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if count_below(diag, off, mid) > index {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The Euclidean inner product (the operator is symmetric).
pub fn euclidean(a: &[f64], b: &[f64]) -> f64 {
    crate::math::linalg::dot(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tridiagonal_eigenvalues_of_the_second_difference() {
        // T = tridiag(-1, 2, -1) of size k: eigenvalues 2 - 2 cos(j pi / (k + 1)).
        let k = 50;
        let diag = vec![2.0; k];
        let off = vec![-1.0; k - 1];
        for j in [0, 1, k / 2, k - 1] {
            let exact = 2.0 - 2.0 * ((j + 1) as f64 * std::f64::consts::PI / (k + 1) as f64).cos();
            let got = tridiagonal_eigenvalue(&diag, &off, j);
            assert!((got - exact).abs() <= 1e-14, "{j}: {got} against {exact}");
        }
    }

    #[test]
    fn lanczos_finds_the_extremes_of_a_diagonal_operator() {
        // A = diag(1, 2, ..., 400) with a cluster at the top: Ritz extremes converge to 1 and 400.
        let n = 400;
        let d: Vec<f64> = (1..=n).map(|i| i as f64).collect();
        let mut start = vec![0.0; n];
        Lanczos::default_start(&mut start);
        let mut lanczos = Lanczos::new(n, 200).unwrap();
        assert!(lanczos.start(&start, euclidean));
        let apply = |x: &[f64], y: &mut [f64]| {
            for ((y, x), d) in y.iter_mut().zip(x).zip(&d) {
                *y = d * x;
            }
        };
        for _ in 0..200 {
            lanczos.step(apply, euclidean);
        }
        let (lo, hi) = lanczos.extremes().unwrap();
        assert!((hi - 400.0).abs() <= 1e-8 * 400.0, "{hi}");
        assert!((lo - 1.0).abs() <= 1e-8, "{lo}");
        // A few steps already give the largest within a few per cent, from below.
        lanczos.start(&start, euclidean);
        for _ in 0..10 {
            lanczos.step(apply, euclidean);
        }
        let (_, hi10) = lanczos.extremes().unwrap();
        assert!(
            (0.9 * 400.0..=400.0 * (1.0 + 1e-12)).contains(&hi10),
            "{hi10}"
        );
    }

    #[test]
    fn lanczos_in_a_weighted_inner_product() {
        // A = M^-1 K with M = diag(m), K = diag(k): self-adjoint in <x, y>_M, eigenvalues k/m.
        let m = [2.0, 0.5, 1.0, 4.0];
        let k = [2.0, 3.0, 5.0, 1.0];
        let inner =
            |a: &[f64], b: &[f64]| a.iter().zip(b).zip(&m).map(|((a, b), m)| a * m * b).sum();
        let mut lanczos = Lanczos::new(4, 4).unwrap();
        assert!(lanczos.start(&[1.0, 1.0, 1.0, 1.0], inner));
        while lanczos.step(
            |x, y| {
                for i in 0..4 {
                    y[i] = k[i] / m[i] * x[i];
                }
            },
            inner,
        ) {}
        let (lo, hi) = lanczos.extremes().unwrap();
        assert!(
            (lo - 0.25).abs() <= 1e-12 && (hi - 6.0).abs() <= 1e-12,
            "{lo} {hi}"
        );
    }
}
