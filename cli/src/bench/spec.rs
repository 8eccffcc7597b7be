//! Solver specs of `fc3d bench --solvers`: what the user writes, and the one function that turns a
//! spec into a [`SolverConfig`].
//!
//! Grammar (case-insensitive, specs separated by commas):
//!
//! * `all` — every implemented combination: NSGS with each local solver of
//!   [`LocalSolverKind::ALL`];
//! * `SOLVER` — a solver with its default local solver: `500` or `NSGS` (= `500/565`);
//! * `TFP` (503), `PFP` (522), `ACLMFP` (516), `SOCLCP` (517) — the optimization-based families
//!   with their Siconos defaults (no local solver);
//! * `SOLVER/LOCAL` — a solver with a local solver given by Siconos id or name:
//!
//! | id | names |
//! | --- | --- |
//! | 550 | `NSN`, `NSN-AC` |
//! | 551 | `NSN-GP`, `NSN-AC-GP` |
//! | 552 | `PROJ`, `SBP`, `FP-DS-ONE` |
//! | 553 | `PROJ-ITER` |
//! | 557 | `CYL`, `SAL` |
//! | 565 | `HYBRID`, `NSN-GP-HYBRID` |
//! | 554 | `PROJ-REG` |
//! | 555 | `PROJ-DIAG` |
//! | 558 | `PROJ-VEL` |
//! | 561 | `FB`, `NSN-FB` |
//! | 562 | `QUARTIC` |
//! | 564 | `CYL-ITER` |
//! | 570 | `FP-VI-UPK` |
//! | 571 | `EBP` |
//! | 572 | `EAL` |
//!
//! * `DSFP` (505), `VI-FPP` (506), `VI-EG` (507), `FPP` (511), `EG` (512), `ADMM` (523): families
//!   without a local solver, with Siconos' defaults (not part of `all`).
//!
//! A new solver family plugs in as a variant of [`SolverFamily`], a row of [`FAMILIES`] and an arm
//! of [`solver_config`].

use std::time::Duration;

use fc3d_core::{
    AdmmOptions, LocalSolverKind, NsgsOptions, NsnFormulation, NsnOptions, ProxInternal,
    ProxOptions, SolverConfig, ViOptions, ViSolver,
};

/// Solver families `fc3d bench` knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SolverFamily {
    /// Nonsmooth Gauss-Seidel (Siconos id 500).
    Nsgs,
    /// The VI / fixed-point family (Siconos ids 505, 506, 507, 511, 512).
    Vi(ViSolver),
    /// ADMM (Siconos id 523).
    Admm,
    /// Tresca successive approximation (Siconos id 503).
    Tfp,
    /// Panagiotopoulos alternating fixed point (Siconos id 522).
    Pfp,
    /// ACLM fixed point (Siconos id 516).
    Aclmfp,
    /// The SOCLCP relaxation on its own (Siconos id 517).
    Soclcp,
    /// Nonsmooth Newton with the given formulation (504 AC and JM, 513 FB, 520 NM), Siconos'
    /// default options.
    Nsn(NsnFormulation),
    /// Proximal point with internal NSN-AC (502, Siconos' default).
    ProxNsn,
    /// Proximal point with internal NSGS (PPA-NSGS-AC).
    ProxNsgs,
}

