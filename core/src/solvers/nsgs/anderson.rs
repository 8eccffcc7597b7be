//! Anderson acceleration of the Gauss-Seidel sweep, with a safeguard.
//!
//! A sweep is a fixed-point map `G`: from the reactions `x` it returns `g = G(x)`, with the
//! residual `f = g - x`. On hyperstatic piles that map contracts very slowly (thousands of sweeps
//! to 1e-4 at 1k contacts), but its iterates move along a few slow directions that a short
//! history identifies. Anderson's type-II step combines the last `m` sweeps: with
//! `dG`, `dF` the differences of successive `g` and `f`, it solves the small least-squares
//! problem `min |f_k - dF gamma|` and proposes `x_{k+1} = g_k - dG gamma`. The point is not
//! projected on the cones: the sweep from it solves every contact again, so its output is
//! admissible, and a projection (tried) made the map less smooth and the run stagnate near 1.5e-4
//! on a 1k-contact pile.
//!
//! Safeguard: a proposed point is kept only if the sweep from it makes a residual no larger
//! than the one of the step that proposed it. Otherwise the run falls back to the plain sweep's
//! output `g_k` (the point Gauss-Seidel alone would have swept next) and the history starts
//! again. The error (133) is always measured on a sweep's output, never on an extrapolated
//! point, so the reported error is the one of the reactions returned.
//!
//! Everything here is sequential arithmetic in a fixed order on the sweep's output, and the
//! sweep is bitwise identical for any number of threads, so the accelerated run is too. Memory:
//! `2 m + 4` vectors of the size of r, allocated once before the first sweep; nothing in the loop
//! allocates.

use crate::error::{try_vec, Fc3dError};

/// Largest history the least-squares step keeps (the small system is solved on the stack).
pub const MAX_MEMORY: usize = 16;

/// State of an accelerated run.
pub(crate) struct Anderson {
    memory: usize,
    /// Differences of successive sweep outputs and residuals: ring buffers of `memory` columns.
    dg: Vec<Vec<f64>>,
    df: Vec<Vec<f64>>,
    /// Columns stored (<= memory) and the slot the next one goes to.
    stored: usize,
    next: usize,
    /// Gram matrix of the stored `df` columns, indexed by slot.
    gram: [[f64; MAX_MEMORY]; MAX_MEMORY],
    /// The input of the sweep under way.
    x_in: Vec<f64>,
    /// Output and residual of the last accepted sweep.
    g_last: Vec<f64>,
    f_last: Vec<f64>,
    has_last: bool,
    /// Work vector for the new residual.
    f_new: Vec<f64>,
    /// |f| of the last accepted sweep: the bound an extrapolated point must meet.
    reference: f64,
    /// Whether the sweep under way started from an extrapolated point.
    extrapolated: bool,
    /// Extrapolated points kept and refused (for reports and tests).
    pub accepted: usize,
    pub rejected: usize,
}

impl Anderson {
    /// Buffers for reactions of length `n` and a history of `memory` (1..=[`MAX_MEMORY`]).
    pub fn new(n: usize, memory: usize) -> Result<Self, Fc3dError> {
        let memory = memory.clamp(1, MAX_MEMORY);
        let what = "Anderson acceleration history";
        let mut dg = Vec::with_capacity(memory);
        let mut df = Vec::with_capacity(memory);
        for _ in 0..memory {
            dg.push(try_vec(n, 0.0, what)?);
            df.push(try_vec(n, 0.0, what)?);
        }
        Ok(Anderson {
            memory,
            dg,
            df,
            stored: 0,
            next: 0,
            gram: [[0.0; MAX_MEMORY]; MAX_MEMORY],
            x_in: try_vec(n, 0.0, what)?,
            g_last: try_vec(n, 0.0, what)?,
            f_last: try_vec(n, 0.0, what)?,
            has_last: false,
            f_new: try_vec(n, 0.0, what)?,
            reference: f64::INFINITY,
            extrapolated: false,
            accepted: 0,
            rejected: 0,
        })
    }

    /// Call before a sweep: remembers its input.
    pub fn before_sweep(&mut self, r: &[f64]) {
        self.x_in.copy_from_slice(r);
    }

    /// Call after a sweep whose output `r` has been tested and found not converged: replaces `r`
    /// by the point the next sweep starts from (extrapolated, or the fallback).
    pub fn after_sweep(&mut self, r: &mut [f64]) {
        let mut norm_sq = 0.0;
        for ((f, &g), &x) in self.f_new.iter_mut().zip(r.iter()).zip(&self.x_in) {
            *f = g - x;
            norm_sq += *f * *f;
        }
        let norm = norm_sq.sqrt();
        if !norm.is_finite() {
            self.reset();
            return;
        }
        if self.extrapolated && norm > self.reference {
            // The extrapolated point swept worse than the plain sweep it replaced: go back to
            // that sweep's output and build a new history from there.
            self.rejected += 1;
            r.copy_from_slice(&self.g_last);
            self.reset();
            return;
        }
        if self.extrapolated {
            self.accepted += 1;
        }
        if self.has_last {
            self.push(r);
        }
        self.g_last.copy_from_slice(r);
        std::mem::swap(&mut self.f_last, &mut self.f_new);
        self.has_last = true;
        self.reference = norm;
        self.extrapolated = self.stored > 0 && self.extrapolate(r);
    }

