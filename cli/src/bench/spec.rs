//! Solver specs of `fc3d bench --solvers`: what the user writes, and the one function that turns a
//! spec into a [`SolverConfig`]. The names come from the core: the families' presets
//! ([`Method::presets`]) and the local solvers' registry ([`LocalSolverKind::names`]), so a new
//! family or local solver needs no edit here.
//!
//! Grammar (case-insensitive, specs separated by commas):
//!
//! * `all` — NSGS with each local solver of [`LocalSolverKind::ALL`];
//! * `SOLVER` — a solver by Siconos id or name with its defaults: `500` or `NSGS` (= `500/565`),
//!   `DSFP`, `VI-FPP`, `NSN-AC`, `PROX-NSGS`, `TFP`, ... ([`solvers_help`] lists them);
//! * `NSGS/LOCAL` (or `500/LOCAL`) — NSGS with a local solver given by Siconos id or name;
//! * a global id (600-615 but 601, 608, 609) or name (`GFC3D_NSGS`, `NSGS_WR`, `NSN_AC`, `IPM`,
//!   ...; a name the local families also use means the local one: `GFC3D_ADMM` is 613, `ADMM`
//!   523) — a global solver with Siconos' defaults, for global problems. A local solver given for
//!   a global problem solves its reduction (`NSGS` there is 600, `AUTO` the reduction with AUTO).

use std::time::Duration;

use fc3d_core::global::{GlobalConfig, GlobalMethod};
use fc3d_core::{LocalSolverKind, Method, NsgsOptions, SolverConfig};

/// One solver to benchmark: a local family with its defaults (for NSGS, its local solver), or a
/// global solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolverSpec {
    Local(Method),
    Global(GlobalMethod),
}

impl SolverSpec {
    /// NSGS with the local solver `local`.
    pub fn nsgs(local: LocalSolverKind) -> Self {
        SolverSpec::Local(Method::Nsgs(NsgsOptions::with_local(local)))
    }

    /// The local solver, for NSGS.
    pub fn local(&self) -> Option<LocalSolverKind> {
        match self {
            SolverSpec::Local(Method::Nsgs(o)) => Some(o.local.kind),
            _ => None,
        }
    }

    /// The label of the CSV and the tables, e.g. `NSGS/552` (the CLI's `SolverConfig::label`),
    /// `GFC3D-NSGS` (605), `WR-NSGS/565` (600).
    pub fn label(&self) -> String {
        match self {
            SolverSpec::Local(m) => m.label(),
            SolverSpec::Global(g) => g.label(),
        }
    }

    /// The method on a local problem; a global solver has none.
    pub fn local_method(&self) -> Result<Method, String> {
        match self {
            SolverSpec::Local(m) => Ok(*m),
            SolverSpec::Global(g) => Err(format!(
                "{} (id {}) is a global solver: it solves global problems (M, H) only",
                g.label(),
                g.siconos_id()
            )),
        }
    }

    /// The method on a global problem: the global solver, or the reduction with the local one.
    pub fn global_method(&self) -> GlobalMethod {
        match self {
            SolverSpec::Local(m) => GlobalMethod::Reduced(*m),
            SolverSpec::Global(g) => *g,
        }
    }

    /// The label with the local solver's short name, for legends: `NSGS/552 PROJ` (families
    /// without a local solver: the label).
    pub fn legend(&self) -> String {
        match self.local() {
            Some(kind) => format!("{} {}", self.label(), local_short_name(kind)),
            None => self.label(),
        }
    }
}

/// The one place where a spec becomes a solver configuration: the family's defaults for
/// everything else, from r given by the caller.
pub fn solver_config(
    spec: &SolverSpec,
    tolerance: f64,
    max_iter: usize,
    time_budget: Option<Duration>,
) -> Result<SolverConfig, String> {
    Ok(SolverConfig::new(spec.local_method()?)
        .with_tolerance(tolerance)
        .with_max_iter(max_iter)
        .with_time_budget(time_budget))
}

