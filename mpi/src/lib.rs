//! libfc3d_mpi: fc3d's NSGS distributed over a host's MPI communicator (header
//! `include/fc3d_mpi.h`). Each rank gives the block rows of its own contacts, with global contact
//! ids; the default sweep is Gauss-Seidel over the colours of the global contact graph, whose
//! results are the same bits for any number of ranks and any partition (docs/mpi.md).
//!
//! MPI is reached through a thin C shim (shim/fc3d_mpi_shim.c) compiled with the MPI compiler
//! wrapper's flags: no bindings generator at build time, and `MPI_Comm` keeps the ABI of the
//! installed `mpi.h` (a pointer in Open MPI, an int in MPICH). The library carries fc3d's
//! native entry (`fc3d_settings_*`, `fc3d_last_error_*`): a host links `-lfc3d_mpi` alone.
//!
//! Every entry is collective over its communicator, runs inside fc3d's panic boundary, and
//! fails collectively: input rejected on one rank gives every rank the same negative code and
//! message (naming the rank), nobody is left waiting in an exchange, and nothing is written.
#![cfg(not(fc3d_no_mpi))]

pub mod comm;
pub mod exact;
pub mod ffi;
mod halo;
pub mod input;
pub mod layout;
pub mod problems;
pub mod solver;

use std::ffi::c_int;
use std::ptr::null_mut;

use comm::{guarded, Comm};
use fc3d::{ffi_guard, CError, CResult, Fc3dResult, Fc3dSettings, FC3D_ERR_INVALID_OPTION};
use fc3d_core::error::try_vec;
use ffi::{MpiComm, MpiFint};
use layout::Mode;
use solver::DistributedSolver;

pub use comm::FC3D_MPI_ERR_COMMUNICATION;
/// The reproducible sweep (default): the same bits for any number of ranks and any partition.
pub const FC3D_MPI_REPRODUCIBLE: c_int = 0;
/// Gauss-Seidel inside each rank, Jacobi across ranks: one exchange per sweep, results depend
/// on the partition.
pub const FC3D_MPI_FAST: c_int = 1;

/// A distributed solver kept across time steps (opaque): fc3d's duplicate of the host's
/// communicator, the sweep mode, and the set-up of the last pattern.
pub struct Fc3dMpiSolver {
    inner: DistributedSolver,
}

/// What `fc3d_mpi_solver_stats` reports, for this rank.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct Fc3dMpiStats {
    pub ranks: c_int,
    /// FC3D_MPI_REPRODUCIBLE or FC3D_MPI_FAST.
    pub mode: c_int,
    /// Colours of the global contact graph (1 in the fast mode).
    pub colours: i64,
    /// Rounds the parallel colouring took.
    pub colouring_rounds: i64,
    /// This rank's contacts, and all ranks'.
    pub contacts: i64,
    pub total_contacts: i64,
    /// Other ranks' contacts this rank reads (received once per sweep).
    pub ghosts: i64,
    /// This rank's contacts other ranks read (sent once per sweep).
    pub boundary: i64,
    /// Ranks this one exchanges with.
    pub neighbours: i64,
    /// Messages and bytes this rank sends per sweep.
    pub messages_per_sweep: i64,
    pub bytes_per_sweep: i64,
    /// Set-ups built and solves done by this solver; sweeps of the last solve.
    pub setups: i64,
    pub solves: i64,
    pub sweeps: i64,
    /// Seconds of the last set-up; of the last solve's sweeps and error measures on this rank
    /// (compute), and of its waits in MPI (halo messages, reductions).
    pub seconds_setup: f64,
    pub seconds_compute: f64,
    pub seconds_wait: f64,
    /// CPU seconds of that compute (below its wall time when other processes share the core).
    pub cpu_seconds_compute: f64,
}

fn mode_of(mode: c_int) -> CResult<Mode> {
    match mode {
        FC3D_MPI_REPRODUCIBLE => Ok(Mode::Reproducible),
        FC3D_MPI_FAST => Ok(Mode::Fast),
        m => Err(CError::new(
            FC3D_ERR_INVALID_OPTION,
            format!("mode {m} is neither FC3D_MPI_REPRODUCIBLE (0) nor FC3D_MPI_FAST (1)"),
        )),
    }
}

/// A solver over `comm` (collective): the communicator duplicated, the mode checked on every
/// rank.
unsafe fn new_solver(comm: *const MpiComm, mode: c_int) -> CResult<DistributedSolver> {
    let comm = Comm::duplicate(comm)?;
    let mode = comm.agree(mode_of(mode))?;
    Ok(DistributedSolver::new(comm, mode))
}