    fn reset(&mut self) {
        self.stored = 0;
        self.next = 0;
        self.has_last = false;
        self.extrapolated = false;
        self.reference = f64::INFINITY;
    }

    /// Stores `g - g_last` and `f_new - f_last` in the next slot and updates the Gram matrix.
    fn push(&mut self, g: &[f64]) {
        let slot = self.next;
        {
            let (dg, df) = (&mut self.dg[slot], &mut self.df[slot]);
            for i in 0..g.len() {
                dg[i] = g[i] - self.g_last[i];
                df[i] = self.f_new[i] - self.f_last[i];
            }
        }
        self.stored = (self.stored + 1).min(self.memory);
        self.next = (self.next + 1) % self.memory;
        for other in 0..self.stored {
            let d = dot(&self.df[slot], &self.df[other]);
            self.gram[slot][other] = d;
            self.gram[other][slot] = d;
        }
    }

    /// Writes the extrapolated point into `r` (holding `g_k`); false (and `r`
    /// untouched) when the small system is degenerate.
    fn extrapolate(&mut self, r: &mut [f64]) -> bool {
        let m = self.stored;
        // Slots in a fixed order (0..m) whatever the ring position: the arithmetic, hence the
        // bits, depend only on the history.
        let mut a = [[0.0; MAX_MEMORY]; MAX_MEMORY];
        let mut b = [0.0; MAX_MEMORY];
        let mut trace = 0.0;
        for i in 0..m {
            for j in 0..m {
                a[i][j] = self.gram[i][j];
            }
            trace += a[i][i];
            b[i] = dot(&self.df[i], &self.f_last);
        }
        if !(trace > 0.0 && trace.is_finite()) {
            return false;
        }
        // Tikhonov regularisation keeps nearly dependent columns from blowing gamma up.
        let lambda = 1e-10 * trace;
        for (i, row) in a.iter_mut().enumerate().take(m) {
            row[i] += lambda;
        }
        let Some(gamma) = solve_small(&mut a, &mut b, m) else {
            return false;
        };
        for (i, v) in r.iter_mut().enumerate() {
            for (j, g) in gamma.iter().enumerate().take(m) {
                *v -= g * self.dg[j][i];
            }
        }
        true
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Gaussian elimination with partial pivoting on the leading `m x m` part; `None` when a pivot
/// vanishes or the result is not finite.
fn solve_small(
    a: &mut [[f64; MAX_MEMORY]; MAX_MEMORY],
    b: &mut [f64; MAX_MEMORY],
    m: usize,
) -> Option<[f64; MAX_MEMORY]> {
    for col in 0..m {
        let pivot = (col..m).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col] == 0.0 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..m {
            let factor = a[row][col] / a[col][col];
            for k in col..m {
                a[row][k] -= factor * a[col][k];
            }
            b[row] -= factor * b[col];
        }
    }
    let mut x = [0.0; MAX_MEMORY];
    for row in (0..m).rev() {
        let mut s = b[row];
        for k in row + 1..m {
            s -= a[row][k] * x[k];
        }
        x[row] = s / a[row][row];
    }
    x[..m].iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_solve_matches_a_known_system() {
        let mut a = [[0.0; MAX_MEMORY]; MAX_MEMORY];
        a[0][0] = 0.0;
        a[0][1] = 2.0;
        a[1][0] = 3.0;
        a[1][1] = 1.0;
        let mut b = [0.0; MAX_MEMORY];
        b[0] = 4.0;
        b[1] = 5.0;
        let x = solve_small(&mut a, &mut b, 2).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 2.0).abs() < 1e-15);
    }

    /// On a linear contraction x -> A x + c, Anderson with memory >= dimension finds the fixed
    /// point in a few steps where the plain iteration needs hundreds.
    #[test]
    fn accelerates_a_slow_linear_fixed_point() {
        let map = |x: &[f64]| -> Vec<f64> {
            vec![
                0.99 * x[0] + 0.01 * 1.0,
                0.98 * x[1] + 0.01 * x[0] * 0.1,
                0.97 * x[2] + 0.01 * 0.2,
            ]
        };
        let fixed = {
            let mut x = vec![1.0, 0.0, 0.0];
            for _ in 0..100_000 {
                x = map(&x);
            }
            x
        };
        let mut acc = Anderson::new(3, 5).unwrap();
        let mut r = vec![1.0, 0.0, 0.0];
        let mut steps = 0;
        while steps < 200 {
            acc.before_sweep(&r);
            let g = map(&r);
            r.copy_from_slice(&g);
            steps += 1;
            let err: f64 = r.iter().zip(&fixed).map(|(a, b)| (a - b).abs()).sum();
            if err < 1e-10 {
                break;
            }
            acc.after_sweep(&mut r);
        }
        assert!(steps < 20, "Anderson took {steps} steps");
        assert!(acc.accepted > 0);
    }
}
