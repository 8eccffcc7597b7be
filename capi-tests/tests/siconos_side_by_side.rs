//! The small Siconos functions fc3d reimplements (the Alart-Curnier functions, the per-contact
//! and velocity/Tresca error measures, `fc3d_checkTrivialCase`,
//! `fc3d_set_internalsolver_tolerance`, `frictionContactProblem_compute_statistics`,
//! `frictionContact_copy` and `frictionContact_rescaling` on dense and sparse-block problems, the
//! state `NM_new`, `NM_null`, `NM_create` and `NM_create_from_data` leave, the structures
//! `SBCM_new_3x3` and `SBCM_to_SBM` build and share) against the installed
//! Siconos 4.4 in one process:
//! c/siconos_side_by_side.c opens both libraries with dlopen and compares every output value and
//! every output slot left alone, on the same random and boundary inputs. Skipped when Siconos is
//! not installed (the test suite installs it).

use std::path::Path;
use std::process::Command;

#[test]
fn small_functions_agree_with_siconos() {
    if !Path::new("/usr/include/siconos/numerics/FrictionContactProblem.h").is_file() {
        eprintln!("Siconos not installed: skipped");
        return;
    }
    let lib = fc3d_capi_tests::shared_library();
    let dir = std::env::temp_dir().join(format!("fc3d-side-by-side-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("siconos_side_by_side");
    fc3d_capi_tests::compile_dlopen_program("siconos_side_by_side.c", &program);
    let run = Command::new(&program)
        .arg(&lib)
        .arg("libsiconos_numerics.so")
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        run.status.success(),
        "{}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    // frictionContactProblem_compute_statistics: both libraries print the same line for each of
    // the 50 inputs (and nothing when do_print is above the verbosity).
    let stdout = String::from_utf8_lossy(&run.stdout);
    let lines: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains("FC3D - STAT"))
        .collect();
    assert_eq!(lines.len(), 100, "{stdout}");
    let mut counts = std::collections::BTreeMap::new();
    for l in &lines {
        *counts.entry(*l).or_insert(0) += 1;
    }
    for (line, count) in counts {
        assert!(count % 2 == 0, "printed by one library only: {line}");
    }
}