/// [`solver_config`] for a global problem.
pub fn global_solver_config(
    spec: &SolverSpec,
    tolerance: f64,
    max_iter: usize,
    time_budget: Option<Duration>,
) -> GlobalConfig {
    let mut config = GlobalConfig::new(spec.global_method());
    config.tolerance = tolerance;
    config.max_iter = max_iter;
    config.time_budget = time_budget;
    config
}

/// Every implemented combination (what `all` stands for).
pub fn all_specs() -> Vec<SolverSpec> {
    LocalSolverKind::ALL.map(SolverSpec::nsgs).to_vec()
}

/// Short name of a local solver (`PROJ`, `HYBRID`, ...).
pub fn local_short_name(kind: LocalSolverKind) -> &'static str {
    kind.names()[0]
}

/// The `--solvers` help: the grammar and every name the core offers.
pub fn solvers_help() -> String {
    let locals: Vec<String> = LocalSolverKind::ALL
        .iter()
        .map(|k| format!("{} {}", k.siconos_id(), k.names().join("|")))
        .collect();
    let families: Vec<String> = Method::presets()
        .iter()
        .map(|m| format!("{} {}", m.siconos_id(), m.name()))
        .collect();
    let globals: Vec<String> = GlobalMethod::presets()
        .iter()
        .chain(&GlobalMethod::own_presets())
        .map(|m| format!("{} GFC3D_{}", m.siconos_id(), m.name().unwrap_or("")))
        .collect();
    format!(
        "Solvers, comma-separated: `all` (NSGS with every local solver), `500` or `NSGS` (NSGS \
         with its default local solver 565), `500/552`, `NSGS/SBP`, ... Local solvers by Siconos \
         id or name: {}. Families by id or name, with their Siconos defaults: {}. Global solvers \
         (for global problems; a local solver solves a global problem's reduction): {}",
        locals.join(", "),
        families.join(", "),
        globals.join(", ")
    )
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
    LocalSolverKind::ALL
        .into_iter()
        .find(|k| k.names().contains(&upper.as_str()))
        .ok_or_else(|| {
            let names: Vec<&str> = LocalSolverKind::ALL
                .iter()
                .flat_map(|k| k.names().iter().copied())
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
    if let Some(global) = parse_global(s)? {
        return Ok(SolverSpec::Global(global));
    }
    let (solver, local) = match s.split_once('/') {
        Some((a, b)) => (a.trim(), Some(b.trim())),
        None => (s, None),
    };
    let Some(method) = Method::preset(solver).filter(|_| !solver.is_empty()) else {
        if let Some(global) = GlobalMethod::preset(s).filter(|_| local.is_none()) {
            return Ok(SolverSpec::Global(global));
        }
        return Err(format!(
            "unknown solver '{solver}' in '{s}' (implemented: {}; global: {}; or `all`)",
            Method::presets()
                .iter()
                .map(|m| format!("{} = {}", m.siconos_id(), m.name()))
                .collect::<Vec<_>>()
                .join(", "),
            GlobalMethod::presets()
                .iter()
                .chain(&GlobalMethod::own_presets())
                .map(|m| format!("{} = GFC3D_{}", m.siconos_id(), m.name().unwrap_or("")))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    };
    match (method, local) {
        // The preset's sweep options (its decomposition) with the local solver asked for.
        (Method::Nsgs(o), local) => Ok(SolverSpec::Local(Method::Nsgs(NsgsOptions {
            local: NsgsOptions::with_local(match local {
                Some(l) => parse_local(l)?,
                None => LocalSolverKind::NewtonHybrid,
            })
            .local,
            ..o
        }))),
        (method, None) => Ok(SolverSpec::Local(method)),
        (_, Some(_)) => Err(format!(
            "solver '{solver}' takes no local solver (in '{s}')"
        )),
    }
}

/// A global id (600-615, 5000) or a name with Siconos' `GFC3D` prefix: the global preset, or
/// the reason fc3d does not run it. `None` for anything else.
fn parse_global(s: &str) -> Result<Option<GlobalMethod>, String> {
    let id = s.parse::<i32>().ok();
    let global_id = id.is_some_and(|id| (600..=615).contains(&id) || id == 5000);
    let prefixed = s.len() >= 5 && s[..5].eq_ignore_ascii_case("gfc3d");
    if !global_id && !prefixed {
        return Ok(None);
    }
    GlobalMethod::preset(s).map(Some).ok_or_else(|| match id {
        Some(601) => "601 (GFC3D_NSGSV_WR) is not run: Siconos 4.4's exits the process on its \
                      default options"
            .to_string(),
        Some(608 | 609) => {
            format!("{s} (GAMS) is not run: GAMS is a commercial solver fc3d does not link")
        }
        Some(5000) => "5000 is the global rolling-friction solver (g_rolling_fc3d_driver): the \
                       CLI solves global problems of dimension 3"
            .to_string(),
        _ => format!(
            "unknown global solver '{s}' (one of {})",
            GlobalMethod::presets()
                .iter()
                .chain(&GlobalMethod::own_presets())
                .map(|m| format!("{} = GFC3D_{}", m.siconos_id(), m.name().unwrap_or("")))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    })
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
        SolverSpec::nsgs(local)
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
        for kind in LocalSolverKind::ALL {
            assert_eq!(
                parse_spec(&format!("500/{}", kind.siconos_id())),
                Ok(nsgs(kind))
            );
            for n in kind.names() {
                assert_eq!(parse_spec(&format!("NSGS/{n}")), Ok(nsgs(kind)));
            }
        }
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
            all.iter().map(|s| s.local().unwrap()).collect::<Vec<_>>(),
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
            let c = solver_config(&s, 1e-7, 12, None).unwrap();
            assert_eq!(c.siconos_id(), id);
            assert_eq!((c.tolerance, c.max_iter), (1e-7, 12));
            assert_eq!(s.label(), label);
            assert_eq!(s.legend(), label);
        }
    }

    #[test]
    fn config_and_labels() {
        let spec = nsgs(LocalSolverKind::ProjectionOnCone);
        let c = solver_config(&spec, 1e-6, 77, Some(Duration::from_millis(5))).unwrap();
        assert_eq!(c.tolerance, 1e-6);
        assert_eq!(c.max_iter, 77);
        assert_eq!(c.time_budget, Some(Duration::from_millis(5)));
        assert_eq!(c.siconos_id(), 500);
        let Method::Nsgs(o) = c.method else {
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
            let c = solver_config(&spec, 1e-8, 33, None).unwrap();
            assert_eq!(c.siconos_id(), id);
            assert_eq!(c.tolerance, 1e-8);
            assert_eq!(c.max_iter, 33);
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
            let c = solver_config(&spec, 1e-8, 50, None).unwrap();
            assert_eq!(c.siconos_id(), id, "{text}");
            assert_eq!(c.tolerance, 1e-8);
            assert_eq!(c.max_iter, 50);
            assert_eq!(spec.label(), label);
            assert_eq!(spec.legend(), label);
        }
        assert!(parse_spec("504/552").is_err());
    }

    #[test]
    fn global_ids_and_names() {
        for (text, id) in [
            ("600", 600),
            ("605", 605),
            ("GFC3D_NSGS", 605),
            ("gfc3d_nsgs_wr", 600),
            ("NSGS_WR", 600),
            ("GFC3D ADMM", 613),
            ("gfc3d-admm", 613),
            ("IPM", 615),
            ("607", 607),
            ("614", 614),
        ] {
            let spec = parse_spec(text).unwrap();
            let SolverSpec::Global(g) = spec else {
                panic!("{text} is global")
            };
            assert_eq!(g.siconos_id(), id, "{text}");
            assert!(solver_config(&spec, 1e-6, 10, None).is_err());
            let c = global_solver_config(&spec, 1e-6, 10, None);
            assert_eq!((c.tolerance, c.max_iter), (1e-6, 10));
        }
        // Local names keep their local meaning; on a global problem they solve the reduction.
        let nsgs = parse_spec("NSGS").unwrap();
        assert_eq!(nsgs.global_method().siconos_id(), 600);
        assert_eq!(parse_spec("ADMM").unwrap().label(), "ADMM");
        for bad in ["601", "608", "609", "5000", "616", "GFC3D_FOO", "605/552"] {
            assert!(parse_spec(bad).is_err(), "{bad}");
        }
    }
}
