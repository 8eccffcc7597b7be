//! Nonsmooth Newton (504, 513, 520) and PROX (502, internal 504 or 500) through `fc3d_driver`
//! with Siconos' default options: analytic single contacts and rejected options in C, and shared
//! problems in dense, sparse-block and CSR storage cross-checked bit for bit with the Rust API.

use std::ffi::CString;
use std::os::raw::c_int;
use std::path::Path;

use fc3d_capi_tests::*;
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{
    solve, Delassus, FrictionProblem, NsgsOptions, NsnFormulation, NsnOptions, ProxInternal,
    ProxOptions, SolverConfig,
};

fn cstr(p: &Path) -> CString {
    CString::new(p.to_str().unwrap()).unwrap()
}

#[test]
fn newton_and_prox_single_contacts_and_rejected_options() {
    assert_eq!(unsafe { capi_check_newton_and_prox() }, 0);
}

/// The Rust configuration `fc3d_driver` must build from `solver_options_create(id)` (and
/// `update_internal(internal)`) with the tolerance and iterations set.
fn rust_config(id: c_int, internal: c_int, tol: f64, max_iter: usize) -> SolverConfig {
    let newton = |f| {
        SolverConfig::new(NsnOptions::new(f))
            .with_tolerance(tol)
            .with_max_iter(max_iter)
    };
    match id {
        504 => newton(NsnFormulation::AlartCurnier),
        513 => newton(NsnFormulation::FischerBurmeister),
        520 => newton(NsnFormulation::NaturalMap),
        502 => {
            let mut o = ProxOptions::default();
            if internal == 500 {
                o.internal = ProxInternal::Nsgs(NsgsOptions::default());
            }
            SolverConfig::new(o)
                .with_tolerance(tol)
                .with_max_iter(max_iter)
        }
        _ => unreachable!(),
    }
}

fn rust_problem(p: &FrictionProblem<'static>, storage: c_int) -> FrictionProblem<'static> {
    let w = match storage {
        STORAGE_AS_FILE => return p.clone(),
        STORAGE_CSR => Delassus::Sparse(p.w().to_csr()),
        STORAGE_SPARSE_BLOCK => Delassus::SparseBlock(p.w().to_block_sparse().unwrap()),
        _ => Delassus::Dense(p.w().to_dense()),
    };
    p.with_w(w).unwrap()
}

#[test]
fn shared_problems_through_fc3d_driver_match_the_rust_api() {
    let tol = 1e-8;
    let solvers: [(c_int, c_int); 5] = [(504, 0), (513, 0), (520, 0), (502, 0), (502, 500)];
    // (file, storage in the file, storages solved)
    let cases = [
        ("FC3D_Example1.dat", 0, [STORAGE_AS_FILE, STORAGE_CSR]),
        (
            "Confeti-ex13-Fc3D-SBM.dat",
            1,
            [STORAGE_AS_FILE, STORAGE_CSR],
        ),
        ("NESpheres_10_1.dat", 0, [STORAGE_AS_FILE, STORAGE_CSR]),
    ];
    for (name, file_storage, storages) in cases {
        let path = data_dir().join(name);
        let problem = read_dat_file(&path).unwrap();
        let n = problem.size();
        for (id, internal) in solvers {
            let max_iter: c_int = if id == 502 { 1000 } else { 200 };
            for storage in storages {
                let mut r = vec![0.0; n];
                let mut u = vec![0.0; n];
                let mut res = CSolveResult::default();
                let rc = unsafe {
                    capi_solve_file_with(
                        cstr(&path).as_ptr(),
                        storage,
                        id,
                        internal,
                        tol,
                        max_iter,
                        r.as_mut_ptr(),
                        u.as_mut_ptr(),
                        n as c_int,
                        &mut res,
                    )
                };
                assert_eq!(rc, 0, "{name} {id}/{internal}: C solve failed");
                let expected_storage = if storage == STORAGE_AS_FILE {
                    file_storage
                } else {
                    storage
                };
                assert_eq!(res.storage, expected_storage);
                assert_eq!(
                    res.info, 0,
                    "{name} {id}/{internal} storage {storage}: {res:?}"
                );
                assert!(res.reported_error <= tol);
                assert!(
                    (res.reported_error - res.independent_error).abs()
                        <= 1e-9 * res.reported_error.max(res.independent_error) + 1e-14,
                    "{name} {id}: dparam[1] {} vs independent {}",
                    res.reported_error,
                    res.independent_error
                );
                let rp = rust_problem(&problem, storage);
                let mut rr = vec![0.0; n];
                let mut ru = vec![0.0; n];
                let config = rust_config(id, internal, tol, max_iter as usize);
                let report = solve(&rp, &config, &mut rr, &mut ru).unwrap();
                assert_eq!(r, rr, "{name} {id}/{internal} storage {storage}: reactions");
                assert_eq!(
                    u, ru,
                    "{name} {id}/{internal} storage {storage}: velocities"
                );
                assert_eq!(res.iterations as usize, report.iterations);
                assert_eq!(res.reported_error, report.error);
            }
        }
    }
}

#[test]
fn siconos_default_iterations_of_nsn_nm_give_an_honest_failure() {
    // solver_options_create(520) asks for a single Newton step (Siconos 4.4's default):
    // fc3d_driver reports info = 1 with the error of that one step.
    let path = data_dir().join("Confeti-ex13-Fc3D-SBM.dat");
    let n = read_dat_file(&path).unwrap().size();
    let mut r = vec![0.0; n];
    let mut u = vec![0.0; n];
    let mut res = CSolveResult::default();
    let rc = unsafe {
        capi_solve_file_with(
            cstr(&path).as_ptr(),
            STORAGE_AS_FILE,
            520,
            0,
            1e-12,
            1,
            r.as_mut_ptr(),
            u.as_mut_ptr(),
            n as c_int,
            &mut res,
        )
    };
    assert_eq!(rc, 0);
    assert_eq!(res.info, 1);
    assert_eq!(res.iterations, 1);
    assert!(res.reported_error > 1e-12 && res.reported_error.is_finite());
    assert!(r.iter().chain(&u).all(|v| v.is_finite()));
}
