//! The native entry: solve from plain arrays, with names Siconos does not use (`fc3d_settings_*`,
//! `fc3d_solve_*`, `fc3d_problem_*`, `fc3d_version`), so a host can link Siconos beside fc3d's
//! native-only build (`libfc3d_native`, header `fc3d_native.h`). The Fortran, Python and Julia
//! bindings call this entry.
//!
//! Ownership: `fc3d_settings_new` and `fc3d_problem_read` return handles the caller releases with
//! `fc3d_settings_free` / `fc3d_problem_free`; every array is the caller's, read or written in
//! place. Sizes and indices are `int64_t`; W's entries are copied into fc3d's storage. On a
//! negative return nothing is written (r, u, result and the settings stay as they were).

use std::ffi::{c_char, CStr};
use std::os::raw::{c_double, c_int};
use std::ptr::null_mut;
use std::time::Instant;

use crate::alloc::{c_calloc, c_free};
use crate::matrix::c_slice;
use crate::option_tree::delete_contents;
use crate::options::create_options;
use crate::params::{config_from_c, OPTIONS_PARAM_SIZE};
use crate::types::SolverOptions;
use crate::{
    ffi_guard, verbose, CError, CResult, FC3D_ERR_INVALID_OPTION, FC3D_ERR_INVALID_SIZE,
    FC3D_ERR_NULL_POINTER,
};
use fc3d_core::{
    solve, BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix, FrictionProblem, LocalSolverKind,
};

/// A solver and its settings (opaque): Siconos' options of a solver id, changed by the setters.
pub struct Fc3dSettings {
    options: *mut SolverOptions,
}

/// A problem read from a file (opaque), with W also kept in compressed rows for
/// `fc3d_problem_get`.
pub struct Fc3dProblem {
    problem: FrictionProblem<'static>,
    csr: CsrMatrix,
}

/// What a solve reports.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct Fc3dResult {
    /// 0 converged, 1 iteration limit, 2 time budget spent, 3 relaxed solution not Coulomb.
    pub info: c_int,
    /// Iterations (sweeps, Newton steps, ...) done.
    pub iterations: i64,
    /// The natural-map error of the returned `(r, u)`.
    pub error: c_double,
    /// Wall-clock time of the solve, seconds.
    pub seconds: c_double,
}

/// The library's version, e.g. "0.2.0" (a static string, do not free).
#[no_mangle]
pub extern "C" fn fc3d_version() -> *const c_char {
    ffi_guard(
        "fc3d_version",
        |_| concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast(),
        || Ok(concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()),
    )
}

// ---------------------------------------------------------------------------------------------
// Settings.

/// Settings of solver `solver_id` (a Siconos id such as 500 NSGS, 504 NSN_AC, 502 PROX) with
/// its defaults; NULL for an id fc3d does not implement (the reason in
/// `fc3d_last_error_message`). Release with `fc3d_settings_free`.
#[no_mangle]
pub extern "C" fn fc3d_settings_new(solver_id: c_int) -> *mut Fc3dSettings {
    ffi_guard(
        "fc3d_settings_new",
        |_| null_mut(),
        || {
            let options = create_options(solver_id)?;
            // Reject ids fc3d only names (their defaults exist for Siconos' API).
            if let Err(e) = unsafe { config_from_c(&*options) } {
                unsafe { release_options(options) };
                return Err(e);
            }
            Ok(Box::into_raw(Box::new(Fc3dSettings { options })))
        },
    )
}

