//! `fc3d bench` end to end: the real binary on the built-in scenes.

use std::path::{Path, PathBuf};
use std::process::Command;

fn fc3d() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fc3d"))
}

/// A fresh output directory under cargo's per-test temporary directory.
fn out_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bench-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn non_empty(path: &Path) {
    let len = std::fs::metadata(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .len();
    assert!(len > 0, "{} is empty", path.display());
}

/// Splits a CSV line of the bench (no quoted field in the scenes' rows).
fn cells(line: &str) -> Vec<&str> {
    line.split(',').collect()
}

#[test]
fn bench_on_the_default_scenes_writes_csv_summary_and_pictures() {
    let out = out_dir("scenes");
    let result = fc3d()
        .args(["bench", "--reps", "1", "--tol", "1e-6", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&result.stdout);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        result.status.success(),
        "stdout:\n{stdout}\nstderr:\n{stderr}"
    );

    // The CSV: header, then one row per (scene, solver) at the single tolerance.
    let csv = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let mut lines = csv.lines();
    let header = cells(lines.next().unwrap());
    assert_eq!(
        header,
        [
            "mode",
            "problem",
            "family",
            "contacts",
            "solver",
            "tolerance",
            "time_budget_s",
            "max_iter",
            "status",
            "info",
            "iterations",
            "error",
            "reported_error",
            "error_check",
            "time_s",
            "reps"
        ]
    );
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(cells).collect();
    let scenes = fc3d_core::scenes::default_scenes();
    let n_solvers = fc3d_core::LocalSolverKind::ALL.len();
    assert_eq!(rows.len(), scenes.len() * n_solvers, "{csv}");
    for scene in &scenes {
        let mine: Vec<&Vec<&str>> = rows
            .iter()
            .filter(|r| r[col("problem")] == scene.name)
            .collect();
        assert_eq!(mine.len(), n_solvers, "{}", scene.name);
        let mut solvers: Vec<&str> = mine.iter().map(|r| r[col("solver")]).collect();
        solvers.sort();
        solvers.dedup();
        assert_eq!(solvers.len(), n_solvers, "one row per solver");
        for r in mine {
            assert_eq!(r.len(), header.len());
            assert_eq!(r[col("mode")], "tolerance");
            assert_eq!(r[col("family")], scene.name);
            assert_eq!(
                r[col("contacts")].parse::<usize>().unwrap(),
                scene.problem.n_contacts()
            );
            assert_eq!(r[col("tolerance")].parse::<f64>().unwrap(), 1e-6);
            assert_eq!(r[col("time_budget_s")].parse::<f64>().unwrap(), 20.0);
            assert_eq!(r[col("reps")], "1");
            assert_eq!(r[col("error_check")], "ok");
            let error: f64 = r[col("error")].parse().unwrap();
            let reported: f64 = r[col("reported_error")].parse().unwrap();
            assert!(error.is_finite() && error >= 0.0);
            assert!((error - reported).abs() <= 1e-13 + 1e-6 * error.max(reported));
            let info: i32 = r[col("info")].parse().unwrap();
            let status = r[col("status")];
            match info {
                0 => {
                    assert_eq!(status, "converged");
                    assert!(error <= 1e-6, "{r:?}");
                }
                1 => assert_eq!(status, "max-iter"),
                2 => assert_eq!(status, "out-of-time"),
                _ => panic!("info {info}"),
            }
            assert!(r[col("time_s")].parse::<f64>().unwrap() > 0.0);
            r[col("iterations")].parse::<usize>().unwrap();
        }
        // The default local solver (hybrid Newton) solves every scene.
        assert!(rows.iter().any(|r| r[col("problem")] == scene.name
            && r[col("solver")] == "NSGS/565"
            && r[col("info")] == "0"));
    }

    // Summary on stdout and in summary.txt: one line per solver at the tolerance.
    let summary = std::fs::read_to_string(out.join("summary.txt")).unwrap();
    assert!(
        summary.contains("NSGS/565") && summary.contains("1.00e-06"),
        "{summary}"
    );
    assert!(stdout.contains(summary.lines().nth(1).unwrap()), "{stdout}");

    // Pictures, SVG and PNG, non-empty: the profile of the tolerance and one work–precision
    // picture per family (a scene is its own family).
    for ext in ["svg", "png"] {
        non_empty(&out.join(format!("profile-1e-6.{ext}")));
        for scene in &scenes {
            non_empty(&out.join(format!("work-precision-{}.{ext}", scene.name)));
        }
    }
    let png = std::fs::read(out.join("profile-1e-6.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let svg = std::fs::read_to_string(out.join("profile-1e-6.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("Performance profile"));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn budget_mode_records_the_error_within_each_budget() {
    let out = out_dir("budget");
    let result = fc3d()
        .args([
            "bench",
            "--budget",
            "1ms,5ms",
            "--reps",
            "1",
            "--solvers",
            "NSGS,500/552",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&result.stdout);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        result.status.success(),
        "stdout:\n{stdout}\nstderr:\n{stderr}"
    );
    let csv = std::fs::read_to_string(out.join("budget.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(cells).collect();
    let n = fc3d_core::scenes::default_scenes().len();
    assert_eq!(rows.len(), n * 2 * 2, "{csv}");
    for r in &rows {
        assert_eq!(r[0], "budget");
        assert_eq!(r[5].parse::<f64>().unwrap(), 1e-14, "{r:?}");
        let budget: f64 = r[6].parse().unwrap();
        assert!(budget == 1e-3 || budget == 5e-3, "{r:?}");
        assert_eq!(r[13], "ok");
    }
    assert!(
        stdout.contains("median error") && stdout.contains("<= 1e-8"),
        "{stdout}"
    );
    for ext in ["svg", "png"] {
        non_empty(&out.join(format!("budget-sphere_pile.{ext}")));
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn bad_bench_arguments_exit_2_and_bad_paths_exit_1() {
    let out = out_dir("bad");
    let s = fc3d()
        .args(["bench", "--solvers", "PSOR"])
        .output()
        .unwrap();
    assert_eq!(s.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&s.stderr).contains("unknown solver"));
    let s = fc3d()
        .args(["bench", "/nonexistent/fc3d.dat", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(s.status.code(), Some(1));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn auto_ratio_is_written_and_auto_max_ratio_sets_the_exit_status() {
    // AUTO and NSGS on the built-in scenes: `auto-ratio.txt` has a row per scene with AUTO's
    // time over the faster of the others; a limit no run can miss passes, one every run misses
    // (AUTO a billion times faster than the best other solver) fails with exit status 1.
    for (limit, succeeds) in [("1e9", true), ("1e-9", false)] {
        let out = out_dir(&format!("auto-ratio-{succeeds}"));
        let result = fc3d()
            .args([
                "bench",
                "--solvers",
                "AUTO,NSGS,NSGS/551",
                "--reps",
                "1",
                "--tol",
                "1e-6",
                "--auto-max-ratio",
                limit,
                "--out",
            ])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.success(), succeeds, "{limit}: {stderr}");
        let table = std::fs::read_to_string(out.join("auto-ratio.txt")).unwrap();
        let rows: Vec<&str> = table
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("problem"))
            .collect();
        assert!(!rows.is_empty(), "{table}");
        assert!(table.contains("# tolerance 1e-6:"), "{table}");
        if !succeeds {
            assert!(table.contains("over the limit"), "{table}");
            assert!(stderr.contains("AUTO more than"), "{stderr}");
        }
    }
}
