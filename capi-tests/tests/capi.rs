//! The C checks of `c/capi_checks.c`, and the cross-check of C results against the Rust API on
//! every 3D problem of the shared Siconos collection, in the storage the file has and rebuilt as
//! dense, sparse-block and CSR.

use std::ffi::CString;
use std::os::raw::c_int;
use std::path::{Path, PathBuf};

use fc3d_capi_tests::*;
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::{solve, Delassus, FrictionProblem, LocalSolverKind, NsgsOptions, SolverConfig};

fn cstr(p: &Path) -> CString {
    CString::new(p.to_str().unwrap()).unwrap()
}

#[test]
fn options_names_and_defaults() {
    assert_eq!(unsafe { capi_check_options() }, 0);
}

#[test]
fn callback_sees_every_iteration() {
    assert_eq!(unsafe { capi_check_callback() }, 0);
}

#[test]
fn single_contacts_with_analytic_answers() {
    assert_eq!(unsafe { capi_check_single_contacts() }, 0);
}

#[test]
fn bad_input_is_rejected_with_codes_and_messages() {
    assert_eq!(
        unsafe { capi_check_bad_input(cstr(&data_dir()).as_ptr()) },
        0
    );
}

#[test]
fn nsgs_sweep_options_through_siconos_indices() {
    assert_eq!(
        unsafe { capi_check_nsgs_options(cstr(&data_dir()).as_ptr()) },
        0
    );
}

#[test]
fn ownership_paths() {
    let scratch = std::env::temp_dir().join(format!("fc3d-capi-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let rc = unsafe { capi_check_ownership(cstr(&data_dir()).as_ptr(), cstr(&scratch).as_ptr()) };
    let _ = std::fs::remove_dir_all(&scratch);
    assert_eq!(rc, 0);
}

/// The 3D local problems of the shared collection (global GFC3D files and 2D files excluded).
fn problems() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(data_dir())
        .expect("../shared/data/siconos")
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_str().unwrap();
            n.ends_with(".dat")
                && ![
                    "GFC3D_",
                    "gfc2d_",
                    "fc2d_",
                    "FC2D_",
                    "FrictionContactProblem",
                    "ACinputs",
                ]
                .iter()
                .any(|pre| n.starts_with(pre))
        })
        .collect();
    v.sort();
    v
}

/// Problems on which NSGS (ours and Siconos 4.4 alike) stalls above 1e-6 within 1e5 sweeps:
/// they are run with a short iteration budget and must report an honest failure.
const STALLING: [&str; 3] = [
    "BoxesStack1-i100000-32.hdf5.dat",
    "OneObject-i100000-316.hdf5.dat",
    "RockPile_tob1.dat",
];

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

