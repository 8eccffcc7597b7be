//! Rolling friction through the C API (`c/rolling_checks.c`): the API checks, and Siconos 4.4's
//! rolling problems (the data files of its source package, extracted by
//! scripts/siconos-suite.sh into target/siconos-src) solved by `rolling_fc3d_driver` at 1e-8
//! with NSGS (3000) and ADMM (3003),
//! the C result equal to the Rust API's and its error recomputed independently in C.

use std::ffi::CString;
use std::path::PathBuf;

use fc3d_capi_tests::*;
use fc3d_core::io::dat::{read_rolling_dat_file, RollingDatProblem};
use fc3d_core::{solve_rolling, AdmmOptions, RollingConfig, RollingMethod, RollingNsgsOptions};

#[test]
fn rolling_api_checks() {
    let scratch = std::env::temp_dir().join(format!("fc3d-rolling-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let s = CString::new(scratch.to_str().unwrap()).unwrap();
    assert_eq!(unsafe { capi_rolling_check_api(s.as_ptr()) }, 0);
    std::fs::remove_dir_all(&scratch).ok();
}

const FILES: &[&str] = &[
    "RFC3D_sphere_1.dat",
    "RFC3D_sphere_2.dat",
    "RFC3D_cube_1.dat",
    "rfc3d_sphere_from_grfc3d.dat",
    "rfc3d_sphere_from_grfc3d_dense.dat",
];

#[test]
fn siconos_rolling_files_through_the_driver() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../target/siconos-src/siconos-4.4.0/numerics/src/FrictionContact/test/data");
    if !dir.is_dir() {
        eprintln!("Siconos' sources not extracted (scripts/siconos-suite.sh): skipped");
        return;
    }
    let tolerance = 1e-8;
    for (file, id) in FILES.iter().flat_map(|f| [(f, 0), (f, 3003)]) {
        let path = dir.join(file);
        let RollingDatProblem::Spatial(p) = read_rolling_dat_file(&path).unwrap() else {
            panic!("{file}: 5D expected")
        };
        let n = p.size();
        let mut r_c = vec![0.0; n];
        let mut out = RollingResult::default();
        let cpath = CString::new(path.to_str().unwrap()).unwrap();
        let code = unsafe {
            capi_rolling_solve_file(
                cpath.as_ptr(),
                id,
                tolerance,
                100_000,
                r_c.as_mut_ptr(),
                n as i32,
                &mut out,
            )
        };
        assert_eq!(code, 0, "{file}");
        assert_eq!(out.info, 0, "{file}: {out:?}");
        assert!(out.reported_error <= tolerance, "{file}: {out:?}");
        assert_eq!(out.reported_error, out.api_error, "{file}");
        assert!(
            (out.independent_error - out.api_error).abs() <= 1e-12,
            "{file}: {out:?}"
        );
        let method = if id == 3003 {
            RollingMethod::Admm(AdmmOptions::default())
        } else {
            RollingMethod::Nsgs(RollingNsgsOptions::default())
        };
        let mut config = RollingConfig::new(method);
        config.tolerance = tolerance;
        config.max_iter = 100_000;
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let report = solve_rolling(&p, &config, &mut r, &mut u).unwrap();
        assert_eq!(r, r_c, "{file}: C and Rust reactions");
        assert_eq!(report.iterations as i32, out.iterations, "{file}");
        let name = if id == 3003 { "ADMM" } else { "NSGS" };
        println!(
            "{file} ({name}): {} iterations, error {:e}",
            out.iterations, out.reported_error
        );
    }
}