unsafe fn release_options(options: *mut SolverOptions) {
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
    if let Err(e) = config_from_c(o) {
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
    if let Err(e) = config_from_c(o) {
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

// ---------------------------------------------------------------------------------------------
// Solving.

fn count(v: i64, what: &str) -> CResult<usize> {
    usize::try_from(v)
        .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, format!("{what} = {v} is negative")))
}

/// `3 n_contacts`, checked.
fn size_of(n_contacts: i64) -> CResult<(usize, usize)> {
    let nc = count(n_contacts, "n_contacts")?;
    let n = nc.checked_mul(3).ok_or_else(|| {
        CError::new(
            FC3D_ERR_INVALID_SIZE,
            format!("n_contacts = {nc} is too large"),
        )
    })?;
    Ok((nc, n))
}

fn indices(v: &[i64], what: &str) -> CResult<Vec<usize>> {
    v.iter().map(|&x| count(x, what)).collect()
}

/// Solves `problem` from `r` with `settings` (NULL: NSGS with Siconos' defaults), writing r, u
/// and the result only on success.
unsafe fn solve_into(
    problem: &FrictionProblem<'_>,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> CResult<c_int> {
    if result.is_null() {
        return Err(CError::null("result"));
    }
    let n = problem.size();
    let r_in = c_slice(r as *const c_double, n, "r")?;
    c_slice(u as *const c_double, n, "u")?;
    let config = if settings.is_null() {
        let o = create_options(500)?;
        let c = config_from_c(&*o);
        release_options(o);
        c?
    } else {
        config_from_c(&*(*settings).options)?
    };
    let mut rr = r_in.to_vec();
    let mut uu = vec![0.0; n];
    let start = Instant::now();
    let report = solve(problem, &config, &mut rr, &mut uu)?;
    let seconds = start.elapsed().as_secs_f64();
    if n > 0 {
        std::ptr::copy_nonoverlapping(rr.as_ptr(), r, n);
        std::ptr::copy_nonoverlapping(uu.as_ptr(), u, n);
    }
    *result = Fc3dResult {
        info: report.status.info_code(),
        iterations: i64::try_from(report.iterations).unwrap_or(i64::MAX),
        error: report.error,
        seconds,
    };
    if verbose() > 0 {
        eprintln!(
            "fc3d: {} on {} contacts: {:?} after {} iterations, error {:e}",
            config.label(),
            problem.n_contacts(),
            report.status,
            report.iterations,
            report.error
        );
        super::driver::print_fill(&report);
    }
    Ok(report.status.info_code())
}

unsafe fn problem_from(
    w: Delassus<'static>,
    nc: usize,
    q: *const c_double,
    mu: *const c_double,
) -> CResult<FrictionProblem<'static>> {
    let q = c_slice(q, 3 * nc, "q")?.to_vec();
    let mu = c_slice(mu, nc, "mu")?.to_vec();
    Ok(FrictionProblem::new(w, q, mu)?)
}

/// Solves FC(W, q, mu) with W dense, column-major `3nc x 3nc`. `r` holds the initial reaction and
/// receives the result, `u` receives `W r + q`; `settings` may be NULL (NSGS, Siconos'
/// defaults). Returns the result's `info` (0..3) or a negative `FC3D_ERR_*` code.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_dense(
    n_contacts: i64,
    w: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_dense",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let len = n.checked_mul(n).ok_or_else(|| {
                CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("a dense W of {n} rows is too large"),
                )
            })?;
            let values = c_slice(w, len, "W")?.to_vec();
            let w = Delassus::Dense(DenseMatrix::new(n, n, values)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W in compressed rows: `row_ptr` (`3nc + 1` entries), `col_idx`
/// and `values` (`nnz` entries each, 0-based; unsorted columns and duplicates are accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_csr(
    n_contacts: i64,
    nnz: i64,
    row_ptr: *const i64,
    col_idx: *const i64,
    values: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_csr",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let nnz = count(nnz, "nnz")?;
            let row_ptr = indices(c_slice(row_ptr, n + 1, "row_ptr")?, "row_ptr")?;
            let col_idx = indices(c_slice(col_idx, nnz, "col_idx")?, "col_idx")?;
            let values = c_slice(values, nnz, "values")?;
            if row_ptr[n] != nnz {
                return Err(CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("row_ptr[{n}] = {} but nnz = {nnz}", row_ptr[n]),
                ));
            }
            let w = Delassus::Sparse(CsrMatrix::from_csr(n, n, &row_ptr, &col_idx, values)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W as `nnz` triplets `(rows[k], cols[k], values[k])` (0-based, any
/// order, duplicates summed).
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_coo(
    n_contacts: i64,
    nnz: i64,
    rows: *const i64,
    cols: *const i64,
    values: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_coo",
        |c| c,
        || {
            let (nc, n) = size_of(n_contacts)?;
            let nnz = count(nnz, "nnz")?;
            let rows = indices(c_slice(rows, nnz, "rows")?, "rows")?;
            let cols = indices(c_slice(cols, nnz, "cols")?, "cols")?;
            let values = c_slice(values, nnz, "values")?;
            let triplets: Vec<(usize, usize, f64)> = rows
                .iter()
                .zip(&cols)
                .zip(values)
                .map(|((&i, &j), &v)| (i, j, v))
                .collect();
            let w = Delassus::Sparse(CsrMatrix::from_triplets(n, n, &triplets)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

/// As `fc3d_solve_dense` with W as `n_blocks` 3x3 blocks in block-compressed rows:
/// `block_row_ptr` (`nc + 1` entries), `block_col_idx` (`n_blocks`, 0-based) and `blocks`
/// (`9 n_blocks` values, each block column-major). Every diagonal block must be present.
#[no_mangle]
pub unsafe extern "C" fn fc3d_solve_blocks(
    n_contacts: i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_idx: *const i64,
    blocks: *const c_double,
    q: *const c_double,
    mu: *const c_double,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_solve_blocks",
        |c| c,
        || {
            let (nc, _) = size_of(n_contacts)?;
            let nb = count(n_blocks, "n_blocks")?;
            let row_ptr = indices(
                c_slice(block_row_ptr, nc + 1, "block_row_ptr")?,
                "block_row_ptr",
            )?;
            let col_idx = indices(
                c_slice(block_col_idx, nb, "block_col_idx")?,
                "block_col_idx",
            )?;
            let len = nb.checked_mul(9).ok_or_else(|| {
                CError::new(
                    FC3D_ERR_INVALID_SIZE,
                    format!("n_blocks = {nb} is too large"),
                )
            })?;
            let values = c_slice(blocks, len, "blocks")?;
            let blocks: Vec<[f64; 9]> = values
                .chunks_exact(9)
                .map(|b| {
                    let mut a = [0.0; 9];
                    a.copy_from_slice(b);
                    a
                })
                .collect();
            let w =
                Delassus::SparseBlock(BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)?);
            let p = problem_from(w, nc, q, mu)?;
            solve_into(&p, r, u, settings, result)
        },
    )
}

// ---------------------------------------------------------------------------------------------
// Problems read from files.

/// Reads a Siconos `.dat` problem (or FCLIB `.hdf5` when fc3d is built with FCLIB); NULL on
/// failure. Release with `fc3d_problem_free`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_read(path: *const c_char) -> *mut Fc3dProblem {
    ffi_guard(
        "fc3d_problem_read",
        |_| null_mut(),
        || {
            if path.is_null() {
                return Err(CError::null("path"));
            }
            let path = CStr::from_ptr(path).to_string_lossy().into_owned();
            let problem = fc3d_core::io::read_problem_file(std::path::Path::new(&path))?;
            let csr = problem.w().to_csr();
            Ok(Box::into_raw(Box::new(Fc3dProblem { problem, csr })))
        },
    )
}

/// Releases a problem read by `fc3d_problem_read` (NULL is accepted).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_free(problem: *mut Fc3dProblem) {
    ffi_guard(
        "fc3d_problem_free",
        |_| (),
        || {
            if !problem.is_null() {
                drop(Box::from_raw(problem));
            }
            Ok(())
        },
    )
}

unsafe fn problem_ref<'a>(problem: *const Fc3dProblem) -> CResult<&'a Fc3dProblem> {
    problem
        .as_ref()
        .ok_or_else(|| CError::new(FC3D_ERR_NULL_POINTER, "problem is NULL"))
}

/// Number of contacts of the problem (-1 and the last error for NULL).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_contacts(problem: *const Fc3dProblem) -> i64 {
    ffi_guard(
        "fc3d_problem_contacts",
        |_| -1,
        || Ok(problem_ref(problem)?.problem.n_contacts() as i64),
    )
}

