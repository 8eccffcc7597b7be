//! fc3d-mpi under `mpirun -np 1, 2, 3, 4 --oversubscribe`: the check program (src/bin) splits
//! shared problems and generated piles over the ranks (contiguous ranges, round-robin, random,
//! an empty rank) and solves them; this test merges each run's results by global id and checks
//! that every process count and partition gives the same bits, that the reported error is the
//! error an independent measurement finds (the core's, on the whole problem), and that rejected
//! inputs fail collectively (every rank the same code and message, nothing written, the next
//! solve going through).
//!
//! Without `mpirun` on PATH the test says so and passes, unless `FC3D_REQUIRE_MPI=1` (CI).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use fc3d_core::{natural_map_error, Delassus, FrictionProblem};
use fc3d_mpi::problems::{global_id, WholeProblem};

const CHECK: &str = env!("CARGO_BIN_EXE_fc3d-mpi-check");
const PROCESS_COUNTS: [usize; 4] = [1, 2, 3, 4];
const PARTITIONS: [&str; 4] = ["ranges", "round-robin", "random", "empty-last"];

fn shared(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/siconos")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// (name, problem, tolerance, sweep limit): solved by every partition on 1..4 processes.
fn cases() -> Vec<(&'static str, String, f64, usize)> {
    vec![
        // Converges: the reported error is checked against the tolerance too.
        (
            "pile",
            "gen:contacts=1000,piles=2,seed=3".into(),
            1e-3,
            1000,
        ),
        (
            "boxes",
            "gen:contacts=1500,piles=3,seed=2,shape=boxes".into(),
            1e-10,
            40,
        ),
        ("spheres", shared("NESpheres_30_1.dat"), 1e-10, 40),
        ("capsules", shared("Capsules-i101-404.dat"), 1e-10, 40),
        ("rover", shared("Rover1040.dat"), 1e-10, 40),
    ]
}

fn mpi_available() -> bool {
    let found = Command::new("mpirun").arg("--version").output().is_ok();
    if !found {
        let required = std::env::var_os("FC3D_REQUIRE_MPI").is_some_and(|v| v != "0");
        assert!(
            !required,
            "FC3D_REQUIRE_MPI is set but mpirun is not on PATH"
        );
        eprintln!("mpirun not found: fc3d-mpi's MPI tests skipped (apt-get install openmpi-bin)");
    }
    found
}

/// Runs the check program on `np` processes; a hang is a failure, not a stuck CI.
fn mpirun(np: usize, out: &Path, args: &[String]) {
    let mut child = Command::new("mpirun")
        .args(["--oversubscribe", "-np", &np.to_string(), CHECK])
        .arg(out)
        .args(args)
        // Open MPI refuses to run as root (CI) unless told.
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .spawn()
        .expect("start mpirun");
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait for mpirun") {
            assert!(status.success(), "mpirun -np {np} {args:?}: {status}");
            return;
        }
        if start.elapsed() > Duration::from_secs(600) {
            let _ = child.kill();
            panic!("mpirun -np {np} {args:?} still running after 600 s (a rank left waiting?)");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// One run's report and its contacts' bits by global id.
#[derive(Debug, PartialEq)]
struct Merged {
    header: String,
    contacts: BTreeMap<i64, String>,
}

fn merge(out: &Path, what: &str, np: usize) -> Merged {
    let mut header = None;
    let mut contacts = BTreeMap::new();
    for rank in 0..np {
        let text = std::fs::read_to_string(out.join(format!("{what}.np{np}.rank{rank}")))
            .unwrap_or_else(|e| panic!("{what} np {np} rank {rank}: {e}"));
        let mut lines = text.lines();
        let h = lines.next().expect("a header").to_string();
        match &header {
            None => header = Some(h),
            Some(first) => assert_eq!(first, &h, "{what} np {np}: ranks report differently"),
        }
        for line in lines {
            let (id, bits) = line.split_once(' ').expect("id and bits");
            assert!(contacts
                .insert(id.parse().unwrap(), bits.to_string())
                .is_none());
        }
    }
    Merged {
        header: header.expect("a rank"),
        contacts,
    }
}

fn bits(word: &str) -> f64 {
    f64::from_bits(u64::from_str_radix(word, 16).expect("hex bits"))
}

/// The reported error against the core's measurement of the merged r on the whole problem, and
/// the returned u against W r + q.
fn check_independently(name: &str, spec: &str, tolerance: f64, merged: &Merged) {
    let p = WholeProblem::load(spec).expect("the problem");
    let n = p.n_contacts();
    assert_eq!(
        merged.contacts.len(),
        n,
        "{name}: every contact returned once"
    );
    let mut r = vec![0.0; 3 * n];
    let mut u_returned = vec![0.0; 3 * n];
    for c in 0..n {
        let words: Vec<f64> = merged.contacts[&global_id(c)]
            .split(' ')
            .map(bits)
            .collect();
        r[3 * c..3 * c + 3].copy_from_slice(&words[..3]);
        u_returned[3 * c..3 * c + 3].copy_from_slice(&words[3..]);
    }
    let problem = FrictionProblem::new(
        Delassus::SparseBlock(p.w.clone()),
        p.q.clone(),
        p.mu.clone(),
    )
    .expect("a valid problem");
    let mut u = vec![0.0; 3 * n];
    let error = natural_map_error(&problem, &r, &mut u);
    let fields: Vec<&str> = merged.header.split(' ').collect();
    let (code, info, reported) = (fields[0], fields[1], bits(fields[3]));
    assert_eq!(code, info, "{name}: the return code is info");
    assert!(
        (reported - error).abs() <= 1e-10 * error.max(1e-300) + 1e-15,
        "{name}: reported error {reported:e}, measured {error:e}"
    );
    let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in u.iter().zip(&u_returned) {
        assert!((a - b).abs() <= 1e-12 * scale, "{name}: u is W r + q");
    }
    if info == "0" {
        assert!(
            error <= tolerance,
            "{name}: converged means error <= tolerance"
        );
    }
    eprintln!(
        "{name}: info {info}, {} sweeps, error {error:.3e}",
        fields[2]
    );
}

#[test]
fn same_bits_for_every_process_count_and_partition() {
    if !mpi_available() {
        return;
    }
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("mpirun");
    let _ = std::fs::remove_dir_all(&out);
    let cases = cases();
    let mut args: Vec<String> = Vec::new();
    for (name, problem, tol, max_iter) in &cases {
        if !args.is_empty() {
            args.push("--".into());
        }
        args.extend([
            "solve".into(),
            name.to_string(),
            problem.clone(),
            tol.to_string(),
            max_iter.to_string(),
        ]);
    }
    for extra in [
        ["errors", "gen:contacts=400,piles=2,seed=5"],
        ["handle", "gen:contacts=1000,piles=2,seed=3"],
    ] {
        args.push("--".into());
        args.extend(extra.iter().map(|s| s.to_string()));
    }
    for np in PROCESS_COUNTS {
        let start = Instant::now();
        mpirun(np, &out, &args);
        eprintln!("np {np}: {:.1} s", start.elapsed().as_secs_f64());
    }
    for (name, problem, tol, _) in &cases {
        let reference = merge(&out, &format!("{name}.ranges"), 1);
        check_independently(name, problem, *tol, &reference);
        for np in PROCESS_COUNTS {
            for partition in PARTITIONS {
                let run = merge(&out, &format!("{name}.{partition}"), np);
                assert!(
                    run == reference,
                    "{name}, {partition} on {np} processes: other bits than on one process"
                );
            }
        }
    }
    check_errors(&out);
    check_handle(&out);
}

/// Rejected inputs: per process count, every rank the same code and message, r and u
/// untouched, the expected code; then a good solve.
fn check_errors(out: &Path) {
    let expected = [
        ("nan-in-q", -4),
        ("unowned-column", -7),
        ("duplicate-id", -3),
        ("negative-mu", -7),
        ("no-diagonal", -7),
        ("bad-row-ptr", -3),
        ("settings-differ", -5),
        ("solver-504", -6),
        ("negative-size", -2),
    ];
    for np in PROCESS_COUNTS {
        let reports: Vec<String> = (0..np)
            .map(|rank| {
                std::fs::read_to_string(out.join(format!("errors.np{np}.rank{rank}"))).unwrap()
            })
            .collect();
        for report in &reports {
            assert_eq!(report, &reports[0], "np {np}: ranks failed differently");
        }
        let lines: Vec<Vec<&str>> = reports[0]
            .lines()
            .map(|l| l.split('\t').collect())
            .collect();
        for (name, code) in expected {
            if name == "settings-differ" && np == 1 {
                continue;
            }
            let line = lines
                .iter()
                .find(|l| l[0] == name)
                .unwrap_or_else(|| panic!("{name} reported"));
            assert_eq!(line[1], code.to_string(), "np {np} {name}: {}", line[3]);
            assert_ne!(
                line[2], "false",
                "np {np} {name}: outputs written on failure"
            );
            assert!(!line[3].is_empty(), "np {np} {name}: a message");
        }
        let good = lines
            .iter()
            .find(|l| l[0] == "good-after")
            .expect("good-after");
        assert!(
            good[1] == "0" || good[1] == "1",
            "np {np}: the solve after the errors"
        );
    }
}

/// A reused solver: one set-up for two solves, the one-shot entry's bits; the fast mode
/// converges; an unknown mode is refused on every rank.
fn check_handle(out: &Path) {
    for np in PROCESS_COUNTS {
        for rank in 0..np {
            let report =
                std::fs::read_to_string(out.join(format!("handle.np{np}.rank{rank}"))).unwrap();
            let lines: Vec<Vec<&str>> = report.lines().map(|l| l.split('\t').collect()).collect();
            for step in ["kept-0", "kept-1"] {
                let l = lines.iter().find(|l| l[0] == step).expect(step);
                assert_eq!(l[1], "0", "np {np} {step}: converged");
                assert_eq!(
                    l[4], "true",
                    "np {np} {step}: same bits as the one-shot entry"
                );
            }
            let stats = lines.iter().find(|l| l[0] == "stats").expect("stats");
            assert_eq!(stats[1], np.to_string(), "ranks");
            assert_eq!(
                stats[2], "1",
                "np {np}: one set-up for two solves of one pattern"
            );
            assert_eq!(stats[3], "2", "solves");
            assert_eq!(stats[6], "1000", "total contacts");
            if np == 1 {
                assert_eq!(stats[8], "0", "one process sends nothing");
            }
            let fast = lines.iter().find(|l| l[0] == "fast").expect("fast");
            assert_eq!(fast[1], "0", "np {np}: the fast mode converges");
            let bad = lines.iter().find(|l| l[0] == "bad-mode").expect("bad-mode");
            assert_eq!(bad[1], "true", "np {np}: an unknown mode is refused");
            assert!(bad[2].contains("mode 7"), "{}", bad[2]);
        }
        let fast = merge(out, "fast", np);
        assert!(
            fast.header.starts_with("0 0 "),
            "np {np}: fast mode {}",
            fast.header
        );
    }
}
