//! `fc3d_driver_in_place`: the same answer as `fc3d_driver`, bit for bit, without the copies of
//! the host's arrays; and nothing written on failure, as `fc3d_driver`: a NaN in the host's W,
//! arrays that overlap, a solver that may fail once started (run on copies) and a callback.

#![cfg(feature = "siconos-abi")]

use std::ffi::CString;
use std::os::raw::{c_double, c_int};
use std::path::{Path, PathBuf};

use fc3d::types::{FrictionContactProblem, SolverOptions};
use fc3d::{FC3D_ERR_INVALID_STORAGE, FC3D_ERR_NON_FINITE};

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn fc3d_driver_in_place(
        p: *mut FrictionContactProblem,
        r: *mut c_double,
        u: *mut c_double,
        o: *mut SolverOptions,
    ) -> c_int;
}

type Driver = unsafe extern "C" fn(
    *mut FrictionContactProblem,
    *mut c_double,
    *mut c_double,
    *mut SolverOptions,
) -> c_int;

fn read(name: &str) -> *mut FrictionContactProblem {
    let path: PathBuf = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/siconos")
        .join(name);
    let c = CString::new(path.to_str().unwrap()).unwrap();
    let p = unsafe { frictionContact_new_from_filename(c.as_ptr()) };
    assert!(!p.is_null(), "{name}");
    p
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// What a call returned: the code, r, u, iterations and error (bits).
#[derive(Debug, PartialEq)]
struct Call {
    code: c_int,
    r: Vec<u64>,
    u: Vec<u64>,
    iterations: c_int,
    error: u64,
}

/// Runs `driver` with solver `id` (`tune` sets its options) from r = `r0`, u = 7.
unsafe fn call(
    driver: Driver,
    p: *mut FrictionContactProblem,
    id: c_int,
    tune: impl Fn(&mut SolverOptions),
    r0: f64,
) -> Call {
    let n = 3 * (*p).numberOfContacts as usize;
    let (mut r, mut u) = (vec![r0; n], vec![7.0; n]);
    let o = solver_options_create(id);
    tune(&mut *o);
    let code = driver(p, r.as_mut_ptr(), u.as_mut_ptr(), o);
    let out = Call {
        code,
        r: bits(&r),
        u: bits(&u),
        iterations: *(*o).iparam.add(1),
        error: (*(*o).dparam.add(1)).to_bits(),
    };
    solver_options_delete(o);
    free(o.cast());
    out
}

/// The calling thread's last error message.
fn last_error() -> String {
    unsafe { std::ffi::CStr::from_ptr(fc3d_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

fn limit(iterations: c_int, tol: f64) -> impl Fn(&mut SolverOptions) {
    move |o: &mut SolverOptions| unsafe {
        *o.iparam = iterations;
        *o.dparam = tol;
    }
}

#[test]
fn in_place_equals_the_driver_bit_for_bit() {
    for name in [
        "Capsules-i101-404.dat",
        "Confeti-ex13-Fc3D-SBM.dat",
        "FC3D_Example1_SBM.dat",
    ] {
        let p = read(name);
        unsafe {
            // NSGS (in place): converged, and stopped at its iteration limit; then the Newton
            // solver, which runs on copies.
            for (id, iterations, tol) in [(500, 10_000, 1e-6), (500, 3, 1e-12), (504, 50, 1e-8)] {
                for r0 in [0.0, 0.25] {
                    let a = call(fc3d_driver, p, id, limit(iterations, tol), r0);
                    let b = call(fc3d_driver_in_place, p, id, limit(iterations, tol), r0);
                    assert!(a.code >= 0, "{name} {id}: {}", a.code);
                    assert_eq!(
                        a, b,
                        "{name}: solver {id}, {iterations} iterations, r0 {r0}"
                    );
                }
            }
            frictionContactProblem_free(p);
        }
    }
}

#[test]
fn nothing_is_written_on_failure() {
    let p = read("Capsules-i100-889.dat");
    unsafe {
        let n = 3 * (*p).numberOfContacts as usize;
        // A NaN in one block of the host's W: refused before r or u is touched (fc3d_driver
        // finds it after the run, on its copies).
        let sbm = &*(*(*p).M).matrix1;
        let block = *sbm.block.add(sbm.nbblocks as usize / 2);
        let kept = *block.add(4);
        *block.add(4) = f64::NAN;
        for driver in [fc3d_driver as Driver, fc3d_driver_in_place] {
            let c = call(driver, p, 500, limit(100, 1e-6), 0.5);
            assert_eq!(c.code, FC3D_ERR_NON_FINITE);
            assert_eq!(c.r, bits(&vec![0.5; n]));
            assert_eq!(c.u, bits(&vec![7.0; n]));
        }
        let sequential = last_error();
        // The coloured sweep checks W on its threads: the same block named, nothing written.
        for threads in 1..=3 {
            let coloured = move |o: &mut SolverOptions| {
                limit(100, 1e-6)(o);
                *o.iparam.add(15) = 1; // FC3D_IPARAM_NSGS_DECOMPOSITION: FC3D_NSGS_COLOURED
                *o.iparam.add(16) = threads; // FC3D_IPARAM_NSGS_THREADS
            };
            let c = call(fc3d_driver_in_place, p, 500, coloured, 0.5);
            assert_eq!(c.code, FC3D_ERR_NON_FINITE, "{threads} threads");
            assert_eq!(c.r, bits(&vec![0.5; n]));
            assert_eq!(c.u, bits(&vec![7.0; n]));
            assert_eq!(last_error(), sequential, "{threads} threads");
        }
        assert!(sequential.contains("block"), "{sequential}");
        *block.add(4) = kept;

        // reaction and velocity overlapping: refused, nothing written.
        let mut both = vec![0.5; n + 3];
        let o = solver_options_create(500);
        let code = fc3d_driver_in_place(p, both.as_mut_ptr(), both.as_mut_ptr().add(3), o);
        assert_eq!(code, FC3D_ERR_INVALID_STORAGE);
        assert_eq!(bits(&both), bits(&vec![0.5; n + 3]));
        // velocity over q: refused too.
        let mut r = vec![0.5; n];
        let q_before = bits(std::slice::from_raw_parts((*p).q, n));
        let code = fc3d_driver_in_place(p, r.as_mut_ptr(), (*p).q, o);
        assert_eq!(code, FC3D_ERR_INVALID_STORAGE);
        assert_eq!(bits(&r), bits(&vec![0.5; n]));
        assert_eq!(bits(std::slice::from_raw_parts((*p).q, n)), q_before);
        solver_options_delete(o);
        free(o.cast());
        frictionContactProblem_free(p);
    }
}
