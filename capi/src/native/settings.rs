//! Settings (`fc3d_settings_*`): a solver id's Siconos options, changed by name or by slot.

use std::ffi::{c_char, CStr};
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;

use super::Fc3dSettings;
use crate::alloc::{c_calloc, c_free};
use crate::option_tree::delete_contents;
use crate::options::create_options;
use crate::params::global::{global_config_from_c, global_rolling_config_from_c};
use crate::params::{config_from_c, OPTIONS_PARAM_SIZE};
use crate::types::SolverOptions;
use crate::{ffi_guard, CError, CResult, FC3D_ERR_INVALID_OPTION};
use fc3d_core::LocalSolverKind;

/// Settings of solver `solver_id` (a Siconos id such as 500 NSGS, 504 NSN_AC, 502 PROX, or a
/// global id 600-615 for `fc3d_solve_global_*`, 5000 for the global rolling solver) with its
/// defaults; NULL for an id fc3d does not implement (the reason in `fc3d_last_error_message`).
/// Release with `fc3d_settings_free`.
#[no_mangle]
pub extern "C" fn fc3d_settings_new(solver_id: c_int) -> *mut Fc3dSettings {
    ffi_guard(
        "fc3d_settings_new",
        |_| null_mut(),
        || {
            let options = create_options(solver_id)?;
            // Reject ids fc3d only names (their defaults exist for Siconos' API).
            if let Err(e) = unsafe { check_settings(&*options) } {
                unsafe { release_options(options) };
                return Err(e);
            }
            Ok(Box::into_raw(Box::new(Fc3dSettings { options })))
        },
    )
}

/// Whether fc3d runs the options as they are: a global id (600-615) as `gfc3d_driver` reads it,
/// 5000 as `g_rolling_fc3d_driver`, any other as `fc3d_driver`.
unsafe fn check_settings(o: &SolverOptions) -> CResult<()> {
    if is_global_id(o.solverId) {
        global_config_from_c(o).map(drop)
    } else if o.solverId == GLOBAL_ROLLING_ID {
        global_rolling_config_from_c(o).map(drop)
    } else {
        config_from_c(o).map(drop)
    }
}

/// Siconos' global rolling id (`g_rolling_fc3d_driver`).
const GLOBAL_ROLLING_ID: c_int = 5000;

/// The ids `gfc3d_driver` dispatches (600-615).
pub(super) fn is_global_id(id: c_int) -> bool {
    (600..=615).contains(&id)
}

pub(super) unsafe fn release_options(options: *mut SolverOptions) {
    delete_contents(options);
    c_free(options);
}

/// Releases settings made by `fc3d_settings_new` (NULL is accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_free(settings: *mut Fc3dSettings) {
    ffi_guard(
        "fc3d_settings_free",
        |_| (),
        || {
            if !settings.is_null() {
                let s = Box::from_raw(settings);
                release_options(s.options);
            }
            Ok(())
        },
    )
}

unsafe fn options_of<'a>(settings: *mut Fc3dSettings) -> CResult<&'a mut SolverOptions> {
    if settings.is_null() {
        return Err(CError::null("settings"));
    }
    Ok(&mut *(*settings).options)
}

/// The options of internal solver 0 (NSGS's local solver).
unsafe fn local_of<'a>(settings: *mut Fc3dSettings) -> CResult<&'a mut SolverOptions> {
    let o = options_of(settings)?;
    if o.numberOfInternalSolvers == 0
        || o.internalSolvers.is_null()
        || (*o.internalSolvers).is_null()
    {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("solver {} has no local (internal) solver", o.solverId),
        ));
    }
    Ok(&mut **o.internalSolvers)
}

fn slot(index: c_int) -> CResult<usize> {
    usize::try_from(index)
        .ok()
        .filter(|&k| k < OPTIONS_PARAM_SIZE as usize)
        .ok_or_else(|| {
            CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("parameter index {index} is outside 0..{OPTIONS_PARAM_SIZE}"),
            )
        })
}

unsafe fn set_iparam(o: &mut SolverOptions, index: c_int, value: c_int) -> CResult<c_int> {
    *o.iparam.add(slot(index)?) = value;
    Ok(0)
}

unsafe fn set_dparam(o: &mut SolverOptions, index: c_int, value: c_double) -> CResult<c_int> {
    *o.dparam.add(slot(index)?) = value;
    Ok(0)
}

/// Tolerance on the relative natural-map error (Siconos' `dparam[0]`). Returns 0, or a negative
/// code (NULL settings); the range is checked when solving.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_tolerance(
    settings: *mut Fc3dSettings,
    tolerance: c_double,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_tolerance",
        |c| c,
        || set_dparam(options_of(settings)?, 0, tolerance),
    )
}

