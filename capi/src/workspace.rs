//! The workspace for time-stepping hosts (`fc3d_workspace_new`, `fc3d_workspace_free`,
//! `fc3d_workspace_driver`) and per-contact diagnostics (`fc3d_contact_diagnostics`). These are
//! fc3d's own functions (Siconos 4.4 has no equivalent).
//!
//! Ownership: `fc3d_workspace_new` allocates a workspace that belongs to the host until it
//! passes it to `fc3d_workspace_free` (once). A workspace keeps copies of what it needs (the
//! reactions by contact id, structures built from W): it never points into the host's problem,
//! ids or arrays after a call returns. One workspace serves one thread at a time.

use std::os::raw::{c_double, c_int};

use super::driver::{auto_stage_lines, solve_into_host};
use super::matrix::c_slice;
use super::params::config_from_c;
use super::problem::{problem_from_c, problem_view_from_c};
use super::types::{FrictionContactProblem, SolverOptions};
use super::{ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_OPTION, FC3D_ERR_INVALID_SIZE};
use crate::codes::FC3D_ERR_NULL_POINTER;
use fc3d_core::{diagnose, ContactStatus, DiagnosticOptions, SolveReport, Workspace};

/// Marks a live workspace: a pointer that was freed (or never was a workspace) is refused
/// when it no longer holds it, rather than used.
const LIVE: u64 = 0x6663_3364_5f77_7331;

/// A workspace (opaque): what one solve learned for the next one of a time-stepping host —
/// the reaction of every contact by the host's contact id, the active set, and the structures
/// built from W while its block pattern does not change.
pub struct Fc3dWorkspace {
    live: u64,
    workspace: Workspace,
}

/// `fc3d_contact_diagnostics` status: no reaction, separating (`u_N > 0`).
pub const FC3D_CONTACT_TAKE_OFF: c_int = 0;
/// `fc3d_contact_diagnostics` status: reaction, no tangential slip.
pub const FC3D_CONTACT_STICK: c_int = 1;
/// `fc3d_contact_diagnostics` status: reaction with tangential slip.
pub const FC3D_CONTACT_SLIDE: c_int = 2;
/// `fc3d_contact_diagnostics` status: no reaction and no separation (the apex of the cone).
pub const FC3D_CONTACT_APEX: c_int = 3;

fn status_code(s: ContactStatus) -> c_int {
    match s {
        ContactStatus::TakeOff => FC3D_CONTACT_TAKE_OFF,
        ContactStatus::Stick => FC3D_CONTACT_STICK,
        ContactStatus::Slide => FC3D_CONTACT_SLIDE,
        ContactStatus::Apex => FC3D_CONTACT_APEX,
    }
}

/// A new, empty workspace (the first solve through it is a cold one); NULL (and the last
/// error) if memory is short. Release it with `fc3d_workspace_free`.
#[no_mangle]
pub extern "C" fn fc3d_workspace_new() -> *mut Fc3dWorkspace {
    ffi_guard(
        "fc3d_workspace_new",
        |_| std::ptr::null_mut(),
        || {
            // A fixed-size struct (the maps and structures grow at the first solve, fallibly).
            let b = Box::new(Fc3dWorkspace {
                live: LIVE,
                workspace: Workspace::new(),
            });
            Ok(Box::into_raw(b))
        },
    )
}

/// Releases a workspace of `fc3d_workspace_new` and everything it kept (NULL is accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_workspace_free(workspace: *mut Fc3dWorkspace) {
    ffi_guard(
        "fc3d_workspace_free",
        |_| (),
        || {
            if workspace.is_null() {
                return Ok(());
            }
            if (*workspace).live != LIVE {
                return Err(CError::new(
                    FC3D_ERR_INVALID_OPTION,
                    "not a live workspace (freed twice?): nothing released",
                ));
            }
            (*workspace).live = 0;
            drop(Box::from_raw(workspace));
            Ok(())
        },
    )
}

