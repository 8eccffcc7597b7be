use super::*;
use std::path::PathBuf;
use std::time::Duration;

use super::args::parse_duration;
use super::csv::RunRecord;
use super::format::duration_name;
use super::plan::Plan;
use super::problems::family_of;
use super::stats::median;
use super::summary::{tolerance_profile, tolerance_summary};

#[test]
fn families() {
    assert_eq!(family_of("Rover1039.dat"), "Rover");
    assert_eq!(family_of("Capsules-i100-889.dat"), "Capsules");
    assert_eq!(family_of("Confeti-ex03-Fc3D-SBM.dat"), "Confeti");
    assert_eq!(family_of("NESpheres_10_1.dat"), "NESpheres");
    assert_eq!(family_of("BoxesStack1-i100000-32.hdf5.dat"), "BoxesStack");
    assert_eq!(
        family_of("FrictionContactProblem00031.dat"),
        "FrictionContactProblem"
    );
    assert_eq!(family_of("ACinputs.dat"), "ACinputs");
    assert_eq!(family_of("123.dat"), "123");
    assert_eq!(family_of("box_stack"), "box_stack");
}

#[test]
fn durations() {
    assert_eq!(parse_duration("20s"), Ok(Duration::from_secs(20)));
    assert_eq!(parse_duration("1ms"), Ok(Duration::from_millis(1)));
    assert_eq!(parse_duration(" 100ms "), Ok(Duration::from_millis(100)));
    assert_eq!(parse_duration("250us"), Ok(Duration::from_micros(250)));
    assert_eq!(parse_duration("250µs"), Ok(Duration::from_micros(250)));
    assert_eq!(parse_duration("1.5"), Ok(Duration::from_millis(1500)));
    assert_eq!(parse_duration("2min"), Ok(Duration::from_secs(120)));
    assert_eq!(parse_duration("1e-3s"), Ok(Duration::from_millis(1)));
    for bad in ["", "0", "0s", "-1s", "x", "10 parsecs", "nan", "inf"] {
        assert!(parse_duration(bad).is_err(), "{bad:?}");
    }
    assert_eq!(duration_name(Duration::from_millis(1)), "1ms");
    assert_eq!(duration_name(Duration::from_micros(2500)), "2.5ms");
    assert_eq!(duration_name(Duration::from_secs(20)), "20s");
    assert_eq!(duration_name(Duration::from_micros(20)), "20us");
}

#[test]
fn plans() {
    use clap::Parser;
    let cli = crate::Cli::try_parse_from(["fc3d", "bench"]).unwrap();
    let Some(crate::Command::Bench(args)) = cli.command else {
        panic!("expected bench")
    };
    assert_eq!(
        Plan::from_args(&args),
        Plan::Tolerances {
            tols: vec![1e-4, 1e-6, 1e-8],
            max_iter: 100_000,
            timeout: Duration::from_secs(20)
        }
    );
    assert_eq!(args.reps, 3);
    assert_eq!(args.out, PathBuf::from("target/bench-out"));
    assert_eq!(args.solvers.0, spec::all_specs());

    let cli = crate::Cli::try_parse_from([
        "fc3d",
        "bench",
        "--budget",
        "1ms,10ms",
        "--tol",
        "1e-6,1e-10",
        "--solvers",
        "500/552",
    ])
    .unwrap();
    let Some(crate::Command::Bench(args)) = cli.command else {
        panic!("expected bench")
    };
    assert_eq!(
        Plan::from_args(&args),
        Plan::Budgets {
            budgets: vec![Duration::from_millis(1), Duration::from_millis(10)],
            tol: 1e-10,
            max_iter: usize::MAX
        }
    );
    assert_eq!(args.solvers.0.len(), 1);

    let cli = crate::Cli::try_parse_from(["fc3d", "bench", "--budget", "5ms"]).unwrap();
    let Some(crate::Command::Bench(args)) = cli.command else {
        panic!("expected bench")
    };
    assert!(matches!(Plan::from_args(&args), Plan::Budgets { tol, .. } if tol == 1e-14));

    for bad in [
        vec!["fc3d", "bench", "--reps", "0"],
        vec!["fc3d", "bench", "--solvers", "PSOR"],
        vec!["fc3d", "bench", "--tol", "1e-4,-1"],
        vec!["fc3d", "bench", "--timeout", "0s"],
        vec!["fc3d", "bench", "--budget", "1ms,soon"],
    ] {
        assert!(crate::Cli::try_parse_from(&bad).is_err(), "{bad:?}");
    }
}

#[test]
fn medians() {
    assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
    assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
    assert!(median(vec![]).is_nan());
}

fn rec(problem: &str, solver: &str, tol: f64, info: i32, time_s: f64, error: f64) -> RunRecord {
    RunRecord {
        mode: "tolerance",
        problem: problem.into(),
        family: family_of(problem),
        contacts: 1,
        solver: solver.into(),
        tolerance: tol,
        time_budget_s: 20.0,
        max_iter: 10,
        status: if info == 0 {
            "converged"
        } else {
            "out-of-time"
        },
        info,
        iterations: 1,
        error,
        reported_error: error,
        error_ok: true,
        time_s,
        reps: 1,
    }
}

#[test]
fn summaries_from_records() {
    let labels = vec!["A".to_string(), "B".to_string()];
    let records = vec![
        rec("p1.dat", "A", 1e-6, 0, 1.0, 1e-7),
        rec("p1.dat", "B", 1e-6, 0, 2.0, 1e-7),
        rec("p2.dat", "A", 1e-6, 2, 20.0, 1e-3),
        rec("p2.dat", "B", 1e-6, 0, 4.0, 1e-7),
    ];
    let at: Vec<&RunRecord> = records.iter().collect();
    let p = tolerance_profile(&at, &labels);
    assert_eq!(p.rho(0, 1.0), 0.5);
    assert_eq!(p.rho(1, 1.0), 0.5);
    assert_eq!(p.rho(1, 2.0), 1.0);
    assert_eq!(p.robustness(0), 0.5);
    let s = tolerance_summary(&records, &labels, &[1e-6], 2);
    let lines: Vec<&str> = s.lines().collect();
    assert_eq!(lines.len(), 3, "{s}");
    assert!(lines[1].starts_with("A") && lines[1].contains("1/2"), "{s}");
    assert!(lines[1].contains("21.000 s"), "{s}");
    assert!(
        lines[2].contains("2/2") && lines[2].contains("3.000 s"),
        "{s}"
    );
}
