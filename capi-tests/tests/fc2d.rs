//! 2D friction through the C API (`c/fc2d_checks.c`): the API checks, and every 2D problem of
//! the shared Siconos collection solved by `fc2d_driver` with each 2D id, the C result equal to
//! the Rust API's, its error recomputed independently in C, and every case that the installed
//! Siconos 4.4 solves (table below) solved.

use std::ffi::CString;
use std::os::raw::c_int;

use fc3d_capi_tests::*;
use fc3d_core::io::dat::{read_dat_file_any, DatProblem};
use fc3d_core::{solve_planar, PlanarConfig, PlanarMethod, PlanarNsgsOptions};

#[test]
fn fc2d_api_checks() {
    assert_eq!(unsafe { capi_fc2d_check_api() }, 0);
}

#[test]
fn fc2d_storages_give_the_same_reaction() {
    for file in [
        "FrictionContactProblem00071.dat",
        "FrictionContactProblem00727.dat",
        "FC2D_SliderCrankLagrangian00000.dat",
    ] {
        let path = CString::new(data_dir().join(file).to_str().unwrap()).unwrap();
        assert_eq!(
            unsafe { capi_fc2d_check_storages(path.as_ptr()) },
            0,
            "{file}"
        );
    }
}

/// Siconos 4.4 (`fc2d_driver` of the installed libsiconos-numerics, tolerance 1e-5, 10000
/// iterations, from r = 0): (file, id, info, iterations). Siconos aborts on the sparse-storage
/// `fc2d_granularflowonwall_*` files (its fc2d_driver handles dense and sparse-block W only) and
/// its enumeration is only run on the slider-crank files (the others have 2^84 cases and more).
/// Siconos' Lemke reports info 0 whatever its error (it compares the error with iparam[0]): on
/// SliderCrank00001 its error is 1.08e-5, above the tolerance.
const SICONOS: &[(&str, c_int, c_int, c_int)] = &[
    ("FC2D_SliderCrankLagrangian00000.dat", 400, 0, 218),
    ("FC2D_SliderCrankLagrangian00000.dat", 402, 0, 44),
    ("FC2D_SliderCrankLagrangian00000.dat", 404, 0, 6),
    ("FC2D_SliderCrankLagrangian00000.dat", 405, 0, 0),
    ("FC2D_SliderCrankLagrangian00001.dat", 400, 0, 225),
    ("FC2D_SliderCrankLagrangian00001.dat", 402, 0, 29),
    ("FC2D_SliderCrankLagrangian00001.dat", 404, 0, 8),
    ("FC2D_SliderCrankLagrangian00001.dat", 405, 0, 0),
    ("FrictionContactProblem00031.dat", 400, 0, 2),
    ("FrictionContactProblem00031.dat", 402, 0, 2),
    ("FrictionContactProblem00031.dat", 404, 0, 16),
    ("FrictionContactProblem00071.dat", 400, 0, 35),
    ("FrictionContactProblem00071.dat", 402, 0, 40),
    ("FrictionContactProblem00071.dat", 404, 0, 134),
    ("FrictionContactProblem00237.dat", 400, 0, 183),
    ("FrictionContactProblem00237.dat", 402, 0, 154),
    ("FrictionContactProblem00237.dat", 404, 0, 650),
    ("FrictionContactProblem00374.dat", 400, 0, 1),
    ("FrictionContactProblem00374.dat", 402, 0, 5),
    ("FrictionContactProblem00374.dat", 404, 0, 20),
    ("FrictionContactProblem00394.dat", 400, 0, 1),
    ("FrictionContactProblem00394.dat", 402, 0, 7),
    ("FrictionContactProblem00394.dat", 404, 0, 11),
    ("FrictionContactProblem00727.dat", 400, 0, 314),
    ("FrictionContactProblem00727.dat", 402, 0, 602),
    ("FrictionContactProblem00727.dat", 404, 0, 678),
];

fn rust_method(id: c_int) -> PlanarMethod {
    match id {
        400 => PlanarMethod::Nsgs(PlanarNsgsOptions::default()),
        402 => PlanarMethod::Cpg,
        404 => PlanarMethod::Lemke,
        _ => PlanarMethod::Enumeration { seed: 0 },
    }
}

#[test]
fn shared_2d_problems_through_fc2d_driver() {
    let tolerance = 1e-5;
    let max_iter = 10000;
    let mut cases = SICONOS.to_vec();
    // Beyond Siconos: the sparse-storage granular flows with NSGS and CPG, and the 6-contact
    // problem by enumeration (2^18 cases).
    cases.push(("fc2d_granularflowonwall_00667_00000.dat", 400, 0, 0));
    cases.push(("fc2d_granularflowonwall_00667_00000.dat", 402, 0, 0));
    cases.push(("fc2d_granularflowonwall_02020_00213.dat", 400, 0, 0));
    cases.push(("FrictionContactProblem00394.dat", 405, 0, 0));
    for (file, id, siconos_info, _) in cases {
        // Enumeration counts cases in iparam[0] (Siconos' enumeration ignores it): 0, every
        // case, as Siconos enumerates them.
        let max_iter = if id == 405 { 0 } else { max_iter };
        let path = data_dir().join(file);
        let c_path = CString::new(path.to_str().unwrap()).unwrap();
        let mut r = vec![0.0; 2 * 2020];
        let mut result = Fc2dResult::default();
        let rc = unsafe {
            capi_fc2d_solve_file(
                c_path.as_ptr(),
                id,
                tolerance,
                max_iter,
                r.as_mut_ptr(),
                r.len() as c_int,
                &mut result,
            )
        };
        assert_eq!(rc, 0, "{file} {id}");
        println!(
            "{file} {id}: info {} in {} iterations, error {:.3e} (independent {:.3e})",
            result.info, result.iterations, result.reported_error, result.independent_error
        );
        if siconos_info == 0 {
            assert_eq!(
                result.info, 0,
                "{file} {id}: Siconos solves it, fc3d does not"
            );
        }
        assert!(result.reported_error <= tolerance);
        let independent = result.independent_error;
        assert!(
            (independent - result.reported_error).abs() <= 1e-9 * (1e-300 + independent.max(1e-6)),
            "{file} {id}: reported {:e}, independent {independent:e}",
            result.reported_error
        );

        // The Rust API gives the same reaction.
        let DatProblem::Planar(p) = read_dat_file_any(&path).unwrap() else {
            panic!("{file} is not 2D")
        };
        let mut config = PlanarConfig::new(rust_method(id));
        config.tolerance = tolerance;
        config.max_iter = max_iter as usize;
        let n = p.size();
        let (mut rr, mut uu) = (vec![0.0; n], vec![0.0; n]);
        let report = solve_planar(&p, &config, &mut rr, &mut uu).unwrap();
        assert_eq!(report.error, result.reported_error, "{file} {id}");
        assert_eq!(&rr[..], &r[..n], "{file} {id}: C and Rust reactions differ");
    }
}