fn rel_close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn shared_problems_through_the_c_api_in_all_storages() {
    let tol = 1e-6;
    let mut table = Vec::new();
    let files = problems();
    assert!(
        files.len() >= 30,
        "expected the 30 shared 3D problems, found {}",
        files.len()
    );
    for path in &files {
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let stalls = STALLING.contains(&name.as_str());
        let max_iter: c_int = if stalls { 300 } else { 100_000 };
        let problem = read_dat_file(path).unwrap();
        let n = problem.size();
        let mut first_r: Option<Vec<f64>> = None;
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
                capi_solve_file(
                    cstr(path).as_ptr(),
                    storage,
                    0,
                    tol,
                    max_iter,
                    r.as_mut_ptr(),
                    u.as_mut_ptr(),
                    n as c_int,
                    &mut res,
                )
            };
            assert_eq!(rc, 0, "{name}: C solve failed");
            // The C result is the Rust API's result on the same input.
            let rp = rust_problem(&problem, storage);
            let mut rr = vec![0.0; n];
            let mut ru = vec![0.0; n];
            let config = SolverConfig::new(NsgsOptions::with_local(LocalSolverKind::NewtonHybrid))
                .with_tolerance(tol)
                .with_max_iter(max_iter as usize);
            let report = solve(&rp, &config, &mut rr, &mut ru).unwrap();
            assert_eq!(
                r, rr,
                "{name} storage {storage}: C and Rust reactions differ"
            );
            assert_eq!(
                u, ru,
                "{name} storage {storage}: C and Rust velocities differ"
            );
            assert_eq!(
                res.iterations as usize, report.iterations,
                "{name}: iterations"
            );
            assert_eq!(
                res.reported_error, report.error,
                "{name}: dparam[1] differs from the Rust report"
            );
            // dparam[1] is an error actually measured on the returned (r, u).
            assert!(
                rel_close(res.reported_error, res.api_error, 1e-12),
                "{name}: dparam[1] {} vs fc3d_compute_error {}",
                res.reported_error,
                res.api_error
            );
            // Summation order differs in the plain-C product W r + q: allow rounding noise of the
            // normalised residual (1e-14 absolute) on top of 1e-9 relative.
            assert!(
                (res.reported_error - res.independent_error).abs()
                    <= 1e-9 * res.reported_error.max(res.independent_error) + 1e-14,
                "{name}: dparam[1] {} vs independent {}",
                res.reported_error,
                res.independent_error
            );
            assert!(
                r.iter().chain(u.iter()).all(|v| v.is_finite()),
                "{name}: non-finite output"
            );
            if stalls {
                assert_eq!(
                    res.info, 1,
                    "{name}: expected an honest failure at {tol} in {max_iter} sweeps"
                );
                assert!(res.reported_error > tol);
            } else {
                assert_eq!(
                    res.info, 0,
                    "{name} storage {storage}: not converged, error {}",
                    res.reported_error
                );
                assert!(res.reported_error <= tol);
            }
            // Every storage gives the same reactions (the sweep sees the same blocks).
            match &first_r {
                None => first_r = Some(r.clone()),
                Some(r0) => {
                    let scale = fc3d_core::math::linalg::norm(r0).max(1e-300);
                    let diff = r
                        .iter()
                        .zip(r0)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max);
                    assert!(
                        diff <= 1e-12 * scale,
                        "{name}: storage {storage} differs by {diff:e}"
                    );
                }
            }
            if storage == STORAGE_AS_FILE {
                table.push(format!(
                    "{name:40} nc={:4} info={} iter={:6} error={:.3e}",
                    problem.n_contacts(),
                    res.info,
                    res.iterations,
                    res.reported_error
                ));
            }
        }
    }
    println!("{}", table.join("\n"));
}

/// NSGS with each local solver added beside 550-553/557/565, selected with
/// `solver_options_update_internal`, gives through `fc3d_driver` exactly the Rust API's result, on
/// small problems in each storage.
#[test]
fn new_local_solvers_through_the_c_api_match_rust() {
    let tol = 1e-8;
    let max_iter: c_int = 2_000;
    for name in ["FC3D_Example1_SBM.dat", "Confeti-ex03-Fc3D-SBM.dat"] {
        let path = data_dir().join(name);
        let problem = read_dat_file(&path).unwrap();
        let n = problem.size();
        for id in [554, 555, 558, 561, 562, 564, 570, 571, 572] {
            let kind = LocalSolverKind::from_siconos_id(id).unwrap();
            for storage in [STORAGE_AS_FILE, STORAGE_DENSE, STORAGE_CSR] {
                let mut r = vec![0.0; n];
                let mut u = vec![0.0; n];
                let mut res = CSolveResult::default();
                let rc = unsafe {
                    capi_solve_file(
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
                assert_eq!(rc, 0, "{name}/{id}: C solve failed");
                let rp = rust_problem(&problem, storage);
                let (mut rr, mut ru) = (vec![0.0; n], vec![0.0; n]);
                let config = SolverConfig::new(NsgsOptions::with_local(kind))
                    .with_tolerance(tol)
                    .with_max_iter(max_iter as usize);
                let report = solve(&rp, &config, &mut rr, &mut ru).unwrap();
                assert_eq!(r, rr, "{name}/{id} storage {storage}: reactions differ");
                assert_eq!(u, ru, "{name}/{id} storage {storage}: velocities differ");
                assert_eq!(res.iterations as usize, report.iterations, "{name}/{id}");
                assert_eq!(res.reported_error, report.error, "{name}/{id}");
            }
        }
    }
}