/// (family, Siconos id, name) for every family.
const FAMILIES: [(SolverFamily, i32, &str); 17] = [
    (SolverFamily::Nsgs, 500, "NSGS"),
    (SolverFamily::Vi(ViSolver::DeSaxceFixedPoint), 505, "DSFP"),
    (
        SolverFamily::Vi(ViSolver::ViFixedPointProjection),
        506,
        "VI-FPP",
    ),
    (SolverFamily::Vi(ViSolver::ViExtraGradient), 507, "VI-EG"),
    (SolverFamily::Vi(ViSolver::FixedPointProjection), 511, "FPP"),
    (SolverFamily::Vi(ViSolver::ExtraGradient), 512, "EG"),
    (SolverFamily::Admm, 523, "ADMM"),
    (SolverFamily::Tfp, 503, "TFP"),
    (SolverFamily::Pfp, 522, "PFP"),
    (SolverFamily::Aclmfp, 516, "ACLMFP"),
    (SolverFamily::Soclcp, 517, "SOCLCP"),
    (
        SolverFamily::Nsn(NsnFormulation::AlartCurnier),
        504,
        "NSN-AC",
    ),
    (SolverFamily::Nsn(NsnFormulation::JeanMoreau), 504, "NSN-JM"),
    (
        SolverFamily::Nsn(NsnFormulation::FischerBurmeister),
        513,
        "NSN-FB",
    ),
    (SolverFamily::Nsn(NsnFormulation::NaturalMap), 520, "NSN-NM"),
    (SolverFamily::ProxNsn, 502, "PROX"),
    (SolverFamily::ProxNsgs, 502, "PROX-NSGS"),
];

/// Local solvers: (kind, names accepted in a spec; the first is the short name used in legends).
const LOCAL_NAMES: [(LocalSolverKind, &[&str]); 15] = [
    (LocalSolverKind::NewtonAlartCurnier, &["NSN", "NSN-AC"]),
    (
        LocalSolverKind::NewtonAlartCurnierGp,
        &["NSN-GP", "NSN-AC-GP"],
    ),
    (
        LocalSolverKind::ProjectionOnCone,
        &["PROJ", "SBP", "FP-DS-ONE"],
    ),
    (
        LocalSolverKind::ProjectionOnConeWithLocalIteration,
        &["PROJ-ITER"],
    ),
    (LocalSolverKind::ProjectionOnCylinder, &["CYL", "SAL"]),
    (LocalSolverKind::NewtonHybrid, &["HYBRID", "NSN-GP-HYBRID"]),
    (
        LocalSolverKind::ProjectionOnConeWithRegularization,
        &["PROJ-REG"],
    ),
    (
        LocalSolverKind::ProjectionOnConeWithDiagonalization,
        &["PROJ-DIAG"],
    ),
    (LocalSolverKind::ProjectionOnConeVelocity, &["PROJ-VEL"]),
    (LocalSolverKind::FischerBurmeisterNewton, &["FB", "NSN-FB"]),
    (LocalSolverKind::Quartic, &["QUARTIC"]),
    (
        LocalSolverKind::ProjectionOnCylinderWithLocalIteration,
        &["CYL-ITER"],
    ),
    (LocalSolverKind::FpViUpk, &["FP-VI-UPK"]),
    (LocalSolverKind::EnhancedBipotential, &["EBP"]),
    (LocalSolverKind::EnhancedAugmentedLagrangian, &["EAL"]),
];

/// One solver to benchmark: a family and, for NSGS, its local solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SolverSpec {
    pub family: SolverFamily,
    pub local: LocalSolverKind,
}

impl SolverSpec {
    /// The label of the CSV and the tables, e.g. `NSGS/552` (the CLI's `SolverConfig::label`).
    pub fn label(&self) -> String {
        solver_config(self, 1e-8, 1, None).label()
    }

    /// The label with the local solver's short name, for legends: `NSGS/552 PROJ` (families
    /// without a local solver: the label).
    pub fn legend(&self) -> String {
        match self.family {
            SolverFamily::Nsgs => format!("{} {}", self.label(), local_short_name(self.local)),
            _ => self.label(),
        }
    }
}

