//! Which global solver runs ([`GlobalMethod`], Siconos' gfc3d ids) and how far
//! ([`GlobalConfig`]: tolerance, iteration limit, time budget).

use crate::config::{Method, MethodChoice, MethodConfig, RollingConfig};
use crate::error::Fc3dError;
use crate::solvers::nsgs::{Decomposition, NsgsOptions};
use crate::solvers::rolling::RollingMethod;

use super::aclm::GlobalAclmOptions;
use super::admm::GlobalAdmmOptions;
use super::alm::GlobalAlmOptions;
use super::ipm::IpmOptions;
use super::jacobi::JacobiOptions;
use super::newton::GlobalNewtonOptions;
use super::rescaling::GlobalRescaling;
use crate::solvers::vi::{ViOptions, ViSolver};

/// A global solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GlobalMethod {
    /// Reduce to the local problem FC(H^T M^-1 H, H^T M^-1 q + b, mu) (W assembled block-sparse
    /// through a factorization of M, see [`crate::matrix::HForm`]), solve it with a local
    /// method, then `v = M^-1 (q + H r)`: Siconos' `_WR` ids with their local solver, 600
    /// NSGS_WR (NSGS 500), 602 PROX_WR (PROX 502), 603 DSFP_WR (DSFP 505), 604 TFP_WR (TFP 503),
    /// 606 NSN_AC_WR (NSN-AC 504), 614 ADMM_WR (ADMM 523); any other local method (AUTO
    /// included) works the same way.
    Reduced(Method),
    /// Siconos' `GFC3D_NSGS` (605): projected Jacobi on the reaction with `v` solved exactly
    /// at every iteration.
    ProjectedJacobi(JacobiOptions),
    /// Siconos' `GFC3D_NSN_AC` (607): semismooth Newton on `(v, u, r)` with the sparse
    /// Jacobian of the unreduced system (no W formed).
    Newton(GlobalNewtonOptions),
    /// Siconos' `GFC3D_VI_FPP` (610) and `GFC3D_VI_EG` (611): the VI fixed point or
    /// extragradient on `(v, r)` (the local VI solvers' implementation).
    Vi(ViOptions),
    /// Siconos' `GFC3D ADMM` (613): ADMM on the splitting `H^T v + b_s = z ∈ K*` with
    /// `M + rho H H^T` factored (the local ADMM's engine).
    Admm(GlobalAdmmOptions),
    /// Siconos' `GFC3D_ACLMFP` (612): fixed point on De Saxcé's term, each convex problem
    /// solved by the global ADMM with the term held fixed.
    Aclm(GlobalAclmOptions),
    /// Siconos' `GFC3D IPM` (615): a primal-dual interior-point method on the second-order cone
    /// program; by default (as Siconos) it solves the convex relaxation, reported as
    /// [`crate::SolveStatus::RelaxationNotCoulomb`] where that is not a Coulomb solution.
    Ipm(IpmOptions),
    /// fc3d's semismooth Newton augmented Lagrangian (fc3d id 690, `SSN_ALM`): the method of
    /// multipliers in the bodies' velocities, Newton steps on `M + rho H D H^T` (M's size),
    /// a fixed point on De Saxcé's term. For a symmetric M.
    AugmentedLagrangian(GlobalAlmOptions),
    /// fc3d's `NSGS_HFORM` (691, no Siconos id): NSGS in the velocity form on H and a
    /// block-diagonal M ([`crate::solvers::nsgs`]'s product Gauss-Seidel): `v = M^-1 (q + H r)`
    /// kept up to date contact by contact, W never formed; the local solver and the sweep
    /// settings of [`NsgsOptions`] (sequential or coloured decomposition, natural order, no
    /// freezing, no acceleration). The stopping test measures the global error.
    HForm(NsgsOptions),
}

/// The global id of Siconos' `_WR` solver built on each local id.
const REDUCED_IDS: [(i32, i32); 6] = [
    (500, 600),
    (502, 602),
    (505, 603),
    (503, 604),
    (504, 606),
    (523, 614),
];

