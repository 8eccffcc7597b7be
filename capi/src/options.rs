//! `SolverOptions` as Siconos' C API manages it: creation with the defaults of `params`, copy,
//! deletion, internal solvers, names, printing.

#![allow(non_snake_case)]

use std::ffi::{c_char, CStr};
use std::os::raw::c_int;
use std::ptr::null_mut;

use super::alloc::{c_box, c_calloc, c_copy, c_free};
use super::option_tree::{
    check_tree, delete_contents, internal_slots, reachable, release_detached, try_delete_contents,
};
use super::params::{self, solver_name, Encoded, OPTIONS_PARAM_SIZE};
use super::types::SolverOptions;
use super::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_OPTION};

/// Builds a C-allocated options struct for `id` with its defaults and internal solvers.
pub(crate) fn create_options(id: c_int) -> CResult<*mut SolverOptions> {
    allocate(&params::defaults(id)?)
}

/// Allocates the C structs of `e` (and of its internal solvers) with the C allocator.
fn allocate(e: &Encoded) -> CResult<*mut SolverOptions> {
    let internals = c_calloc::<*mut SolverOptions>(e.internal.len())?;
    for (k, i) in e.internal.iter().enumerate() {
        // SAFETY: internals has e.internal.len() slots.
        unsafe { *internals.add(k) = allocate(i)? };
    }
    c_box(SolverOptions {
        solverId: e.id,
        isSet: 1,
        iSize: OPTIONS_PARAM_SIZE,
        iparam: c_copy(&e.iparam)?,
        dSize: OPTIONS_PARAM_SIZE,
        dparam: c_copy(&e.dparam)?,
        filterOn: 1,
        dWorkSize: 0,
        dWork: null_mut(),
        iWorkSize: 0,
        iWork: null_mut(),
        numberOfInternalSolvers: e.internal.len(),
        internalSolvers: internals,
        callback: null_mut(),
        solverParameters: null_mut(),
        solverData: null_mut(),
    })
}

/// A deep copy of a checked tree (`check_tree`: the recursion is bounded by the depth limit).
unsafe fn copy_options(src: &SolverOptions) -> CResult<*mut SolverOptions> {
    let ip = super::matrix::c_slice(src.iparam, src.iSize.max(0) as usize, "iparam")?;
    let dp = super::matrix::c_slice(src.dparam, src.dSize.max(0) as usize, "dparam")?;
    let slots = internal_slots(src, &[])?;
    let n = slots.len();
    // Built in a zeroed struct that owns what is allocated so far, so that a failure midway
    // releases it.
    let copy = c_box(SolverOptions {
        solverId: src.solverId,
        isSet: src.isSet,
        iSize: src.iSize,
        iparam: null_mut(),
        dSize: src.dSize,
        dparam: null_mut(),
        filterOn: src.filterOn,
        dWorkSize: 0,
        dWork: null_mut(),
        iWorkSize: 0,
        iWork: null_mut(),
        numberOfInternalSolvers: 0,
        internalSolvers: null_mut(),
        callback: src.callback,
        solverParameters: src.solverParameters,
        solverData: src.solverData,
    })?;
    let fill = || -> CResult<()> {
        let c = &mut *copy;
        c.iparam = c_copy(ip)?;
        c.dparam = c_copy(dp)?;
        if n > 0 {
            c.internalSolvers = c_calloc::<*mut SolverOptions>(n)?;
            c.numberOfInternalSolvers = n;
            for (k, &s) in slots.iter().enumerate() {
                if !s.is_null() {
                    *c.internalSolvers.add(k) = copy_options(&*s)?;
                }
            }
        }
        Ok(())
    };
    if let Err(e) = fill() {
        delete_contents(copy);
        c_free(copy);
        return Err(e);
    }
    Ok(copy)
}

// ---------------------------------------------------------------------------------------------
// Siconos API.

/// Options for solver `solverId` with Siconos 4.4's defaults (and default internal solvers).
/// NULL for an id that is not an fc3d solver. Release with `solver_options_delete` then `free`.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn solver_options_create(solverId: c_int) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_create",
        |_| null_mut(),
        || create_options(solverId),
    )
}

/// Releases everything `options` owns (parameter arrays, work arrays, internal solvers), but not
/// the struct itself, nor `callback`, `solverParameters`, `solverData` (the caller's). Each
/// internal solver is released once however often it appears in the tree (shared or in a cycle),
/// without recursion, whatever the depth. Refused (nothing released, the reason in
/// `fc3d_last_error_message`) when a struct declares more than
/// `FC3D_OPTIONS_MAX_INTERNAL_SOLVERS` internal solvers.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_delete(options: *mut SolverOptions) {
    ffi_guard(
        "solver_options_delete",
        |_| (),
        || try_delete_contents(options),
    )
}

