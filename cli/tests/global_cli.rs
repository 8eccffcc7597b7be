//! Global problems (M, H, q, b, mu) through the real `fc3d` binary: `fc3d solve` recognises a
//! global `.dat` file by its content and solves it (by default the reduction with AUTO, or the
//! global id given); `fc3d scene --global` writes the generated scene in the global form (the
//! spec syntax of `compare-siconos-global.sh` too); `fc3d convert` keeps a global problem global
//! or writes its reduction; `fc3d bench` runs global ids with its own error check.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use fc3d_core::io::dat::{read_global_dat_file, GlobalDatProblem};
use fc3d_core::io::read_problem_file;
use fc3d_core::problem::GlobalProblem;
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> Option<PathBuf> {
    let p = Path::new(DATA_DIR).join(name);
    if p.is_file() {
        Some(p)
    } else {
        eprintln!("{} missing: skipped", p.display());
        None
    }
}

fn out_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("global-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn fc3d<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args(args)
        .output()
        .unwrap()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn global_of(path: &Path) -> GlobalProblem<'static> {
    match read_global_dat_file(path).unwrap().problem {
        GlobalDatProblem::Spatial(p) => p,
        GlobalDatProblem::Planar(_) => panic!("3D expected"),
    }
}

/// The row of `name` in a solve table: (status, error).
fn row<'a>(out: &'a str, name: &str) -> (&'a str, f64) {
    let line = out
        .lines()
        .find(|l| l.starts_with(name))
        .unwrap_or_else(|| panic!("no row for {name} in\n{out}"));
    let cells: Vec<&str> = line.split_whitespace().collect();
    // ... error status time unit
    let n = cells.len();
    (cells[n - 3], cells[n - 4].parse().unwrap())
}