impl GlobalMethod {
    /// Siconos' id (600-615); a reduction over a local method Siconos has no `_WR` id for
    /// keeps the local id.
    pub fn siconos_id(&self) -> i32 {
        match self {
            GlobalMethod::Reduced(m) => {
                let local = m.siconos_id();
                REDUCED_IDS
                    .iter()
                    .find(|(l, _)| *l == local)
                    .map_or(local, |(_, g)| *g)
            }
            GlobalMethod::ProjectedJacobi(_) => 605,
            GlobalMethod::Newton(_) => 607,
            GlobalMethod::Vi(o) => match o.solver {
                ViSolver::ViExtraGradient => 611,
                _ => 610,
            },
            GlobalMethod::Admm(_) => 613,
            GlobalMethod::Aclm(_) => 612,
            GlobalMethod::Ipm(_) => 615,
            GlobalMethod::AugmentedLagrangian(_) => 690,
            GlobalMethod::HForm(_) => HFORM_ID,
        }
    }

    /// The rescaling the method runs on (Siconos reads one for 607 and 613 only).
    pub fn rescaling(&self) -> GlobalRescaling {
        match self {
            GlobalMethod::Newton(o) => o.rescaling,
            GlobalMethod::Admm(o) => o.rescaling,
            _ => GlobalRescaling::None,
        }
    }

    /// The same method on the problem as given.
    pub fn without_rescaling(self) -> GlobalMethod {
        match self {
            GlobalMethod::Newton(o) => GlobalMethod::Newton(GlobalNewtonOptions {
                rescaling: GlobalRescaling::None,
                ..o
            }),
            GlobalMethod::Admm(o) => GlobalMethod::Admm(GlobalAdmmOptions {
                rescaling: GlobalRescaling::None,
                ..o
            }),
            other => other,
        }
    }

    /// The local id a `_WR` id reduces to (600 -> 500, ...), `None` for the other ids.
    pub fn reduced_local_id(global_id: i32) -> Option<i32> {
        REDUCED_IDS
            .iter()
            .find(|(_, g)| *g == global_id)
            .map(|(l, _)| *l)
    }

    /// Short label for tables: `WR-NSGS/565`, ...
    pub fn label(&self) -> String {
        match self {
            GlobalMethod::Reduced(m) => format!("WR-{}", m.label()),
            GlobalMethod::ProjectedJacobi(_) => "GFC3D-NSGS".to_string(),
            GlobalMethod::Newton(o) => format!("GFC3D-{}", o.formulation.short_name()),
            GlobalMethod::Vi(o) => format!("GFC3D-{}", o.solver.short_name()),
            GlobalMethod::Admm(o) if o.update_s => "GFC3D-ADMM".to_string(),
            GlobalMethod::Admm(_) => "GFC3D-ADMM-convex".to_string(),
            GlobalMethod::Aclm(_) => "GFC3D-ACLMFP".to_string(),
            GlobalMethod::Ipm(o) => format!(
                "GFC3D-IPM{}{}",
                if o.update_s { "" } else { "-convex" },
                if o.nesterov_todd { "" } else { "-arrow" }
            ),
            GlobalMethod::AugmentedLagrangian(_) => "GFC3D-SSN-ALM".to_string(),
            GlobalMethod::HForm(o) => format!(
                "GFC3D-NSGS-HFORM{}/{}",
                if o.decomposition == Decomposition::Coloured {
                    "-COLOURED"
                } else {
                    ""
                },
                o.local.kind.siconos_id()
            ),
        }
    }

    /// Siconos' default `(tolerance, max_iter)` for the id (a `_WR` id takes its local
    /// solver's).
    pub fn default_limits(&self) -> (f64, usize) {
        match self {
            GlobalMethod::Reduced(m) => m.default_limits(),
            GlobalMethod::ProjectedJacobi(_) => (1e-4, 1000),
            GlobalMethod::Newton(_) => (1e-10, 200),
            GlobalMethod::Vi(o) => o.solver.default_limits(),
            GlobalMethod::Admm(_) => (1e-6, 20000),
            GlobalMethod::Aclm(_) => (1e-4, 1000),
            GlobalMethod::Ipm(_) => (1e-8, 200),
            GlobalMethod::AugmentedLagrangian(_) => (1e-6, 500),
            GlobalMethod::HForm(_) => (1e-4, 1000),
        }
    }

    pub fn validate(&self) -> Result<(), Fc3dError> {
        match self {
            GlobalMethod::Reduced(m) => m.family().validate(),
            GlobalMethod::ProjectedJacobi(o) => o.validate(),
            GlobalMethod::Newton(o) => o.validate(),
            GlobalMethod::Vi(o) => super::vi::validate(o),
            GlobalMethod::Admm(o) => o.validate(),
            GlobalMethod::Aclm(o) => o.validate(),
            GlobalMethod::Ipm(o) => o.validate(),
            GlobalMethod::AugmentedLagrangian(o) => o.validate(),
            GlobalMethod::HForm(o) => super::hform::validate(o),
        }
    }
}

