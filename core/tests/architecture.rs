//! The layering of the core, checked from its source: every `crate::` path a module uses points
//! at its own layer or below, the solver families import each other without cycles, and no two
//! modules of one folder import each other in a cycle. Layers, bottom to top:
//! `error` → `math` → `matrix` → `problem` → `measure`, `io`, `scenes` → `contract` → `local` →
//! `solvers` → `config` → `solve` (docs/architecture.md).

use std::path::Path;

mod module_graph;
use module_graph::{assert_no_sibling_cycle, crate_paths, sibling_edges, Source};

const LAYERS: &[(&str, usize)] = &[
    ("error", 0),
    ("alloc", 0),
    ("math", 1),
    ("matrix", 2),
    ("problem", 3),
    ("measure", 4),
    ("io", 4),
    ("scenes", 4),
    ("diagnostics", 4),
    ("contract", 5),
    ("local", 6),
    ("solvers", 7),
    ("config", 8),
    ("solve", 9),
    ("workspace", 10),
    ("global", 10),
];

fn layer(module: &str) -> usize {
    LAYERS
        .iter()
        .find(|(m, _)| *m == module)
        .unwrap_or_else(|| panic!("module `{module}` has no layer in tests/architecture.rs"))
        .1
}

fn source() -> Source {
    Source::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"))
}

#[test]
fn every_module_imports_its_layer_or_below() {
    let source = source();
    let mut violations = Vec::new();
    // The crate root's re-exports would hide a dependency from this check: inside the crate,
    // items are named by their module path.
    for (module, text) in &source.modules {
        for path in crate_paths(text) {
            if path.len() == 1 && path[0].starts_with(|c: char| c.is_ascii_uppercase()) {
                violations.push(format!("{} names crate::{}", module.join("::"), path[0]));
            }
        }
    }
    for (from, to) in source.edges() {
        if layer(&to[0]) > layer(&from[0]) {
            violations.push(format!("{} imports {}", from.join("::"), to.join("::")));
        }
    }
    assert!(
        violations.is_empty(),
        "upward imports:\n{}",
        violations.join("\n")
    );
}

#[test]
fn no_import_cycles_between_families_or_sibling_modules() {
    let by_folder = sibling_edges(&source());
    assert_no_sibling_cycle(&by_folder);
    // The families form a DAG: e.g. PFP uses TFP's sub-problem, PROX uses NSGS and NSN.
    assert!(by_folder.contains_key(&vec!["solvers".to_string()]));
}

/// The checker sees the imports it must see (a regression guard for the parser).
#[test]
fn the_checker_parses_paths() {
    let paths = crate_paths(
        "use crate::math::linalg::{norm, Vec3};\n// crate::config::X\nlet x = crate::measure::f(crate::problem::P);",
    );
    assert_eq!(
        paths,
        vec![
            vec!["math", "linalg"],
            vec!["measure", "f"],
            vec!["problem", "P"],
        ]
        .into_iter()
        .map(|p| p.into_iter().map(String::from).collect::<Vec<_>>())
        .collect::<Vec<_>>()
    );
    let source = source();
    let edges = source.edges();
    let solvers_to_contract = edges
        .iter()
        .any(|(a, b)| a[0] == "solvers" && b[0] == "contract");
    assert!(solvers_to_contract);
}
