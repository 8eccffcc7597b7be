//! The iterations of TFP, PFP, ACLMFP and SOCLCP allocate nothing: with tolerance 0 (every
//! iteration runs), a whole `fc3d_core::solve` allocates as many times for `max_iter = 1` as for
//! `max_iter = 30`, whatever the inner solver. A counting global allocator (this test binary
//! only, thread-local counter) counts the allocations.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use fc3d_core::{
    solve, AclmInnerSolver, AclmOptions, Delassus, PfpOptions, SoclcpOptions, SolverConfig,
    TrescaInnerSolver, TrescaOptions,
};

struct CountingAllocator;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

#[inline]
fn record() {
    if COUNTING.try_with(Cell::get).unwrap_or(false) {
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

fn count_allocations(f: impl FnOnce()) -> usize {
    COUNT.with(|c| c.set(0));
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    COUNT.with(Cell::get)
}

fn configs(max_iter: usize) -> Vec<SolverConfig> {
    let mut v: Vec<SolverConfig> = [
        TrescaInnerSolver::GaussSeidel,
        TrescaInnerSolver::FixedPointViUpk,
        TrescaInnerSolver::ProjectedGradient,
        TrescaInnerSolver::apgd(),
        TrescaInnerSolver::spg(),
    ]
    .into_iter()
    .flat_map(|inner| {
        [
            SolverConfig::new(TrescaOptions {
                inner,
                inner_max_iter: 5,
                ..Default::default()
            }),
            SolverConfig::new(PfpOptions {
                tangent: inner,
                inner_max_iter: 5,
                ..Default::default()
            }),
        ]
    })
    .collect();
    for inner in [
        AclmInnerSolver::GaussSeidel,
        AclmInnerSolver::Apgd(Default::default()),
        AclmInnerSolver::Spg(Default::default()),
    ] {
        v.push(SolverConfig::new(AclmOptions {
            inner,
            inner_max_iter: 5,
            ..Default::default()
        }));
    }
    v.push(SolverConfig::new(SoclcpOptions::default()));
    v.into_iter()
        .map(|c| c.with_max_iter(max_iter).with_tolerance(0.0))
        .collect()
}

#[test]
fn iterations_allocate_nothing() {
    let sbm = fc3d_core::io::read_problem_file(std::path::Path::new(
        "../../shared/data/siconos/Confeti-ex03-Fc3D-SBM.dat",
    ))
    .unwrap();
    let csr = sbm.with_w(Delassus::Sparse(sbm.w().to_csr())).unwrap();
    for p in [&sbm, &csr] {
        let n = p.size();
        for (short, long) in configs(1).iter().zip(configs(30)) {
            let mut r = vec![0.0; n];
            let mut u = vec![0.0; n];
            let a1 = count_allocations(|| {
                solve(p, short, &mut r, &mut u).unwrap();
            });
            r.iter_mut().for_each(|v| *v = 0.0);
            let a30 = count_allocations(|| {
                solve(p, &long, &mut r, &mut u).unwrap();
            });
            assert_eq!(
                a1,
                a30,
                "{}: allocations grow with iterations",
                long.label()
            );
        }
    }
}
