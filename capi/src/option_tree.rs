//! Trees of `SolverOptions` as a host hands them over: the checks that make a tree safe to
//! read, copy or print (finite, acyclic, within the limits below), and the release of what a
//! tree owns, each node once, without recursion.

use std::collections::{HashMap, HashSet};
use std::os::raw::c_int;
use std::ptr::null_mut;

use super::alloc::c_free;
use super::types::SolverOptions;
use super::{CError, CResult, FC3D_ERR_INVALID_OPTION};

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
pub(crate) unsafe fn internal_slots<'a>(
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
pub(crate) unsafe fn reachable(root: *mut SolverOptions) -> CResult<Vec<*mut SolverOptions>> {
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
pub(crate) unsafe fn release_detached(root: *mut SolverOptions, old: *mut SolverOptions) {
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
