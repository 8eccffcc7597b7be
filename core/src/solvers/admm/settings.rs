//! Settings of ADMM (Siconos id 523) with Siconos 4.4's defaults.

use crate::error::{require_setting, Fc3dError};

/// How the first rho is chosen (Siconos' iparam[10]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdmmInitialRho {
    /// [`AdmmOptions::rho`] as given [0, Siconos' default].
    Given,
    /// `||W||_inf`, the largest absolute row sum [1].
    NormInf,
    /// `sqrt(lambda_max max(lambda_min, 1e-2 lambda_max))`, from the moduli of W's extreme
    /// eigenvalues by power iterations on W and W^{-1} [2]. The floor matters
    /// for the singular W of scenes with more contacts than degrees of freedom: there
    /// `lambda_min ≈ 0` gives a rho so small that `W + rho I` is numerically singular and the
    /// iteration diverges (measured on Rover1040, OneObject-i1028-138); with the floor, rho lies
    /// in `[0.1 lambda_max, lambda_max]`, which converged on every shared problem tried.
    Eigenvalues,
}

/// How rho evolves (Siconos' iparam[9]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdmmRhoStrategy {
    /// rho stays at its initial value [0, Siconos' default].
    Constant,
    /// Residual balancing: multiply rho by tau when the primal residual `||x - z||` exceeds phi
    /// times the dual one `rho ||z - ẑ||`, divide it by tau in the opposite case [2].
    ResidualBalancing,
    /// The same on residuals relative to `max(||x||, ||z||)` and `||rho ξ||` [3].
    ScaledResidualBalancing,
}

/// Nesterov acceleration (Siconos' iparam[11]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdmmAcceleration {
    /// Plain ADMM [0].
    None,
    /// Extrapolation, restarted from the previous iterate whenever the combined residual
    /// `||x - z||^2 + rho^2 ||z - ẑ||^2` does not decrease by the factor eta [1 and 2: Siconos 4.4
    /// restarts in both modes; 2 is its default].
    Accelerated,
}

/// Settings of ADMM (Siconos id 523), Siconos 4.4's defaults. Its limits default to 20000
/// iterations and a tolerance of 1e-6 on the natural-map error, measured at every iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmmOptions {
    /// rho for [`AdmmInitialRho::Given`] (default 1).
    pub rho: f64,
    /// Default [`AdmmInitialRho::Given`].
    pub initial_rho: AdmmInitialRho,
    /// Default [`AdmmRhoStrategy::Constant`].
    pub rho_strategy: AdmmRhoStrategy,
    /// Default [`AdmmAcceleration::Accelerated`].
    pub acceleration: AdmmAcceleration,
    /// Restart factor eta in (0, 1] of the acceleration (default 0.999).
    pub restart_eta: f64,
    /// Residual-balancing factor tau > 1 (default 2).
    pub balancing_tau: f64,
    /// Residual-balancing ratio phi > 1 (default 2).
    pub balancing_phi: f64,
    /// Siconos' scalar rescaling (`iparam[3]` = 1): the iteration runs on `(W / a, q / a)`,
    /// `a = ||W||_inf` (the same reactions), keeping the rho chosen for W. Default false.
    pub scalar_rescaling: bool,
}

impl Default for AdmmOptions {
    fn default() -> Self {
        AdmmOptions {
            rho: 1.0,
            initial_rho: AdmmInitialRho::Given,
            rho_strategy: AdmmRhoStrategy::Constant,
            acceleration: AdmmAcceleration::Accelerated,
            restart_eta: 0.999,
            balancing_tau: 2.0,
            balancing_phi: 2.0,
            scalar_rescaling: false,
        }
    }
}

impl AdmmOptions {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        if self.initial_rho == AdmmInitialRho::Given {
            let rho = self.rho;
            require_setting(
                rho > 0.0 && rho.is_finite(),
                "admm.rho",
                rho,
                "finite and > 0",
            )?;
        }
        let eta = self.restart_eta;
        require_setting(
            eta > 0.0 && eta <= 1.0,
            "admm.restart_eta",
            eta,
            "in (0, 1]",
        )?;
        if self.rho_strategy != AdmmRhoStrategy::Constant {
            let (tau, phi) = (self.balancing_tau, self.balancing_phi);
            require_setting(
                tau > 1.0 && tau.is_finite(),
                "admm.balancing_tau",
                tau,
                "finite and > 1",
            )?;
            require_setting(
                phi > 1.0 && phi.is_finite(),
                "admm.balancing_phi",
                phi,
                "finite and > 1",
            )?;
        }
        Ok(())
    }
}
