//! Restarted GMRES with right preconditioning, its Krylov basis allocated once: solves
//! `A x = b` for a non-symmetric A given by its product, with `P^-1` applied in place (the
//! Newton steps of the global SSN-ALM: A the true Newton matrix, P its symmetric part
//! factored).

use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{dot, norm};

/// GMRES(`restart`) work space for systems of size n.
pub struct Gmres {
    n: usize,
    restart: usize,
    /// The Krylov basis, `restart + 1` vectors of n, one after the other.
    basis: Vec<f64>,
    /// The preconditioned directions `P^-1 v_j` (right preconditioning keeps them for the
    /// update of x), `restart` vectors.
    directions: Vec<f64>,
    /// The Hessenberg matrix column by column (`restart + 1` entries a column), the Givens
    /// rotations and the rotated right-hand side.
    hessenberg: Vec<f64>,
    cosines: Vec<f64>,
    sines: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
    work: Vec<f64>,
}

/// What a GMRES solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresOutcome {
    /// Products with A (one an inner iteration, one a restart).
    pub products: usize,
    /// `||b - A x|| / ||b||` at the end.
    pub relative_residual: f64,
}

impl Gmres {
    pub fn new(n: usize, restart: usize) -> Result<Self, Fc3dError> {
        let restart = restart.max(1);
        let what = "the GMRES Krylov basis";
        Ok(Gmres {
            n,
            restart,
            basis: try_vec(n.saturating_mul(restart + 1), 0.0, what)?,
            directions: try_vec(n.saturating_mul(restart), 0.0, what)?,
            hessenberg: try_vec((restart + 1) * restart, 0.0, what)?,
            cosines: try_vec(restart, 0.0, what)?,
            sines: try_vec(restart, 0.0, what)?,
            g: try_vec(restart + 1, 0.0, what)?,
            y: try_vec(restart, 0.0, what)?,
            work: try_vec(n, 0.0, what)?,
        })
    }

    /// Solves `A x = b` from the initial guess in `x` until `||b - A x|| <= tolerance ||b||`
    /// or `max_products` products with A. `apply(x, y)` writes `y = A x`; `precondition(z)`
    /// replaces z by `P^-1 z`.
    pub fn solve(
        &mut self,
        mut apply: impl FnMut(&[f64], &mut [f64]),
        mut precondition: impl FnMut(&mut [f64]),
        b: &[f64],
        x: &mut [f64],
        tolerance: f64,
        max_products: usize,
    ) -> GmresOutcome {
        let (n, m) = (self.n, self.restart);
        let b_norm = norm(b);
        if b_norm == 0.0 {
            x.iter_mut().for_each(|v| *v = 0.0);
            return GmresOutcome {
                products: 0,
                relative_residual: 0.0,
            };
        }
        let mut products = 0;
        loop {
            // r0 = b - A x into the first basis vector.
            apply(x, &mut self.work);
            products += 1;
            let (v0, _) = self.basis.split_at_mut(n);
            for i in 0..n {
                v0[i] = b[i] - self.work[i];
            }
            let beta = norm(v0);
            let relative = beta / b_norm;
            if relative <= tolerance || products >= max_products || !beta.is_finite() {
                return GmresOutcome {
                    products,
                    relative_residual: relative,
                };
            }
            v0.iter_mut().for_each(|v| *v /= beta);
            self.g.iter_mut().for_each(|v| *v = 0.0);
            self.g[0] = beta;
            let mut k = 0;
            let mut residual = beta;
            while k < m && products < max_products {
                // z_k = P^-1 v_k, w = A z_k.
                let z = &mut self.directions[k * n..(k + 1) * n];
                z.copy_from_slice(&self.basis[k * n..(k + 1) * n]);
                precondition(z);
                apply(z, &mut self.work);
                products += 1;
                // Modified Gram-Schmidt against v_0..v_k.
                let column = &mut self.hessenberg[k * (m + 1)..(k + 1) * (m + 1)];
                for j in 0..=k {
                    let vj = &self.basis[j * n..(j + 1) * n];
                    let h = dot(&self.work, vj);
                    column[j] = h;
                    for i in 0..n {
                        self.work[i] -= h * vj[i];
                    }
                }
                let h_next = norm(&self.work);
                column[k + 1] = h_next;
                if h_next > 0.0 {
                    let next = &mut self.basis[(k + 1) * n..(k + 2) * n];
                    for i in 0..n {
                        next[i] = self.work[i] / h_next;
                    }
                }
                // Apply the previous rotations, then the new one that zeroes h_{k+1,k}.
                for j in 0..k {
                    let (a, b2) = (column[j], column[j + 1]);
                    column[j] = self.cosines[j] * a + self.sines[j] * b2;
                    column[j + 1] = -self.sines[j] * a + self.cosines[j] * b2;
                }
                let (a, b2) = (column[k], column[k + 1]);
                let r = a.hypot(b2);
                let (c, s) = if r > 0.0 { (a / r, b2 / r) } else { (1.0, 0.0) };
                self.cosines[k] = c;
                self.sines[k] = s;
                column[k] = r;
                column[k + 1] = 0.0;
                self.g[k + 1] = -s * self.g[k];
                self.g[k] *= c;
                residual = self.g[k + 1].abs();
                k += 1;
                if residual <= tolerance * b_norm || h_next == 0.0 {
                    break;
                }
            }
            // y = R^-1 g (upper triangular k x k), x += sum_j y_j z_j.
            for i in (0..k).rev() {
                let mut s = self.g[i];
                for j in i + 1..k {
                    s -= self.hessenberg[j * (m + 1) + i] * self.y[j];
                }
                let d = self.hessenberg[i * (m + 1) + i];
                self.y[i] = if d != 0.0 { s / d } else { 0.0 };
            }
            for j in 0..k {
                let z = &self.directions[j * n..(j + 1) * n];
                for i in 0..n {
                    x[i] += self.y[j] * z[i];
                }
            }
            if residual <= tolerance * b_norm || products >= max_products {
                return GmresOutcome {
                    products,
                    relative_residual: residual / b_norm,
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric tridiagonal system, with and without a (Jacobi) preconditioner.
    #[test]
    fn solves_a_non_symmetric_system() {
        let n = 60;
        let apply = |x: &[f64], y: &mut [f64]| {
            for i in 0..n {
                let mut s = (3.0 + i as f64 * 0.1) * x[i];
                if i > 0 {
                    s -= 1.3 * x[i - 1];
                }
                if i + 1 < n {
                    s -= 0.4 * x[i + 1];
                }
                y[i] = s;
            }
        };
        let exact: Vec<f64> = (0..n).map(|i| (i as f64 * 0.21).cos()).collect();
        let mut b = vec![0.0; n];
        apply(&exact, &mut b);
        for restart in [5, 60] {
            let mut gmres = Gmres::new(n, restart).unwrap();
            let mut x = vec![0.0; n];
            let out = gmres.solve(
                apply,
                |z| {
                    for (i, v) in z.iter_mut().enumerate() {
                        *v /= 3.0 + i as f64 * 0.1;
                    }
                },
                &b,
                &mut x,
                1e-12,
                1000,
            );
            assert!(out.relative_residual <= 1e-12, "{out:?}");
            for (a, e) in x.iter().zip(&exact) {
                assert!((a - e).abs() < 1e-9);
            }
        }
        // The product limit holds.
        let mut gmres = Gmres::new(n, 10).unwrap();
        let mut x = vec![0.0; n];
        let out = gmres.solve(apply, |_| {}, &b, &mut x, 1e-14, 7);
        assert!(out.products <= 7, "{out:?}");
    }
}
