//! The VI / projection family (505, 506, 507, 508, 511, 512) and ADMM (523) through `fc3d_driver`:
//! analytic single contacts and rejected options in C, and shared problems in every storage,
//! cross-checked bit for bit against the Rust API with the same (Siconos default) options.

use std::ffi::CString;
use std::os::raw::c_int;
use std::path::Path;

use fc3d_capi_tests::*;
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{
    solve, AdmmInitialRho, AdmmOptions, Delassus, FrictionProblem, SolverConfig, ViOptions,
    ViSolver,
};

fn cstr(p: &Path) -> CString {
    CString::new(p.to_str().unwrap()).unwrap()
}

#[test]
fn single_contacts_with_analytic_answers() {
    assert_eq!(unsafe { capi_check_vi_admm_single_contacts() }, 0);
}

#[test]
fn unimplemented_options_are_rejected() {
    assert_eq!(unsafe { capi_check_vi_admm_options() }, 0);
}

fn rust_config(id: c_int, tol: f64, max_iter: usize) -> SolverConfig {
    match ViSolver::from_siconos_id(id) {
        Some(s) => SolverConfig::new(ViOptions::new(s)),
        // solver_options_create(523) is Siconos' default: the given rho (dparam[3] = 1).
        None => SolverConfig::new(AdmmOptions {
            initial_rho: AdmmInitialRho::Given,
            ..AdmmOptions::default()
        }),
    }
    .with_tolerance(tol)
    .with_max_iter(max_iter)
}

fn rust_problem(p: &FrictionProblem<'static>, storage: c_int) -> FrictionProblem<'static> {
    let w = match storage {
        STORAGE_AS_FILE => return p.clone(),
        STORAGE_DENSE => Delassus::Dense(p.w().to_dense()),
        STORAGE_SPARSE_BLOCK => Delassus::SparseBlock(p.w().to_block_sparse().unwrap()),
        STORAGE_CSR => Delassus::Sparse(p.w().to_csr()),
        _ => unreachable!(),
    };
    p.with_w(w).unwrap()
}

/// (problem, solver id, expected to converge at 1e-8 within max_iter).
const CASES: [(&str, c_int, bool); 16] = [
    ("NESpheres_10_1.dat", 505, true),
    ("NESpheres_10_1.dat", 506, true),
    ("NESpheres_10_1.dat", 507, true),
    ("NESpheres_10_1.dat", 511, true),
    ("NESpheres_10_1.dat", 512, true),
    ("NESpheres_10_1.dat", 523, true),
    ("Confeti-ex03-Fc3D-SBM.dat", 505, false),
    ("Confeti-ex03-Fc3D-SBM.dat", 506, true),
    ("Confeti-ex03-Fc3D-SBM.dat", 507, true),
    ("Confeti-ex03-Fc3D-SBM.dat", 508, false),
    ("Confeti-ex03-Fc3D-SBM.dat", 511, true),
    ("Confeti-ex03-Fc3D-SBM.dat", 512, true),
    // With Siconos' default (given rho = 1) ADMM stops at 3000 iterations with 6.33e-4, as
    // Siconos 4.4 does (info 1, 3000 iterations, 6.33186e-4).
    ("Confeti-ex03-Fc3D-SBM.dat", 523, false),
    ("Rover1040.dat", 506, true),
    ("Rover1040.dat", 523, true),
    ("OneObject-i1028-138.hdf5.dat", 511, false),
];

#[test]
fn shared_problems_in_every_storage_match_the_rust_api() {
    let tol = 1e-8;
    let max_iter: c_int = 3000;
    for (name, id, converges) in CASES {
        let path = data_dir().join(name);
        let problem = read_dat_file(&path).unwrap();
        let n = problem.size();
        for storage in [
            STORAGE_AS_FILE,
            STORAGE_DENSE,
            STORAGE_SPARSE_BLOCK,
            STORAGE_CSR,
        ] {
            let what = format!("{name} id {id} storage {storage}");
            let mut r = vec![0.0; n];
            let mut u = vec![0.0; n];
            let mut res = CSolveResult::default();
            let rc = unsafe {
                capi_solve_file_with_solver(
                    cstr(&path).as_ptr(),
                    storage,
                    id,
                    tol,
                    max_iter,
                    r.as_mut_ptr(),
                    u.as_mut_ptr(),
                    n as c_int,
                    &mut res,
                )
            };
            assert_eq!(rc, 0, "{what}: C solve failed");
            let rp = rust_problem(&problem, storage);
            let mut rr = vec![0.0; n];
            let mut ru = vec![0.0; n];
            let report = solve(
                &rp,
                &rust_config(id, tol, max_iter as usize),
                &mut rr,
                &mut ru,
            )
            .unwrap();
            assert_eq!(r, rr, "{what}: C and Rust reactions differ");
            assert_eq!(u, ru, "{what}: C and Rust velocities differ");
            assert_eq!(res.iterations as usize, report.iterations, "{what}");
            assert_eq!(res.reported_error, report.error, "{what}: dparam[1]");
            assert!(
                (res.reported_error - res.independent_error).abs()
                    <= 1e-9 * res.reported_error.max(res.independent_error) + 1e-14,
                "{what}: dparam[1] {} vs independent {}",
                res.reported_error,
                res.independent_error
            );
            assert!(r.iter().chain(&u).all(|v| v.is_finite()), "{what}");
            assert_eq!(
                res.info == 0,
                converges,
                "{what}: info {} error {:e}",
                res.info,
                res.reported_error
            );
            assert_eq!(res.info == 0, res.reported_error <= tol, "{what}");
        }
    }
}
