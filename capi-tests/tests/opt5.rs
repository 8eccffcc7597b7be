//! TFP (503), PFP (522), ACLMFP (516) and SOCLCP (517) through `fc3d_driver`: analytic single
//! contacts and option checks in C, and the C results cross-checked bit for bit against the Rust
//! API on shared problems in the file's storage and rebuilt as dense, sparse-block and CSR.

use std::ffi::CString;
use std::os::raw::c_int;

use fc3d_capi_tests::*;
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{
    solve, AclmOptions, Delassus, FrictionProblem, Method, PfpOptions, SoclcpOptions, SolveStatus,
    SolverConfig, TrescaInnerSolver, TrescaOptions,
};

#[test]
fn single_contacts_and_options_in_c() {
    assert_eq!(unsafe { opt5_check_single_contacts_and_options() }, 0);
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

/// The Rust configuration the C defaults of `id` (with `internal` renamed) stand for.
fn rust_config(id: c_int, internal: c_int, tol: f64, max_iter: usize) -> SolverConfig {
    let method: Method = match id {
        503 => TrescaOptions {
            inner: if internal == 0 {
                TrescaInnerSolver::GaussSeidel
            } else {
                TrescaInnerSolver::from_siconos_id(internal).unwrap()
            },
            ..Default::default()
        }
        .into(),
        522 => PfpOptions::default().into(),
        516 => AclmOptions::default().into(),
        517 => SoclcpOptions::default().into(),
        _ => unreachable!(),
    };
    SolverConfig::new(method)
        .with_tolerance(tol)
        .with_max_iter(max_iter)
}

#[test]
fn shared_problems_c_equals_rust_in_all_storages() {
    let tol = 1e-8;
    let max_iter = 1000;
    let cases: [(c_int, c_int); 6] = [
        (503, 0),
        (503, 566),
        (503, 567),
        (522, 0),
        (516, 0),
        (517, 0),
    ];
    for name in [
        "Rover1039.dat",
        "Confeti-ex03-Fc3D-SBM.dat",
        "NESpheres_10_1.dat",
    ] {
        let path = data_dir().join(name);
        let cpath = CString::new(path.to_str().unwrap()).unwrap();
        let problem = read_dat_file(&path).unwrap();
        let n = problem.size();
        for (id, internal) in cases {
            for storage in [
                STORAGE_AS_FILE,
                STORAGE_DENSE,
                STORAGE_SPARSE_BLOCK,
                STORAGE_CSR,
            ] {
                let mut r = vec![0.0; n];
                let mut u = vec![0.0; n];
                let mut res = CSolveResult::default();
                let rc = unsafe {
                    capi_solve_file_with(
                        cpath.as_ptr(),
                        storage,
                        id,
                        internal,
                        tol,
                        max_iter as c_int,
                        r.as_mut_ptr(),
                        u.as_mut_ptr(),
                        n as c_int,
                        &mut res,
                    )
                };
                assert_eq!(rc, 0, "{name} {id}/{internal}: C solve failed");
                let rp = rust_problem(&problem, storage);
                let mut rr = vec![0.0; n];
                let mut ru = vec![0.0; n];
                let report = solve(
                    &rp,
                    &rust_config(id, internal, tol, max_iter),
                    &mut rr,
                    &mut ru,
                )
                .unwrap();
                let what = format!("{name} {id}/{internal} storage {storage}");
                assert_eq!(r, rr, "{what}: C and Rust reactions differ");
                assert_eq!(u, ru, "{what}: C and Rust velocities differ");
                assert_eq!(res.iterations as usize, report.iterations, "{what}");
                assert_eq!(res.reported_error, report.error, "{what}: dparam[1]");
                assert_eq!(res.info, report.status.info_code(), "{what}: info");
                assert!(r.iter().chain(&u).all(|v| v.is_finite()), "{what}");
                // dparam[1] is the Coulomb error measured on the returned (r, u).
                assert!(
                    (res.reported_error - res.api_error).abs() <= 1e-12 * res.api_error + 1e-15,
                    "{what}: dparam[1] {} vs fc3d_compute_error {}",
                    res.reported_error,
                    res.api_error
                );
                assert!(
                    (res.reported_error - res.independent_error).abs()
                        <= 1e-9 * res.reported_error + 1e-14,
                    "{what}: dparam[1] {} vs independent {}",
                    res.reported_error,
                    res.independent_error
                );
                if id == 517 {
                    assert_eq!(report.status, SolveStatus::RelaxationNotCoulomb, "{what}");
                    assert!(res.reported_error > tol);
                } else {
                    assert_eq!(res.info, 0, "{what}: error {}", res.reported_error);
                    assert!(res.reported_error <= tol);
                }
            }
        }
    }
}
