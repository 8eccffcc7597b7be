//! The layering of the core, checked from its source: every `crate::` path a module uses points
//! at its own layer or below, the solver families import each other without cycles, and no two
//! modules of one folder import each other in a cycle. Layers, bottom to top:
//! `error` → `math` → `matrix` → `problem` → `measure`, `io`, `scenes` → `contract` → `local` →
//! `solvers` → `config` → `solve` (docs/architecture.md).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const LAYERS: &[(&str, usize)] = &[
    ("error", 0),
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

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a source file: `solvers/nsgs/mod.rs` → `["solvers", "nsgs"]`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

/// The `crate::a::b::...` paths of the code of `text` (comments skipped), as segment lists.
fn crate_paths(text: &str) -> Vec<Vec<String>> {
    paths_after(text, "crate::")
}

/// The paths that follow `prefix` in the code of `text`.
fn paths_after(text: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    for line in text.lines() {
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        let mut rest = code;
        while let Some(i) = rest.find(prefix) {
            if rest[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
                rest = &rest[i + prefix.len()..];
                continue;
            }
            let after = &rest[i + prefix.len()..];
            let mut segments = Vec::new();
            let mut tail = after;
            loop {
                let end = tail
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(tail.len());
                if end == 0 {
                    break;
                }
                segments.push(tail[..end].to_string());
                tail = &tail[end..];
                match tail.strip_prefix("::") {
                    Some(t) => tail = t,
                    None => break,
                }
            }
            if !segments.is_empty() {
                paths.push(segments);
            }
            rest = after;
        }
    }
    paths
}

struct Source {
    modules: BTreeMap<Vec<String>, String>,
}

impl Source {
    fn read() -> Self {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let modules = files
            .iter()
            .map(|f| (module_of(&src, f), std::fs::read_to_string(f).unwrap()))
            .collect();
        Source { modules }
    }

    /// The longest known module that `path` starts with.
    fn target(&self, path: &[String]) -> Option<Vec<String>> {
        (1..=path.len())
            .rev()
            .map(|n| path[..n].to_vec())
            .find(|p| self.modules.contains_key(p))
    }

    /// Edges module → module of every `crate::` and `super::` path (self edges and the crate
    /// root excluded).
    fn edges(&self) -> BTreeSet<(Vec<String>, Vec<String>)> {
        let mut edges = BTreeSet::new();
        for (module, text) in &self.modules {
            let parent = &module[..module.len().saturating_sub(1)];
            let relative = paths_after(text, "super::").into_iter().map(|p| {
                let mut full = parent.to_vec();
                full.extend(p);
                full
            });
            for path in crate_paths(text).into_iter().chain(relative) {
                if let Some(target) = self.target(&path) {
                    if &target != module && !target.is_empty() && !module.is_empty() {
                        edges.insert((module.clone(), target));
                    }
                }
            }
        }
        edges
    }
}

#[test]
fn every_module_imports_its_layer_or_below() {
    let source = Source::read();
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

/// A cycle in `edges` restricted to the nodes `keep` maps to a group, as the groups on it.
fn find_cycle(edges: &BTreeSet<(String, String)>) -> Option<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.iter().flat_map(|(a, b)| [a, b]).collect();
    // Depth-first search with colours: 1 on the stack, 2 done.
    let mut colour: BTreeMap<&String, u8> = BTreeMap::new();
    fn visit<'a>(
        n: &'a String,
        edges: &'a BTreeSet<(String, String)>,
        colour: &mut BTreeMap<&'a String, u8>,
        stack: &mut Vec<&'a String>,
    ) -> Option<Vec<String>> {
        colour.insert(n, 1);
        stack.push(n);
        for (_, m) in edges.iter().filter(|(a, _)| a == n) {
            match colour.get(m) {
                Some(1) => {
                    let start = stack.iter().position(|s| *s == m).unwrap();
                    return Some(stack[start..].iter().map(|s| s.to_string()).collect());
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(m, edges, colour, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        colour.insert(n, 2);
        None
    }
    for n in nodes {
        if !colour.contains_key(n) {
            if let Some(c) = visit(n, edges, &mut colour, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn no_import_cycles_between_families_or_sibling_modules() {
    let source = Source::read();
    // Group every module by (folder, child of that folder) for each folder it lies in, so that
    // a cycle through submodules of two siblings counts as a cycle between the siblings.
    let mut by_folder: BTreeMap<Vec<String>, BTreeSet<(String, String)>> = BTreeMap::new();
    for (from, to) in source.edges() {
        let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
        // An edge between a module and its own ancestor (a parent's re-exports) is no sibling
        // edge.
        if common == from.len() || common == to.len() {
            continue;
        }
        by_folder
            .entry(from[..common].to_vec())
            .or_default()
            .insert((from[common].clone(), to[common].clone()));
    }
    for (folder, edges) in &by_folder {
        if let Some(cycle) = find_cycle(edges) {
            panic!(
                "import cycle between the modules of `{}`: {}",
                if folder.is_empty() {
                    "crate".to_string()
                } else {
                    folder.join("::")
                },
                cycle.join(" -> ")
            );
        }
    }
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
    let source = Source::read();
    let edges = source.edges();
    let solvers_to_contract = edges
        .iter()
        .any(|(a, b)| a[0] == "solvers" && b[0] == "contract");
    assert!(solvers_to_contract);
}
