//! Worst overrun of the time budget in anytime mode (tolerance 0, a large iteration limit) on
//! small shared problems, per solver.
//!
//! `cargo run --release -p fc3d-core --example budget_overrun [-- REPEATS [BUDGET_MS...]]`

use std::time::{Duration, Instant};

use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{
    solve_with_observer, AdmmOptions, Method, NsgsOptions, ProxInternal, ProxOptions, SolverConfig,
    ViOptions,
};

const PROBLEMS: [&str; 8] = [
    "FC3D_Example1.dat",
    "Confeti-ex13-4contact-Fc3D-SBM.dat",
    "Rover4609.dat",
    "Rover1039.dat",
    "Rover4396.dat",
    "NESpheres_10_1.dat",
    "OneObject-i1028-138.hdf5.dat",
    "BoxesStack1-i100000-32.hdf5.dat",
];

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}

/// CPU time of this thread in ns (Linux, 64-bit: CLOCK_THREAD_CPUTIME_ID = 3). The run queue's
/// waits (other processes on a loaded machine) do not count.
fn schedstat() -> (u64, u64) {
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid pointer to a timespec; clock 3 is the calling thread's CPU clock.
    unsafe { clock_gettime(3, &mut ts) };
    (ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64, 0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let repeats: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let budgets: Vec<u64> = if args.len() > 1 {
        args[1..].iter().map(|a| a.parse().unwrap()).collect()
    } else {
        vec![1, 10]
    };
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
    let methods: Vec<(&str, Method)> = vec![
        ("PROX/NSN-AC", ProxOptions::default().into()),
        (
            "PROX/NSGS",
            ProxOptions {
                internal: ProxInternal::Nsgs(NsgsOptions::default()),
                ..ProxOptions::default()
            }
            .into(),
        ),
        ("ADMM", AdmmOptions::default().into()),
        ("VI", ViOptions::default().into()),
    ];
    for name in PROBLEMS {
        let p = read_dat_file(std::path::Path::new(&format!("{dir}{name}"))).unwrap();
        let n = p.size();
        for (label, method) in &methods {
            for &ms in &budgets {
                let budget = Duration::from_millis(ms);
                let config = SolverConfig::new(method.clone())
                    .with_tolerance(0.0)
                    .with_max_iter(usize::MAX / 2)
                    .with_time_budget(Some(budget));
                let mut worst = Duration::ZERO;
                let mut overruns = Vec::with_capacity(repeats);
                // CPU time (not waiting for a core) from the last iteration reported before the deadline to
                // the return: an upper bound of the overrun the code itself causes.
                let mut worst_active = 0.0_f64;
                {
                    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
                    let _ = solve_with_observer(&p, &config, &mut r, &mut u, &mut |_| {});
                }
                let mut last = None;
                for _ in 0..repeats {
                    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
                    let t = Instant::now();
                    // CPU time at the start and at the last iteration reported before the deadline.
                    let mut cpu_at_last = schedstat().0;
                    let rep = solve_with_observer(&p, &config, &mut r, &mut u, &mut |_| {
                        if t.elapsed() < budget {
                            cpu_at_last = schedstat().0;
                        }
                    });
                    let e = t.elapsed();
                    let cpu_after = (schedstat().0 - cpu_at_last) as f64 * 1e-9;
                    worst_active = worst_active.max(cpu_after);
                    worst = worst.max(e.saturating_sub(budget));
                    overruns.push(e.saturating_sub(budget));
                    last = Some(rep);
                }
                let rep = last.unwrap();
                overruns.sort();
                let median = overruns[overruns.len() / 2];
                let (status, it, err) = match rep {
                    Ok(r) => (format!("{:?}", r.status), r.iterations, r.error),
                    Err(e) => (format!("Err {e}"), 0, f64::NAN),
                };
                println!(
                    "{name:38} {label:12} {ms:3} ms  overrun median {:7.3} worst {:7.3} ms, CPU from the last iteration before the deadline to the return <= {:7.3} ms  {status} it {it} err {err:.1e}",
                    1e3 * median.as_secs_f64(),
                    1e3 * worst.as_secs_f64(),
                    1e3 * worst_active
                );
            }
        }
    }
}
