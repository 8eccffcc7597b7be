//! The problems a bench runs on, and the family each belongs to.

use std::path::PathBuf;

use crate::inputs::AnyProblem;

/// Problem family: the file name's prefix before the first digit or dash, without trailing
/// `_`/`.` (`Rover1039.dat` → `Rover`, `Capsules-i100-889.dat` → `Capsules`,
/// `NESpheres_10_1.dat` → `NESpheres`); the whole stem when that prefix is empty.
pub fn family_of(file_name: &str) -> String {
    let stem = file_name.strip_suffix(".dat").unwrap_or(file_name);
    let cut = stem
        .find(|c: char| c.is_ascii_digit() || c == '-')
        .unwrap_or(stem.len());
    let prefix = stem[..cut].trim_end_matches(['_', '.', ' ']);
    if prefix.is_empty() {
        stem.to_string()
    } else {
        prefix.to_string()
    }
}

/// A loaded problem.
pub(super) struct Problem {
    pub(super) name: String,
    pub(super) family: String,
    pub(super) problem: AnyProblem,
}

/// Loads the inputs with the CLI's rules (folder scan, skips); errors go to stderr.
pub(super) fn load_problems(paths: &[PathBuf], failed: &mut bool) -> Vec<Problem> {
    if paths.is_empty() {
        return fc3d_core::scenes::default_scenes()
            .into_iter()
            .map(|s| Problem {
                name: s.name.to_string(),
                family: s.name.to_string(),
                problem: AnyProblem::Local(s.problem),
            })
            .collect();
    }
    let (inputs, errors) = crate::inputs::expand_paths(paths);
    for message in &errors {
        eprintln!("fc3d: {message}");
    }
    *failed |= !errors.is_empty();
    let mut problems = Vec::new();
    for input in inputs {
        match crate::inputs::load_input(input) {
            crate::inputs::Loaded::Problem(name, problem) => problems.push(Problem {
                family: family_of(&name),
                name,
                problem,
            }),
            crate::inputs::Loaded::Skipped => {}
            crate::inputs::Loaded::Failed => *failed = true,
        }
    }
    problems
}