/// The collective solve of every entry: one rank's arguments checked, the checks agreed on,
/// then the distributed run; r, u and result written only on success.
#[allow(clippy::too_many_arguments)]
unsafe fn solve_with(
    solver: &mut DistributedSolver,
    n_local: i64,
    contact_ids: *const i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_ids: *const i64,
    blocks: *const f64,
    q: *const f64,
    mu: *const f64,
    r: *mut f64,
    u: *mut f64,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> CResult<c_int> {
    let checked = guarded(|| {
        let rows = input::read_rows(
            n_local,
            contact_ids,
            n_blocks,
            block_row_ptr,
            block_col_ids,
            blocks,
            q,
            mu,
            r,
            u,
        )?;
        let settings = input::run_settings(settings)?;
        if result.is_null() {
            return Err(CError::new(fc3d::FC3D_ERR_NULL_POINTER, "result is NULL"));
        }
        // The results are written only at the end: their copies, allocated fallibly now so that
        // a failure is agreed on like bad input.
        let n3 = 3 * rows.n_local();
        let outputs = (try_vec(n3, 0.0, "r")?, try_vec(n3, 0.0, "u")?);
        Ok((rows, settings, outputs))
    });
    let (rows, settings, (mut r_out, mut u_out)) = solver.comm.agree(checked)?;
    let n3 = 3 * rows.n_local();
    let outcome = solver.solve(&rows, &settings, &mut r_out, &mut u_out)?;
    if n3 > 0 {
        std::ptr::copy_nonoverlapping(r_out.as_ptr(), r, n3);
        std::ptr::copy_nonoverlapping(u_out.as_ptr(), u, n3);
    }
    *result = Fc3dResult {
        info: outcome.info,
        iterations: outcome.iterations as i64,
        error: outcome.error,
        seconds: outcome.seconds,
    };
    Ok(outcome.info)
}

/// Solves FC(W, q, mu) distributed over `comm` (collective), with NSGS in the reproducible
/// mode: each rank gives its `n_local` contacts' global ids and their block rows (columns by
/// global id), q, mu and the warm start r, and receives its part of r and u = W r + q. The
/// result (info, sweeps, error of the whole problem) is the same on every rank.
///
/// # Safety
/// `comm` is a valid communicator; non-NULL pointers point to arrays of the given sizes.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solve_blocks(
    comm: MpiComm,
    n_local: i64,
    contact_ids: *const i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_ids: *const i64,
    blocks: *const f64,
    q: *const f64,
    mu: *const f64,
    r: *mut f64,
    u: *mut f64,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_mpi_solve_blocks",
        |c| c,
        || {
            let mut solver = new_solver(&comm, FC3D_MPI_REPRODUCIBLE)?;
            solve_with(
                &mut solver,
                n_local,
                contact_ids,
                n_blocks,
                block_row_ptr,
                block_col_ids,
                blocks,
                q,
                mu,
                r,
                u,
                settings,
                result,
            )
        },
    )
}

/// `fc3d_mpi_solve_blocks` for Fortran hosts: the communicator as its Fortran INTEGER handle
/// (`MPI_COMM_WORLD` of `use mpi`), passed by value.
///
/// # Safety
/// As `fc3d_mpi_solve_blocks`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solve_blocks_f(
    comm: MpiFint,
    n_local: i64,
    contact_ids: *const i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_ids: *const i64,
    blocks: *const f64,
    q: *const f64,
    mu: *const f64,
    r: *mut f64,
    u: *mut f64,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    let mut c: MpiComm = std::mem::zeroed();
    ffi::fc3d_mpi_shim_f2c(comm, &mut c);
    fc3d_mpi_solve_blocks(
        c,
        n_local,
        contact_ids,
        n_blocks,
        block_row_ptr,
        block_col_ids,
        blocks,
        q,
        mu,
        r,
        u,
        settings,
        result,
    )
}

/// A solver over `comm` for a sequence of solves (collective; NULL on every rank on failure):
/// its set-up (directory, ghosts, colouring, message schedule) is kept while every rank's
/// contact ids and block pattern stay the same. `mode`: `FC3D_MPI_REPRODUCIBLE` or
/// `FC3D_MPI_FAST`. Release with `fc3d_mpi_solver_free` (collective).
///
/// # Safety
/// `comm` is a valid communicator.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solver_new(comm: MpiComm, mode: c_int) -> *mut Fc3dMpiSolver {
    ffi_guard(
        "fc3d_mpi_solver_new",
        |_| null_mut(),
        || {
            let inner = new_solver(&comm, mode)?;
            Ok(Box::into_raw(Box::new(Fc3dMpiSolver { inner })))
        },
    )
}

