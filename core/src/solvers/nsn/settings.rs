//! Typed options of the nonsmooth Newton family (Siconos ids 504, 513, 520) with Siconos 4.4's
//! defaults.

use crate::error::{require_setting, Fc3dError};
use crate::local::{AlgorithmVariant, RhoRule};

/// The nonsmooth equation `F(r) = 0` Newton is applied to (section 3 of Acary-Brémond-Huber).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NsnFormulation {
    /// Alart-Curnier (61): disk radius `mu (r_N - rho_N u_N)_+` [504 NSN_AC].
    AlartCurnier,
    /// Jean-Moreau (59): disk radius `mu (r_N)_+` [504 NSN_AC with iparam[10] = 1 or 3].
    JeanMoreau,
    /// Fischer-Burmeister on the second-order cone (77) [513 NSN_FB]; uses no rho.
    FischerBurmeister,
    /// Natural map (49): `r - P_K(r - rho (u + mu ||u_T|| e_N))` [520 NSN_NM].
    NaturalMap,
}

impl NsnFormulation {
    /// The Siconos solver id that runs this formulation.
    pub fn siconos_id(self) -> i32 {
        match self {
            NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau => 504,
            NsnFormulation::FischerBurmeister => 513,
            NsnFormulation::NaturalMap => 520,
        }
    }

    /// Short name used in labels (`NSN-AC`, `NSN-JM`, `NSN-FB`, `NSN-NM`).
    pub fn short_name(self) -> &'static str {
        match self {
            NsnFormulation::AlartCurnier => "NSN-AC",
            NsnFormulation::JeanMoreau => "NSN-JM",
            NsnFormulation::FischerBurmeister => "NSN-FB",
            NsnFormulation::NaturalMap => "NSN-NM",
        }
    }
}

/// Globalisation of the Newton step on the merit function `q(t) = ||F(r + t d)||^2 / 2`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NsnLineSearch {
    /// Full steps, `t = 1` (Siconos iparam[11] = -1).
    None,
    /// Goldstein-Price (Algorithm 5), Siconos' default (iparam[11] = 0).
    GoldsteinPrice,
    /// Armijo backtracking (Algorithm 6) (iparam[11] = 1).
    Armijo,
    /// Armijo against the largest merit of the last [`NONMONOTONE_MEMORY`] iterates (Grippo,
    /// Lampariello, Lucidi), which lets Newton cross the kinks of F without shrinking to zero.
    /// Rust API only: Siconos 4.4 has no index for it.
    NonMonotone,
}

/// How many past merits the non-monotone line search compares against.
pub const NONMONOTONE_MEMORY: usize = 10;

/// Settings of a nonsmooth Newton solve. [`NsnOptions::new`] gives Siconos 4.4's defaults for the
/// formulation's id. Its limits default to 200 Newton iterations and a tolerance of 1e-3 on the
/// relative natural-map error (Siconos creates 520 with one iteration: see [`NsnOptions::new`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NsnOptions {
    pub formulation: NsnFormulation,
    /// Penalty parameters per contact from its diagonal block (rules (109)-(112)); Siconos:
    /// [`RhoRule::SpectralNorm`] for 504, a constant 1 for 513 and 520. Fischer-Burmeister
    /// ignores it.
    pub rho_rule: RhoRule,
    /// Line search (Siconos: Goldstein-Price).
    pub line_search: NsnLineSearch,
    /// Maximum trial steps per line search (Siconos: 100).
    pub line_search_max_iter: usize,
    /// [`AlgorithmVariant::Siconos`] (default): Siconos 4.4's iteration (its Goldstein-Price
    /// search, bisecting from an upper bound of 1e10, and the full Newton step when the search
    /// fails; Siconos' rho rules). [`AlgorithmVariant::Fc3d`]: fc3d's search (extrapolation by
    /// 2 up to 8 Newton steps, the best trial when the search fails), the eigenvalues of `W_T`
    /// in the split rho rules.
    pub variant: AlgorithmVariant,
}

impl NsnOptions {
    /// Siconos 4.4's defaults for the formulation (`solver_options_create(id)`). The limits are
    /// 200 iterations for every formulation: Siconos creates 520 with `iparam[0] = 1`, which the
    /// C API reproduces but which would leave a Rust caller a solver that stops after one step.
    pub fn new(formulation: NsnFormulation) -> Self {
        let rho_rule = match formulation {
            NsnFormulation::AlartCurnier | NsnFormulation::JeanMoreau => RhoRule::SpectralNorm,
            NsnFormulation::FischerBurmeister | NsnFormulation::NaturalMap => {
                RhoRule::Constant(1.0)
            }
        };
        NsnOptions {
            formulation,
            rho_rule,
            line_search: NsnLineSearch::GoldsteinPrice,
            line_search_max_iter: 100,
            variant: AlgorithmVariant::Siconos,
        }
    }

    /// Short label, e.g. `NSN-AC/GP`.
    pub fn label(&self) -> String {
        let ls = match self.line_search {
            NsnLineSearch::None => "full",
            NsnLineSearch::GoldsteinPrice => "GP",
            NsnLineSearch::Armijo => "A",
            NsnLineSearch::NonMonotone => "NM-A",
        };
        format!("{}/{ls}", self.formulation.short_name())
    }
}

impl NsnOptions {
    /// Checks the settings a caller may get wrong.
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        if let RhoRule::Constant(rho) = self.rho_rule {
            require_setting(
                rho > 0.0 && rho.is_finite(),
                "nsn.rho",
                rho,
                "finite and > 0",
            )?;
        }
        require_setting(
            self.line_search == NsnLineSearch::None || self.line_search_max_iter > 0,
            "nsn.line_search_max_iter",
            self.line_search_max_iter,
            ">= 1 with a line search",
        )
    }
}

impl Default for NsnOptions {
    /// Alart-Curnier with Siconos' NSN_AC (504) defaults.
    fn default() -> Self {
        NsnOptions::new(NsnFormulation::AlartCurnier)
    }
}
