//! Kernel benchmarks (issue "Measure the speed–accuracy trade", item 4).
//!
//! * `sweep/<problem>/<storage>`: one NSGS sweep (`Sweeper::sweep`, Siconos' default local solver
//!   565 NewtonHybrid) on real Siconos problems, W converted to dense, sparse-block and CSR so that
//!   the storages are compared on the same W. Each measured sweep starts from the same realistic
//!   reaction: the one reached after 10 sweeps from r = 0. `iter_batched_ref` hands every sweep a
//!   fresh copy of that reaction; the copy is made outside the timed region (criterion times the
//!   batch of routines only), so the figure is one sweep from a fixed state, not the cost of a
//!   sweep deep in a converged run.
//! * `local/<id-kind>/<regime>`: each local solver (`LocalSolverKind::ALL`) on one contact from
//!   r = 0, in the stick, slide and take-off regimes (same contacts as tests/no_alloc.rs, which
//!   checks that the regimes are what their names say).
//! * `mul_add/<problem>/<storage>`: `y += W x` (`Delassus::mul_add`) for the dense, sparse-block
//!   and CSR storage of the same W, with x the reaction after 10 sweeps (the product a full error
//!   evaluation does; the dense kernel skips the zero columns of take-off contacts).
//!
//! Run: `cargo bench --bench kernels -- --warm-up-time 1 --measurement-time 2`
//! (the defaults set below are 1 s warm-up, 3 s measurement; command-line flags override them).

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::local::{AnyLocalSolver, LocalProblem, LocalSolver};
use fc3d_core::{Delassus, FrictionProblem, LocalSolverKind, LocalSolverOptions, Sweeper};

/// Real problems: (short name, file).
const PROBLEMS: [(&str, &str); 3] = [
    ("Capsules-i100-889", "Capsules-i100-889.dat"), // sparse-block on file, 276 contacts
    ("NESpheres_30_1", "NESpheres_30_1.dat"),       // dense on file, 44 contacts
    ("RockPile_tob1", "RockPile_tob1.dat"),         // sparse-block on file, 463 contacts
];

/// Sweeps from r = 0 before the measured one.
const WARM_UP_SWEEPS: usize = 10;

fn siconos(file: &str) -> FrictionProblem<'static> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
    read_dat_file(&Path::new(dir).join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The problem with W in dense, sparse-block and CSR storage (all converted from the W on file).
fn storages(p: &FrictionProblem<'static>) -> Vec<(&'static str, FrictionProblem<'static>)> {
    vec![
        (
            "dense",
            p.with_w(Delassus::Dense(p.w().to_dense())).unwrap(),
        ),
        (
            "sparse-block",
            p.with_w(Delassus::SparseBlock(p.w().to_block_sparse().unwrap()))
                .unwrap(),
        ),
        ("csr", p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap()),
    ]
}

/// The reaction after `WARM_UP_SWEEPS` default-NSGS sweeps from r = 0.
fn warm_reaction(p: &FrictionProblem<'_>) -> Vec<f64> {
    let mut sweeper = Sweeper::new(p, &LocalSolverOptions::default()).unwrap();
    let mut r = vec![0.0; p.size()];
    for _ in 0..WARM_UP_SWEEPS {
        sweeper.sweep(p.q(), p.mu(), &mut r);
    }
    r
}

fn bench_sweep(c: &mut Criterion) {
    let mut group = c.benchmark_group("sweep");
    for (name, file) in PROBLEMS {
        let original = siconos(file);
        let r0 = warm_reaction(&original);
        group.throughput(Throughput::Elements(original.n_contacts() as u64));
        for (storage, p) in storages(&original) {
            let mut sweeper = Sweeper::new(&p, &LocalSolverOptions::default()).unwrap();
            let (q, mu) = (p.q(), p.mu());
            group.bench_function(format!("{name}/{storage}"), |b| {
                b.iter_batched_ref(
                    || r0.clone(),
                    |r| sweeper.sweep(black_box(q), black_box(mu), r),
                    BatchSize::SmallInput,
                )
            });
        }
    }
    group.finish();
}

/// A symmetric positive definite diagonal block and mu = 0.5; the q's put the contact in stick,
/// slide and take-off (see tests/no_alloc.rs).
const W: [[f64; 3]; 3] = [[1.0, 0.1, 0.05], [0.1, 0.8, 0.02], [0.05, 0.02, 0.9]];
const MU: f64 = 0.5;
const REGIMES: [(&str, [f64; 3]); 3] = [
    ("stick", [-1.0, 0.1, 0.05]),
    ("slide", [-1.0, 2.0, 1.0]),
    ("take-off", [1.0, 0.5, -0.2]),
];

fn bench_local(c: &mut Criterion) {
    let mut group = c.benchmark_group("local");
    for kind in LocalSolverKind::ALL {
        let mut solver = AnyLocalSolver::new(&LocalSolverOptions::new(kind));
        for (regime, q) in REGIMES {
            let p = LocalProblem { w: &W, q, mu: MU };
            group.bench_function(format!("{}-{kind:?}/{regime}", kind.siconos_id()), |b| {
                b.iter(|| {
                    let mut r = [0.0; 3];
                    solver.solve(black_box(&p), &mut r);
                    r
                })
            });
        }
    }
    group.finish();
}

fn bench_mul_add(c: &mut Criterion) {
    let mut group = c.benchmark_group("mul_add");
    for (name, file) in PROBLEMS {
        let original = siconos(file);
        let x = warm_reaction(&original);
        group.throughput(Throughput::Elements(original.size() as u64));
        for (storage, p) in storages(&original) {
            let w = p.w();
            let mut y = vec![0.0; p.size()];
            group.bench_function(format!("{name}/{storage}"), |b| {
                b.iter(|| w.mul_add(black_box(&x), black_box(&mut y)))
            });
        }
    }
    group.finish();
}

fn config() -> Criterion {
    // Short runs on a 2-core machine; command-line flags override these.
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

criterion_group! {
    name = kernels;
    config = config();
    targets = bench_sweep, bench_local, bench_mul_add
}
criterion_main!(kernels);
