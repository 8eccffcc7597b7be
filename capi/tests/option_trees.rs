//! Option trees are finite (issue 13, item 5), through the C ABI as a host calls it:
//! * a `SolverOptions` that is its own internal solver, directly or deeper, is refused by
//!   `fc3d_driver`, `solver_options_copy` and `solver_options_print` with
//!   FC3D_ERR_INVALID_OPTION, and `solver_options_delete` releases it without recursion or
//!   double free;
//! * a chain of internal solvers deeper than `FC3D_OPTIONS_MAX_DEPTH` is refused, one at the
//!   limit is accepted, and `solver_options_delete` releases a chain of 100000 levels from a
//!   thread with a 256 KiB stack;
//! * `numberOfInternalSolvers` without an array or above `FC3D_OPTIONS_MAX_INTERNAL_SOLVERS`,
//!   and `iSize`/`dSize` that are negative, short or above `FC3D_OPTIONS_MAX_PARAM_SIZE`, are
//!   refused;
//! * an internal solver shared by two slots is released once, and replacing one of its slots
//!   does not release it;
//! * a callback that frees or changes the options during a solve is refused (nothing written),
//!   not a crash;
//! * huge values mean "unlimited" where that is their meaning (a budget of 1e300 s, INT_MAX
//!   iterations), and a positive budget below a nanosecond is a budget, not a rejection.
//!
//! Run under valgrind or ASan (`scripts/test-all.sh`) any double free or read of freed memory
//! shows; without them glibc aborts on most double frees.

use std::ffi::{c_void, CStr};
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use fc3d::types::{Callback, FrictionContactProblem, NumericsMatrix, SolverOptions};
use fc3d::FC3D_ERR_INVALID_OPTION;

mod siconos_api;
use siconos_api::*;

/// The limits of `fc3d.h` (checked against the header below).
const FC3D_OPTIONS_MAX_DEPTH: c_int = 8;
const FC3D_OPTIONS_MAX_INTERNAL_SOLVERS: c_int = 16;
const FC3D_OPTIONS_MAX_PARAM_SIZE: c_int = 1024;

#[test]
fn the_limits_are_the_headers() {
    let h =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/include/fc3d.h")).unwrap();
    for (name, value) in [
        ("FC3D_OPTIONS_MAX_DEPTH", FC3D_OPTIONS_MAX_DEPTH),
        (
            "FC3D_OPTIONS_MAX_INTERNAL_SOLVERS",
            FC3D_OPTIONS_MAX_INTERNAL_SOLVERS,
        ),
        ("FC3D_OPTIONS_MAX_PARAM_SIZE", FC3D_OPTIONS_MAX_PARAM_SIZE),
    ] {
        assert!(
            h.contains(&format!("#define {name} {value}\n")),
            "{name} is not {value} in fc3d.h"
        );
    }
}

extern "C" {
    fn solver_options_copy(o: *mut SolverOptions) -> *mut SolverOptions;
    fn solver_options_print(o: *mut SolverOptions);
    fn solver_options_set_internal_solver(o: *mut SolverOptions, n: usize, s: *mut SolverOptions);
}

