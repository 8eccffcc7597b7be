//! fc3d's global results scored by the installed Siconos 4.4 (issue 26):
//! c/global_side_by_side.c opens both libraries with dlopen, solves every global `.dat` file of
//! `../shared/data/siconos` with each `_WR` id through fc3d's `gfc3d_driver`, and has Siconos'
//! `gfc3d_compute_error` (on Siconos' own reading of the file) score the result: it equals fc3d's
//! `dparam[1]` and is at most the tolerance wherever fc3d reports info 0; fc3d's
//! `gfc3d_compute_error` and `_convex` agree with Siconos' on the same arrays. Skipped when
//! Siconos is not installed (the test suite installs it).

use std::path::{Path, PathBuf};
use std::process::Command;

#[test]
fn siconos_scores_fc3d_global_results_as_fc3d_does() {
    if !Path::new("/usr/include/siconos/numerics/GlobalFrictionContactProblem.h").is_file() {
        eprintln!("Siconos not installed: skipped");
        return;
    }
    let data = fc3d_capi_tests::data_dir();
    let files: Vec<PathBuf> = [
        "GFC3D_Example0.dat",
        "GFC3D_Example00.dat",
        "GFC3D_Example00_badly_scaled.dat",
        "GFC3D_Example0_SBM.dat",
        "GFC3D_Example1.dat",
        "GFC3D_OneContact.dat",
        "GFC3D_TwoRods1.dat",
    ]
    .iter()
    .map(|f| data.join(f))
    .collect();
    if !files[0].is_file() {
        eprintln!("../shared/data/siconos missing: skipped");
        return;
    }
    let lib = fc3d_capi_tests::shared_library();
    let dir = std::env::temp_dir().join(format!("fc3d-global-side-by-side-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("global_side_by_side");
    fc3d_capi_tests::compile_dlopen_program("global_side_by_side.c", &program);
    let run = Command::new(&program)
        .arg(&lib)
        .arg("libsiconos_numerics.so")
        .args(&files)
        .current_dir(&dir)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    // Every file with every id was scored.
    let scored = stdout
        .lines()
        .filter(|l| l.contains("Siconos' error"))
        .count();
    assert_eq!(scored, files.len() * 13, "{stdout}");
}
