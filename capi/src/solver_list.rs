//! The solvers of the native entry, listed for bindings that name them: every id
//! `fc3d_settings_new` accepts for the local solves (`fc3d_solve_*`), with the constant that
//! names it in the C headers and Siconos' name string. (The global ids 600-615 and 5000 it also
//! accepts, for `fc3d_solve_global_*`, are not listed: the bindings name them apart,
//! `fc3d.GLOBAL_SOLVERS` and `FC3D_GFC3D_*`.) Python builds `fc3d.SOLVERS` from this list at import, and a test checks the
//! Fortran module's constants against it, so neither binding keeps a list of its own that could
//! drift from the library.

use std::ffi::{c_char, CStr, CString};
use std::os::raw::c_int;
use std::sync::OnceLock;

use crate::alloc::c_free;
use crate::names::{named_ids, solver_constant, solver_name};
use crate::option_tree::delete_contents;
use crate::options::create_options;
use crate::params::config_from_c;
use crate::{ffi_guard, CError, FC3D_ERR_INVALID_SIZE};

/// AUTO, fc3d's solver that chooses (in 568..=599, a range Siconos 4.4 leaves free; named
/// "FC3D_AUTO" by `solver_options_id_to_name`): from cheap features of the problem, the
/// tolerance and the budget it picks a plan of stages (NSGS, NSN-AC, PROX, ADMM, TFP, EG) and
/// switches stage when the error stalls, each stage going on from the best iterate. iparam[0]
/// counts the iterations of all stages, `dparam[FC3D_DPARAM_TIME_BUDGET]` is one budget for all
/// of them; a tolerance of 0 with a budget is an anytime solve (the best iterate reached, with
/// its true error in dparam[1]). The stages taken are written to
/// `iparam[FC3D_IPARAM_AUTO_STAGES]`.
pub const FC3D_AUTO: c_int = 590;

/// One solver of the native entry.
struct NativeSolver {
    id: c_int,
    /// The header constant (`SICONOS_FRICTION_3D_NSGS`, `FC3D_AUTO`), NUL-terminated.
    constant: CString,
    /// Siconos' name string (`FC3D_NSGS`).
    name: &'static CStr,
}

/// Every named id that `fc3d_settings_new` accepts, in increasing order (worked out once).
fn native_solvers() -> &'static [NativeSolver] {
    static LIST: OnceLock<Vec<NativeSolver>> = OnceLock::new();
    LIST.get_or_init(|| {
        named_ids()
            .into_iter()
            .filter(|&id| accepted_by_native_entry(id))
            .filter_map(|id| {
                Some(NativeSolver {
                    id,
                    constant: CString::new(solver_constant(id)?).ok()?,
                    name: solver_name(id),
                })
            })
            .collect()
    })
}

/// What `fc3d_settings_new` decides for `id`, without touching the caller's last error.
fn accepted_by_native_entry(id: c_int) -> bool {
    let Ok(options) = create_options(id) else {
        return false;
    };
    // SAFETY: create_options returned a complete options tree, released here once.
    unsafe {
        let accepted = config_from_c(&*options).is_ok();
        delete_contents(options);
        c_free(options);
        accepted
    }
}

/// The number of solvers `fc3d_settings_new` accepts for the local solves: every top-level 3D
/// solver of the native entry, AUTO included (list them with `fc3d_solver_at`; the global ids
/// 600-615 are not listed).
#[no_mangle]
pub extern "C" fn fc3d_solver_count() -> c_int {
    ffi_guard(
        "fc3d_solver_count",
        |code| code,
        || Ok(native_solvers().len() as c_int),
    )
}