/// Number of stored entries of W in compressed rows (-1 for NULL).
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_nnz(problem: *const Fc3dProblem) -> i64 {
    ffi_guard(
        "fc3d_problem_nnz",
        |_| -1,
        || Ok(problem_ref(problem)?.csr.nnz() as i64),
    )
}

/// Copies the problem into the caller's arrays: W in compressed rows (`row_ptr`: `3nc + 1`,
/// `col_idx` and `values`: `fc3d_problem_nnz` entries), `q` (`3nc`), `mu` (`nc`). Returns 0.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_get(
    problem: *const Fc3dProblem,
    row_ptr: *mut i64,
    col_idx: *mut i64,
    values: *mut c_double,
    q: *mut c_double,
    mu: *mut c_double,
) -> c_int {
    ffi_guard(
        "fc3d_problem_get",
        |c| c,
        || {
            let p = problem_ref(problem)?;
            let (n, nnz, nc) = (p.problem.size(), p.csr.nnz(), p.problem.n_contacts());
            c_slice(row_ptr as *const i64, n + 1, "row_ptr")?;
            c_slice(col_idx as *const i64, nnz, "col_idx")?;
            c_slice(values as *const c_double, nnz, "values")?;
            c_slice(q as *const c_double, n, "q")?;
            c_slice(mu as *const c_double, nc, "mu")?;
            for (k, &v) in p.csr.row_ptr().iter().enumerate() {
                *row_ptr.add(k) = v as i64;
            }
            for (k, &v) in p.csr.col_idx().iter().enumerate() {
                *col_idx.add(k) = v as i64;
            }
            if nnz > 0 {
                std::ptr::copy_nonoverlapping(p.csr.values().as_ptr(), values, nnz);
            }
            if n > 0 {
                std::ptr::copy_nonoverlapping(p.problem.q().as_ptr(), q, n);
                std::ptr::copy_nonoverlapping(p.problem.mu().as_ptr(), mu, nc);
            }
            Ok(0)
        },
    )
}

/// Solves a problem read by `fc3d_problem_read` in the storage of its file, as
/// `fc3d_solve_dense` does.
#[no_mangle]
pub unsafe extern "C" fn fc3d_problem_solve(
    problem: *const Fc3dProblem,
    r: *mut c_double,
    u: *mut c_double,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_problem_solve",
        |c| c,
        || {
            let p = problem_ref(problem)?;
            solve_into(&p.problem, r, u, settings, result)
        },
    )
}
