//! `fc3d_driver` on problems whose W is a near-empty triplet matrix, under address-space limits
//! (issue 29, item 6): whatever memory fc3d is left, a call ends in `FC3D_ERR_OUT_OF_MEMORY` or
//! a solution, never in an abort, and writes nothing when it fails.
//!
//! * 10^8 contacts (W 3x10^8 x 3x10^8, a few entries), the case. The host's own arrays
//!   cost what they cost whatever the library does: q, r and u hold 3x10^8 doubles each and mu
//!   10^8, 8 GiB of address space (allocated with `calloc` and never written, so they take no
//!   physical memory). The test allocates them, then lowers its own address-space limit to what
//!   the process holds plus a headroom for fc3d: 1 GiB (less than the row pointers of W in
//!   compressed rows, 2.4 GB) and 3 GiB (room for those, not for the copy of the reaction).
//! * 10^5 contacts, every headroom from 0 up by 1 MiB until the solve succeeds: each allocation
//!   on the way (W in compressed rows, the copies of r and u, the block rows, the sweep's and
//!   AUTO's work arrays, the error measure) fails in turn, each time with the error code.
//!
//! Both are ignored in plain runs: `scripts/test-memory-limit.sh` runs them under an
//! address-space limit large enough for the host's arrays (they lower it themselves).

#![cfg(feature = "siconos-abi")]

use std::ffi::{c_int, CStr};
use std::os::raw::c_double;

use fc3d::types::{FrictionContactProblem, NumericsMatrix};
use fc3d::FC3D_ERR_OUT_OF_MEMORY;

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn NM_create(storage: c_int, size0: c_int, size1: c_int) -> *mut NumericsMatrix;
    fn NM_triplet_alloc(m: *mut NumericsMatrix, nzmax: c_int);
    fn NM_entry(m: *mut NumericsMatrix, i: c_int, j: c_int, v: c_double) -> c_int;
    fn NM_free(m: *mut NumericsMatrix) -> *mut NumericsMatrix;
}

const NM_SPARSE: c_int = 2;
const CONTACTS: usize = 100_000_000;
const GIB: u64 = 1 << 30;

/// The process's address space in bytes (VmSize).
fn address_space_used() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let kib: u64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmSize:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmSize in /proc/self/status");
    kib * 1024
}

fn limit() -> libc::rlimit {
    let mut l = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    assert_eq!(unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut l) }, 0);
    l
}

fn set_soft_limit(bytes: libc::rlim_t) {
    let l = libc::rlimit {
        rlim_cur: bytes,
        rlim_max: limit().rlim_max,
    };
    assert_eq!(unsafe { libc::setrlimit(libc::RLIMIT_AS, &l) }, 0);
}

/// A zeroed C array of `n` doubles (untouched pages: address space, no physical memory).
fn host_array(n: usize) -> *mut c_double {
    let p = unsafe { calloc(n, std::mem::size_of::<c_double>()) } as *mut c_double;
    assert!(
        !p.is_null(),
        "the host's array of {n} doubles does not fit the address-space limit: \
         scripts/test-memory-limit.sh gives this test room for it"
    );
    p
}

/// `fc3d_driver` on `problem` with `id`'s default options, under the address space the process
/// holds plus `headroom`: the code it returned (r and u checked untouched when it failed).
unsafe fn solve_with_headroom(
    problem: &mut FrictionContactProblem,
    id: c_int,
    headroom: u64,
    r: *mut c_double,
    u: *mut c_double,
) -> c_int {
    let n = 3 * problem.numberOfContacts as usize;
    let options = solver_options_create(id);
    fc3d_clear_last_error();
    let saved = limit();
    // Memory freed by earlier calls goes back to the system first (it would serve this call
    // within the address space already held).
    libc::malloc_trim(0);
    set_soft_limit(address_space_used() + headroom);
    let info = fc3d_driver(problem, r, u, options);
    set_soft_limit(saved.rlim_cur);
    solver_options_delete(options);
    free(options.cast());
    if info < 0 {
        let message = CStr::from_ptr(fc3d_last_error_message()).to_string_lossy();
        assert_eq!(info, FC3D_ERR_OUT_OF_MEMORY, "id {id}: {message}");
        assert!(message.contains("out of memory"), "{message}");
        // (Their ends: reading 2.4 GB of untouched pages costs more than the call.)
        for v in [r, u] {
            let v = std::slice::from_raw_parts(v, n);
            let mut ends = v.iter().take(1 << 20).chain(v.iter().rev().take(1 << 20));
            assert!(ends.all(|&x| x == 0.0), "id {id}: written on failure");
        }
    }
    info
}

