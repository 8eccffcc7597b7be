//! AUTO through the C ABI: `FC3D_AUTO` is found by name, `solver_options_create` gives usable
//! defaults, `fc3d_driver` solves with them, `dparam[1]` is the error `fc3d_compute_error`
//! measures on the returned reaction, and `iparam[FC3D_IPARAM_AUTO_STAGES]` decodes into the
//! stages taken; with tolerance 0 and a budget it is an anytime solve.

use std::ffi::CString;
use std::os::raw::c_int;

use fc3d::types::SolverOptions;
use fc3d::{FC3D_AUTO, FC3D_DPARAM_TIME_BUDGET, FC3D_IPARAM_AUTO_STAGES};

mod siconos_api;
use siconos_api::*;

fn shared(name: &str) -> CString {
    CString::new(format!(
        "{}/../../shared/data/siconos/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// Solves `name` with AUTO's defaults after `edit`; returns (info, dparam[1], the error
/// recomputed by fc3d_compute_error, iterations, stage code).
unsafe fn solve(name: &str, edit: impl Fn(*mut SolverOptions)) -> (c_int, f64, f64, c_int, c_int) {
    let path = shared(name);
    let p = frictionContact_new_from_filename(path.as_ptr());
    assert!(!p.is_null(), "{name}");
    let n = 3 * (*p).numberOfContacts as usize;
    let norm_q = std::slice::from_raw_parts((*p).q, n)
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    let o = solver_options_create(FC3D_AUTO);
    assert!(!o.is_null());
    edit(o);
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let info = fc3d_driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o);
    let reported = *(*o).dparam.add(1);
    let mut e = f64::NAN;
    let mut w = vec![0.0; n];
    fc3d_compute_error(p, r.as_mut_ptr(), w.as_mut_ptr(), 0.0, o, norm_q, &mut e);
    let out = (
        info,
        reported,
        e,
        *(*o).iparam.add(1),
        *(*o).iparam.add(FC3D_IPARAM_AUTO_STAGES as usize),
    );
    solver_options_delete(o);
    free(o.cast());
    frictionContactProblem_free(p);
    out
}

#[test]
fn auto_is_found_by_name_and_has_usable_defaults() {
    unsafe {
        let name = CString::new("FC3D_AUTO").unwrap();
        assert_eq!(solver_options_name_to_id(name.as_ptr()), FC3D_AUTO);
        let back = std::ffi::CStr::from_ptr(solver_options_id_to_name(FC3D_AUTO));
        assert_eq!(back.to_str().unwrap(), "FC3D_AUTO");
        let o = solver_options_create(FC3D_AUTO);
        assert!(!o.is_null());
        assert_eq!((*o).solverId, FC3D_AUTO);
        assert_eq!(*(*o).iparam, 10_000);
        assert_eq!(*(*o).dparam, 1e-4);
        assert_eq!(*(*o).dparam.add(FC3D_DPARAM_TIME_BUDGET as usize), 0.0);
        solver_options_delete(o);
        free(o.cast());
    }
}

#[test]
fn driver_solves_with_the_defaults_and_reports_true_error_and_stages() {
    for name in [
        "Rover1039.dat",
        "NESpheres_30_1.dat",
        "Capsules-i101-404.dat",
        "OneObject-i100000-316.hdf5.dat",
    ] {
        for tol in [1e-4, 1e-8] {
            let (info, reported, recomputed, iterations, code) = unsafe {
                solve(name, |o| {
                    *(*o).dparam = tol;
                    *(*o).dparam.add(FC3D_DPARAM_TIME_BUDGET as usize) = 20.0;
                })
            };
            assert_eq!(info, 0, "{name} {tol}: error {reported:e}");
            assert!(reported <= tol);
            assert_eq!(reported, recomputed, "{name} {tol}");
            assert!(iterations >= 1);
            assert!(code >= 1, "{name}: stage code {code}");
            // Every digit is a stage kind (1..=7).
            let mut c = code;
            while c > 0 {
                assert!((1..=7).contains(&(c % 10)), "{name}: stage code {code}");
                c /= 10;
            }
        }
    }
}

#[test]
fn anytime_solve_returns_the_best_iterate_with_its_true_error() {
    let (info, reported, recomputed, _, code) = unsafe {
        solve("RockPile_tob1.dat", |o| {
            *(*o).iparam = c_int::MAX;
            *(*o).dparam = 0.0;
            *(*o).dparam.add(FC3D_DPARAM_TIME_BUDGET as usize) = 0.02;
        })
    };
    assert_eq!(info, 2, "out of time");
    assert_eq!(reported, recomputed);
    assert!(reported.is_finite() && reported < 1.0);
    assert!(code >= 1);
}