unsafe fn workspace_mut<'a>(w: *mut Fc3dWorkspace) -> CResult<&'a mut Workspace> {
    let w = w
        .as_mut()
        .ok_or_else(|| CError::new(FC3D_ERR_NULL_POINTER, "workspace is NULL"))?;
    if w.live != LIVE {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            "not a live workspace (freed, or not made by fc3d_workspace_new)",
        ));
    }
    Ok(&mut w.workspace)
}

/// `fc3d_driver` for a host stepping in time: solves `problem` with the solver of `options`,
/// starting each contact from the reaction the contact with the same id had at the end of the
/// previous call on this workspace (zero for a contact that appeared; the ids of contacts that
/// vanished are forgotten), and reusing the structures prepared from W when its block pattern
/// is unchanged (NSGS's block rows, NSN's symbolic factorization).
///
/// `contact_ids` holds one id per contact (`problem->numberOfContacts` of them, unique within
/// the call; any values, e.g. a hash of the two bodies and the feature). `reaction` is an
/// output: its values on entry are ignored (the warm start replaces them). Return codes,
/// outputs (`reaction`, `velocity`, `iparam[1]`, `dparam[1]`) and the callback are those of
/// `fc3d_driver`; on a negative return nothing is written and the workspace still holds the
/// previous step's reactions. The workspace copies what it keeps: the problem, ids and arrays
/// stay the host's.
#[no_mangle]
pub unsafe extern "C" fn fc3d_workspace_driver(
    workspace: *mut Fc3dWorkspace,
    problem: *mut FrictionContactProblem,
    contact_ids: *const i64,
    reaction: *mut c_double,
    velocity: *mut c_double,
    options: *mut SolverOptions,
) -> c_int {
    ffi_guard(
        "fc3d_workspace_driver",
        |c| c,
        || {
            let ws = workspace_mut(workspace)?;
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            if options.is_null() {
                return Err(CError::null("options"));
            }
            let config = config_from_c(&*options)?;
            // The host's sparse-block W is read in place on every call, never converted (the
            // workspace keeps its pattern to refill the block rows; the solve checks values).
            let p = problem_view_from_c(&*problem)?;
            if p.n_contacts() > 0 && contact_ids.is_null() {
                return Err(CError::null("contact_ids"));
            }
            let ids = c_slice(contact_ids, p.n_contacts(), "contact_ids")?;
            let report = solve_into_host(&p, reaction, velocity, options, |r, u, observer| {
                ws.solve_with_observer(&p, &config, ids, r, u, observer)
            })?;
            if verbose() > 0 {
                eprint!(
                    "{}",
                    verbose_text(&config.label(), p.n_contacts(), ws, &report)
                );
            }
            Ok(report.status.info_code())
        },
    )
}

/// What `fc3d_workspace_driver` prints when verbose: the solve with what the workspace reused,
/// then, for AUTO, its stages as `fc3d_driver` prints them.
fn verbose_text(label: &str, n_contacts: usize, ws: &Workspace, report: &SolveReport) -> String {
    let s = ws.stats();
    let mut text = format!(
        "fc3d: {label} on {n_contacts} contacts (workspace: {} warm, {} cold so far; W structure reused {}, built {}; AUTO resumed {}): {:?} after {} iterations, error {:e}\n",
        s.warm_contacts,
        s.cold_contacts,
        s.structure_reused,
        s.structure_built,
        s.auto_resumed,
        report.status,
        report.iterations,
        report.error,
    );
    text.push_str(&auto_stage_lines(report));
    text
}