/// The one place where a spec becomes a solver configuration: Siconos' defaults for everything
/// else, from r given by the caller.
pub fn solver_config(
    spec: &SolverSpec,
    tolerance: f64,
    max_iter: usize,
    time_budget: Option<Duration>,
) -> SolverConfig {
    match spec.family {
        SolverFamily::Nsgs => {
            let mut o = NsgsOptions::with_local(spec.local);
            o.tolerance = tolerance;
            o.max_iter = max_iter;
            o.time_budget = time_budget;
            SolverConfig::Nsgs(o)
        }
        SolverFamily::Vi(solver) => {
            let mut o = ViOptions::new(solver);
            o.tolerance = tolerance;
            o.max_iter = max_iter;
            o.time_budget = time_budget;
            SolverConfig::Vi(o)
        }
        SolverFamily::Admm => SolverConfig::Admm(AdmmOptions {
            tolerance,
            max_iter,
            time_budget,
            ..Default::default()
        }),
        SolverFamily::Tfp => SolverConfig::Tresca(fc3d_core::tresca::TrescaOptions {
            tolerance,
            max_iter,
            time_budget,
            ..Default::default()
        }),
        SolverFamily::Pfp => SolverConfig::Pfp(fc3d_core::pfp::PfpOptions {
            tolerance,
            max_iter,
            time_budget,
            ..Default::default()
        }),
        SolverFamily::Aclmfp => SolverConfig::Aclm(fc3d_core::soclcp::AclmOptions {
            tolerance,
            max_iter,
            time_budget,
            ..Default::default()
        }),
        SolverFamily::Soclcp => SolverConfig::Soclcp(fc3d_core::soclcp::SoclcpOptions {
            tolerance,
            max_iter,
            time_budget,
            ..Default::default()
        }),
        SolverFamily::Nsn(formulation) => {
            let mut o = NsnOptions::new(formulation);
            o.tolerance = tolerance;
            o.max_iter = max_iter;
            o.time_budget = time_budget;
            SolverConfig::Nsn(o)
        }
        SolverFamily::ProxNsn | SolverFamily::ProxNsgs => {
            let mut o = ProxOptions::default();
            if spec.family == SolverFamily::ProxNsgs {
                o.internal = ProxInternal::Nsgs(NsgsOptions::default());
            }
            o.tolerance = tolerance;
            o.max_iter = max_iter;
            o.time_budget = time_budget;
            SolverConfig::Prox(o)
        }
    }
}

/// Every implemented combination (what `all` stands for).
pub fn all_specs() -> Vec<SolverSpec> {
    LocalSolverKind::ALL
        .iter()
        .map(|&local| SolverSpec {
            family: SolverFamily::Nsgs,
            local,
        })
        .collect()
}

/// Short name of a local solver (`PROJ`, `HYBRID`, ...).
pub fn local_short_name(kind: LocalSolverKind) -> &'static str {
    LOCAL_NAMES
        .iter()
        .find(|(k, _)| *k == kind)
        .map(|(_, names)| names[0])
        .unwrap_or("?")
}

