//! The shim's functions (shim/fc3d_mpi_shim.c) and MPI's C types for this MPI.

use std::ffi::{c_char, c_int, c_void};

include!(concat!(env!("OUT_DIR"), "/mpi_types.rs"));

extern "C" {
    pub fn fc3d_mpi_shim_dup(host: *const MpiComm, out: *mut *mut c_void) -> c_int;
    pub fn fc3d_mpi_shim_free(comm: *mut c_void);
    pub fn fc3d_mpi_shim_rank_size(comm: *mut c_void, rank: *mut c_int, size: *mut c_int) -> c_int;
    pub fn fc3d_mpi_shim_allreduce_i64(
        comm: *mut c_void,
        v: *mut i64,
        n: c_int,
        op: c_int,
    ) -> c_int;
    pub fn fc3d_mpi_shim_bcast(
        comm: *mut c_void,
        buf: *mut c_void,
        bytes: c_int,
        root: c_int,
    ) -> c_int;
    pub fn fc3d_mpi_shim_alltoall_i64(comm: *mut c_void, send: *const i64, recv: *mut i64)
        -> c_int;
    pub fn fc3d_mpi_shim_alltoallv_i64(
        comm: *mut c_void,
        send: *const i64,
        send_counts: *const c_int,
        send_displs: *const c_int,
        recv: *mut i64,
        recv_counts: *const c_int,
        recv_displs: *const c_int,
    ) -> c_int;
    pub fn fc3d_mpi_shim_requests(n: c_int) -> *mut c_void;
    pub fn fc3d_mpi_shim_requests_free(requests: *mut c_void);
    pub fn fc3d_mpi_shim_irecv(
        comm: *mut c_void,
        buf: *mut i64,
        n: c_int,
        source: c_int,
        tag: c_int,
        requests: *mut c_void,
        k: c_int,
    ) -> c_int;
    pub fn fc3d_mpi_shim_isend(
        comm: *mut c_void,
        buf: *const i64,
        n: c_int,
        dest: c_int,
        tag: c_int,
        requests: *mut c_void,
        k: c_int,
    ) -> c_int;
    pub fn fc3d_mpi_shim_waitall(requests: *mut c_void, first: c_int, n: c_int) -> c_int;
    pub fn fc3d_mpi_shim_f2c(fortran: MpiFint, out: *mut MpiComm);
    pub fn fc3d_mpi_shim_error_string(code: c_int, text: *mut c_char, capacity: c_int);
    pub fn fc3d_mpi_shim_init() -> c_int;
    pub fn fc3d_mpi_shim_world(out: *mut MpiComm);
    pub fn fc3d_mpi_shim_finalize() -> c_int;
    pub fn fc3d_mpi_shim_thread_cpu_seconds() -> f64;
}
