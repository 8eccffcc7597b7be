//! `SolverOptions` as Siconos' C API manages it: creation with the defaults of `params`, copy,
//! deletion, internal solvers, names, printing.

#![allow(non_snake_case)]

use std::collections::{HashMap, HashSet};
use std::ffi::{c_char, CStr};
use std::os::raw::c_int;
use std::ptr::null_mut;

use super::alloc::{c_box, c_calloc, c_copy, c_free};
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

// ---------------------------------------------------------------------------------------------
// Option trees: finite, acyclic, within the limits below.

/// The deepest chain of internal solvers fc3d accepts: the options given to a function are
/// level 0, their internal solvers level 1, and so on (fc3d's own trees are at most 2 deep: PROX
/// -> NSGS -> local solver). `fc3d_driver`, `solver_options_copy` and `solver_options_print`
/// refuse a deeper chain, and a cycle (an options struct that is its own internal solver,
/// directly or deeper), with `FC3D_ERR_INVALID_OPTION`.
pub const FC3D_OPTIONS_MAX_DEPTH: c_int = 8;
/// The most internal solvers one options struct may declare (`numberOfInternalSolvers`).
pub const FC3D_OPTIONS_MAX_INTERNAL_SOLVERS: c_int = 16;
/// The largest `iSize` / `dSize` accepted (fc3d reads the first `OPTIONS_PARAM_SIZE` slots).
pub const FC3D_OPTIONS_MAX_PARAM_SIZE: c_int = 1024;

const MAX_DEPTH: usize = FC3D_OPTIONS_MAX_DEPTH as usize;
const MAX_INTERNAL: usize = FC3D_OPTIONS_MAX_INTERNAL_SOLVERS as usize;

type Node = *const SolverOptions;

/// Where a node is, for messages: "options" or "internalSolvers[0]->internalSolvers[1]".
fn describe(path: &[usize]) -> String {
    if path.is_empty() {
        "options".into()
    } else {
        path.iter()
            .map(|k| format!("internalSolvers[{k}]"))
            .collect::<Vec<_>>()
            .join("->")
    }
}

/// The internal solver pointers of `o` (NULL entries included), after checking that they can
/// be read: no more than `FC3D_OPTIONS_MAX_INTERNAL_SOLVERS`, and an array when there are any.
unsafe fn internal_slots<'a>(
    o: &'a SolverOptions,
    path: &[usize],
) -> CResult<&'a [*mut SolverOptions]> {
    let n = o.numberOfInternalSolvers;
    if n == 0 {
        return Ok(&[]);
    }
    if n > MAX_INTERNAL {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!(
                "{}: numberOfInternalSolvers = {n} is above fc3d's limit of {MAX_INTERNAL} internal solvers",
                describe(path)
            ),
        ));
    }
    if o.internalSolvers.is_null() {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!(
                "{}: numberOfInternalSolvers = {n} but internalSolvers is NULL",
                describe(path)
            ),
        ));
    }
    Ok(std::slice::from_raw_parts(o.internalSolvers, n))
}

/// Checks the tree of options below `root` before it is read, copied or printed: no cycle, no
/// chain deeper than `FC3D_OPTIONS_MAX_DEPTH`, internal solver counts that match an array and
/// stay within `FC3D_OPTIONS_MAX_INTERNAL_SOLVERS`, sizes in `0..=FC3D_OPTIONS_MAX_PARAM_SIZE`
/// with an array when positive. A node shared by several parents (not a cycle) is accepted.
/// Recursion is bounded by the depth limit; each node is explored again only when reached
/// deeper than before, so a shared node costs at most `FC3D_OPTIONS_MAX_DEPTH` visits.
pub(crate) unsafe fn check_tree(root: &SolverOptions) -> CResult<()> {
    let mut deepest = HashMap::new();
    let mut on_path = Vec::new();
    let mut path = Vec::new();
    check_node(root, &mut on_path, &mut path, &mut deepest)
}

