//! `fc3d convert` end to end: the real binary converts shared problems `.dat` -> `.hdf5` ->
//! `.dat` without changing the text, carries FCLIB's info strings over, and fails with exit code
//! 1 and a message naming the file on bad inputs. In a build without FCLIB support
//! (`fc3d_core::io::FCLIB_AVAILABLE` false) converting from or to `.hdf5` fails the same way,
//! with a message naming the missing `fclib` feature, and writes nothing; `.dat` -> `.dat` still
//! works. Run both ways: `cargo test -p fc3d-cli --test convert [--features fclib]`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use fc3d_core::io::dat::{read_global_dat_file, GlobalDatProblem};
use fc3d_core::io::{
    read_fclib_global_file, read_fclib_info, read_problem_file, write_dat, FclibInfo,
    FCLIB_AVAILABLE,
};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

/// A fresh directory under cargo's per-test temporary directory.
fn out_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("convert-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn convert(input: &Path, output: &Path, flags: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .arg("convert")
        .arg(input)
        .arg(output)
        .args(flags)
        .output()
        .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn succeeds(out: &Output) {
    assert!(
        out.status.success(),
        "stdout:\n{}\nstderr:\n{}",
        text(&out.stdout),
        text(&out.stderr)
    );
}

/// Exit code 1 with a message holding every `needle`.
fn fails_with(out: &Output, needles: &[&str]) {
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "stderr:\n{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "'{needle}' not in:\n{stderr}");
    }
}

/// The `.dat` text fc3d writes for a problem file (every number exact).
fn dat_text(path: &Path) -> String {
    let mut bytes = Vec::new();
    write_dat(&read_problem_file(path).unwrap(), &mut bytes).unwrap();
    String::from_utf8(bytes).unwrap()
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn dat_to_hdf5_to_dat_gives_back_the_same_text() {
    let dir = out_dir("roundtrip");
    // A dense and a sparse-block problem.
    for name in ["Rover1040.dat", "Confeti-ex03-Fc3D-SBM.dat"] {
        let hdf5 = dir.join(format!("{name}.hdf5"));
        let dat = dir.join(format!("back-{name}"));
        let out = convert(&data(name), &hdf5, &[]);
        if !FCLIB_AVAILABLE {
            fails_with(
                &out,
                &[&hdf5.display().to_string(), "without the `fclib` feature"],
            );
            assert!(names(&dir).is_empty(), "{:?}", names(&dir));
            continue;
        }
        succeeds(&out);
        assert!(text(&out.stdout).contains("W "), "{}", text(&out.stdout));
        succeeds(&convert(&hdf5, &dat, &[]));
        assert_eq!(
            std::fs::read_to_string(&dat).unwrap(),
            dat_text(&data(name)),
            "{name}"
        );
        // The default info names the input.
        let info = read_fclib_info(&hdf5).unwrap();
        assert_eq!(info.title.as_deref(), Some(name));
        assert_eq!(
            info.description,
            Some(format!("converted from {name} by fc3d convert"))
        );
    }
    // .dat -> .dat works in every build.
    let copy = dir.join("copy.dat");
    succeeds(&convert(&data("Rover1040.dat"), &copy, &[]));
    assert_eq!(
        std::fs::read_to_string(&copy).unwrap(),
        dat_text(&data("Rover1040.dat"))
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fclib_to_fclib_keeps_the_info_unless_flags_replace_it() {
    let dir = out_dir("info");
    let input = data("LMGC_100_PR_PerioBox-i00361-60-03000.hdf5");
    let out_file = dir.join("perio.h5");
    let out = convert(&input, &out_file, &["--math-info", "none"]);
    if !FCLIB_AVAILABLE {
        fails_with(
            &out,
            &["LMGC_100_PR_PerioBox", "without the `fclib` feature"],
        );
        assert!(names(&dir).is_empty());
        return;
    }
    succeeds(&out);
    let original = read_fclib_info(&input).unwrap();
    assert_eq!(
        read_fclib_info(&out_file).unwrap(),
        FclibInfo {
            math_info: Some("none".into()),
            ..original
        }
    );
    assert_eq!(
        read_problem_file(&out_file).unwrap(),
        read_problem_file(&input).unwrap()
    );
    // A global problem stays global, or with --reduce is converted as its reduction.
    let global = dir.join("boxes.dat");
    succeeds(&convert(&data("Box_Stacks-i0122-82-5.hdf5"), &global, &[]));
    match read_global_dat_file(&global).unwrap().problem {
        GlobalDatProblem::Spatial(p) => assert_eq!(
            p,
            read_fclib_global_file(&data("Box_Stacks-i0122-82-5.hdf5")).unwrap()
        ),
        other => panic!("a 3D global problem, not {other:?}"),
    }
    let reduced = dir.join("boxes-reduced.dat");
    succeeds(&convert(
        &data("Box_Stacks-i0122-82-5.hdf5"),
        &reduced,
        &["--reduce"],
    ));
    assert_eq!(
        read_problem_file(&reduced).unwrap(),
        read_problem_file(&data("Box_Stacks-i0122-82-5.hdf5")).unwrap()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_conversions_exit_1_and_write_nothing() {
    let dir = out_dir("bad");
    // An output format fc3d does not know, checked before the input is read.
    fails_with(
        &convert(&dir.join("missing.dat"), &dir.join("out.txt"), &[]),
        &["out.txt", ".dat", ".hdf5"],
    );
    // A missing input, a 2D problem, an unreadable output place.
    fails_with(
        &convert(&dir.join("missing.dat"), &dir.join("out.dat"), &[]),
        &["missing.dat"],
    );
    fails_with(
        &convert(
            &data("FrictionContactProblem00031.dat"),
            &dir.join("out.dat"),
            &[],
        ),
        &["FrictionContactProblem00031.dat"],
    );
    fails_with(
        &convert(&dir.join("missing.hdf5"), &dir.join("out.dat"), &[]),
        &["missing.hdf5"],
    );
    fails_with(
        &convert(
            &data("Rover1040.dat"),
            &dir.join("no/such/dir/out.hdf5"),
            &[],
        ),
        &["no/such/dir/out.hdf5"],
    );
    assert!(names(&dir).is_empty(), "{:?}", names(&dir));
    // A missing argument is a usage error.
    let usage = Command::new(env!("CARGO_BIN_EXE_fc3d"))
        .args(["convert", "a.dat"])
        .output()
        .unwrap();
    assert_eq!(usage.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}
