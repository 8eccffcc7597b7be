//! Siconos' direct solver entries of fc3d_Solvers.h (c/solver_entries.c): each gives
//! `fc3d_driver`'s answer for options of its id and refuses options of another id; the GAMS ids
//! and the Tresca sub-solvers end with `FC3D_ERR_UNSUPPORTED_SOLVER` and a message;
//! `fc3d_checkTrivialCase` and `fc3d_set_internalsolver_tolerance` on a shared problem.

use std::ffi::CString;

use fc3d_capi_tests::{capi_check_problem_copy, capi_check_solver_entries, data_dir};

#[test]
fn direct_solver_entries_behave_as_the_driver() {
    let dir = CString::new(data_dir().to_str().unwrap()).unwrap();
    assert_eq!(unsafe { capi_check_solver_entries(dir.as_ptr()) }, 0);
}

/// `frictionContact_copy` keeps the storage and its layout and shares nothing;
/// `frictionContact_rescaling` scales M and q as Siconos does (dense, sparse-block, sparse).
#[test]
fn problem_copy_and_rescaling() {
    let dir = CString::new(data_dir().to_str().unwrap()).unwrap();
    assert_eq!(unsafe { capi_check_problem_copy(dir.as_ptr()) }, 0);
}