/// Siconos' global ids gfc3d_driver runs, with the name of each (Siconos' `SICONOS_GLOBAL_*_STR`
/// without the `GFC3D_` prefix, a space or dash read as `_`).
const GLOBAL_NAMES: [(i32, &str); 13] = [
    (600, "NSGS_WR"),
    (602, "PROX_WR"),
    (603, "DSFP_WR"),
    (604, "TFP_WR"),
    (605, "NSGS"),
    (606, "NSN_AC_WR"),
    (607, "NSN_AC"),
    (610, "VI_FPP"),
    (611, "VI_EG"),
    (612, "ACLMFP"),
    (613, "ADMM"),
    (614, "ADMM_WR"),
    (615, "IPM"),
];

/// fc3d's own global methods (not Siconos ids: gfc3d_driver does not run them), by id and name.
const FC3D_GLOBAL_NAMES: [(i32, &str); 1] = [(690, "SSN_ALM")];
/// fc3d's own global id of [`GlobalMethod::HForm`] (Siconos' global ids end at 615; 590 is
/// fc3d's AUTO).
pub const HFORM_ID: i32 = 691;

/// fc3d's own global methods by name: the sequential and the coloured H-form sweep (one id).
const OWN_GLOBAL_NAMES: [(&str, Decomposition); 2] = [
    ("NSGS_HFORM", Decomposition::Sequential),
    ("NSGS_HFORM_COLOURED", Decomposition::Coloured),
];

impl GlobalMethod {
    /// Every global id `gfc3d_driver` runs, with Siconos' defaults (the `_WR` ids with the
    /// preset of their local id): what the CLI looks ids and names up in. The C layer reads the
    /// same defaults from `solver_options_create`; a test checks that they agree.
    pub fn presets() -> Vec<GlobalMethod> {
        GLOBAL_NAMES
            .iter()
            .filter_map(|&(id, _)| GlobalMethod::of_id(id))
            .collect()
    }

    /// fc3d's own global methods (no Siconos id) under their names: 691 `NSGS_HFORM` and
    /// `NSGS_HFORM_COLOURED`, with the NSGS defaults, and 690 `SSN_ALM`.
    pub fn own_presets() -> Vec<GlobalMethod> {
        OWN_GLOBAL_NAMES
            .iter()
            .filter_map(|(name, _)| GlobalMethod::preset(name))
            .chain(
                FC3D_GLOBAL_NAMES
                    .iter()
                    .filter_map(|&(id, _)| GlobalMethod::of_id(id)),
            )
            .collect()
    }

    fn of_id(id: i32) -> Option<GlobalMethod> {
        if let Some(local) = GlobalMethod::reduced_local_id(id) {
            return Method::preset(&local.to_string()).map(GlobalMethod::Reduced);
        }
        Some(match id {
            605 => GlobalMethod::ProjectedJacobi(JacobiOptions::default()),
            607 => GlobalMethod::Newton(GlobalNewtonOptions::default()),
            610 => GlobalMethod::Vi(ViOptions::new(ViSolver::ViFixedPointProjection)),
            611 => GlobalMethod::Vi(ViOptions::new(ViSolver::ViExtraGradient)),
            612 => GlobalMethod::Aclm(GlobalAclmOptions::default()),
            613 => GlobalMethod::Admm(GlobalAdmmOptions::default()),
            615 => GlobalMethod::Ipm(IpmOptions::default()),
            690 => GlobalMethod::AugmentedLagrangian(GlobalAlmOptions::default()),
            _ => return None,
        })
    }

