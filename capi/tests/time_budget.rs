//! The time budget through `fc3d_driver` is a hard limit (hardening issue, item 1): every solver
//! id, NSGS with every local solver, with `INT_MAX` in every iteration slot (the solver's, its
//! internal solver's, line-search trials and hybrid rounds), a tolerance of 0 and a 50 ms budget
//! on RockPile_tob1 (463 contacts, never solved in that time) returns within the budget plus one
//! sweep or Newton step (asserted with a margin for a loaded machine) with info 2 (or 3/4 where
//! the run ends so), and `dparam[1]` equal to `fc3d_compute_error` of the returned reaction.

use std::ffi::CString;
use std::os::raw::c_int;
use std::time::{Duration, Instant};

use fc3d::types::SolverOptions;

mod siconos_api;
use siconos_api::*;

const BUDGET: f64 = 0.05;

/// Sets `INT_MAX` in every iteration-count slot fc3d reads for `o` (and 0 in its tolerance).
unsafe fn largest_limits(o: *mut SolverOptions) {
    let o = &mut *o;
    *o.iparam = c_int::MAX;
    *o.dparam = 0.0;
    match o.solverId {
        // Nonsmooth Newton: line-search trials.
        504 | 513 | 520 => *o.iparam.add(12) = c_int::MAX,
        // VI family with a self-adaptive step: trials per iteration.
        506 | 507 | 512 => *o.iparam.add(9) = c_int::MAX,
        // Local Newton solvers: line-search trials, hybrid rounds and their projections.
        550 | 551 | 565 => {
            *o.iparam.add(12) = c_int::MAX;
            *o.iparam.add(15) = c_int::MAX;
            *o.iparam.add(16) = c_int::MAX;
        }
        _ => {}
    }
    for k in 0..o.numberOfInternalSolvers {
        let i = *o.internalSolvers.add(k);
        if !i.is_null() {
            largest_limits(i);
        }
    }
}

#[test]
fn every_solver_id_keeps_a_50_ms_budget_with_int_max_limits() {
    let path = CString::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos/RockPile_tob1.dat"
    ))
    .unwrap();
    let mut variants: Vec<(c_int, Option<c_int>)> = [
        500, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523, 590,
    ]
    .iter()
    .map(|&id| (id, None))
    .collect();
    variants.extend(
        [
            550, 551, 552, 553, 554, 555, 557, 558, 561, 562, 564, 565, 570, 571, 572,
        ]
        .iter()
        .map(|&l| (500, Some(l))),
    );
    // PROX with NSGS inside, TFP with its other sub-problem solvers.
    variants.extend([(502, Some(500)), (503, Some(566)), (503, Some(567))]);
    unsafe {
        let p = frictionContact_new_from_filename(path.as_ptr());
        assert!(!p.is_null());
        let n = 3 * (*p).numberOfContacts as usize;
        let norm_q = std::slice::from_raw_parts((*p).q, n)
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt();
        let mut slowest = (String::new(), Duration::ZERO);
        for (id, internal) in variants {
            let label = match internal {
                Some(i) => format!("{id}/{i}"),
                None => id.to_string(),
            };
            let o = solver_options_create(id);
            assert!(!o.is_null(), "{label}");
            if let Some(i) = internal {
                solver_options_update_internal(o, 0, i);
                if (**(*o).internalSolvers).solverId != i {
                    (**(*o).internalSolvers).solverId = i;
                }
            }
            largest_limits(o);
            *(*o).dparam.add(fc3d::FC3D_DPARAM_TIME_BUDGET as usize) = BUDGET;
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let start = Instant::now();
            let info = fc3d_driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o);
            let elapsed = start.elapsed();
            let reported = *(*o).dparam.add(1);
            eprintln!(
                "{label:>8}: info {info}, {:>7.1} ms, {} iterations, error {reported:.2e}",
                elapsed.as_secs_f64() * 1e3,
                *(*o).iparam.add(1)
            );
            assert!(
                elapsed <= Duration::from_secs_f64(BUDGET) + Duration::from_millis(250),
                "{label}: {elapsed:?} on a {BUDGET} s budget"
            );
            assert!((2..=4).contains(&info), "{label}: info {info}");
            let mut e = 0.0;
            let mut w = vec![0.0; n];
            fc3d_compute_error(p, r.as_mut_ptr(), w.as_mut_ptr(), 0.0, o, norm_q, &mut e);
            assert_eq!(
                e, reported,
                "{label}: dparam[1] is not the returned reaction's error"
            );
            assert!(r.iter().chain(&u).all(|v| v.is_finite()), "{label}");
            if elapsed > slowest.1 {
                slowest = (label, elapsed);
            }
            solver_options_delete(o);
            free(o.cast());
        }
        eprintln!("slowest return: {} after {:?}", slowest.0, slowest.1);
        frictionContactProblem_free(p);
    }
}

extern "C" {
    fn fc2d_driver(
        problem: *mut fc3d::types::FrictionContactProblem,
        reaction: *mut f64,
        velocity: *mut f64,
        options: *mut SolverOptions,
    ) -> c_int;
}

/// `fc2d_driver` with enumeration (405) on the 667-contact granular flow (an LCP of 2001
/// unknowns, a dense 2001x2001 solve per case): with Siconos' defaults (no iteration limit, no
/// budget) it is refused at once, nothing written; `iparam[0]` = 1 stops it after one case
/// (info 1, `iparam[1]` = 1); a 50 ms budget stops it within its first case (info 2).
#[test]
fn fc2d_enumeration_holds_its_limits_on_667_contacts() {
    let path = CString::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/data/siconos/fc2d_granularflowonwall_00667_00000.dat"
    ))
    .unwrap();
    unsafe {
        let p = frictionContact_new_from_filename(path.as_ptr());
        assert!(!p.is_null());
        let n = 2 * (*p).numberOfContacts as usize;
        for (max_iter, budget, expected) in [
            (0, 0.0, fc3d::FC3D_ERR_INVALID_OPTION),
            (1, 0.0, 1),
            (0, BUDGET, 2),
        ] {
            let o = solver_options_create(405);
            *(*o).iparam = max_iter;
            *(*o).dparam.add(fc3d::FC3D_DPARAM_TIME_BUDGET as usize) = budget;
            let (mut r, mut u) = (vec![7.0; n], vec![7.0; n]);
            let start = Instant::now();
            let info = fc2d_driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o);
            let elapsed = start.elapsed();
            eprintln!("405, iparam[0] {max_iter}, budget {budget}: info {info} in {elapsed:?}");
            assert_eq!(info, expected);
            if info < 0 {
                assert!(r.iter().chain(&u).all(|&v| v == 7.0), "written on failure");
            } else {
                let cases = *(*o).iparam.add(1);
                assert!(cases <= 1 && (max_iter == 0 || cases == 1), "{cases} cases");
                assert!(r.iter().all(|&v| v == 0.0));
                assert!(elapsed < Duration::from_secs(10));
            }
            if budget > 0.0 {
                assert!(elapsed <= Duration::from_secs_f64(budget) + Duration::from_millis(250));
            }
            solver_options_delete(o);
            free(o.cast());
        }
        frictionContactProblem_free(p);
    }
}
