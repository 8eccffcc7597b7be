//! Settings of the accelerated first-order sub-problem solvers, with their defaults.

use crate::error::{require_setting, Fc3dError};

/// Nesterov's accelerated projected gradient with adaptive restart (APGD).
///
/// Each iteration steps from the extrapolated point `y` to `x+ = P(y - (W y + c) / L)`, one
/// product with W; while `d.W d > L ||d||^2` along `d = x+ - y` (the quadratic's sufficient
/// decrease, known from that product) L doubles and the step is redone. After an accepted step L
/// shrinks by `step_shrink` so the step can grow back (Mazhar et al. 2015), and the momentum
/// restarts (O'Donoghue and Candès 2015, gradient-mapping form: `(y - x+).(x+ - x) > 0`) when
/// it points uphill.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApgdSettings {
    /// Lanczos steps on W for the first L, the largest eigenvalue (default 10 products, once per
    /// solve: within a few per cent from below on the generated piles).
    pub spectral_steps: usize,
    /// Factor applied to L after every accepted step, in (0, 1] (default 0.9; 1 keeps L fixed).
    pub step_shrink: f64,
    /// The adaptive restart of the momentum (default on).
    pub adaptive_restart: bool,
}

impl Default for ApgdSettings {
    fn default() -> Self {
        ApgdSettings {
            spectral_steps: 10,
            step_shrink: 0.9,
            adaptive_restart: true,
        }
    }
}

impl ApgdSettings {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.spectral_steps >= 1,
            "apgd.spectral_steps",
            self.spectral_steps,
            ">= 1",
        )?;
        require_setting(
            self.step_shrink > 0.0 && self.step_shrink <= 1.0,
            "apgd.step_shrink",
            self.step_shrink,
            "in (0, 1]",
        )
    }
}

/// The spectral projected gradient (SPG2 of Birgin, Martínez and Raydan 2000).
///
/// Each iteration takes the direction `d = P(r - alpha g) - r` (`g = W r + c`, one product gives
/// `W d`) and the largest `lambda` of 1, then safeguarded quadratic interpolations (the exact
/// minimiser along d, kept in `[sigma_low, sigma_high] lambda`, else `lambda / 2`), that passes
/// the non-monotone Armijo test `f(r + lambda d) <= max of the last memory values of f + gamma
/// lambda g.d`; then `alpha = d.d / d.W d` (Barzilai-Borwein), clamped to
/// `[alpha_min, alpha_max] / lambda_max(W)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpgSettings {
    /// Lanczos steps on W for the first step `1 / lambda_max` (default 10, once per solve).
    pub spectral_steps: usize,
    /// Values of f the non-monotone test looks back on (default 10, the paper's M).
    pub memory: usize,
    /// Sufficient decrease gamma, in (0, 1) (default 1e-4).
    pub sufficient_decrease: f64,
    /// Safeguard interval of the interpolated step, `0 < low < high < 1` (default 0.1, 0.9).
    pub sigma_low: f64,
    pub sigma_high: f64,
    /// Bounds of the spectral step times `lambda_max(W)` (default 1e-10 and 1e10: wide, as the
    /// paper's 1e-30 and 1e30 for unscaled problems).
    pub alpha_min: f64,
    pub alpha_max: f64,
}

impl Default for SpgSettings {
    fn default() -> Self {
        SpgSettings {
            spectral_steps: 10,
            memory: 10,
            sufficient_decrease: 1e-4,
            sigma_low: 0.1,
            sigma_high: 0.9,
            alpha_min: 1e-10,
            alpha_max: 1e10,
        }
    }
}

impl SpgSettings {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.spectral_steps >= 1,
            "spg.spectral_steps",
            self.spectral_steps,
            ">= 1",
        )?;
        require_setting(self.memory >= 1, "spg.memory", self.memory, ">= 1")?;
        let g = self.sufficient_decrease;
        require_setting(
            g > 0.0 && g < 1.0,
            "spg.sufficient_decrease",
            g,
            "in (0, 1)",
        )?;
        require_setting(
            self.sigma_low > 0.0 && self.sigma_low < self.sigma_high,
            "spg.sigma_low",
            self.sigma_low,
            "in (0, sigma_high)",
        )?;
        require_setting(
            self.sigma_high < 1.0,
            "spg.sigma_high",
            self.sigma_high,
            "in (sigma_low, 1)",
        )?;
        require_setting(
            self.alpha_min > 0.0 && self.alpha_min < self.alpha_max,
            "spg.alpha_min",
            self.alpha_min,
            "in (0, alpha_max)",
        )?;
        require_setting(
            self.alpha_max.is_finite(),
            "spg.alpha_max",
            self.alpha_max,
            "finite and > alpha_min",
        )
    }
}