unsafe fn check_node(
    o: &SolverOptions,
    on_path: &mut Vec<Node>,
    path: &mut Vec<usize>,
    deepest: &mut HashMap<Node, usize>,
) -> CResult<()> {
    let me = o as Node;
    let depth = path.len();
    if on_path.contains(&me) {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!(
                "{} is the options struct itself or one of its ancestors: a cycle of internal solvers",
                describe(path)
            ),
        ));
    }
    if depth > MAX_DEPTH {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!(
                "the chain of internal solvers is deeper than fc3d's limit of {MAX_DEPTH} levels ({})",
                describe(&path[..MAX_DEPTH + 1])
            ),
        ));
    }
    if deepest.get(&me).is_some_and(|&d| d >= depth) {
        return Ok(());
    }
    deepest.insert(me, depth);
    for (size, array, name) in [
        (o.iSize, o.iparam.is_null(), "iSize"),
        (o.dSize, o.dparam.is_null(), "dSize"),
    ] {
        if !(0..=FC3D_OPTIONS_MAX_PARAM_SIZE).contains(&size) {
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!(
                    "{}: {name} = {size} is outside 0..={FC3D_OPTIONS_MAX_PARAM_SIZE}",
                    describe(path)
                ),
            ));
        }
        if size > 0 && array {
            let arr = if name == "iSize" { "iparam" } else { "dparam" };
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("{}: {name} = {size} but {arr} is NULL", describe(path)),
            ));
        }
    }
    let slots = internal_slots(o, path)?;
    on_path.push(me);
    for (k, &s) in slots.iter().enumerate() {
        if !s.is_null() {
            path.push(k);
            check_node(&*s, on_path, path, deepest)?;
            path.pop();
        }
    }
    on_path.pop();
    Ok(())
}

/// Every distinct options struct reachable from `root` (root first), found without recursion.
/// Refuses (nothing is touched) a node whose internal solvers cannot be read safely.
unsafe fn reachable(root: *mut SolverOptions) -> CResult<Vec<*mut SolverOptions>> {
    let mut seen = HashSet::new();
    let mut order = Vec::new();
    let mut stack = vec![root];
    while let Some(o) = stack.pop() {
        if o.is_null() || !seen.insert(o as Node) {
            continue;
        }
        order.push(o);
        // The slots only: sizes and arrays are freed, not read.
        let n = (*o).numberOfInternalSolvers;
        if n > 0 && !(*o).internalSolvers.is_null() {
            if n > MAX_INTERNAL {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    format!(
                        "numberOfInternalSolvers = {n} is above fc3d's limit of {MAX_INTERNAL} internal solvers: not released"
                    ),
                ));
            }
            stack.extend(
                std::slice::from_raw_parts((*o).internalSolvers, n)
                    .iter()
                    .rev(),
            );
        }
    }
    Ok(order)
}

/// Frees what each node owns (parameter, work and internal solver arrays) and, except for
/// `keep_struct`, the node itself. Every node is distinct.
unsafe fn release_nodes(nodes: &[*mut SolverOptions], keep_struct: *mut SolverOptions) {
    for &o in nodes {
        let o = &mut *o;
        c_free(o.iparam);
        c_free(o.dparam);
        c_free(o.dWork);
        c_free(o.iWork);
        c_free(o.internalSolvers);
        o.iparam = null_mut();
        o.dparam = null_mut();
        o.dWork = null_mut();
        o.iWork = null_mut();
        o.dWorkSize = 0;
        o.iWorkSize = 0;
        o.internalSolvers = null_mut();
        o.numberOfInternalSolvers = 0;
        o.iSize = 0;
        o.dSize = 0;
    }
    for &o in nodes {
        if o != keep_struct {
            c_free(o);
        }
    }
}

/// Releases what `options` owns: parameter and work arrays, internal solvers (their structs
/// included, each once however often it appears, without recursion). The struct itself is not
/// freed (Siconos 4.4 semantics), even when it appears as its own internal solver.
pub(crate) unsafe fn try_delete_contents(o: *mut SolverOptions) -> CResult<()> {
    if o.is_null() {
        return Ok(());
    }
    let nodes = reachable(o)?;
    release_nodes(&nodes, o);
    Ok(())
}

/// `try_delete_contents` for the trees fc3d builds itself (always valid).
pub(crate) unsafe fn delete_contents(o: *mut SolverOptions) {
    let _ = try_delete_contents(o);
}

/// Releases `old` (struct included) and what it owns, except the nodes still reachable from
/// `root`: `old` has just been replaced in `root`'s tree, and may still be referenced elsewhere
/// in it. When the tree cannot be walked, nothing is released (a leak, not a dangling pointer).
unsafe fn release_detached(root: *mut SolverOptions, old: *mut SolverOptions) {
    if old.is_null() {
        return;
    }
    let (Ok(keep), Ok(old_nodes)) = (reachable(root), reachable(old)) else {
        return;
    };
    let keep: HashSet<Node> = keep.iter().map(|&o| o as Node).collect();
    let detached: Vec<_> = old_nodes
        .into_iter()
        .filter(|&o| !keep.contains(&(o as Node)))
        .collect();
    release_nodes(&detached, null_mut());
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