/// The solver at `index` (0 <= index < `fc3d_solver_count()`, in increasing id order): returns
/// its Siconos id, and stores in `*constant` the name of the constant that names it in the
/// headers (`"SICONOS_FRICTION_3D_NSGS"`, `"SICONOS_FRICTION_3D_ONECONTACT_QUARTIC"`,
/// `"FC3D_AUTO"`) and in `*name` Siconos' name of the solver (`solver_options_id_to_name`:
/// `"FC3D_NSGS"`, `"FC3D_DeSaxceFixedPoint"`, `"FC3D_AUTO"`); both strings are static (do not
/// free). `constant` and `name` may be NULL. An index out of range returns
/// `FC3D_ERR_INVALID_SIZE` and writes nothing.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solver_at(
    index: c_int,
    constant: *mut *const c_char,
    name: *mut *const c_char,
) -> c_int {
    ffi_guard(
        "fc3d_solver_at",
        |code| code,
        || {
            let solvers = native_solvers();
            let solver = usize::try_from(index)
                .ok()
                .and_then(|i| solvers.get(i))
                .ok_or_else(|| {
                    CError::new(
                        FC3D_ERR_INVALID_SIZE,
                        format!("index {index} outside 0..{}", solvers.len()),
                    )
                })?;
            if !constant.is_null() {
                *constant = solver.constant.as_ptr();
            }
            if !name.is_null() {
                *name = solver.name.as_ptr();
            }
            Ok(solver.id)
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ptr::null_mut;

    fn listed() -> Vec<(c_int, String, String)> {
        (0..fc3d_solver_count())
            .map(|i| {
                let (mut constant, mut name) = (std::ptr::null(), std::ptr::null());
                let id = unsafe { fc3d_solver_at(i, &mut constant, &mut name) };
                let text =
                    |p: *const c_char| unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_string();
                (id, text(constant), text(name))
            })
            .collect()
    }

    #[test]
    fn the_list_is_what_fc3d_settings_new_accepts() {
        let listed = listed();
        let ids: Vec<c_int> = listed.iter().map(|s| s.0).collect();
        // Every id 0..6000 that the native entry accepts for a local solve is listed, and only
        // those: the global ids it accepts are for the global solves.
        let global = |id: c_int| (600..=615).contains(&id) || id == 5000;
        let accepted: Vec<c_int> = (0..6000)
            .filter(|&id| !global(id))
            .filter(|&id| {
                let s = crate::native::settings::fc3d_settings_new(id);
                unsafe { crate::native::settings::fc3d_settings_free(s) };
                !s.is_null()
            })
            .collect();
        assert_eq!(ids, accepted);
        assert!(ids.windows(2).all(|w| w[0] < w[1]));
        assert!(listed.contains(&(590, "FC3D_AUTO".into(), "FC3D_AUTO".into())));
        assert!(listed.contains(&(500, "SICONOS_FRICTION_3D_NSGS".into(), "FC3D_NSGS".into())));
        assert!(listed.contains(&(
            505,
            "SICONOS_FRICTION_3D_DSFP".into(),
            "FC3D_DeSaxceFixedPoint".into()
        )));
    }

    #[test]
    fn an_index_out_of_range_writes_nothing() {
        let mut constant: *const c_char = std::ptr::null();
        for index in [-1, fc3d_solver_count(), c_int::MAX] {
            let code = unsafe { fc3d_solver_at(index, &mut constant, null_mut()) };
            assert_eq!(code, FC3D_ERR_INVALID_SIZE);
            assert!(constant.is_null());
        }
        assert_eq!(
            unsafe { fc3d_solver_at(0, null_mut(), null_mut()) },
            listed()[0].0
        );
    }

    /// The constants are the ones the headers define with these values.
    #[test]
    fn constants_are_the_headers() {
        let include = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("include");
        let headers = ["fc3d.h", "siconos-compat/Friction_cst.h"]
            .map(|h| std::fs::read_to_string(include.join(h)).unwrap())
            .join("\n");
        for (id, constant, _) in listed() {
            assert!(
                headers.contains(&format!("{constant} = {id}"))
                    || headers.contains(&format!("#define {constant} {id}")),
                "{constant} = {id} is not in the headers"
            );
        }
    }
}