    /// Siconos' short name of the method's id (`NSGS_WR`, `NSN_AC`, `IPM`, ...; with the
    /// `GFC3D_` prefix in Siconos; fc3d's own `NSGS_HFORM`, `NSGS_HFORM_COLOURED`), `None` for
    /// a reduction over a local method Siconos has no `_WR` id for.
    pub fn name(&self) -> Option<&'static str> {
        if let GlobalMethod::HForm(o) = self {
            let coloured = o.decomposition == Decomposition::Coloured;
            return Some(OWN_GLOBAL_NAMES[usize::from(coloured)].0);
        }
        let id = self.siconos_id();
        GLOBAL_NAMES
            .iter()
            .chain(&FC3D_GLOBAL_NAMES)
            .find(|(i, _)| *i == id)
            .map(|(_, n)| *n)
    }

    /// The preset of a global id (`605`) or name (`NSGS_WR`, `gfc3d_nsgs_wr`, `GFC3D ADMM`,
    /// `nsn-ac`; case-insensitive), with Siconos' defaults; fc3d's own 691 / `NSGS_HFORM`
    /// (sequential, the NSGS defaults) and `NSGS_HFORM_COLOURED` (threads from
    /// `FC3D_NUM_THREADS` or the machine). `None` for anything else (the local ids and names
    /// included).
    pub fn preset(name: &str) -> Option<GlobalMethod> {
        let name = name.trim();
        let hform = |decomposition| {
            GlobalMethod::HForm(NsgsOptions {
                decomposition,
                ..Default::default()
            })
        };
        let id = match name.parse::<i32>() {
            Ok(HFORM_ID) => return Some(hform(Decomposition::Sequential)),
            Ok(id) => id,
            Err(_) => {
                let upper = name.to_ascii_uppercase().replace([' ', '-'], "_");
                let short = upper.strip_prefix("GFC3D_").unwrap_or(&upper);
                if let Some((_, d)) = OWN_GLOBAL_NAMES.iter().find(|(n, _)| *n == short) {
                    return Some(hform(*d));
                }
                GLOBAL_NAMES
                    .iter()
                    .chain(&FC3D_GLOBAL_NAMES)
                    .find(|(_, n)| *n == short)?
                    .0
            }
        };
        GlobalMethod::of_id(id)
    }
}

impl MethodChoice for GlobalMethod {
    fn default_limits(&self) -> (f64, usize) {
        GlobalMethod::default_limits(self)
    }
    fn validate(&self) -> Result<(), Fc3dError> {
        GlobalMethod::validate(self)
    }
}

/// Which global solver to run and how far.
///
/// ```
/// use fc3d_core::global::{GlobalConfig, GlobalMethod};
/// use fc3d_core::{Method, NsgsOptions};
/// let config = GlobalConfig::new(GlobalMethod::Reduced(Method::Nsgs(NsgsOptions::default())));
/// assert_eq!((config.tolerance, config.max_iter), (1e-4, 1000));
/// assert_eq!(config.method.siconos_id(), 600);
/// ```
pub type GlobalConfig = MethodConfig<GlobalMethod>;

/// The global rolling solver: Siconos' 5000 (`GFC3D_NSGS_WR` for rolling problems) reduces to
/// the local rolling problem and runs a rolling method (rolling NSGS 3000 by default).
pub type GlobalRollingConfig = RollingConfig;

/// The rolling method Siconos' id 5000 runs on the reduced problem.
pub fn global_rolling_default() -> RollingMethod {
    RollingMethod::Nsgs(Default::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_cover_the_ids_gfc3d_driver_runs_by_id_and_name() {
        let presets = GlobalMethod::presets();
        let ids: Vec<i32> = presets.iter().map(GlobalMethod::siconos_id).collect();
        assert_eq!(
            ids,
            [600, 602, 603, 604, 605, 606, 607, 610, 611, 612, 613, 614, 615]
        );
        for m in &presets {
            let id = m.siconos_id();
            assert_eq!(GlobalMethod::preset(&id.to_string()), Some(*m));
            let name = m.name().unwrap();
            assert_eq!(GlobalMethod::preset(name), Some(*m));
            assert_eq!(
                GlobalMethod::preset(&format!("gfc3d_{}", name.to_lowercase())),
                Some(*m)
            );
            m.validate().unwrap();
        }
        assert_eq!(
            GlobalMethod::preset("GFC3D ADMM").map(|m| m.siconos_id()),
            Some(613)
        );
        assert_eq!(
            GlobalMethod::preset("nsn-ac").map(|m| m.siconos_id()),
            Some(607)
        );
        for refused in ["500", "601", "608", "5000", "AUTO", "", "NSGS_WRX"] {
            assert_eq!(GlobalMethod::preset(refused), None, "{refused:?}");
        }
        // The reductions run their local id's preset.
        assert_eq!(
            GlobalMethod::preset("606"),
            Some(GlobalMethod::Reduced(Method::preset("504").unwrap()))
        );
    }
}
