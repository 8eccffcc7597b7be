//! The hot loops allocate nothing: a counting global allocator (installed for this test binary
//! only) counts the allocations made on the calling thread while a measurement is on.
//!
//! * one `Sweeper::sweep` on real problems, W in every storage, with every local solver: 0;
//! * every local solver's `solve` on a stick, a slide and a take-off contact: 0;
//! * `Delassus::mul_add` in dense, sparse-block and CSR storage: 0;
//! * a whole `fc3d_core::solve` with NSGS (tolerance 0, so every sweep runs) allocates as many times
//!   for `max_iter = 1` as for `max_iter = 200`, for every `ErrorEvaluation` mode: the set-up
//!   allocates, the iterations do not. (With tolerance 0 the cheap error never passes, so
//!   `LightWithFullFinal` measures the full error only after the loop; the full error inside
//!   the loop is the `Full` mode's, which is checked too.)
//!
//! The counter and its on/off flag are thread-local, so tests that libtest runs in parallel
//! threads (and libtest's own threads) cannot disturb each other's counts.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;
use std::time::Duration;

use fc3d_core::io::dat::read_dat_file;
use fc3d_core::local::{AnyLocalSolver, LocalProblem, LocalSolver};
use fc3d_core::{
    solve, Delassus, ErrorEvaluation, FrictionProblem, LocalSolverKind, LocalSolverOptions,
    NsgsOptions, SolveStatus, SolverConfig, Sweeper,
};

// ---------------------------------------------------------------------------------------------
// The counting allocator.

struct CountingAllocator;

