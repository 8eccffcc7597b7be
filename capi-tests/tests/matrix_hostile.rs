//! The C side of the matrix helpers' hardening (issue 13, item 4): c/matrix_hostile.c calls
//! NM_*, SBM_*, SBCM_* and fc3d_driver as a C host would, with structs whose counts disagree,
//! NULL blocks and index arrays pointing anywhere, over malloc'd arrays of the declared lengths.
//! scripts/test-all.sh runs the same checks under valgrind (ownership_main.c).

use fc3d_capi_tests::capi_check_hostile_matrices;

#[test]
fn hostile_matrices_from_c() {
    assert_eq!(unsafe { capi_check_hostile_matrices() }, 0);
}
