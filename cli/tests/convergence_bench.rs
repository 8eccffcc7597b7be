//! The convergence-at-scale harness (`scripts/convergence-bench.sh`, the `convergence_bench`
//! binary) stays working: tiny sizes, one method, a few steps; no timed assertions.

use std::path::{Path, PathBuf};
use std::process::Command;

use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{natural_map_error, solve, Method, SolverConfig};

fn out_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("convergence-bench-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn bench(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_convergence_bench"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "convergence_bench {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// The value of `column` in a CSV row under `header`.
fn cell<'a>(header: &str, row: &'a str, column: &str) -> &'a str {
    let i = header
        .split(',')
        .position(|c| c == column)
        .unwrap_or_else(|| panic!("no column {column} in {header}"));
    row.split(',').nth(i).unwrap()
}

#[test]
fn solve_rows_report_the_solve_the_library_makes() {
    let header = bench(&["header"]);
    let header = header.trim();
    let spec = "contacts=100,piles=2,seed=1,shape=spheres";
    let out = bench(&[
        "solve",
        "--scene",
        spec,
        "--method",
        "NSGS",
        "--tols",
        "1e-6,1e-4",
        "--budget",
        "20",
    ]);
    let rows: Vec<&str> = out.lines().collect();
    assert_eq!(rows.len(), 2, "{out}");
    // Loosest tolerance first.
    assert_eq!(cell(header, rows[0], "tolerance"), "1e-4");
    assert_eq!(cell(header, rows[1], "tolerance"), "1e-6");
    // The same solve in the library: the same iterations and error.
    let p = GeneratedScene::parse(spec).unwrap().generate().unwrap();
    for (row, tol) in rows.iter().zip([1e-4, 1e-6]) {
        let config = SolverConfig::new(Method::preset("NSGS").unwrap())
            .with_tolerance(tol)
            .with_max_iter(1_000_000);
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        assert!(report.converged());
        assert_eq!(cell(header, row, "status"), "converged");
        assert_eq!(
            cell(header, row, "iterations"),
            report.iterations.to_string()
        );
        // A sweep counts as one product.
        assert_eq!(cell(header, row, "products"), report.iterations.to_string());
        let error: f64 = cell(header, row, "error").parse().unwrap();
        let recomputed: f64 = cell(header, row, "recomputed_error").parse().unwrap();
        let independent = natural_map_error(&p, &r, &mut u);
        assert!(error <= tol && (error - independent).abs() <= 1e-3 * independent.max(1e-300));
        assert!((recomputed - independent).abs() <= 1e-3 * independent.max(1e-300));
        let cpu: f64 = cell(header, row, "cpu_s").parse().unwrap();
        assert!(cpu >= 0.0);
    }
    // An unknown method is an error, not a row.
    let o = Command::new(env!("CARGO_BIN_EXE_convergence_bench"))
        .args(["solve", "--scene", spec, "--method", "NO-SUCH"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown method"));
}

#[test]
fn settling_solves_every_step_warm_and_writes_them() {
    let dir = out_dir("settling");
    let steps_csv = dir.join("steps.csv");
    let dat = dir.join("steps");
    let summary = bench(&[
        "settling",
        "--spheres",
        "40",
        "--per-side",
        "4",
        "--steps",
        "12",
        "--method",
        "NSGS",
        "--budget",
        "20",
        "--steps-csv",
        steps_csv.to_str().unwrap(),
        "--dat-dir",
        dat.to_str().unwrap(),
        "--dat-every",
        "4",
    ]);
    let header = bench(&["settling-header"]);
    let row = summary.trim();
    let steps = std::fs::read_to_string(&steps_csv).unwrap();
    let solved = steps.lines().count() - 1;
    assert!(solved > 0, "{steps}");
    assert_eq!(cell(header.trim(), row, "solved_steps"), solved.to_string());
    assert_eq!(cell(header.trim(), row, "not_converged"), "0");
    // Once the spheres rest on the ground, later steps start warm.
    let warm: usize = steps
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse::<usize>().unwrap())
        .sum();
    assert!(warm > 0, "{steps}");
    // Every 4th step written as a .dat file that the solve mode reads.
    let files: Vec<_> = std::fs::read_dir(&dat).unwrap().collect();
    assert_eq!(files.len(), 12 / 4, "{files:?}");
    let file = files[0].as_ref().unwrap().path();
    let out = bench(&[
        "solve",
        "--scene",
        file.to_str().unwrap(),
        "--method",
        "TFP",
        "--tols",
        "1e-4",
    ]);
    assert!(out.contains(",fc3d,TFP,1e-4,converged,"), "{out}");
}

/// A global method runs the sequence in the global form (M and H given), warm-started by
/// contact id: every step converges, later steps start warm, and a short run's steps match the
/// library's own global solves of the same sequence (same iterations and error).
#[test]
fn settling_in_the_global_form_runs_the_h_form_warm() {
    use fc3d_core::global::{solve_global, GlobalConfig, GlobalMethod};
    use fc3d_core::scenes::sequences::pile_settling_in_bin_global;
    let dir = out_dir("settling-global");
    let steps_csv = dir.join("steps.csv");
    let summary = bench(&[
        "settling",
        "--spheres",
        "40",
        "--per-side",
        "4",
        "--steps",
        "12",
        "--method",
        "NSGS_HFORM",
        "--tol",
        "1e-6",
        "--budget",
        "20",
        "--steps-csv",
        steps_csv.to_str().unwrap(),
    ]);
    let header = bench(&["settling-header"]);
    let row = summary.trim();
    assert_eq!(cell(header.trim(), row, "method"), "NSGS_HFORM");
    assert_eq!(cell(header.trim(), row, "not_converged"), "0", "{row}");
    let steps = std::fs::read_to_string(&steps_csv).unwrap();
    let rows: Vec<Vec<&str>> = steps
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert!(!rows.is_empty(), "{steps}");
    assert_eq!(
        cell(header.trim(), row, "solved_steps"),
        rows.len().to_string()
    );
    let warm: usize = rows.iter().map(|r| r[2].parse::<usize>().unwrap()).sum();
    assert!(warm > 0, "{steps}");
    // The same sequence stepped by the library with the same warm start.
    let mut config = GlobalConfig::new(GlobalMethod::preset("NSGS_HFORM").unwrap());
    config.tolerance = 1e-6;
    config.max_iter = 1_000_000;
    config.time_budget = Some(std::time::Duration::from_secs(20));
    let mut memory = std::collections::HashMap::<i64, [f64; 3]>::new();
    let mut k = 0;
    pile_settling_in_bin_global(40, 4, 12, &mut |step| {
        let p = &step.problem;
        let mut r = vec![0.0; p.size()];
        for (rc, id) in r.chunks_exact_mut(3).zip(&step.ids) {
            if let Some(m) = memory.get(id) {
                rc.copy_from_slice(m);
            }
        }
        let (mut u, mut v) = (vec![0.0; p.size()], vec![0.0; p.ndof()]);
        let report = solve_global(p, &config, &mut r, &mut u, &mut v).unwrap();
        assert!(report.converged() && report.error <= 1e-6);
        assert_eq!(rows[k][1], p.n_contacts().to_string());
        assert_eq!(rows[k][6], report.iterations.to_string());
        assert_eq!(rows[k][7], format!("{:.3e}", report.error));
        memory = step
            .ids
            .iter()
            .zip(r.chunks_exact(3))
            .map(|(&id, rc)| (id, [rc[0], rc[1], rc[2]]))
            .collect();
        k += 1;
        r
    });
    assert_eq!(k, rows.len());
    // The global form writes no .dat files.
    let o = Command::new(env!("CARGO_BIN_EXE_convergence_bench"))
        .args([
            "settling",
            "--spheres",
            "40",
            "--per-side",
            "4",
            "--steps",
            "2",
        ])
        .args([
            "--method",
            "691",
            "--dat-dir",
            dir.join("d").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("takes a local method"));
}

#[test]
fn the_script_runs_quick_and_reports() {
    let dir = out_dir("script");
    let bin_dir = Path::new(env!("CARGO_BIN_EXE_convergence_bench"))
        .parent()
        .unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/convergence-bench.sh");
    let o = Command::new("bash")
        .arg(&script)
        .args(["--quick", "--out"])
        .arg(&dir)
        .env("FC3D_CONVERGENCE_BENCH_BIN", bin_dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(
        report.contains("| spheres | 100 | fc3d | NSGS |"),
        "{report}"
    );
    assert!(report.contains("## Settling sequence"), "{report}");
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert!(
        csv.contains("spheres,100,4,1,fc3d,NSGS,1e-4,converged,"),
        "{csv}"
    );
    // Siconos' row when it is installed (the script compiles bench/scale.c against it).
    if Path::new("/usr/include/siconos/numerics/SiconosNumerics.h").exists() {
        assert!(csv.contains(",siconos,500,1e-4,converged,"), "{csv}");
    }
}
