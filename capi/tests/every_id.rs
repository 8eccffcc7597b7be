//! Every solver id of the compat headers (Friction_cst.h's FRICTION_SOLVER, VI_cst.h,
//! SOCLCP_cst.h, ConvexQP_cst.h: Siconos 4.4's ids, checked against the installed headers by
//! `scripts/siconos-constants.sh`) through the C ABI: `solver_options_create` returns options
//! (Siconos' defaults) and the name tables agree; `fc3d_driver` with those options, unchanged,
//! either solves a one-contact problem or refuses the id with FC3D_ERR_UNSUPPORTED_SOLVER and a
//! message naming the id and the solver, writing nothing.

use std::ffi::CStr;
use std::os::raw::c_int;

use fc3d::types::{FrictionContactProblem, NumericsMatrix};
use fc3d::FC3D_ERR_UNSUPPORTED_SOLVER;

mod siconos_api;
use siconos_api::*;

/// The enumerators of `enum <name>` in a compat header, with their values.
fn enumerators(header: &str, name: &str) -> Vec<(String, c_int)> {
    let path = format!(
        "{}/include/siconos-compat/{header}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let start = text
        .find(&format!("enum {name}\n"))
        .unwrap_or_else(|| panic!("enum {name} in {header}"));
    let body = &text[start..start + text[start..].find("};").unwrap()];
    body.lines()
        .filter_map(|l| {
            let (n, v) = l.split_once('=')?;
            let v = v.trim().trim_end_matches(',').trim();
            Some((n.trim().to_string(), v.parse().ok()?))
        })
        .collect()
}

#[test]
fn every_id_is_created_and_then_solved_or_refused_by_name() {
    let mut ids = enumerators("Friction_cst.h", "FRICTION_SOLVER");
    // fc3d's own one-contact ids (568..599, which Siconos leaves free) are not Siconos'.
    ids.retain(|(_, id)| !(568..600).contains(id));
    assert_eq!(
        ids.len(),
        67,
        "Siconos 4.4's Friction_cst.h has 67 solver ids"
    );
    ids.extend(enumerators("VI_cst.h", "VI_SOLVER"));
    ids.extend(enumerators("SOCLCP_cst.h", "SOCLCP_SOLVER"));
    ids.extend(enumerators("ConvexQP_cst.h", "CONVEXQP_SOLVER"));

    // One contact, W = I, q = (-1, 0.5, 0), mu = 0.5.
    let mut w = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let mut q = [-1.0, 0.5, 0.0];
    let mut mu = [0.5];
    // SAFETY: an all-zero NumericsMatrix is a valid empty value.
    let mut m: NumericsMatrix = unsafe { std::mem::zeroed() };
    m.storageType = 0;
    m.size0 = 3;
    m.size1 = 3;
    m.matrix0 = w.as_mut_ptr();
    let mut problem = FrictionContactProblem {
        dimension: 3,
        numberOfContacts: 1,
        M: &mut m,
        q: q.as_mut_ptr(),
        mu: mu.as_mut_ptr(),
    };

    let (mut solved, mut refused, mut failures) = (Vec::new(), Vec::new(), Vec::new());
    for (symbol, id) in &ids {
        let id = *id;
        unsafe {
            let name = CStr::from_ptr(solver_options_id_to_name(id))
                .to_string_lossy()
                .into_owned();
            let o = solver_options_create(id);
            if o.is_null() {
                failures.push(format!(
                    "{symbol} = {id}: solver_options_create returned NULL"
                ));
                continue;
            }
            if (*o).solverId != id {
                failures.push(format!("{symbol}: solverId {}", (*o).solverId));
            }
            if name != "NONAME" {
                let back = solver_options_name_to_id(solver_options_id_to_name(id));
                // Siconos registers one name twice (600 and 5000): the first id wins.
                if back != id && !(id == 5000 && back == 600) {
                    failures.push(format!("{symbol}: name {name} maps back to {back}"));
                }
            }
            let (mut r, mut u) = ([0.0; 3], [-7.0; 3]);
            let rc = fc3d_driver(&mut problem, r.as_mut_ptr(), u.as_mut_ptr(), o);
            let message = CStr::from_ptr(fc3d_last_error_message())
                .to_string_lossy()
                .into_owned();
            if rc >= 0 {
                solved.push(id);
            } else if rc == FC3D_ERR_UNSUPPORTED_SOLVER {
                refused.push(id);
                if !message.contains(&format!("solver id {id} ({name})")) {
                    failures.push(format!("{symbol}: message {message:?} does not name it"));
                }
                if r != [0.0; 3] || u != [-7.0; 3] {
                    failures.push(format!("{symbol}: refused but wrote r or u"));
                }
            } else {
                failures.push(format!("{symbol} = {id}: code {rc}: {message}"));
            }
            solver_options_delete(o);
            free(o.cast());
        }
    }
    println!("solved: {solved:?}\nrefused: {refused:?}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The ids fc3d implements run; GAMS, global and rolling ids are refused.
    for id in [
        500, 502, 503, 504, 505, 506, 507, 511, 512, 513, 516, 517, 520, 522, 523,
    ] {
        assert!(solved.contains(&id), "{id} not solved");
    }
    for id in [514, 515, 518, 519, 600, 613, 615, 3000, 3003, 5000] {
        assert!(refused.contains(&id), "{id} not refused");
    }
}