/// `fc3d_mpi_solver_new` with the communicator's Fortran handle.
///
/// # Safety
/// As `fc3d_mpi_solver_new`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solver_new_f(comm: MpiFint, mode: c_int) -> *mut Fc3dMpiSolver {
    let mut c: MpiComm = std::mem::zeroed();
    ffi::fc3d_mpi_shim_f2c(comm, &mut c);
    fc3d_mpi_solver_new(c, mode)
}

/// Solves with a solver made by `fc3d_mpi_solver_new`: the arguments and results of
/// `fc3d_mpi_solve_blocks` (collective over the solver's communicator).
///
/// # Safety
/// `solver` was made by `fc3d_mpi_solver_new` and not freed; arrays as in
/// `fc3d_mpi_solve_blocks`.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solver_solve(
    solver: *mut Fc3dMpiSolver,
    n_local: i64,
    contact_ids: *const i64,
    n_blocks: i64,
    block_row_ptr: *const i64,
    block_col_ids: *const i64,
    blocks: *const f64,
    q: *const f64,
    mu: *const f64,
    r: *mut f64,
    u: *mut f64,
    settings: *const Fc3dSettings,
    result: *mut Fc3dResult,
) -> c_int {
    ffi_guard(
        "fc3d_mpi_solver_solve",
        |c| c,
        || {
            if solver.is_null() {
                return Err(CError::new(fc3d::FC3D_ERR_NULL_POINTER, "solver is NULL"));
            }
            solve_with(
                &mut (*solver).inner,
                n_local,
                contact_ids,
                n_blocks,
                block_row_ptr,
                block_col_ids,
                blocks,
                q,
                mu,
                r,
                u,
                settings,
                result,
            )
        },
    )
}

/// This rank's statistics of the solver's set-up and last solve (not collective). Returns 0,
/// or a negative code (NULL arguments; nothing written).
///
/// # Safety
/// `solver` was made by `fc3d_mpi_solver_new` and not freed; `stats` points to a struct.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solver_stats(
    solver: *const Fc3dMpiSolver,
    stats: *mut Fc3dMpiStats,
) -> c_int {
    ffi_guard(
        "fc3d_mpi_solver_stats",
        |c| c,
        || {
            if solver.is_null() || stats.is_null() {
                let what = if solver.is_null() { "solver" } else { "stats" };
                return Err(CError::new(
                    fc3d::FC3D_ERR_NULL_POINTER,
                    format!("{what} is NULL"),
                ));
            }
            *stats = statistics_of(&(*solver).inner);
            Ok(0)
        },
    )
}

/// The statistics of a solver (also for Rust hosts).
pub fn statistics_of(s: &DistributedSolver) -> Fc3dMpiStats {
    let st = &s.statistics;
    let mut out = Fc3dMpiStats {
        ranks: s.comm.size() as c_int,
        mode: s.mode.code(),
        setups: st.setups as i64,
        solves: st.solves as i64,
        sweeps: st.sweeps as i64,
        seconds_setup: st.seconds_setup,
        seconds_compute: st.seconds_compute,
        seconds_wait: st.seconds_wait,
        cpu_seconds_compute: st.cpu_seconds_compute,
        ..Default::default()
    };
    if let Some((layout, halo)) = s.layout() {
        let (messages, bytes) = halo.sent_per_sweep();
        let boundary: usize = layout.steps.iter().map(|c| c.boundary.len()).sum();
        out.colours = layout.colours as i64;
        out.colouring_rounds = layout.colouring_rounds as i64;
        out.contacts = layout.known_of_host.len() as i64;
        out.total_contacts = layout.total_contacts;
        out.ghosts = halo.ghosts_received() as i64;
        out.boundary = boundary as i64;
        out.neighbours = halo.neighbours() as i64;
        out.messages_per_sweep = messages as i64;
        out.bytes_per_sweep = bytes as i64;
    }
    out
}

/// Releases a solver (collective over its communicator: the duplicate is freed). NULL is
/// accepted.
///
/// # Safety
/// `solver` was made by `fc3d_mpi_solver_new` and not freed.
#[no_mangle]
pub unsafe extern "C" fn fc3d_mpi_solver_free(solver: *mut Fc3dMpiSolver) {
    ffi_guard(
        "fc3d_mpi_solver_free",
        |_| (),
        || {
            if !solver.is_null() {
                drop(Box::from_raw(solver));
            }
            Ok(())
        },
    )
}
