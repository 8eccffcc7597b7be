//! Nesterov's accelerated projected gradient with backtracking and adaptive restart (APGD).

use std::time::Instant;

use super::{ApgdSettings, Best, ConvexSet, ConvexSubproblem, FirstOrderWork};
use crate::contract::deadline_passed;

/// Doublings of L one step may take (L grows by 2^60 at most: past any rounding).
const MAX_BACKTRACK: usize = 60;

impl FirstOrderWork {
    pub(super) fn apgd<S: ConvexSet>(
        &mut self,
        settings: &ApgdSettings,
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
        let mut l = self.curvature.unwrap_or(1.0);
        self.y.copy_from_slice(r);
        self.g_y.copy_from_slice(&self.g);
        let mut theta = 1.0_f64;
        let mut done = 0;
        for it in 1..=max_iter {
            if deadline_passed(deadline) {
                break;
            }
            done = it;
            for _ in 0..MAX_BACKTRACK {
                for ((t, y), g) in self.trial.iter_mut().zip(&self.y).zip(&self.g_y) {
                    *t = y - g / l;
                }
                sub.set.project(&mut self.trial);
                self.products += 1;
                rows.velocity(c, &self.trial, &mut self.g_trial);
                // Along d = trial - y: W d = g(trial) - g(y).
                let (mut d_w_d, mut d_d) = (0.0, 0.0);
                for (((t, y), gt), gy) in self
                    .trial
                    .iter()
                    .zip(&self.y)
                    .zip(&self.g_trial)
                    .zip(&self.g_y)
                {
                    let d = t - y;
                    d_w_d += d * (gt - gy);
                    d_d += d * d;
                }
                if d_w_d <= l * d_d || !(d_w_d.is_finite()) {
                    break;
                }
                l *= 2.0;
            }
            let theta_next = 0.5 * theta * ((theta * theta + 4.0).sqrt() - theta);
            let mut beta = theta * (1.0 - theta) / (theta * theta + theta_next);
            theta = theta_next;
            if settings.adaptive_restart {
                // The gradient mapping (y - trial) against the progress (trial - x).
                let uphill: f64 = self
                    .y
                    .iter()
                    .zip(&self.trial)
                    .zip(r.iter())
                    .map(|((y, t), x)| (y - t) * (t - x))
                    .sum();
                if uphill > 0.0 {
                    theta = 1.0;
                    beta = 0.0;
                }
            }
            // y+ = trial + beta (trial - x), its gradient by linearity; then x = trial.
            for ((y, x), t) in self.y.iter_mut().zip(r.iter_mut()).zip(&self.trial) {
                *y = t + beta * (t - *x);
                *x = *t;
            }
            for ((gy, g), gt) in self.g_y.iter_mut().zip(&self.g).zip(&self.g_trial) {
                *gy = gt + beta * (gt - g);
            }
            std::mem::swap(&mut self.g, &mut self.g_trial);
            l *= settings.step_shrink;
            residual = Self::residual(&mut self.scratch, sub, r, &self.g);
            best.offer(residual, r, &mut self.best);
            if residual <= tol {
                break;
            }
        }
        self.curvature = Some(l);
        best.restore(residual, &self.best, r);
        done
    }
}
