//! The problems a command reads: the built-in scenes, generated scenes
//! (`gen:contacts=N,piles=P,seed=S[,shape=boxes]`), `.dat` and FCLIB files, and folders of them.
//! `fc3d solve` and `fc3d bench` take the same inputs. A file named on the command line may hold
//! a global problem (M, H, q, b, mu: Siconos' global `.dat` format or FCLIB `/fclib_global`):
//! it is recognised by its content and solved as one.

use std::path::{Path, PathBuf};

use fc3d_core::io::dat::{read_global_dat_file, GlobalDat, GlobalDatProblem, GlobalStorage};
use fc3d_core::problem::GlobalProblem;
use fc3d_core::{Fc3dError, FrictionProblem};

/// A problem in the local (Delassus) form or in the global one.
pub(crate) enum AnyProblem {
    Local(FrictionProblem<'static>),
    /// With the storages its file gave M and H (sparse for FCLIB and generated scenes).
    Global(Box<GlobalProblem<'static>>, GlobalStorage),
}

impl AnyProblem {
    pub(crate) fn n_contacts(&self) -> usize {
        match self {
            AnyProblem::Local(p) => p.n_contacts(),
            AnyProblem::Global(p, _) => p.n_contacts(),
        }
    }
}

/// One problem to solve: a built-in scene, a generated one
/// (`gen:contacts=N,piles=P,seed=S[,shape=boxes]`) or a file.
pub(crate) enum Input {
    Scene(fc3d_core::scenes::Scene),
    Generated(fc3d_core::scenes::GeneratedScene),
    File { path: PathBuf, from_directory: bool },
}

/// What reading one input gave.
pub(crate) enum Loaded {
    Problem(String, AnyProblem),
    /// Found by a folder scan but not a problem fc3d handles (a note was printed).
    Skipped,
    /// Could not be read (a message naming it was printed).
    Failed,
}

/// Reads one input; messages go to stderr.
pub(crate) fn load_input(input: Input) -> Loaded {
    match input {
        Input::Scene(s) => Loaded::Problem(s.name.to_string(), AnyProblem::Local(s.problem)),
        Input::Generated(spec) => match spec.generate() {
            Ok(p) => Loaded::Problem(spec.name(), AnyProblem::Local(p)),
            Err(e) => {
                eprintln!("fc3d: {e}");
                Loaded::Failed
            }
        },
        Input::File {
            path,
            from_directory,
        } => match read_any_problem(&path, !from_directory) {
            Ok(p) => Loaded::Problem(display_name(&path), p),
            // The reader's messages name the file.
            Err(Fc3dError::Unsupported(why)) if from_directory => {
                eprintln!("fc3d: skipping {why}");
                Loaded::Skipped
            }
            // A folder of Siconos test data holds other inputs too (global problems,
            // unit-test tables): they are not counted as failures when found by a scan.
            Err(e) if from_directory => {
                eprintln!("fc3d: skipping (not a local fc3d problem) {e}");
                Loaded::Skipped
            }
            Err(e) => {
                eprintln!("fc3d: {e}");
                Loaded::Failed
            }
        },
    }
}

fn display_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// An input named `gen:contacts=N,piles=P,seed=S` is a generated pile scene
/// ([`fc3d_core::scenes::sphere_piles`], or [`fc3d_core::scenes::box_piles`] with
/// `,shape=boxes`), not a file.
const GENERATED_PREFIX: &str = "gen:";

/// Files as given, directories replaced by their `*.dat` files sorted by name; paths that cannot
/// be used are returned as messages (the others are still solved).
pub(crate) fn expand_paths(paths: &[PathBuf]) -> (Vec<Input>, Vec<String>) {
    let mut inputs = Vec::new();
    let mut errors = Vec::new();
    for path in paths {
        if let Some(spec) = path.to_str().and_then(|p| p.strip_prefix(GENERATED_PREFIX)) {
            match fc3d_core::scenes::GeneratedScene::parse(spec) {
                Ok(spec) => inputs.push(Input::Generated(spec)),
                Err(e) => errors.push(e.to_string()),
            }
            continue;
        }
        match std::fs::metadata(path) {
            Err(e) => errors.push(format!("{}: {e}", path.display())),
            Ok(meta) if meta.is_dir() => match dat_files_in(path) {
                Ok(files) if files.is_empty() => errors.push(format!(
                    "{}: no .dat file in this directory",
                    path.display()
                )),
                Ok(files) => inputs.extend(files.into_iter().map(|path| Input::File {
                    path,
                    from_directory: true,
                })),
                Err(e) => errors.push(format!("{}: {e}", path.display())),
            },
            Ok(_) => inputs.push(Input::File {
                path: path.clone(),
                from_directory: false,
            }),
        }
    }
    (inputs, errors)
}

/// Reads a problem file, local or global: with `detect_global`, a global problem (Siconos'
/// global `.dat` format, or an FCLIB file with `/fclib_global`) is read as one; otherwise, and
/// when the file is not a global problem, as [`read_problem`] does.
///
/// A global `.dat` file is recognised by reading it as one (its text may also parse as a wrong
/// local problem, so the global reader goes first); when that fails the local reader's answer
/// is returned, except for a file Siconos' way names global (`GFC3D_*`, `gfc2d_*`), whose global
/// reader's error is the one that explains it.
pub(crate) fn read_any_problem(path: &Path, detect_global: bool) -> Result<AnyProblem, Fc3dError> {
    if !detect_global {
        return read_problem(path).map(AnyProblem::Local);
    }
    let global = if is_fclib(path) {
        fc3d_core::io::read_fclib_global_file(path)
            .map(|p| AnyProblem::Global(Box::new(p), sparse_storage()))
    } else {
        match read_global_dat_file(path) {
            Ok(GlobalDat {
                problem: GlobalDatProblem::Spatial(p),
                storage,
            }) => Ok(AnyProblem::Global(Box::new(p), storage)),
            Ok(_) => {
                return Err(Fc3dError::Unsupported(format!(
                    "{}: a global problem of dimension 2 (gfc2d): fc3d solves dimension 3",
                    path.display()
                )))
            }
            Err(e) => Err(e),
        }
    };
    match global {
        Ok(p) => Ok(p),
        Err(e) if is_global_name(path) => Err(e),
        Err(_) => read_problem(path).map(AnyProblem::Local),
    }
}

/// M and H as triplets (Siconos' `NM_SPARSE`): the storage of a global problem that came
/// without one.
pub(crate) fn sparse_storage() -> GlobalStorage {
    GlobalStorage::default()
}

/// Siconos names global problem files `GFC3D_*` / `gfc3d_*` (`gfc2d_*` in 4.5).
fn is_global_name(path: &Path) -> bool {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    name.starts_with("gfc3d_") || name.starts_with("gfc2d_")
}

/// `.hdf5`/`.h5` files are FCLIB problems (read when built with the `fclib` feature, refused
/// with a clear message otherwise); any other path is read as a Siconos `.dat` file.
pub(crate) fn read_problem(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    if is_fclib(path) {
        fc3d_core::io::read_problem_file(path)
    } else {
        fc3d_core::io::dat::read_dat_file(path)
    }
}

fn is_fclib(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("hdf5") || e.eq_ignore_ascii_case("h5"))
}

fn dat_files_in(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if !path.is_file() || !(path.extension().is_some_and(|e| e == "dat") || is_fclib(&path)) {
            continue;
        }
        // Siconos names global problems (M, H, q, b, mu) GFC3D_/gfc3d_/gfc2d_: their text
        // happens to parse as a (wrong) local problem, so a folder scan (which compares local
        // solvers) leaves them out; named one by one, they are solved as global problems.
        if is_global_name(&path) {
            eprintln!(
                "fc3d: skipping {}: a global (M, H) problem (name it to solve it)",
                path.display()
            );
            continue;
        }
        files.push(path);
    }
    files.sort();
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_inputs_are_scenes_not_files() {
        let (inputs, errors) = expand_paths(&[
            PathBuf::from("gen:contacts=10,piles=2"),
            PathBuf::from("gen:piles=2"),
            PathBuf::from("gen:contacts=30,shape=boxes"),
            PathBuf::from("gen:contacts=30,shape=cones"),
        ]);
        assert_eq!((inputs.len(), errors.len()), (2, 2), "{errors:?}");
        let mut loaded = inputs.into_iter().map(load_input);
        match loaded.next().unwrap() {
            Loaded::Problem(name, AnyProblem::Local(p)) => {
                assert_eq!(name, "piles-c10-p2-s1");
                assert_eq!(p.n_contacts(), 10);
            }
            _ => panic!("a generated scene loads"),
        }
        match loaded.next().unwrap() {
            Loaded::Problem(name, AnyProblem::Local(p)) => {
                assert_eq!(name, "boxes-c30-p1-s1");
                assert_eq!(p.n_contacts(), 30);
            }
            _ => panic!("a generated box scene loads"),
        }
    }

    #[test]
    fn paths_that_cannot_be_used_are_reported() {
        let (inputs, errors) = expand_paths(&[
            PathBuf::from("/nonexistent/fc3d/a.dat"),
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src"),
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"),
        ]);
        assert_eq!(inputs.len(), 1);
        assert_eq!(errors.len(), 2, "{errors:?}");
        assert!(errors[1].contains("no .dat file"));
    }
}