/// A problem of `nc` contacts whose W holds the diagonal blocks of the first and last contacts
/// and a coupling between them, with q pushing both into the ground; the host's arrays are
/// zeroed C arrays (q, mu, r, u).
unsafe fn near_empty_problem(nc: usize) -> (FrictionContactProblem, *mut c_double, *mut c_double) {
    let n = 3 * nc;
    let (q, mu) = (host_array(n), host_array(nc));
    let w = NM_create(NM_SPARSE, n as c_int, n as c_int);
    assert!(!w.is_null());
    NM_triplet_alloc(w, 8);
    for (i, j, v) in [
        (0, 0, 2.0),
        (1, 1, 2.0),
        (2, 2, 2.0),
        (n - 3, n - 3, 1.0),
        (0, n - 3, 0.5),
        (n - 3, 0, 0.5),
    ] {
        assert_eq!(NM_entry(w, i as c_int, j as c_int, v), 0);
    }
    *q = -1.0;
    *q.add(n - 3) = -1.0;
    *mu = 0.3;
    *mu.add(nc - 1) = 0.3;
    let problem = FrictionContactProblem {
        dimension: 3,
        numberOfContacts: nc as c_int,
        M: w,
        q,
        mu,
    };
    (problem, host_array(n), host_array(n))
}

unsafe fn release(problem: FrictionContactProblem, r: *mut c_double, u: *mut c_double) {
    NM_free(problem.M);
    for p in [problem.q, problem.mu, r, u] {
        free(p.cast());
    }
}

#[test]
#[ignore = "needs 8 GiB of address space for the host's arrays: scripts/test-memory-limit.sh"]
fn under_memory_limit_a_huge_near_empty_triplet_w_is_out_of_memory() {
    unsafe {
        let (mut problem, r, u) = near_empty_problem(CONTACTS);
        for headroom in [GIB, 3 * GIB] {
            for id in [500, 590] {
                let info = solve_with_headroom(&mut problem, id, headroom, r, u);
                let message = CStr::from_ptr(fc3d_last_error_message()).to_string_lossy();
                eprintln!(
                    "headroom {} GiB, id {id}: {info}: {message}",
                    headroom / GIB
                );
                assert_eq!(info, FC3D_ERR_OUT_OF_MEMORY);
            }
        }
        release(problem, r, u);
    }
}

#[test]
#[ignore = "lowers its own address-space limit: scripts/test-memory-limit.sh"]
fn under_memory_limit_every_headroom_ends_in_a_solution_or_out_of_memory() {
    const STEP: u64 = 1 << 20;
    unsafe {
        let (mut problem, r, u) = near_empty_problem(100_000);
        for id in [500, 507, 503, 522, 516, 517] {
            let (mut failures, mut stopped) = (0, 0);
            let mut headroom = 0;
            let n = 3 * problem.numberOfContacts as usize;
            loop {
                let info = solve_with_headroom(&mut problem, id, headroom, r, u);
                if info == 0 {
                    eprintln!(
                        "id {id}: solved with {} MiB; {failures} smaller headrooms out of \
                         memory, {stopped} not converged",
                        headroom >> 20
                    );
                    break;
                }
                // Not converged: a stage of AUTO that could not have its memory was skipped.
                if info > 0 {
                    stopped += 1;
                    std::slice::from_raw_parts_mut(r, n).fill(0.0);
                    std::slice::from_raw_parts_mut(u, n).fill(0.0);
                } else {
                    failures += 1;
                }
                headroom += STEP;
                assert!(headroom < GIB, "id {id}: not solved with 1 GiB");
            }
            assert!(failures > 0, "id {id}: the smallest headroom is enough");
            // The next solver starts from r = 0 (and u = 0, to see that nothing is written).
            std::slice::from_raw_parts_mut(r, n).fill(0.0);
            std::slice::from_raw_parts_mut(u, n).fill(0.0);
        }
        release(problem, r, u);
    }
}