thread_local! {
    // `const` initialisers without destructors: reading them never allocates or registers a
    // thread-exit destructor, so they are safe to touch from inside the allocator.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

#[inline]
fn record() {
    // `try_with`: during thread teardown the slots may be gone; such allocations are not ours.
    let on = COUNTING.try_with(Cell::get).unwrap_or(false);
    if on {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
    }
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        record();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        record();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        record();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// Runs `f` and returns the number of allocations (alloc, alloc_zeroed, realloc) it made on
/// this thread, with its result.
fn count_allocations<R>(f: impl FnOnce() -> R) -> (usize, R) {
    COUNT.with(|c| c.set(0));
    COUNTING.with(|c| c.set(true));
    let out = f();
    COUNTING.with(|c| c.set(false));
    (COUNT.with(Cell::get), out)
}

// ---------------------------------------------------------------------------------------------
// Problems.

fn siconos(name: &str) -> FrictionProblem<'static> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
    read_dat_file(&Path::new(dir).join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Real problems, each with W in its own storage and in the three storages.
fn problems() -> Vec<(String, FrictionProblem<'static>)> {
    let mut out = Vec::new();
    for name in [
        "Capsules-i100-889.dat", // sparse-block, 276 contacts
        "NESpheres_30_1.dat",    // dense, 44 contacts
        "RockPile_tob1.dat",     // sparse-block, 463 contacts
    ] {
        let p = siconos(name);
        let dense = p.with_w(Delassus::Dense(p.w().to_dense())).unwrap();
        let block = p
            .with_w(Delassus::SparseBlock(p.w().to_block_sparse().unwrap()))
            .unwrap();
        let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
        out.push((format!("{name} (as read, {})", p.w().storage_name()), p));
        out.push((format!("{name} (dense)"), dense));
        out.push((format!("{name} (sparse-block)"), block));
        out.push((format!("{name} (csr)"), csr));
    }
    out
}

/// A symmetric positive definite diagonal block of a contact.
const W: [[f64; 3]; 3] = [[1.0, 0.1, 0.05], [0.1, 0.8, 0.02], [0.05, 0.02, 0.9]];
const MU: f64 = 0.5;

/// One contact in each regime: (name, q). With W above and mu = 0.5, the solution is
/// stick `r = -W^{-1} q` (r_N ≈ 1.03, ||r_T|| ≈ 0.27 < mu r_N ≈ 0.52), slide (r_N ≈ 1.06,
/// ||r_T|| = mu r_N, ||u_T|| ≈ 1.9) and take-off (r = 0, u = q).
const REGIMES: [(&str, [f64; 3]); 3] = [
    ("stick", [-1.0, 0.1, 0.05]),
    ("slide", [-1.0, 2.0, 1.0]),
    ("take-off", [1.0, 0.5, -0.2]),
];

// ---------------------------------------------------------------------------------------------
// Tests.

#[test]
fn counter_sees_allocations() {
    // The instrument itself: a Vec allocates once, a resize reallocates, nothing else counts.
    let (n, v) = count_allocations(|| {
        let mut v = Vec::<f64>::with_capacity(1);
        v.extend_from_slice(&[1.0, 2.0, 3.0]);
        std::hint::black_box(v)
    });
    assert_eq!(n, 2);
    drop(v);
    let (n, _) = count_allocations(|| std::hint::black_box(1.0_f64).sqrt());
    assert_eq!(n, 0);
}

#[test]
fn sweep_allocates_nothing() {
    for (name, p) in problems() {
        for kind in LocalSolverKind::ALL {
            let mut sweeper = Sweeper::new(&p, &LocalSolverOptions::new(kind)).unwrap();
            let mut r = vec![0.0; p.size()];
            // From r = 0 and from a partly converged r.
            for round in 0..3 {
                let (n, inc) = count_allocations(|| sweeper.sweep(p.q(), p.mu(), &mut r));
                assert_eq!(n, 0, "{name}, {kind:?}, sweep {round}: {n} allocations");
                assert!(inc.is_finite());
            }
        }
    }
}

#[test]
fn local_solvers_allocate_nothing() {
    for kind in LocalSolverKind::ALL {
        let mut solver = AnyLocalSolver::new(&LocalSolverOptions::new(kind));
        for (regime, q) in REGIMES {
            let p = LocalProblem { w: &W, q, mu: MU };
            let mut r = [0.0; 3];
            let (n, _) = count_allocations(|| solver.solve(&p, &mut r));
            assert_eq!(n, 0, "{kind:?} on {regime}: {n} allocations");
            assert!(
                r.iter().all(|v| v.is_finite()),
                "{kind:?} on {regime}: {r:?}"
            );
            // A few more solves from the answer (warm start, as inside a sweep).
            let (n, _) = count_allocations(|| {
                for _ in 0..5 {
                    solver.solve(&p, &mut r);
                }
            });
            assert_eq!(n, 0, "{kind:?} on {regime} (warm): {n} allocations");
        }
    }
}

#[test]
fn local_regimes_are_what_their_names_say() {
    // The regimes above are checked on the converged Newton answer, so that the two tests above
    // (and the benchmark, which uses the same contacts) cover the three branches.
    let mut solver = AnyLocalSolver::new(&LocalSolverOptions::new(
        LocalSolverKind::NewtonAlartCurnierGp,
    ));
    for (regime, q) in REGIMES {
        let p = LocalProblem { w: &W, q, mu: MU };
        let mut r = [0.0; 3];
        assert!(solver.solve(&p, &mut r).converged, "{regime}");
        let u = p.velocity(&r);
        let rt = r[1].hypot(r[2]);
        match regime {
            "stick" => {
                assert!(r[0] > 0.0 && rt < 0.9 * MU * r[0], "{r:?}");
                assert!(u.iter().all(|v| v.abs() < 1e-10), "{u:?}");
            }
            "slide" => {
                assert!(r[0] > 0.0 && (rt - MU * r[0]).abs() < 1e-10, "{r:?}");
                assert!(u[1].hypot(u[2]) > 1e-3, "{u:?}");
            }
            "take-off" => {
                assert_eq!(r, [0.0; 3]);
                assert!(u[0] > 0.0);
            }
            _ => unreachable!(),
        }
    }
}

#[test]
fn mul_add_allocates_nothing() {
    for (name, p) in problems() {
        let n = p.size();
        let x: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.25).collect();
        let mut y = vec![0.0; n];
        let (count, _) = count_allocations(|| {
            p.w().mul_add(&x, &mut y);
            p.w().mul_add(&x, &mut y);
        });
        assert_eq!(count, 0, "{name}: {count} allocations");
        let (count, _) = count_allocations(|| p.velocity(&x, &mut y));
        assert_eq!(count, 0, "{name} (velocity): {count} allocations");
    }
}

/// Allocations of a whole NSGS solve from r = 0 that runs exactly `max_iter` sweeps (`config`
/// with tolerance 0 and `max_iter`).
fn solve_allocations(p: &FrictionProblem<'_>, config: SolverConfig, max_iter: usize) -> usize {
    let options = SolverConfig {
        max_iter,
        tolerance: 0.0,
        ..config
    };
    let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
    let (n, report) = count_allocations(|| solve(p, &options, &mut r, &mut u).unwrap());
    assert_eq!(report.iterations, max_iter, "{options:?}");
    assert_eq!(
        report.status,
        SolveStatus::MaxIterationsReached,
        "{report:?} {options:?}"
    );
    n
}

#[test]
fn solve_allocations_do_not_grow_with_iterations() {
    // Capsules needs thousands of sweeps to reach 1e-8, so 200 sweeps never stop early (unlike
    // NESpheres_30_1, which one sweep solves exactly: 41 of its 44 contacts take off).
    let capsules = siconos("Capsules-i100-889.dat");
    let dense = capsules
        .with_w(Delassus::Dense(capsules.w().to_dense()))
        .unwrap();
    let csr = capsules
        .with_w(Delassus::Sparse(capsules.w().to_csr()))
        .unwrap();
    let cases: [(&str, &FrictionProblem<'_>); 3] = [
        ("Capsules-i100-889 (sparse-block)", &capsules),
        ("Capsules-i100-889 (dense)", &dense),
        ("Capsules-i100-889 (csr)", &csr),
    ];
    for (name, p) in cases {
        for mode in [
            ErrorEvaluation::Full,
            ErrorEvaluation::Light,
            ErrorEvaluation::LightWithFullFinal,
            ErrorEvaluation::DumontCriterion,
        ] {
            for kind in [
                LocalSolverKind::NewtonHybrid,
                LocalSolverKind::ProjectionOnConeWithLocalIteration,
            ] {
                for budget in [None, Some(Duration::from_secs(3600))] {
                    let options = SolverConfig::new(NsgsOptions {
                        error_evaluation: mode,
                        ..NsgsOptions::with_local(kind)
                    })
                    .with_time_budget(budget);
                    let one = solve_allocations(p, options, 1);
                    let many = solve_allocations(p, options, 200);
                    println!(
                        "{name}, {mode:?}, {kind:?}, budget {budget:?}: {one} allocations for \
                         1 sweep, {many} for 200"
                    );
                    assert_eq!(
                        one, many,
                        "{name}, {mode:?}, {kind:?}, budget {budget:?}: {one} allocations for \
                         1 sweep but {many} for 200"
                    );
                }
            }
        }
    }
    // Every sweep option at once: shuffled each sweep, relaxed, frozen, adaptive local tolerance
    // (which rebuilds the local solver), tested every 3 sweeps.
    for (name, p) in cases {
        let options = SolverConfig::new(NsgsOptions {
            order: fc3d_core::ContactOrder::ShuffledEachSweep { seed: 3 },
            relaxation: Some(1.2),
            freezing: Some(4),
            local_tolerance: fc3d_core::LocalTolerance::AdaptivePerContact { ratio: 10.0 },
            evaluation_frequency: 3,
            ..NsgsOptions::default()
        });
        let one = solve_allocations(p, options, 1);
        let many = solve_allocations(p, options, 200);
        assert_eq!(one, many, "{name}, all sweep options: {one} vs {many}");
    }
    // The parallel decompositions on two threads (the pool, kept for the process, is started
    // by a first solve): the calling thread allocates nothing per sweep. A pile of 5000
    // contacts is one island large enough to be swept coloured by both threads.
    let pile = fc3d_core::scenes::sphere_piles(&fc3d_core::scenes::PileSpec {
        contacts: 5000,
        piles: 1,
        seed: 3,
    })
    .unwrap();
    let parallel_cases = [cases[0], cases[1], cases[2], ("pile of 5000", &pile)];
    for (name, p) in parallel_cases {
        for decomposition in [
            fc3d_core::Decomposition::Coloured,
            fc3d_core::Decomposition::Islands,
        ] {
            let options = SolverConfig::new(NsgsOptions {
                decomposition,
                threads: 2,
                relaxation: Some(1.2),
                ..NsgsOptions::default()
            });
            solve_allocations(p, options, 1);
            let one = solve_allocations(p, options, 1);
            let many = solve_allocations(p, options, 200);
            assert_eq!(one, many, "{name}, {decomposition:?}: {one} vs {many}");
        }
    }
}

/// The mixed-precision NSGS (early sweeps on the f32 copy of W's coupling blocks): a sweep on
/// the copy allocates nothing, and a whole solve allocates as often for 1 sweep as for 200,
/// sequential and coloured on two threads, the copy left (switch error 1: at the first test)
/// or kept throughout (switch error 1e-30 and tolerance 0: no rule fires on Capsules).
#[test]
fn f32_sweeps_allocate_nothing() {
    for (name, p) in problems() {
        let options = NsgsOptions {
            f32_sweeps: Some(fc3d_core::F32Sweeps::default()),
            ..NsgsOptions::default()
        };
        let mut sweeper = Sweeper::with_options(&p, &options, 0.0).unwrap();
        let mut r = vec![0.0; p.size()];
        for round in 0..3 {
            let (n, inc) = count_allocations(|| sweeper.sweep(p.q(), p.mu(), &mut r));
            assert_eq!(n, 0, "{name}, f32 copy, sweep {round}: {n} allocations");
            assert!(inc.is_finite());
        }
    }
    let capsules = siconos("Capsules-i100-889.dat");
    for decomposition in [
        fc3d_core::Decomposition::Sequential,
        fc3d_core::Decomposition::Coloured,
    ] {
        for mode in [ErrorEvaluation::Full, ErrorEvaluation::LightWithFullFinal] {
            for switch_error in [1e-30, 1.0] {
                let options = SolverConfig::new(NsgsOptions {
                    decomposition,
                    threads: 2,
                    error_evaluation: mode,
                    f32_sweeps: Some(fc3d_core::F32Sweeps { switch_error }),
                    ..NsgsOptions::default()
                });
                solve_allocations(&capsules, options, 1);
                let one = solve_allocations(&capsules, options, 1);
                let many = solve_allocations(&capsules, options, 200);
                assert_eq!(
                    one, many,
                    "{decomposition:?}, {mode:?}, switch {switch_error}: {one} vs {many}"
                );
            }
        }
    }
}

/// Allocations of a whole solve with `config` (tolerance 0, so every iteration runs).
fn config_allocations(
    p: &FrictionProblem<'_>,
    config: fc3d_core::SolverConfig,
    max_iter: usize,
) -> usize {
    let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
    let (n, report) = count_allocations(|| solve(p, &config, &mut r, &mut u).unwrap());
    assert_eq!(report.iterations, max_iter, "{config:?}");
    n
}

#[test]
fn vi_and_admm_iterations_allocate_nothing() {
    // Constant-rho ADMM refactors nothing inside the loop; the VI family allocates its work
    // vectors before the first iteration.
    let p = siconos("Confeti-ex03-Fc3D-SBM.dat");
    let csr = p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap();
    let dense = p.with_w(Delassus::Dense(p.w().to_dense())).unwrap();
    for q in [&p, &csr, &dense] {
        for make in [
            |k: usize| {
                fc3d_core::SolverConfig::new(fc3d_core::ViOptions::new(
                    fc3d_core::ViSolver::ViExtraGradient,
                ))
                .with_max_iter(k)
                .with_tolerance(0.0)
            },
            |k: usize| {
                fc3d_core::SolverConfig::new(fc3d_core::ViOptions {
                    error_evaluation: ErrorEvaluation::Full,
                    ..fc3d_core::ViOptions::new(fc3d_core::ViSolver::ViFixedPointProjection)
                })
                .with_max_iter(k)
                .with_tolerance(0.0)
            },
            |k: usize| {
                fc3d_core::SolverConfig::new(fc3d_core::AdmmOptions::default())
                    .with_max_iter(k)
                    .with_tolerance(0.0)
            },
        ] {
            let one = config_allocations(q, make(1), 1);
            let many = config_allocations(q, make(200), 200);
            assert_eq!(
                one,
                many,
                "{:?}: {one} allocations for 1 iteration, {many} for 200",
                make(1)
            );
        }
    }
}

/// The 2D solvers' iterations allocate nothing either: a whole NSGS (every error evaluation,
/// with and without a time budget) or CPG solve of FrictionContactProblem00727 (367 contacts,
/// 2x2 sparse blocks read as CSR) allocates as many times for 1 iteration as for 50.
#[test]
fn planar_solve_allocations_do_not_grow_with_iterations() {
    use fc3d_core::io::dat::{read_dat_file_any, DatProblem};
    use fc3d_core::{solve_planar, PlanarConfig, PlanarMethod, PlanarNsgsOptions};
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/siconos/FrictionContactProblem00727.dat");
    let DatProblem::Planar(p) = read_dat_file_any(&path).unwrap() else {
        panic!("not 2D")
    };
    let dense = p.with_w(Delassus::Dense(p.w().to_dense())).unwrap();
    let allocations = |p: &fc3d_core::FrictionProblem2d<'_>, mut config: PlanarConfig, k| {
        config.max_iter = k;
        config.tolerance = 0.0;
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        let (n, report) = count_allocations(|| solve_planar(p, &config, &mut r, &mut u).unwrap());
        assert_eq!(report.iterations, k, "{config:?}");
        n
    };
    for p in [&p, &dense] {
        let mut methods = vec![PlanarMethod::Cpg];
        for mode in [
            ErrorEvaluation::Full,
            ErrorEvaluation::Light,
            ErrorEvaluation::LightWithFullFinal,
        ] {
            methods.push(PlanarMethod::Nsgs(PlanarNsgsOptions {
                error_evaluation: mode,
                ..PlanarNsgsOptions::default()
            }));
        }
        methods.push(PlanarMethod::Nsgs(PlanarNsgsOptions {
            order: fc3d_core::ContactOrder::ShuffledEachSweep { seed: 1 },
            relaxation: Some(1.3),
            freezing: Some(3),
            ..PlanarNsgsOptions::default()
        }));
        for method in methods {
            for budget in [None, Some(Duration::from_secs(3600))] {
                let mut config = PlanarConfig::new(method);
                config.time_budget = budget;
                let one = allocations(p, config, 1);
                let many = allocations(p, config, 50);
                assert_eq!(
                    one, many,
                    "{method:?} {budget:?}: {one} for 1 iteration, {many} for 50"
                );
            }
        }
    }
}

/// The rolling solvers' iterations allocate nothing: a whole rolling NSGS (both local solvers,
/// every error evaluation, relaxation, shuffling and freezing, with and without a time budget)
/// or ADMM solve of Siconos' rfc3d_sphere_from_grfc3d (from the source package that
/// scripts/siconos-suite.sh extracts; skipped without it) allocates as many times for 1
/// iteration as for 50.
#[test]
fn rolling_solve_allocations_do_not_grow_with_iterations() {
    use fc3d_core::io::dat::{read_rolling_dat_file, RollingDatProblem};
    use fc3d_core::{
        solve_rolling, AdmmOptions, RollingConfig, RollingLocalSolver, RollingMethod,
        RollingNsgsOptions,
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(
        "../target/siconos-src/siconos-4.4.0/numerics/src/FrictionContact/test/data/\
         rfc3d_sphere_from_grfc3d.dat",
    );
    if !path.is_file() {
        eprintln!("Siconos' sources not extracted: skipped");
        return;
    }
    let RollingDatProblem::Spatial(p) = read_rolling_dat_file(&path).unwrap() else {
        panic!("not 5D")
    };
    let allocations = |mut config: RollingConfig, k| {
        config.max_iter = k;
        config.tolerance = 0.0;
        let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
        let (n, report) = count_allocations(|| solve_rolling(&p, &config, &mut r, &mut u).unwrap());
        assert_eq!(report.iterations, k, "{config:?}");
        n
    };
    let mut methods = vec![RollingMethod::Admm(AdmmOptions::default())];
    for local in [
        RollingLocalSolver::default(),
        RollingLocalSolver::Projection { unit_step: false },
    ] {
        for mode in [
            ErrorEvaluation::Full,
            ErrorEvaluation::Light,
            ErrorEvaluation::LightWithFullFinal,
            ErrorEvaluation::DumontCriterion,
        ] {
            methods.push(RollingMethod::Nsgs(RollingNsgsOptions {
                error_evaluation: mode,
                local,
                ..RollingNsgsOptions::default()
            }));
        }
        methods.push(RollingMethod::Nsgs(RollingNsgsOptions {
            order: fc3d_core::ContactOrder::ShuffledEachSweep { seed: 1 },
            relaxation: Some(1.3),
            freezing: Some(3),
            filter_local_solution: true,
            local,
            ..RollingNsgsOptions::default()
        }));
    }
    for method in methods {
        for budget in [None, Some(Duration::from_secs(3600))] {
            let mut config = RollingConfig::new(method);
            config.time_budget = budget;
            let one = allocations(config, 1);
            let many = allocations(config, 50);
            assert_eq!(
                one, many,
                "{method:?} {budget:?}: {one} for 1 iteration, {many} for 50"
            );
        }
    }
}

/// A global interior-point solve (615) allocates as many times for 2 iterations as for 12: the
/// Newton matrix's pattern, analysis and work vectors are set up once; the iterations (blocks,
/// factorization on the fixed pattern, solves, steps, the error of the triple) allocate nothing.
/// The allocations of a global solve of a 60-contact generated pile running exactly `k`
/// iterations of `method` (asserted).
fn global_solve_allocations(
    shape: fc3d_core::scenes::PileShape,
    method: fc3d_core::global::GlobalMethod,
    k: usize,
) -> usize {
    use fc3d_core::global::{solve_global, GlobalConfig};
    use fc3d_core::scenes::{GeneratedScene, PileSpec};
    let p = GeneratedScene {
        pile: PileSpec {
            contacts: 60,
            piles: 1,
            seed: 3,
        },
        shape,
    }
    .generate_global()
    .unwrap();
    let config = GlobalConfig {
        tolerance: 0.0,
        max_iter: k,
        ..GlobalConfig::new(method)
    };
    let (mut r, mut u, mut v) = (
        vec![0.0; p.size()],
        vec![0.0; p.size()],
        vec![0.0; p.ndof()],
    );
    let (n, report) =
        count_allocations(|| solve_global(&p, &config, &mut r, &mut u, &mut v).unwrap());
    assert_eq!(report.iterations, k);
    n
}

#[test]
fn global_ipm_iterations_allocate_nothing() {
    use fc3d_core::global::{GlobalMethod, IpmOptions};
    use fc3d_core::scenes::PileShape;
    for (shape, update_s, nesterov_todd) in [
        (PileShape::Spheres, false, true),
        (PileShape::Boxes, true, false),
    ] {
        let method = GlobalMethod::Ipm(IpmOptions {
            update_s,
            nesterov_todd,
            ..Default::default()
        });
        let allocations = |k| global_solve_allocations(shape, method, k);
        let (few, many) = (allocations(2), allocations(12));
        assert_eq!(
            few, many,
            "{shape:?}: {few} for 2 iterations, {many} for 12"
        );
    }
}

/// A global H-form solve (691) allocates as many times for 2 sweeps as for 30, sequential and
/// coloured (on the calling thread), with the global error measured after every sweep and under
/// a time budget (the best iterate kept): the sweep, the recomputed `v` and the error of the
/// triple allocate nothing.
#[test]
fn global_hform_sweeps_allocate_nothing() {
    use fc3d_core::global::{solve_global, GlobalConfig, GlobalMethod};
    use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};
    use fc3d_core::Decomposition;
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let p = GeneratedScene {
            pile: PileSpec {
                contacts: 1200,
                piles: 1,
                seed: 3,
            },
            shape,
        }
        .generate_global()
        .unwrap();
        for (decomposition, error_evaluation, budget) in [
            (
                Decomposition::Sequential,
                ErrorEvaluation::LightWithFullFinal,
                None,
            ),
            (Decomposition::Sequential, ErrorEvaluation::Full, None),
            (Decomposition::Coloured, ErrorEvaluation::Full, None),
            (
                Decomposition::Sequential,
                ErrorEvaluation::LightWithFullFinal,
                Some(Duration::from_secs(600)),
            ),
        ] {
            let allocations = |k| {
                let config = GlobalConfig {
                    tolerance: 0.0,
                    max_iter: k,
                    time_budget: budget,
                    ..GlobalConfig::new(GlobalMethod::HForm(NsgsOptions {
                        decomposition,
                        error_evaluation,
                        threads: 1,
                        ..Default::default()
                    }))
                };
                let (mut r, mut u, mut v) = (
                    vec![0.0; p.size()],
                    vec![0.0; p.size()],
                    vec![0.0; p.ndof()],
                );
                let (n, report) = count_allocations(|| {
                    solve_global(&p, &config, &mut r, &mut u, &mut v).unwrap()
                });
                assert_eq!(report.iterations, k);
                n
            };
            let (few, many) = (allocations(2), allocations(30));
            assert_eq!(
                few, many,
                "{shape:?} {decomposition:?} {error_evaluation:?} {budget:?}: {few} for 2 \
                 sweeps, {many} for 30"
            );
        }
    }
}

/// fc3d's SSN-ALM (690) allocates as many times for 3 Newton steps as for 15: the body-space
/// pattern, its Cholesky analysis, GMRES' basis and the work vectors are set up once; the steps
/// (contact maps, assembly and factorization on the fixed pattern, solves, GMRES, the line
/// search, the error of the exact triple) allocate nothing.
#[test]
fn global_alm_iterations_allocate_nothing() {
    use fc3d_core::global::{GlobalAlmOptions, GlobalMethod};
    use fc3d_core::scenes::PileShape;
    for shape in [PileShape::Spheres, PileShape::Boxes] {
        let method = GlobalMethod::AugmentedLagrangian(GlobalAlmOptions::default());
        let allocations = |k| global_solve_allocations(shape, method, k);
        let (few, many) = (allocations(3), allocations(15));
        assert_eq!(
            few, many,
            "{shape:?}: {few} for 3 iterations, {many} for 15"
        );
    }
}
