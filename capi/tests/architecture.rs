//! The C layer's modules import each other one way: no two modules of one folder of `capi/src`
//! import each other in a cycle (as `fclib.rs` and `problem.rs`, `options.rs` and `params/`,
//! `params/siconos.rs` and its table once did). Read from the source with the core's checker
//! (`core/tests/architecture.rs`). Test modules (`tests`) are left out: they drive the module
//! they test from above (`params::tests` allocates options through `options.rs`).

use std::collections::BTreeMap;
use std::path::Path;

#[path = "../../core/tests/module_graph/mod.rs"]
mod module_graph;
use module_graph::{assert_no_sibling_cycle, find_cycle, sibling_edges, Source};

fn segments(path: &str) -> Vec<String> {
    path.split("::").map(String::from).collect()
}

fn library_source() -> Source {
    let mut source = Source::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    source
        .modules
        .retain(|module, _| module.last().is_none_or(|m| m != "tests"));
    source
}

#[test]
fn no_import_cycles_between_sibling_modules() {
    let source = library_source();
    let edges = source.edges();
    // The checker sees the imports it must see (a regression guard for the parser).
    for (from, to) in [
        ("driver", "params"),
        ("problem_files", "fclib"),
        ("fclib", "problem"),
        ("params", "option_tree"),
        ("params::siconos", "params::siconos_table"),
    ] {
        assert!(
            edges.contains(&(segments(from), segments(to))),
            "{from} -> {to} not seen"
        );
    }
    assert_no_sibling_cycle(&sibling_edges(&source));
}

/// Two sibling modules that import each other are a cycle for the checker.
#[test]
fn the_checker_finds_a_two_module_cycle() {
    let modules = BTreeMap::from([
        (vec![], String::new()),
        (segments("problem"), "use super::fclib::read;".into()),
        (segments("fclib"), "let p = crate::problem::to_c(x);".into()),
    ]);
    let by_folder = sibling_edges(&Source { modules });
    let cycle = find_cycle(&by_folder[&Vec::<String>::new()]).expect("a cycle");
    assert_eq!(cycle.len(), 2);
}