fn parse_local(s: &str) -> Result<LocalSolverKind, String> {
    if let Ok(id) = s.parse::<i32>() {
        return LocalSolverKind::from_siconos_id(id).ok_or_else(|| {
            format!(
                "unknown local solver id {id} (one of {})",
                LocalSolverKind::ALL
                    .iter()
                    .map(|k| k.siconos_id().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        });
    }
    let upper = s.to_ascii_uppercase().replace('_', "-");
    LOCAL_NAMES
        .iter()
        .find(|(_, names)| names.contains(&upper.as_str()))
        .map(|(k, _)| *k)
        .ok_or_else(|| {
            let names: Vec<&str> = LOCAL_NAMES
                .iter()
                .flat_map(|(_, n)| n.iter().copied())
                .collect();
            format!(
                "unknown local solver '{s}' (a Siconos id or one of {})",
                names.join(", ")
            )
        })
}

/// Parses one spec (not `all`).
pub fn parse_spec(s: &str) -> Result<SolverSpec, String> {
    let s = s.trim();
    let (solver, local) = match s.split_once('/') {
        Some((a, b)) => (a.trim(), Some(b.trim())),
        None => (s, None),
    };
    let family = FAMILIES
        .iter()
        .find(|(_, id, name)| solver == id.to_string() || solver.eq_ignore_ascii_case(name))
        .map(|(f, _, _)| *f)
        .ok_or_else(|| {
            format!(
                "unknown solver '{solver}' in '{s}' (implemented: {}; or `all`)",
                FAMILIES
                    .iter()
                    .map(|(_, id, name)| format!("{id} = {name}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })?;
    let local = match (family, local) {
        (SolverFamily::Nsgs, None) => LocalSolverKind::NewtonHybrid,
        (SolverFamily::Nsgs, Some(l)) => parse_local(l)?,
        // Families without a local solver keep the default in the unused field.
        (_, None) => LocalSolverKind::NewtonHybrid,
        (_, Some(_)) => {
            return Err(format!(
                "solver '{solver}' takes no local solver (in '{s}')"
            ))
        }
    };
    Ok(SolverSpec { family, local })
}

/// Parses the `--solvers` list: comma-separated specs, `all` anywhere stands for every
/// combination; duplicates are dropped, the order of first appearance is kept.
pub fn parse_spec_list(s: &str) -> Result<Vec<SolverSpec>, String> {
    let mut specs: Vec<SolverSpec> = Vec::new();
    for item in s.split(',').map(str::trim) {
        if item.is_empty() {
            return Err(format!("empty solver spec in '{s}'"));
        }
        let new = if item.eq_ignore_ascii_case("all") {
            all_specs()
        } else {
            vec![parse_spec(item)?]
        };
        for spec in new {
            if !specs.contains(&spec) {
                specs.push(spec);
            }
        }
    }
    Ok(specs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nsgs(local: LocalSolverKind) -> SolverSpec {
        SolverSpec {
            family: SolverFamily::Nsgs,
            local,
        }
    }

    #[test]
    fn ids_names_and_defaults() {
        assert_eq!(parse_spec("500"), Ok(nsgs(LocalSolverKind::NewtonHybrid)));
        assert_eq!(parse_spec("nsgs"), Ok(nsgs(LocalSolverKind::NewtonHybrid)));
        assert_eq!(
            parse_spec("500/552"),
            Ok(nsgs(LocalSolverKind::ProjectionOnCone))
        );
        assert_eq!(
            parse_spec(" NSGS/SBP "),
            Ok(nsgs(LocalSolverKind::ProjectionOnCone))
        );
        assert_eq!(
            parse_spec("NSGS/sal"),
            Ok(nsgs(LocalSolverKind::ProjectionOnCylinder))
        );
        assert_eq!(
            parse_spec("500/nsn_gp"),
            Ok(nsgs(LocalSolverKind::NewtonAlartCurnierGp))
        );
        assert_eq!(
            parse_spec("NSGS/proj-iter"),
            Ok(nsgs(LocalSolverKind::ProjectionOnConeWithLocalIteration))
        );
        assert_eq!(
            parse_spec("NSGS/550"),
            Ok(nsgs(LocalSolverKind::NewtonAlartCurnier))
        );
        // Every local solver is reachable by id and by each of its names.
        for (kind, names) in LOCAL_NAMES {
            assert_eq!(
                parse_spec(&format!("500/{}", kind.siconos_id())),
                Ok(nsgs(kind))
            );
            for n in names {
                assert_eq!(parse_spec(&format!("NSGS/{n}")), Ok(nsgs(kind)));
            }
        }
        assert_eq!(LOCAL_NAMES.len(), LocalSolverKind::ALL.len());
    }

    #[test]
    fn bad_specs_are_errors() {
        for bad in [
            "",
            "501",
            "NSGS/500",
            "NSGS/xyz",
            "PSOR",
            "500/",
            "/552",
            "500/552/1",
        ] {
            assert!(parse_spec(bad).is_err(), "{bad:?}");
        }
        assert!(parse_spec_list("500,,552").is_err());
        assert!(parse_spec_list("500,foo").is_err());
        assert!(parse_spec("TFP/552").is_err());
    }

    #[test]
    fn lists_and_all() {
        let all = parse_spec_list("all").unwrap();
        assert_eq!(all.len(), LocalSolverKind::ALL.len());
        assert_eq!(
            all.iter().map(|s| s.local).collect::<Vec<_>>(),
            LocalSolverKind::ALL.to_vec()
        );
        // Duplicates are dropped, first appearance kept.
        let l = parse_spec_list("500/552, NSGS, 500/565, NSGS/SBP").unwrap();
        assert_eq!(
            l,
            vec![
                nsgs(LocalSolverKind::ProjectionOnCone),
                nsgs(LocalSolverKind::NewtonHybrid)
            ]
        );
        assert!(parse_spec_list("552x").is_err());
        let l = parse_spec_list("500/557,ALL").unwrap();
        assert_eq!(l[0], nsgs(LocalSolverKind::ProjectionOnCylinder));
        assert_eq!(l.len(), LocalSolverKind::ALL.len());
    }

    #[test]
    fn optimization_families() {
        for (spec, id, label) in [
            ("TFP", 503, "TFP/500"),
            ("503", 503, "TFP/500"),
            ("pfp", 522, "PFP/566"),
            ("ACLMFP", 516, "ACLMFP"),
            ("517", 517, "SOCLCP"),
        ] {
            let s = parse_spec(spec).unwrap();
            let c = solver_config(&s, 1e-7, 12, None);
            assert_eq!(c.siconos_id(), id);
            assert_eq!((c.tolerance(), c.max_iter()), (1e-7, 12));
            assert_eq!(s.label(), label);
            assert_eq!(s.legend(), label);
        }
    }

    #[test]
    fn config_and_labels() {
        let spec = nsgs(LocalSolverKind::ProjectionOnCone);
        let c = solver_config(&spec, 1e-6, 77, Some(Duration::from_millis(5)));
        assert_eq!(c.tolerance(), 1e-6);
        assert_eq!(c.max_iter(), 77);
        assert_eq!(c.time_budget(), Some(Duration::from_millis(5)));
        assert_eq!(c.siconos_id(), 500);
        #[allow(irrefutable_let_patterns)]
        let SolverConfig::Nsgs(o) = c
        else {
            panic!("expected NSGS")
        };
        assert_eq!(o.local.kind, LocalSolverKind::ProjectionOnCone);
        assert_eq!(spec.label(), "NSGS/552");
        assert_eq!(spec.legend(), "NSGS/552 PROJ");
    }

    #[test]
    fn vi_and_admm_families() {
        for (name, id, label) in [
            ("DSFP", 505, "DSFP"),
            ("vi-fpp", 506, "VI-FPP"),
            ("507", 507, "VI-EG"),
            ("FPP", 511, "FPP"),
            ("eg", 512, "EG"),
            ("ADMM", 523, "ADMM"),
        ] {
            let spec = parse_spec(name).unwrap();
            let c = solver_config(&spec, 1e-8, 33, None);
            assert_eq!(c.siconos_id(), id);
            assert_eq!(c.tolerance(), 1e-8);
            assert_eq!(c.max_iter(), 33);
            assert_eq!(spec.label(), label);
            assert_eq!(spec.legend(), label);
        }
        assert!(parse_spec("DSFP/552").is_err());
        assert!(parse_spec("ADMM/HYBRID").is_err());
    }

    #[test]
    fn newton_and_proximal_families() {
        for (text, id, label) in [
            ("504", 504, "NSN-AC/GP"),
            ("nsn-ac", 504, "NSN-AC/GP"),
            ("NSN-JM", 504, "NSN-JM/GP"),
            ("513", 513, "NSN-FB/GP"),
            ("nsn-nm", 520, "NSN-NM/GP"),
            ("502", 502, "PROX/NSN-AC"),
            ("PROX-NSGS", 502, "PROX/NSGS"),
        ] {
            let spec = parse_spec(text).unwrap();
            let c = solver_config(&spec, 1e-8, 50, None);
            assert_eq!(c.siconos_id(), id, "{text}");
            assert_eq!(c.tolerance(), 1e-8);
            assert_eq!(c.max_iter(), 50);
            assert_eq!(spec.label(), label);
            assert_eq!(spec.legend(), label);
        }
        assert!(parse_spec("504/552").is_err());
    }
}