/// Iteration limit (`iparam[0]`), 0..=INT_MAX.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_max_iter(
    settings: *mut Fc3dSettings,
    max_iter: i64,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_max_iter",
        |c| c,
        || set_max_iter(settings, max_iter),
    )
}

unsafe fn set_max_iter(settings: *mut Fc3dSettings, max_iter: i64) -> CResult<c_int> {
    let v = c_int::try_from(max_iter)
        .ok()
        .filter(|v| *v >= 0)
        .ok_or_else(|| {
            CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("max_iter = {max_iter} is outside 0..=INT_MAX"),
            )
        })?;
    set_iparam(options_of(settings)?, 0, v)
}

/// Wall-clock budget in seconds (`dparam[FC3D_DPARAM_TIME_BUDGET]`; 0: none).
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_time_budget(
    settings: *mut Fc3dSettings,
    seconds: c_double,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_time_budget",
        |c| c,
        || {
            set_dparam(
                options_of(settings)?,
                crate::FC3D_DPARAM_TIME_BUDGET,
                seconds,
            )
        },
    )
}

/// The local solver of NSGS (internal solver 0), by Siconos id (550-565, 570-572), with its
/// defaults.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_local_solver(
    settings: *mut Fc3dSettings,
    local_solver_id: c_int,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_local_solver",
        |c| c,
        || set_local_solver(settings, local_solver_id),
    )
}

unsafe fn set_local_solver(settings: *mut Fc3dSettings, local_solver_id: c_int) -> CResult<c_int> {
    if LocalSolverKind::from_siconos_id(local_solver_id).is_none() {
        return Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("{local_solver_id} is not a local (one-contact) solver id"),
        ));
    }
    set_internal_solver(settings, local_solver_id)
}

/// Internal solver 0, by Siconos id, with its defaults: NSGS's local solver, PROX's NSN_AC (504)
/// or NSGS (500), the Tresca sub-problem solver of TFP and PFP (500, 566, 567). Refused (the
/// settings unchanged) when the solver cannot use it.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_internal_solver(
    settings: *mut Fc3dSettings,
    internal_solver_id: c_int,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_internal_solver",
        |c| c,
        || set_internal_solver(settings, internal_solver_id),
    )
}

unsafe fn set_internal_solver(settings: *mut Fc3dSettings, id: c_int) -> CResult<c_int> {
    let o = options_of(settings)?;
    // The new internal solver's options: its defaults, or (566, 567: sub-problem solvers without
    // options of their own) NSGS' defaults under its id, as a Siconos host builds them.
    let fresh = match create_options(id) {
        Ok(f) => f,
        Err(_) => {
            let f = create_options(500)?;
            (*f).solverId = id;
            f
        }
    };
    if o.numberOfInternalSolvers == 0 || o.internalSolvers.is_null() {
        // Only PFP is created without the internal solver it can take: give it its slot.
        if o.solverId != 522 {
            release_options(fresh);
            return Err(CError::new(
                FC3D_ERR_INVALID_OPTION,
                format!("solver {} has no local or internal solver", o.solverId),
            ));
        }
        let slots = c_calloc::<*mut SolverOptions>(1).inspect_err(|_| release_options(fresh))?;
        if !o.internalSolvers.is_null() {
            c_free(o.internalSolvers);
        }
        o.internalSolvers = slots;
        o.numberOfInternalSolvers = 1;
    }
    // PFP created with Siconos' two internal solvers: 202 PGS is the normal part's (slot 0),
    // 1200/1201 the tangent part's (slot 1); any other solver becomes its single one.
    let index = match (o.solverId, o.numberOfInternalSolvers, id) {
        (522, 2, 1200 | 1201) => 1,
        (522, 2, 202) => 0,
        (522, 2, _) => return set_pfp_single_internal_solver(o, fresh, id),
        _ => 0,
    };
    let slot = o.internalSolvers.add(index);
    let previous = *slot;
    *slot = fresh;
    if let Err(e) = check_settings(o) {
        *slot = previous;
        release_options(fresh);
        return Err(internal_solver_refused(o, id, e));
    }
    if !previous.is_null() {
        release_options(previous);
    }
    Ok(0)
}

/// `FC3D_ERR_INVALID_OPTION` for an internal solver `id` that `o`'s solver cannot use.
fn internal_solver_refused(o: &SolverOptions, id: c_int, e: CError) -> CError {
    CError::new(
        FC3D_ERR_INVALID_OPTION,
        format!(
            "internal solver {id} cannot be used by solver {}: {}",
            o.solverId, e.message
        ),
    )
}

