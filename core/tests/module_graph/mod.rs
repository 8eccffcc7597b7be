//! The module graph of a crate read from its source, for the architecture tests of the core
//! (`core/tests/architecture.rs`) and of the C layer (`capi/tests/architecture.rs`): the
//! `crate::` and `super::` paths of every module (comments skipped) as edges module -> module,
//! and the import cycles between the modules of one folder.

#![allow(dead_code)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

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
pub fn module_of(src: &Path, file: &Path) -> Vec<String> {
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
pub fn crate_paths(text: &str) -> Vec<Vec<String>> {
    paths_after(text, "crate::")
}

/// The paths that follow `prefix` in the code of `text`.
pub fn paths_after(text: &str, prefix: &str) -> Vec<Vec<String>> {
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

pub struct Source {
    /// Every module of the crate (its path, `[]` for the root) and its source text.
    pub modules: BTreeMap<Vec<String>, String>,
}

impl Source {
    /// The modules of the crate whose sources are in `src`.
    pub fn read(src: &Path) -> Self {
        let mut files = Vec::new();
        rust_files(src, &mut files);
        let modules = files
            .iter()
            .map(|f| (module_of(src, f), std::fs::read_to_string(f).unwrap()))
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
    pub fn edges(&self) -> BTreeSet<(Vec<String>, Vec<String>)> {
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

/// A cycle in `edges`, as the nodes on it.
pub fn find_cycle(edges: &BTreeSet<(String, String)>) -> Option<Vec<String>> {
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

/// The imports between sibling modules, by folder: every module is grouped by (folder, child of
/// that folder) for each folder it lies in, so that an import between submodules of two
/// siblings counts as one between the siblings. An edge between a module and its own ancestor
/// (a parent's re-exports) is no sibling edge.
pub fn sibling_edges(source: &Source) -> BTreeMap<Vec<String>, BTreeSet<(String, String)>> {
    let mut by_folder: BTreeMap<Vec<String>, BTreeSet<(String, String)>> = BTreeMap::new();
    for (from, to) in source.edges() {
        let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
        if common == from.len() || common == to.len() {
            continue;
        }
        by_folder
            .entry(from[..common].to_vec())
            .or_default()
            .insert((from[common].clone(), to[common].clone()));
    }
    by_folder
}

/// Panics naming the first import cycle between the modules of one folder.
pub fn assert_no_sibling_cycle(by_folder: &BTreeMap<Vec<String>, BTreeSet<(String, String)>>) {
    for (folder, edges) in by_folder {
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
}
