//! The global family through the C API as a C host uses it (`c/global_checks.c`): files, copies,
//! solves, velocities and reformulations of every shared global problem, the LMGC and rolling
//! drivers, and the rejections. scripts/test-all.sh runs the same checks under valgrind.

use std::ffi::CString;

use fc3d_capi_tests::*;

#[test]
fn global_api_checks() {
    if !data_dir().join("GFC3D_TwoRods1.dat").is_file() {
        eprintln!("../shared/data/siconos missing: skipped");
        return;
    }
    let scratch = std::env::temp_dir().join(format!("fc3d-global-checks-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let data = CString::new(data_dir().to_str().unwrap()).unwrap();
    let s = CString::new(scratch.to_str().unwrap()).unwrap();
    let rc = unsafe { capi_check_global(data.as_ptr(), s.as_ptr()) };
    let _ = std::fs::remove_dir_all(&scratch);
    assert_eq!(rc, 0);
}
