//! The spectral projected gradient with a non-monotone line search (SPG2, Birgin, Martínez and
//! Raydan 2000).

use std::time::Instant;

use super::{Best, ConvexSet, ConvexSubproblem, FirstOrderWork, SpgSettings};
use crate::contract::deadline_passed;

/// Step reductions of one line search (the interpolation at least halves the step).
const MAX_BACKTRACK: usize = 60;

impl FirstOrderWork {
    pub(super) fn spg<S: ConvexSet>(
        &mut self,
        settings: &SpgSettings,
        sub: &ConvexSubproblem<'_, '_, S>,
        tol: f64,
        max_iter: usize,
        deadline: Option<Instant>,
        r: &mut [f64],
    ) -> usize {
        let (rows, c) = (sub.rows, sub.linear);
        sub.set.project(r);
        self.products += 1;
        rows.velocity(c, r, &mut self.g);
        let mut best = Best {
            residual: f64::INFINITY,
        };
        let mut residual = Self::residual(&mut self.scratch, sub, r, &self.g);
        best.offer(residual, r, &mut self.best);
        if residual <= tol {
            return 0;
        }
        let (alpha_min, alpha_max) = (
            settings.alpha_min / self.lambda_max,
            settings.alpha_max / self.lambda_max,
        );
        let mut alpha = (1.0 / self.curvature.unwrap_or(1.0)).clamp(alpha_min, alpha_max);
        // f relative to its value at the first iterate of this solve, from exact increments.
        let mut f = 0.0;
        self.history.clear();
        self.history.push(f);
        let mut next_slot = 1 % settings.memory;
        let mut done = 0;
        for it in 1..=max_iter {
            if deadline_passed(deadline) {
                break;
            }
            done = it;
            for ((t, x), g) in self.trial.iter_mut().zip(r.iter()).zip(&self.g) {
                *t = x - alpha * g;
            }
            sub.set.project(&mut self.trial);
            self.products += 1;
            rows.velocity(c, &self.trial, &mut self.g_trial);
            // d = trial - r, W d = g(trial) - g(r).
            let (mut g_d, mut d_w_d, mut d_d) = (0.0, 0.0, 0.0);
            for (((t, x), gt), g) in self
                .trial
                .iter()
                .zip(r.iter())
                .zip(&self.g_trial)
                .zip(&self.g)
            {
                let d = t - x;
                g_d += g * d;
                d_w_d += d * (gt - g);
                d_d += d * d;
            }
            if !(d_d > 0.0 && g_d.is_finite() && d_w_d.is_finite()) {
                // A fixed point of the projected step (or a non-finite product): stationary
                // to rounding, or nothing more this method can do.
                break;
            }
            let f_max = self
                .history
                .iter()
                .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
            let mut lambda = 1.0_f64;
            let mut increment = lambda * g_d + 0.5 * lambda * lambda * d_w_d;
            for _ in 0..MAX_BACKTRACK {
                if f + increment <= f_max + settings.sufficient_decrease * lambda * g_d {
                    break;
                }
                // The minimiser of the quadratic along d, safeguarded.
                let exact = if d_w_d > 0.0 { -g_d / d_w_d } else { 0.0 };
                lambda = if exact >= settings.sigma_low * lambda
                    && exact <= settings.sigma_high * lambda
                {
                    exact
                } else {
                    0.5 * lambda
                };
                increment = lambda * g_d + 0.5 * lambda * lambda * d_w_d;
            }
            if lambda == 1.0 {
                r.copy_from_slice(&self.trial);
                std::mem::swap(&mut self.g, &mut self.g_trial);
            } else {
                for (((x, g), t), gt) in r
                    .iter_mut()
                    .zip(self.g.iter_mut())
                    .zip(&self.trial)
                    .zip(&self.g_trial)
                {
                    *x += lambda * (t - *x);
                    *g += lambda * (gt - *g);
                }
            }
            f += increment;
            if self.history.len() < settings.memory {
                self.history.push(f);
            } else {
                self.history[next_slot] = f;
            }
            next_slot = (next_slot + 1) % settings.memory;
            alpha = if d_w_d > 0.0 {
                (d_d / d_w_d).clamp(alpha_min, alpha_max)
            } else {
                alpha_max
            };
            residual = Self::residual(&mut self.scratch, sub, r, &self.g);
            best.offer(residual, r, &mut self.best);
            if residual <= tol {
                break;
            }
        }
        self.curvature = Some(1.0 / alpha);
        best.restore(residual, &self.best, r);
        done
    }
}
