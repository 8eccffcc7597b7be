//! The C checks of `c/workspace_checks.c`: warm start by contact id through
//! `fc3d_workspace_driver` (appearing and vanishing contacts, equal to a cold `fc3d_driver`,
//! rejected input) and `fc3d_contact_diagnostics` on contacts with known status.

use fc3d_capi_tests::capi_check_workspace;

#[test]
fn workspace_and_diagnostics_from_c() {
    assert_eq!(unsafe { capi_check_workspace() }, 0);
}
