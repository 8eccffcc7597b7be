//! Every option slot at its extremes (issue 13, item 2): for every solver variant fc3d
//! implements, every `iparam`/`dparam` slot of the options and of their internal solvers (and of
//! the internal solvers' own internal solvers), set one at a time to every extreme value of
//! `OPTION_CASE_INTS` / `OPTION_CASE_DOUBLES` (INT_MIN, INT_MAX, -1, 0, NaN, +-inf, 1e308,
//! subnormals, ...). Each run goes through `fc3d_driver` as a C host calls it and must give a
//! clean solve (0..=4, finite r and u, `dparam[1]` = `fc3d_compute_error`) or a clean rejection
//! (a negative code other than FC3D_ERR_INTERNAL, a message naming the slot, nothing written):
//! `option_case_check` of `fuzz/fuzz_targets/options_case.rs`, the contract the `options` fuzz
//! target checks on random combinations.

#![allow(clippy::missing_safety_doc)]

include!("../../fuzz/fuzz_targets/options_case.rs");

use std::time::{Duration, Instant};

mod siconos_api;
use siconos_api::*;

/// A solver as a host sets it up: a top-level id and, where it has one, the id of internal
/// solver 0 (set with `solver_options_update_internal`, or by overwriting `solverId` for the
/// Tresca sub-problem solvers 566/567, which `solver_options_create` does not make).
#[derive(Clone, Copy, Debug)]
struct Variant {
    id: c_int,
    internal: Option<c_int>,
}

fn variants() -> Vec<Variant> {
    let mut v: Vec<Variant> = [
        500, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523, 590,
    ]
    .iter()
    .map(|&id| Variant { id, internal: None })
    .collect();
    for local in [
        550, 551, 552, 553, 554, 555, 557, 558, 561, 562, 564, 570, 571, 572,
    ] {
        v.push(Variant {
            id: 500,
            internal: Some(local),
        });
    }
    v.push(Variant {
        id: 502,
        internal: Some(500),
    });
    for id in [503, 522] {
        for i in [566, 567] {
            v.push(Variant {
                id,
                internal: Some(i),
            });
        }
    }
    v
}

unsafe fn options(v: Variant) -> *mut SolverOptions {
    let o = solver_options_create(v.id);
    assert!(!o.is_null(), "{v:?}");
    if let Some(i) = v.internal {
        if (*o).numberOfInternalSolvers == 0 {
            // PFP is created without an internal solver: give it one, as a host does.
            let slots =
                calloc(1, std::mem::size_of::<*mut SolverOptions>()) as *mut *mut SolverOptions;
            *slots = solver_options_create(500);
            free((*o).internalSolvers.cast());
            (*o).internalSolvers = slots;
            (*o).numberOfInternalSolvers = 1;
        }
        if matches!(i, 566 | 567) {
            (**(*o).internalSolvers).solverId = i;
        } else {
            solver_options_update_internal(o, 0, i);
        }
    }
    o
}

/// The budget of every run: short, so that iteration counts of INT_MAX end.
const BUDGET: f64 = 2e-3;

enum Slot {
    I(usize, c_int),
    D(usize, f64),
}

/// Runs `v` with one slot of the node at `depth` set; returns the code and the wall time.
unsafe fn run_one(
    problem: &mut OptionCaseProblem,
    v: Variant,
    depth: usize,
    slot: &Slot,
) -> Option<(c_int, Duration)> {
    let o = options(v);
    let node = option_case_node(o, depth);
    if node.is_null() {
        option_case_release(o);
        return None;
    }
    *(*o).dparam.add(19) = BUDGET;
    match *slot {
        Slot::I(k, x) => *(*node).iparam.add(k) = x,
        Slot::D(k, x) => *(*node).dparam.add(k) = x,
    }
    // The top-level budget itself is swept too: keep the sweep short with few iterations then.
    if depth == 0 && matches!(slot, Slot::D(19, _)) && *(*o).iparam > 50 {
        *(*o).iparam = 50;
    }
    let start = Instant::now();
    let rc = option_case_check(problem, o);
    let t = start.elapsed();
    option_case_release(o);
    Some((rc, t))
}

fn sweep(depths: std::ops::RangeInclusive<usize>, filter: impl Fn(&Variant) -> bool) {
    let mut problem = OptionCaseProblem::new(3, 7);
    let mut runs = 0;
    let mut slow = Vec::new();
    let mut codes = std::collections::BTreeMap::new();
    for v in variants().into_iter().filter(|v| filter(v)) {
        for depth in depths.clone() {
            let mut slots = Vec::new();
            for k in 0..20 {
                slots.extend(OPTION_CASE_INTS.iter().map(|&x| Slot::I(k, x)));
                slots.extend(OPTION_CASE_DOUBLES.iter().map(|&x| Slot::D(k, x)));
            }
            for s in &slots {
                let label = match s {
                    Slot::I(k, x) => format!("{v:?} depth {depth} iparam[{k}] = {x}"),
                    Slot::D(k, x) => format!("{v:?} depth {depth} dparam[{k}] = {x:e}"),
                };
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| unsafe {
                    run_one(&mut problem, v, depth, s)
                }));
                match r {
                    Ok(None) => break,
                    Ok(Some((rc, t))) => {
                        runs += 1;
                        *codes.entry(rc).or_insert(0usize) += 1;
                        if t > Duration::from_millis(500) {
                            slow.push(format!("{label}: {t:?}"));
                        }
                    }
                    Err(e) => {
                        let m = e
                            .downcast_ref::<String>()
                            .cloned()
                            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                            .unwrap_or_default();
                        panic!("{label}: {m}");
                    }
                }
            }
        }
    }
    eprintln!("{runs} runs, return codes {codes:?}");
    assert!(
        slow.is_empty(),
        "runs over the budget by far:\n{}",
        slow.join("\n")
    );
}

/// The top-level slots of every implemented solver id.
#[test]
fn top_level_slots_at_their_extremes() {
    sweep(0..=0, |v| v.internal.is_none());
}

/// The slots of internal solvers (NSGS's local solvers, PROX's NSN_AC or NSGS and its local
/// solver, TFP/PFP's sub-problem solvers).
#[test]
fn internal_solver_slots_at_their_extremes() {
    sweep(1..=2, |_| true);
}