/// Replaces internal solver number `internal_solver_number` of `parent` by new options for
/// `solver_id` with their defaults (the old internal solver is released, except the parts of it
/// still referenced elsewhere in `parent`'s tree).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_update_internal(
    parent: *mut SolverOptions,
    internal_solver_number: usize,
    solver_id: c_int,
) {
    ffi_guard(
        "solver_options_update_internal",
        |_| (),
        || {
            if parent.is_null() {
                return Err(CError::null("parent"));
            }
            let p = &mut *parent;
            if internal_solver_number >= p.numberOfInternalSolvers || p.internalSolvers.is_null() {
                return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("internal solver {internal_solver_number} does not exist ({} internal solvers)", p.numberOfInternalSolvers),
            ));
            }
            let fresh = create_options(solver_id)?;
            let slot = p.internalSolvers.add(internal_solver_number);
            let old = *slot;
            *slot = fresh;
            release_detached(parent, old);
            Ok(())
        },
    )
}

/// Sets internal solver `n` of `options` to `NSO`, which `options` then owns (the previous one is
/// released, except the parts of it still referenced elsewhere in the tree). Refused when `NSO`
/// is `options` or contains it (a cycle).
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_set_internal_solver(
    options: *mut SolverOptions,
    n: usize,
    NSO: *mut SolverOptions,
) {
    ffi_guard(
        "solver_options_set_internal_solver",
        |_| (),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let o = &mut *options;
            if n >= o.numberOfInternalSolvers || o.internalSolvers.is_null() {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "internal solver {n} does not exist ({} internal solvers)",
                        o.numberOfInternalSolvers
                    ),
                ));
            }
            if !NSO.is_null() && reachable(NSO)?.contains(&options) {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!("internal solver {n}: the options given are the parent itself or contain it (a cycle of internal solvers)"),
                ));
            }
            let slot = o.internalSolvers.add(n);
            let old = *slot;
            if old != NSO {
                *slot = NSO;
                release_detached(options, old);
            }
            Ok(())
        },
    )
}

/// Internal solver `n` of `options` (owned by `options`), or NULL.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_get_internal_solver(
    options: *mut SolverOptions,
    n: usize,
) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_get_internal_solver",
        |_| null_mut(),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let o = &*options;
            if n >= o.numberOfInternalSolvers || o.internalSolvers.is_null() {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "internal solver {n} does not exist ({} internal solvers)",
                        o.numberOfInternalSolvers
                    ),
                ));
            }
            Ok(*o.internalSolvers.add(n))
        },
    )
}

/// A deep copy of `source` (parameters and internal solvers); `callback`, `solverParameters` and
/// `solverData` are shared, as in Siconos. NULL (the reason in `fc3d_last_error_message`) for a
/// cycle of internal solvers, a chain deeper than `FC3D_OPTIONS_MAX_DEPTH`, or sizes and counts
/// outside fc3d's limits.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_copy(source: *mut SolverOptions) -> *mut SolverOptions {
    ffi_guard(
        "solver_options_copy",
        |_| null_mut(),
        || {
            if source.is_null() {
                return Err(CError::null("source"));
            }
            check_tree(&*source)?;
            copy_options(&*source)
        },
    )
}

/// Siconos' name of a solver id ("NONAME" if unknown); a static string, do not free.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub extern "C" fn solver_options_id_to_name(Id: c_int) -> *const c_char {
    ffi_guard(
        "solver_options_id_to_name",
        |_| c"NONAME".as_ptr(),
        || Ok(solver_name(Id).as_ptr()),
    )
}

/// The id of a Siconos solver name, 0 if unknown.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_name_to_id(pName: *const c_char) -> c_int {
    ffi_guard(
        "solver_options_name_to_id",
        |_| 0,
        || {
            if pName.is_null() {
                return Err(CError::null("pName"));
            }
            let name = CStr::from_ptr(pName);
            Ok(params::solver_name_to_id(name))
        },
    )
}

/// Prints the options (and internal solvers) to stdout. Nothing is printed (the reason in
/// `fc3d_last_error_message`) for a tree `solver_options_copy` refuses.
#[cfg(feature = "siconos-abi")]
#[no_mangle]
pub unsafe extern "C" fn solver_options_print(options: *mut SolverOptions) {
    ffi_guard(
        "solver_options_print",
        |_| (),
        || {
            if options.is_null() {
                return Err(CError::null("options"));
            }
            check_tree(&*options)?;
            print_options(&*options, 0);
            Ok(())
        },
    )
}

/// Prints a checked tree (`check_tree`: the recursion is bounded by the depth limit).
unsafe fn print_options(o: &SolverOptions, depth: usize) {
    let pad = "  ".repeat(depth);
    println!(
        "{pad}solver {} ({})",
        o.solverId,
        solver_name(o.solverId).to_string_lossy()
    );
    if let Ok(ip) = super::matrix::c_slice(o.iparam, o.iSize.max(0) as usize, "iparam") {
        println!("{pad}  iparam: {ip:?}");
    }
    if let Ok(dp) = super::matrix::c_slice(o.dparam, o.dSize.max(0) as usize, "dparam") {
        println!("{pad}  dparam: {dp:?}");
    }
    for (k, &s) in internal_slots(o, &[]).unwrap_or(&[]).iter().enumerate() {
        if !s.is_null() {
            println!("{pad}  internal solver {k}:");
            print_options(&*s, depth + 2);
        }
    }
}