/// PFP with Siconos' two internal solvers given another one (the Tresca solvers of fc3d 0.2's
/// layout: 500, 567, ...): it becomes PFP's single internal solver. On failure the options are
/// left as they were.
unsafe fn set_pfp_single_internal_solver(
    o: &mut SolverOptions,
    fresh: *mut SolverOptions,
    id: c_int,
) -> CResult<c_int> {
    let single = c_calloc::<*mut SolverOptions>(1).inspect_err(|_| release_options(fresh))?;
    *single = fresh;
    let (pair, count) = (o.internalSolvers, o.numberOfInternalSolvers);
    o.internalSolvers = single;
    o.numberOfInternalSolvers = 1;
    if let Err(e) = check_settings(o) {
        o.internalSolvers = pair;
        o.numberOfInternalSolvers = count;
        c_free(single);
        release_options(fresh);
        return Err(internal_solver_refused(o, id, e));
    }
    for k in 0..count {
        let previous = *pair.add(k);
        if !previous.is_null() {
            release_options(previous);
        }
    }
    c_free(pair);
    Ok(0)
}

/// Siconos' `iparam[index]` of the solver (index 0..OPTIONS_PARAM_SIZE).
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_iparam(
    settings: *mut Fc3dSettings,
    index: c_int,
    value: c_int,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_iparam",
        |c| c,
        || set_iparam(options_of(settings)?, index, value),
    )
}

/// Siconos' `dparam[index]` of the solver.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_dparam(
    settings: *mut Fc3dSettings,
    index: c_int,
    value: c_double,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_dparam",
        |c| c,
        || set_dparam(options_of(settings)?, index, value),
    )
}

/// `iparam[index]` of the local (internal) solver.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_local_iparam(
    settings: *mut Fc3dSettings,
    index: c_int,
    value: c_int,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_local_iparam",
        |c| c,
        || set_iparam(local_of(settings)?, index, value),
    )
}

/// `dparam[index]` of the local (internal) solver.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set_local_dparam(
    settings: *mut Fc3dSettings,
    index: c_int,
    value: c_double,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set_local_dparam",
        |c| c,
        || set_dparam(local_of(settings)?, index, value),
    )
}

/// A setting by name, for bindings: `tolerance`, `max_iter`, `time_budget`, `local_solver`,
/// `internal_solver`, `iparam[K]`, `dparam[K]`, `local_iparam[K]`, `local_dparam[K]` (the last
/// two: internal solver 0). Integer settings take an
/// integral `value`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_settings_set(
    settings: *mut Fc3dSettings,
    name: *const c_char,
    value: c_double,
) -> c_int {
    ffi_guard(
        "fc3d_settings_set",
        |c| c,
        || {
            if name.is_null() {
                return Err(CError::null("name"));
            }
            let name = CStr::from_ptr(name).to_string_lossy();
            let integer = || -> CResult<c_int> {
                if value.fract() != 0.0 || value.is_nan() {
                    Err(CError::new(
                        FC3D_ERR_INVALID_OPTION,
                        format!("{name} = {value} must be an integer"),
                    ))
                } else if value < c_int::MIN as f64 || value > c_int::MAX as f64 {
                    Err(CError::new(
                        FC3D_ERR_INVALID_OPTION,
                        format!("{name} = {value} is outside the range of a C int"),
                    ))
                } else {
                    Ok(value as c_int)
                }
            };
            let indexed = |prefix: &str| -> Option<CResult<c_int>> {
                let rest = name
                    .strip_prefix(prefix)?
                    .strip_prefix('[')?
                    .strip_suffix(']')?;
                Some(rest.trim().parse::<c_int>().map_err(|_| {
                    CError::new(FC3D_ERR_INVALID_OPTION, format!("bad index in '{name}'"))
                }))
            };
            match name.as_ref() {
                "tolerance" => set_dparam(options_of(settings)?, 0, value),
                "max_iter" => set_max_iter(settings, i64::from(integer()?)),
                "time_budget" => {
                    set_dparam(options_of(settings)?, crate::FC3D_DPARAM_TIME_BUDGET, value)
                }
                "local_solver" => set_local_solver(settings, integer()?),
                "internal_solver" => set_internal_solver(settings, integer()?),
                _ => {
                    if let Some(k) = indexed("local_iparam") {
                        set_iparam(local_of(settings)?, k?, integer()?)
                    } else if let Some(k) = indexed("local_dparam") {
                        set_dparam(local_of(settings)?, k?, value)
                    } else if let Some(k) = indexed("iparam") {
                        set_iparam(options_of(settings)?, k?, integer()?)
                    } else if let Some(k) = indexed("dparam") {
                        set_dparam(options_of(settings)?, k?, value)
                    } else {
                        Err(CError::new(
                        FC3D_ERR_INVALID_OPTION,
                        format!("unknown setting '{name}' (tolerance, max_iter, time_budget, local_solver, internal_solver, iparam[K], dparam[K], local_iparam[K], local_dparam[K])"),
                    ))
                    }
                }
            }
        },
    )
}