#[test]
fn solve_recognises_and_solves_global_files() {
    let Some(two_rods) = data("GFC3D_TwoRods1.dat") else {
        return;
    };
    let o = fc3d([two_rods.as_os_str()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("global problems: WR-AUTO"), "{out}");
    assert!(out.contains("global (M sparse-block)"), "{out}");
    let (status, error) = row(&out, "GFC3D_TwoRods1.dat");
    assert_eq!(status, "converged", "{out}");
    assert!(error <= 1e-8, "{out}");
    // Global ids and names, with their defaults and the tolerance given.
    // fc3d's own 691 (the H-form sweep) by id and names, with NSGS' --local.
    for solver in [
        "600",
        "605",
        "GFC3D_NSN_AC",
        "614",
        "NSGS",
        "691",
        "NSGS_HFORM_COLOURED",
        "NSGS_HFORM --local 552",
    ] {
        let mut words = solver.split(' ');
        let mut args = vec![
            "solve".as_ref(),
            two_rods.as_os_str(),
            "--solver".as_ref(),
            words.next().unwrap().as_ref(),
            "--tol".as_ref(),
            "1e-8".as_ref(),
        ];
        args.extend(words.map(std::ffi::OsStr::new));
        let o = fc3d(args);
        assert!(o.status.success(), "{solver}: {}", stderr(&o));
        let out = stdout(&o);
        let (status, error) = row(&out, "GFC3D_TwoRods1.dat");
        assert_eq!(status, "converged", "{solver}: {out}");
        assert!(error <= 1e-8);
    }
    // A global id on a local problem: that problem fails, exit 1.
    if let Some(rover) = data("Rover1039.dat") {
        let o = fc3d([
            rover.as_os_str(),
            two_rods.as_os_str(),
            "--solver".as_ref(),
            "607".as_ref(),
        ]);
        assert_eq!(o.status.code(), Some(1));
        assert!(stderr(&o).contains("is a global solver"), "{}", stderr(&o));
        assert_eq!(row(&stdout(&o), "GFC3D_TwoRods1.dat").0, "converged");
    }
    // Refused ids and flags a global solver cannot take are command-line errors.
    for bad in [
        vec!["--solver", "601"],
        vec!["--solver", "608"],
        vec!["--solver", "605", "--local", "552"],
        vec![
            "--solver",
            "605",
            "--option",
            "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE=0.5",
        ],
    ] {
        let o = fc3d(std::iter::once(two_rods.as_os_str()).chain(bad.iter().map(|s| s.as_ref())));
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
    }
}

#[test]
fn scene_global_writes_the_generated_global_problem() {
    let dir = out_dir("scene");
    let spec = dir.join("spec.dat");
    let flags = dir.join("flags.dat");
    let o = fc3d([
        "scene".as_ref(),
        "contacts=80,piles=2,seed=4,shape=boxes".as_ref(),
        "--global".as_ref(),
        "-o".as_ref(),
        spec.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = fc3d([
        "scene",
        "--contacts",
        "80",
        "--piles",
        "2",
        "--seed",
        "4",
        "--shape",
        "boxes",
        "--global",
        "-o",
        flags.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(&spec).unwrap(),
        std::fs::read(&flags).unwrap()
    );
    let made = GeneratedScene {
        pile: PileSpec {
            contacts: 80,
            piles: 2,
            seed: 4,
        },
        shape: PileShape::Boxes,
    }
    .generate_global()
    .unwrap();
    assert_eq!(global_of(&spec), made);
    // The spec and the flags together are a usage error.
    let o = fc3d([
        "scene",
        "contacts=80",
        "--contacts",
        "80",
        "-o",
        spec.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    // The written scene solves as a global problem (reduced, and in the H form).
    for solver in ["606", "NSGS_HFORM"] {
        let o = fc3d([spec.as_os_str(), "--solver".as_ref(), solver.as_ref()]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(
            row(&stdout(&o), "spec.dat").0,
            "converged",
            "{solver}: {}",
            stdout(&o)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn convert_keeps_global_problems_global_or_reduces_them() {
    let Some(two_rods) = data("GFC3D_TwoRods1.dat") else {
        return;
    };
    let dir = out_dir("convert");
    let once = dir.join("once.dat");
    let twice = dir.join("twice.dat");
    for (from, to) in [(&two_rods, &once), (&once, &twice)] {
        let o = fc3d(["convert".as_ref(), from.as_os_str(), to.as_os_str()]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stdout(&o).contains("global, M 54x54"), "{}", stdout(&o));
    }
    assert_eq!(global_of(&once), global_of(&two_rods));
    assert_eq!(
        std::fs::read_to_string(&once).unwrap(),
        std::fs::read_to_string(&twice).unwrap()
    );
    let reduced = dir.join("reduced.dat");
    let o = fc3d([
        "convert".as_ref(),
        two_rods.as_os_str(),
        reduced.as_os_str(),
        "--reduce".as_ref(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let local = read_problem_file(&reduced).unwrap();
    let p = global_of(&two_rods);
    let mut operator = p.operator().unwrap();
    assert_eq!(local, p.reduce(&mut operator).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_runs_global_ids_and_checks_their_error() {
    let Some(two_rods) = data("GFC3D_TwoRods1.dat") else {
        return;
    };
    let dir = out_dir("bench");
    let o = fc3d([
        "bench".as_ref(),
        two_rods.as_os_str(),
        "--solvers".as_ref(),
        "600,605,607,NSGS".as_ref(),
        "--tol".as_ref(),
        "1e-6".as_ref(),
        "--reps".as_ref(),
        "1".as_ref(),
        "--out".as_ref(),
        dir.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    // 600 and NSGS are the same solver on a global problem: the spec list keeps both labels.
    assert_eq!(rows.len(), 4, "{csv}");
    for r in &rows {
        assert!(r.contains("GFC3D_TwoRods1.dat"), "{r}");
        assert!(r.contains(",converged,"), "{r}");
        assert!(!r.contains("MISMATCH"), "{r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