fn message() -> String {
    unsafe { CStr::from_ptr(fc3d_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

unsafe fn release(o: *mut SolverOptions) {
    solver_options_delete(o);
    free(o.cast());
}

/// `n` C-allocated internal solver slots, given to `o` (the old array and solvers released).
unsafe fn give_slots(o: *mut SolverOptions, slots: &[*mut SolverOptions]) {
    let a =
        calloc(slots.len(), std::mem::size_of::<*mut SolverOptions>()) as *mut *mut SolverOptions;
    for (k, &s) in slots.iter().enumerate() {
        *a.add(k) = s;
    }
    for k in 0..(*o).numberOfInternalSolvers {
        let s = *(*o).internalSolvers.add(k);
        if !slots.contains(&s) {
            release(s);
        }
    }
    free((*o).internalSolvers.cast());
    (*o).internalSolvers = a;
    (*o).numberOfInternalSolvers = slots.len();
}

unsafe fn internal(o: *mut SolverOptions, k: usize) -> *mut SolverOptions {
    *(*o).internalSolvers.add(k)
}

/// One contact, W = I, q = (-1, 0.5, 0), mu = 0.5: solved by every solver in a few iterations.
struct Problem {
    w: Vec<f64>,
    q: Vec<f64>,
    mu: Vec<f64>,
    m: Box<NumericsMatrix>,
}

impl Problem {
    fn new() -> Self {
        let mut p = Problem {
            w: vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            q: vec![-1.0, 0.5, 0.0],
            mu: vec![0.5],
            // SAFETY: an all-zero NumericsMatrix is a valid empty value.
            m: Box::new(unsafe { std::mem::zeroed() }),
        };
        p.m.storageType = 0;
        p.m.size0 = 3;
        p.m.size1 = 3;
        p.m.matrix0 = p.w.as_mut_ptr();
        p
    }

    /// `fc3d_driver` from r = 0; the code and whether r, u were written.
    unsafe fn solve(&mut self, o: *mut SolverOptions) -> (c_int, bool) {
        let mut raw = FrictionContactProblem {
            dimension: 3,
            numberOfContacts: 1,
            M: &mut *self.m,
            q: self.q.as_mut_ptr(),
            mu: self.mu.as_mut_ptr(),
        };
        let (mut r, mut u) = ([0.0; 3], [-7.0; 3]);
        fc3d_clear_last_error();
        let rc = fc3d_driver(&mut raw, r.as_mut_ptr(), u.as_mut_ptr(), o);
        (rc, u != [-7.0; 3])
    }
}

/// Asserts that `fc3d_driver`, `solver_options_copy` and `solver_options_print` refuse `o` with
/// FC3D_ERR_INVALID_OPTION and a message containing `why`.
unsafe fn refused_everywhere(o: *mut SolverOptions, why: &str) {
    let mut p = Problem::new();
    let (rc, written) = p.solve(o);
    assert_eq!(rc, FC3D_ERR_INVALID_OPTION, "driver: {}", message());
    assert!(!written);
    assert!(message().contains(why), "driver: {}", message());
    fc3d_clear_last_error();
    assert!(solver_options_copy(o).is_null(), "copy accepted it");
    assert_eq!(fc3d_last_error_code(), FC3D_ERR_INVALID_OPTION);
    assert!(message().contains(why), "copy: {}", message());
    fc3d_clear_last_error();
    solver_options_print(o);
    assert_eq!(fc3d_last_error_code(), FC3D_ERR_INVALID_OPTION);
    assert!(message().contains(why), "print: {}", message());
}

/// An options struct that is its own internal solver, for NSGS and for PROX (whose internal
/// solver is read as a whole configuration: before, PROX -> itself recursed until the stack
/// overflowed), directly and two levels down; then released by `solver_options_delete`.
#[test]
fn cycles_are_refused_and_released_once() {
    unsafe {
        for id in [500, 502, 503] {
            // Directly: internalSolvers[0] = the options themselves.
            let o = solver_options_create(id);
            give_slots(o, &[o]);
            refused_everywhere(o, "cycle");
            // Released once: the struct is not freed by delete (it is the caller's).
            solver_options_delete(o);
            assert_eq!((*o).numberOfInternalSolvers, 0);
            assert!((*o).iparam.is_null());
            free(o.cast());
        }
        // Deeper: PROX -> NSGS -> local solver -> PROX.
        let o = solver_options_create(502);
        solver_options_update_internal(o, 0, 500);
        let local = internal(internal(o, 0), 0);
        give_slots(local, &[o]);
        refused_everywhere(o, "cycle");
        // The local solver's slot points back at the root: refused from the middle too.
        refused_everywhere(internal(o, 0), "cycle");
        release(o);
    }
}

/// `solver_options_set_internal_solver` refuses to make a cycle and leaves the options as they
/// were.
#[test]
fn set_internal_solver_refuses_a_cycle() {
    unsafe {
        let o = solver_options_create(502);
        solver_options_update_internal(o, 0, 500);
        let nsgs = internal(o, 0);
        let local = internal(nsgs, 0);
        fc3d_clear_last_error();
        solver_options_set_internal_solver(o, 0, o);
        assert_eq!(
            fc3d_last_error_code(),
            FC3D_ERR_INVALID_OPTION,
            "{}",
            message()
        );
        assert_eq!(internal(o, 0), nsgs);
        fc3d_clear_last_error();
        solver_options_set_internal_solver(nsgs, 0, o);
        assert_eq!(
            fc3d_last_error_code(),
            FC3D_ERR_INVALID_OPTION,
            "{}",
            message()
        );
        assert!(message().contains("cycle"));
        assert_eq!(internal(nsgs, 0), local);
        let mut p = Problem::new();
        assert_eq!(p.solve(o).0, 0, "{}", message());
        release(o);
    }
}

/// A chain of internal solvers (hung below NSGS's local solver, which reads none) exactly
/// `FC3D_OPTIONS_MAX_DEPTH` deep is solved and copied; one level more is refused.
#[test]
fn chains_deeper_than_the_limit_are_refused() {
    unsafe {
        for depth in [
            FC3D_OPTIONS_MAX_DEPTH as usize,
            FC3D_OPTIONS_MAX_DEPTH as usize + 1,
        ] {
            let o = solver_options_create(500);
            let mut last = internal(o, 0); // level 1
            for _ in 2..=depth {
                let next = solver_options_create(565);
                give_slots(last, &[next]);
                last = next;
            }
            if depth <= FC3D_OPTIONS_MAX_DEPTH as usize {
                let mut p = Problem::new();
                assert_eq!(p.solve(o).0, 0, "{}", message());
                let c = solver_options_copy(o);
                assert!(!c.is_null(), "{}", message());
                assert_eq!(p.solve(c).0, 0);
                release(c);
            } else {
                refused_everywhere(o, "deeper than fc3d's limit");
            }
            release(o);
        }
    }
}

/// `solver_options_delete` walks the tree without recursion: a chain of 100000 internal solvers
/// is released from a thread with a 256 KiB stack (before: one stack frame per level).
#[test]
fn a_very_long_chain_is_released_from_a_small_stack() {
    let (root, count) = unsafe {
        let root = solver_options_create(500);
        let mut last = root;
        for _ in 0..100_000 {
            let next = calloc(1, std::mem::size_of::<SolverOptions>()) as *mut SolverOptions;
            give_slots(last, &[next]);
            last = next;
        }
        (root as usize, 100_000)
    };
    std::thread::Builder::new()
        .stack_size(256 << 10)
        .spawn(move || unsafe {
            let root = root as *mut SolverOptions;
            fc3d_clear_last_error();
            // Refused by the driver (too deep), then released.
            let mut p = Problem::new();
            assert_eq!(p.solve(root).0, FC3D_ERR_INVALID_OPTION);
            solver_options_delete(root);
            assert_eq!((*root).numberOfInternalSolvers, 0);
            free(root.cast());
        })
        .unwrap()
        .join()
        .unwrap();
    assert!(count > 0);
}

/// Counts without arrays, counts above the limit, and sizes that are negative, short or huge.
#[test]
fn inconsistent_counts_and_sizes_are_refused() {
    unsafe {
        // numberOfInternalSolvers huge with internalSolvers NULL (before: the driver took it for
        // "no internal solver" and solver_options_copy tried to allocate usize::MAX slots).
        for n in [1usize, 1000, usize::MAX] {
            let o = solver_options_create(500);
            let (saved_n, saved_a) = ((*o).numberOfInternalSolvers, (*o).internalSolvers);
            (*o).numberOfInternalSolvers = n;
            (*o).internalSolvers = null_mut();
            refused_everywhere(o, "internal");
            (*o).numberOfInternalSolvers = saved_n;
            (*o).internalSolvers = saved_a;
            release(o);
        }
        // More internal solvers than the limit: refused, and not walked by delete either.
        let o = solver_options_create(500);
        let many: Vec<_> = (0..=FC3D_OPTIONS_MAX_INTERNAL_SOLVERS)
            .map(|_| solver_options_create(565))
            .collect();
        give_slots(o, &many);
        refused_everywhere(o, "above fc3d's limit");
        fc3d_clear_last_error();
        solver_options_delete(o);
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_INVALID_OPTION);
        assert!(!(*o).iparam.is_null(), "a refused delete releases nothing");
        give_slots(o, &many[..1]); // releases the others
        release(o);
        // iSize / dSize.
        for size in [c_int::MIN, -1, 0, 5, 19, 1025, c_int::MAX] {
            for which in 0..2 {
                let o = solver_options_create(504);
                let saved = ((*o).iSize, (*o).dSize);
                if which == 0 {
                    (*o).iSize = size;
                } else {
                    (*o).dSize = size;
                }
                let mut p = Problem::new();
                let (rc, written) = p.solve(o);
                assert_eq!(rc, FC3D_ERR_INVALID_OPTION, "size {size}: {}", message());
                assert!(!written);
                assert!(message().contains("Size"), "{}", message());
                if !(0..=FC3D_OPTIONS_MAX_PARAM_SIZE).contains(&size) {
                    refused_everywhere(o, "Size");
                } else {
                    // A consistent short struct is copied as it is (and still refused by the
                    // driver).
                    let c = solver_options_copy(o);
                    assert!(!c.is_null(), "{}", message());
                    assert_eq!(p.solve(c).0, FC3D_ERR_INVALID_OPTION);
                    release(c);
                }
                ((*o).iSize, (*o).dSize) = saved;
                release(o);
            }
        }
        // A positive size with a NULL array.
        let o = solver_options_create(504);
        let saved = (*o).dparam;
        (*o).dparam = null_mut();
        refused_everywhere(o, "NULL");
        (*o).dparam = saved;
        release(o);
    }
}

/// An internal solver in two slots (a DAG, not a cycle) is solved, copied, and released once;
/// replacing one of its slots does not release it while the other slot holds it.
#[test]
fn shared_internal_solvers_are_released_once() {
    unsafe {
        let o = solver_options_create(500);
        let local = internal(o, 0);
        give_slots(o, &[local, local]);
        let mut p = Problem::new();
        assert_eq!(p.solve(o).0, 0, "{}", message());
        let c = solver_options_copy(o);
        assert!(!c.is_null());
        release(c);
        // Replace slot 0: `local` stays (slot 1 holds it).
        let fresh = solver_options_create(551);
        solver_options_set_internal_solver(o, 0, fresh);
        assert_eq!(internal(o, 1), local);
        assert_eq!((*local).solverId, 565, "slot 1 was released");
        solver_options_update_internal(o, 1, 552);
        assert_eq!((*internal(o, 1)).solverId, 552);
        assert_eq!(p.solve(o).0, 0, "{}", message());
        release(o);
        // Shared, then deleted: released once.
        let o = solver_options_create(500);
        let local = internal(o, 0);
        give_slots(o, &[local, local, local]);
        release(o);
    }
}

// ---------------------------------------------------------------------------------------------
// Callbacks.

#[repr(C)]
struct Env {
    options: *mut SolverOptions,
    action: c_int,
    calls: c_int,
}

unsafe extern "C" fn meddle(
    env: *mut c_void,
    _size: c_int,
    _r: *mut c_double,
    _u: *mut c_double,
    _error: c_double,
    _extra: *mut c_void,
) {
    let e = &mut *(env as *mut Env);
    e.calls += 1;
    let o = e.options;
    match e.action {
        // Release the options' arrays and internal solvers (before: the driver then wrote
        // iparam[1] through a NULL pointer, a segfault).
        1 => solver_options_delete(o),
        2 => *(*o).dparam = 1e-2,
        3 => *(*o).iparam.add(5) = 1,
        4 => solver_options_update_internal(o, 0, 552),
        // Reads only.
        _ => {
            let _ = *(*o).dparam;
        }
    }
}

/// A callback that frees or changes the options during the solve is refused (FC3D_ERR_INVALID_OPTION,
/// nothing written, the callback not called again), not a crash; one that only reads is fine.
#[test]
fn callbacks_that_free_or_change_the_options_are_refused() {
    unsafe {
        for action in 0..5 {
            let o = solver_options_create(500);
            *(*o).dparam = 1e-14;
            *(*o).iparam = 50;
            let mut env = Env {
                options: o,
                action,
                calls: 0,
            };
            let mut cb = Callback {
                env: (&mut env as *mut Env).cast(),
                collectStatsIteration: Some(meddle),
            };
            (*o).callback = &mut cb;
            // A problem that takes several sweeps.
            let mut p = Problem::new();
            p.w = vec![2.0, 0.5, 0.3, 0.5, 1.0, 0.2, 0.3, 0.2, 1.5];
            p.m.matrix0 = p.w.as_mut_ptr();
            let (rc, written) = p.solve(o);
            if action == 0 {
                assert!(rc >= 0, "{}", message());
                assert!(env.calls > 1);
            } else {
                assert_eq!(
                    rc,
                    FC3D_ERR_INVALID_OPTION,
                    "action {action}: {}",
                    message()
                );
                assert!(!written);
                assert!(
                    message().contains("changed during the solve"),
                    "{}",
                    message()
                );
                assert_eq!(env.calls, 1, "called again after it changed the options");
            }
            (*o).callback = null_mut();
            release(o);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Huge values.

/// "Huge = unlimited": a time budget of 1e300 s or +inf is no budget, INT_MAX iterations are
/// unlimited iterations (the budget or the tolerance stops the solver); a positive budget below
/// the clock's resolution (5e-324 s) is spent at once (info 2, or 0 when r is already a
/// solution), not rejected; negative counts and NaN budgets are rejected naming their slot.
#[test]
fn huge_values_mean_unlimited_and_the_rest_is_named() {
    unsafe {
        let mut p = Problem::new();
        for id in [
            500, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523,
        ] {
            for budget in [1e300, f64::INFINITY, f64::MAX] {
                let o = solver_options_create(id);
                *(*o).dparam.add(19) = budget;
                let (rc, _) = p.solve(o);
                assert!(
                    (0..=4).contains(&rc),
                    "{id} budget {budget}: {rc} {}",
                    message()
                );
                release(o);
            }
            let o = solver_options_create(id);
            *(*o).dparam.add(19) = 5e-324;
            let (rc, _) = p.solve(o);
            assert!(
                matches!(rc, 0 | 2),
                "{id} budget 5e-324: {rc} {}",
                message()
            );
            release(o);
            let o = solver_options_create(id);
            *(*o).iparam = c_int::MAX;
            *(*o).dparam.add(19) = 0.05;
            let (rc, _) = p.solve(o);
            assert!(
                (0..=4).contains(&rc),
                "{id} INT_MAX iterations: {rc} {}",
                message()
            );
            release(o);
            for (slot, value) in [(0usize, -1.0), (19, -1.0), (19, f64::NAN), (0, f64::NAN)] {
                let o = solver_options_create(id);
                *(*o).dparam.add(slot) = value;
                let (rc, _) = p.solve(o);
                assert_eq!(rc, FC3D_ERR_INVALID_OPTION, "{id} dparam[{slot}] = {value}");
                assert!(
                    message().contains(&format!("dparam[{slot}]")),
                    "{}",
                    message()
                );
                release(o);
            }
            let o = solver_options_create(id);
            *(*o).iparam = c_int::MIN;
            assert_eq!(p.solve(o).0, FC3D_ERR_INVALID_OPTION);
            assert!(message().contains("iparam[0]"), "{}", message());
            release(o);
        }
    }
}
