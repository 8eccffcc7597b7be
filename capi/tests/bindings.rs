//! The Fortran module names every solver of the native entry: for each solver the library lists
//! (`fc3d_solver_count` / `fc3d_solver_at`), `fortran/fc3d.f90` declares `FC3D_<NAME> = id`,
//! `<NAME>` being the header constant without `SICONOS_FRICTION_3D_` (and `ONECONTACT_`) or
//! fc3d's `FC3D_AUTO`. (Python builds `fc3d.SOLVERS` from the same list at import.)

use std::collections::BTreeMap;
use std::ffi::{c_char, CStr};

use fc3d::{fc3d_solver_at, fc3d_solver_count};

/// The library's solvers: (id, header constant).
fn listed() -> Vec<(i32, String)> {
    (0..fc3d_solver_count())
        .map(|i| {
            let mut constant: *const c_char = std::ptr::null();
            let id = unsafe { fc3d_solver_at(i, &mut constant, std::ptr::null_mut()) };
            assert!(id > 0, "fc3d_solver_at({i}) = {id}");
            let constant = unsafe { CStr::from_ptr(constant) }
                .to_str()
                .unwrap()
                .to_string();
            (id, constant)
        })
        .collect()
}

/// The binding's name of a header constant.
fn binding_name(constant: &str) -> String {
    let short = constant
        .strip_prefix("SICONOS_FRICTION_3D_")
        .or_else(|| constant.strip_prefix("FC3D_"))
        .unwrap_or(constant);
    let short = short.strip_prefix("ONECONTACT_").unwrap_or(short);
    format!("FC3D_{}", short.to_uppercase())
}

/// `integer(c_int), parameter, public :: NAME = VALUE` lines of the Fortran module.
fn fortran_constants() -> BTreeMap<String, i64> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fortran/fc3d.f90");
    let text = std::fs::read_to_string(&path).unwrap();
    text.lines()
        .filter_map(|line| {
            let rest = line
                .trim()
                .strip_prefix("integer(c_int), parameter, public ::")?;
            let (name, value) = rest.split_once('=')?;
            let value = value.split('!').next()?.trim().parse().ok()?;
            Some((name.trim().to_uppercase(), value))
        })
        .collect()
}

#[test]
fn the_fortran_module_names_every_solver_of_the_library() {
    let constants = fortran_constants();
    let solvers = listed();
    assert!(solvers.iter().any(|(id, _)| *id == 590), "AUTO is listed");
    for (id, constant) in &solvers {
        let name = binding_name(constant);
        assert_eq!(
            constants.get(&name),
            Some(&(*id as i64)),
            "fortran/fc3d.f90 must declare {name} = {id} (the library's {constant})"
        );
    }
}