/// Per-contact diagnostics of the reaction `reaction` (3 per contact) of `problem`, with
/// `u = W r + q` recomputed: why a step did not converge, which contacts to look at.
///
/// Fills, for each contact `c` (arrays of `problem->numberOfContacts` entries, each may be NULL
/// when not wanted): `status[c]` (`FC3D_CONTACT_TAKE_OFF`, `_STICK`, `_SLIDE`, `_APEX`, by the
/// rules of fc3d_core's `diagnostics` module with relative tolerance `tolerance`; pass 0 or a
/// negative value for the default 1e-6), `error_contribution[c]` (the contact's part of the
/// relative natural-map error: the sum of their squares is the error squared),
/// `normal_velocity[c]` (`u_N`, negative when penetrating). `worst` (`k` entries, NULL when
/// `k` is 0) receives the 0-based indices of the `k` contacts with the largest contributions,
/// largest first, then -1 where there are fewer than `k` contacts.
///
/// Returns 0, or a negative code on invalid input (nothing written). Nothing is kept.
#[allow(clippy::too_many_arguments)]
#[no_mangle]
pub unsafe extern "C" fn fc3d_contact_diagnostics(
    problem: *mut FrictionContactProblem,
    reaction: *const c_double,
    tolerance: c_double,
    status: *mut c_int,
    error_contribution: *mut c_double,
    normal_velocity: *mut c_double,
    k: c_int,
    worst: *mut c_int,
) -> c_int {
    ffi_guard(
        "fc3d_contact_diagnostics",
        |c| c,
        || {
            if problem.is_null() {
                return Err(CError::null("problem"));
            }
            let p = problem_from_c(&*problem)?;
            let nc = p.n_contacts();
            if p.size() > 0 && reaction.is_null() {
                return Err(CError::null("reaction"));
            }
            let r = c_slice(reaction, p.size(), "reaction")?;
            if k < 0 {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("k = {k} must be >= 0"),
                ));
            }
            let k = k as usize;
            if k > 0 && worst.is_null() {
                return Err(CError::null("worst"));
            }
            // Every output array is checked before anything is written.
            if !status.is_null() {
                c_slice(status as *const c_int, nc, "status")?;
            }
            if !error_contribution.is_null() {
                c_slice(error_contribution as *const f64, nc, "error_contribution")?;
            }
            if !normal_velocity.is_null() {
                c_slice(normal_velocity as *const f64, nc, "normal_velocity")?;
            }
            if k > 0 {
                c_slice(worst as *const c_int, k, "worst")?;
            }
            let tau = if tolerance > 0.0 {
                tolerance
            } else if tolerance.is_nan() {
                return Err(CError::new(FC3D_ERR_INVALID_OPTION, "tolerance is NaN"));
            } else {
                DiagnosticOptions::default().tolerance
            };
            let d = diagnose(&p, r, &DiagnosticOptions { tolerance: tau })?;
            let order = d.worst(k);
            for (c, cd) in d.contacts.iter().enumerate() {
                if !status.is_null() {
                    *status.add(c) = status_code(cd.status);
                }
                if !error_contribution.is_null() {
                    *error_contribution.add(c) = cd.error_contribution;
                }
                if !normal_velocity.is_null() {
                    *normal_velocity.add(c) = cd.normal_velocity;
                }
            }
            for i in 0..k {
                *worst.add(i) = order.get(i).map_or(-1, |&c| c as c_int);
            }
            Ok(0)
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc3d_core::{AutoOptions, Delassus, DenseMatrix, FrictionProblem, SolverConfig};

    #[test]
    fn the_verbose_text_shows_autos_stages_as_fc3d_driver_does() {
        let w = DenseMatrix::new(3, 3, vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
        let p = FrictionProblem::new(Delassus::Dense(w), vec![-1.0, 2.0, 0.0], vec![0.5]).unwrap();
        let config = SolverConfig::new(AutoOptions::default()).with_tolerance(1e-10);
        let mut ws = Workspace::new();
        let mut text = String::new();
        for _ in 0..2 {
            let (mut r, mut u) = (vec![0.0; 3], vec![0.0; 3]);
            let report = ws.solve(&p, &config, &[7], &mut r, &mut u).unwrap();
            let stages = auto_stage_lines(&report);
            assert!(stages.starts_with("fc3d: AUTO stage 1: NSGS "), "{stages}");
            text = verbose_text(&config.label(), 1, &ws, &report);
            assert!(text.ends_with(&stages), "{text}");
        }
        assert!(text.contains("AUTO resumed 1)"), "{text}");
    }
}
