//! The problems a command reads: the built-in scenes, generated scenes
//! (`gen:contacts=N,piles=P,seed=S[,shape=boxes]`), `.dat` and FCLIB files, and folders of them.
//! `fc3d solve` and `fc3d bench` take the same inputs.

use std::path::{Path, PathBuf};

use fc3d_core::{Fc3dError, FrictionProblem};

/// One problem to solve: a built-in scene, a generated one
/// (`gen:contacts=N,piles=P,seed=S[,shape=boxes]`) or a file.
pub(crate) enum Input {
    Scene(fc3d_core::scenes::Scene),
    Generated(fc3d_core::scenes::GeneratedScene),
    File { path: PathBuf, from_directory: bool },
}

/// What reading one input gave.
pub(crate) enum Loaded {
    Problem(String, FrictionProblem<'static>),
    /// Found by a folder scan but not a problem fc3d handles (a note was printed).
    Skipped,
    /// Could not be read (a message naming it was printed).
    Failed,
}

/// Reads one input; messages go to stderr.
pub(crate) fn load_input(input: Input) -> Loaded {
    match input {
        Input::Scene(s) => Loaded::Problem(s.name.to_string(), s.problem),
        Input::Generated(spec) => match spec.generate() {
            Ok(p) => Loaded::Problem(spec.name(), p),
            Err(e) => {
                eprintln!("fc3d: {e}");
                Loaded::Failed
            }
        },
        Input::File {
            path,
            from_directory,
        } => match read_problem(&path) {
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
        // happens to parse as a (wrong) local problem, so a folder scan leaves them out.
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_lowercase())
            .unwrap_or_default();
        if name.starts_with("gfc3d_") || name.starts_with("gfc2d_") {
            eprintln!(
                "fc3d: skipping {}: a global (M, H) problem, not an fc3d input",
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
            Loaded::Problem(name, p) => {
                assert_eq!(name, "piles-c10-p2-s1");
                assert_eq!(p.n_contacts(), 10);
            }
            _ => panic!("a generated scene loads"),
        }
        match loaded.next().unwrap() {
            Loaded::Problem(name, p) => {
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
