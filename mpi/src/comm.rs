//! fc3d's communicator (a duplicate of the host's) and the collective steps built on the shim:
//! reductions, the agreement on errors that makes every failure collective, and the exchange of
//! lists between all ranks used while setting up.

use std::ffi::{c_int, c_void};

use crate::ffi::{self, MpiComm};
use fc3d::{CError, CResult, FC3D_ERR_INTERNAL, FC3D_ERR_INVALID_SIZE};

/// An MPI call failed, or the communicator is unusable (MPI_COMM_NULL, MPI not initialised).
pub const FC3D_MPI_ERR_COMMUNICATION: c_int = -20;

/// Bytes of an error message carried to every rank (longer ones are cut).
const MESSAGE_BYTES: usize = 1024;

/// An MPI call that failed, named, with MPI's own explanation.
pub fn mpi_failure(call: &str, code: c_int) -> CError {
    let mut text = [0 as std::ffi::c_char; 512];
    // SAFETY: the buffer holds 512 bytes and the shim writes at most that, NUL included.
    unsafe { ffi::fc3d_mpi_shim_error_string(code, text.as_mut_ptr(), 512) };
    // SAFETY: NUL-terminated by the shim.
    let why = unsafe { std::ffi::CStr::from_ptr(text.as_ptr()) }.to_string_lossy();
    CError::new(
        FC3D_MPI_ERR_COMMUNICATION,
        format!("{call} failed (MPI error {code}: {why})"),
    )
}

fn check(call: &str, code: c_int) -> CResult<()> {
    if code == 0 {
        Ok(())
    } else {
        Err(mpi_failure(call, code))
    }
}

/// Runs `f` with panics caught as [`FC3D_ERR_INTERNAL`]: a rank that hits a bug still takes part
/// in the next agreement instead of leaving the others waiting.
pub fn guarded<T>(f: impl FnOnce() -> CResult<T>) -> CResult<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(CError::new(
                FC3D_ERR_INTERNAL,
                format!("internal error: {what}"),
            ))
        }
    }
}

/// CPU seconds of the calling thread.
pub fn thread_cpu_seconds() -> f64 {
    // SAFETY: no arguments; reads a clock.
    unsafe { ffi::fc3d_mpi_shim_thread_cpu_seconds() }
}

/// Reduction operators of [`Comm::allreduce`].
#[derive(Debug, Clone, Copy)]
pub enum Op {
    Sum = 0,
    Max = 1,
    Min = 2,
}

/// fc3d's own communicator: a duplicate of the host's (fc3d's messages never match the host's),
/// with MPI errors returned rather than fatal. Released (collectively) on drop.
pub struct Comm {
    raw: *mut c_void,
    rank: usize,
    size: usize,
}

impl Comm {
    /// Duplicates the host's communicator (collective).
    ///
    /// # Safety
    /// `host` points to a communicator handle of this MPI.
    pub unsafe fn duplicate(host: *const MpiComm) -> CResult<Comm> {
        let mut raw = std::ptr::null_mut();
        match ffi::fc3d_mpi_shim_dup(host, &mut raw) {
            0 => {}
            -1 => {
                return Err(CError::new(
                    FC3D_MPI_ERR_COMMUNICATION,
                    "the communicator is MPI_COMM_NULL",
                ))
            }
            -2 => {
                return Err(CError::new(
                    FC3D_MPI_ERR_COMMUNICATION,
                    "MPI is not initialised (or already finalised)",
                ))
            }
            e => return Err(mpi_failure("MPI_Comm_dup", e)),
        }
        let (mut rank, mut size) = (0, 0);
        // Released on drop if what follows fails.
        let mut comm = Comm {
            raw,
            rank: 0,
            size: 1,
        };
        check(
            "MPI_Comm_rank",
            ffi::fc3d_mpi_shim_rank_size(raw, &mut rank, &mut size),
        )?;
        comm.rank = rank as usize;
        comm.size = size as usize;
        Ok(comm)
    }

    pub fn rank(&self) -> usize {
        self.rank
    }

    pub fn size(&self) -> usize {
        self.size
    }

    pub(crate) fn raw(&self) -> *mut c_void {
        self.raw
    }

    /// Reduces `values` over the ranks, in place. Integer reductions are exact, so the result
    /// does not depend on the order MPI combines the ranks in.
    pub fn allreduce(&self, values: &mut [i64], op: Op) -> CResult<()> {
        let n = c_int::try_from(values.len()).expect("small reductions");
        // SAFETY: `values` holds n entries.
        check("MPI_Allreduce", unsafe {
            ffi::fc3d_mpi_shim_allreduce_i64(self.raw, values.as_mut_ptr(), n, op as c_int)
        })
    }

    /// The largest of a non-negative `f64` over the ranks (its bits order as the values do).
    pub fn max_f64(&self, v: f64) -> CResult<f64> {
        let mut bits = [v.max(0.0).to_bits() as i64];
        self.allreduce(&mut bits, Op::Max)?;
        Ok(f64::from_bits(bits[0] as u64))
    }

    fn bcast(&self, buffer: &mut [u8], root: usize) -> CResult<()> {
        let n = c_int::try_from(buffer.len()).expect("small broadcasts");
        // SAFETY: `buffer` holds n bytes.
        check("MPI_Bcast", unsafe {
            ffi::fc3d_mpi_shim_bcast(self.raw, buffer.as_mut_ptr().cast(), n, root as c_int)
        })
    }

    /// Makes a step collective: every rank returns `Ok` when every rank's `local` is `Ok`, and
    /// otherwise the error of the lowest failing rank (same code and message on every rank,
    /// the message naming that rank).
    pub fn agree<T>(&self, local: CResult<T>) -> CResult<T> {
        let mut first = [if local.is_err() {
            self.rank as i64
        } else {
            self.size as i64
        }];
        self.allreduce(&mut first, Op::Min)?;
        let root = first[0] as usize;
        if root >= self.size {
            return local;
        }
        let mut buffer = vec![0u8; 8 + MESSAGE_BYTES];
        if let Err(e) = &local {
            if self.rank == root {
                let mut text = e.message.as_bytes();
                if text.len() > MESSAGE_BYTES {
                    let mut cut = MESSAGE_BYTES;
                    while !e.message.is_char_boundary(cut) {
                        cut -= 1;
                    }
                    text = &text[..cut];
                }
                buffer[..4].copy_from_slice(&e.code.to_le_bytes());
                buffer[4..8].copy_from_slice(&(text.len() as u32).to_le_bytes());
                buffer[8..8 + text.len()].copy_from_slice(text);
            }
        }
        self.bcast(&mut buffer, root)?;
        let code = i32::from_le_bytes(buffer[..4].try_into().expect("4 bytes"));
        let len = u32::from_le_bytes(buffer[4..8].try_into().expect("4 bytes")) as usize;
        let message = String::from_utf8_lossy(&buffer[8..8 + len.min(MESSAGE_BYTES)]);
        let message = if self.size > 1 {
            format!("rank {root}: {message}")
        } else {
            message.into_owned()
        };
        Err(CError::new(code, message))
    }

    /// Sends `lists[p]` to rank p, for every p, and returns what each rank sent to this one
    /// (collective). Fails on every rank alike when a rank's lists exceed MPI's int counts.
    pub fn exchange(&self, lists: &[Vec<i64>]) -> CResult<Vec<Vec<i64>>> {
        let p = self.size;
        assert_eq!(lists.len(), p);
        let send_counts: Vec<i64> = lists.iter().map(|l| l.len() as i64).collect();
        let mut recv_counts = vec![0i64; p];
        // SAFETY: both arrays hold one entry per rank.
        check("MPI_Alltoall", unsafe {
            ffi::fc3d_mpi_shim_alltoall_i64(
                self.raw,
                send_counts.as_ptr(),
                recv_counts.as_mut_ptr(),
            )
        })?;
        let fits = |counts: &[i64]| counts.iter().sum::<i64>() <= i64::from(c_int::MAX);
        let sizes = if fits(&send_counts) && fits(&recv_counts) {
            Ok(())
        } else {
            Err(CError::new(
                FC3D_ERR_INVALID_SIZE,
                "a set-up exchange exceeds 2^31 words on one rank: use more ranks",
            ))
        };
        self.agree(sizes)?;
        let displs = |counts: &[i64]| -> Vec<c_int> {
            let mut at = 0;
            counts
                .iter()
                .map(|&c| {
                    let d = at;
                    at += c as c_int;
                    d
                })
                .collect()
        };
        let (sc, sd) = (
            send_counts.iter().map(|&c| c as c_int).collect::<Vec<_>>(),
            displs(&send_counts),
        );
        let (rc, rd) = (
            recv_counts.iter().map(|&c| c as c_int).collect::<Vec<_>>(),
            displs(&recv_counts),
        );
        let send: Vec<i64> = lists.concat();
        let mut recv = vec![0i64; recv_counts.iter().sum::<i64>() as usize];
        // SAFETY: counts and displacements describe `send` and `recv` exactly.
        check("MPI_Alltoallv", unsafe {
            ffi::fc3d_mpi_shim_alltoallv_i64(
                self.raw,
                send.as_ptr(),
                sc.as_ptr(),
                sd.as_ptr(),
                recv.as_mut_ptr(),
                rc.as_ptr(),
                rd.as_ptr(),
            )
        })?;
        Ok((0..p)
            .map(|q| recv[rd[q] as usize..(rd[q] + rc[q]) as usize].to_vec())
            .collect())
    }
}

impl Drop for Comm {
    fn drop(&mut self) {
        // SAFETY: made by fc3d_mpi_shim_dup, released once.
        unsafe { ffi::fc3d_mpi_shim_free(self.raw) }
    }
}

/// Pending nonblocking messages of one sweep, waited for by groups.
pub struct Requests {
    raw: *mut c_void,
    len: usize,
}

impl Requests {
    pub fn new(len: usize) -> CResult<Self> {
        let n = c_int::try_from(len)
            .map_err(|_| CError::new(FC3D_ERR_INVALID_SIZE, "too many messages per sweep"))?;
        // SAFETY: plain allocation by the shim.
        let raw = unsafe { ffi::fc3d_mpi_shim_requests(n) };
        if raw.is_null() {
            return Err(CError::new(
                fc3d::FC3D_ERR_OUT_OF_MEMORY,
                "MPI requests could not be allocated",
            ));
        }
        Ok(Requests { raw, len })
    }

    /// Posts the receive of `buffer` from `source` as request `k`.
    ///
    /// # Safety
    /// `buffer` stays valid and untouched until request `k` is waited for.
    pub unsafe fn receive(
        &mut self,
        comm: &Comm,
        buffer: &mut [f64],
        source: usize,
        tag: usize,
        k: usize,
    ) -> CResult<()> {
        assert!(k < self.len);
        check("MPI_Irecv", unsafe {
            ffi::fc3d_mpi_shim_irecv(
                comm.raw(),
                buffer.as_mut_ptr().cast(),
                buffer.len() as c_int,
                source as c_int,
                tag as c_int,
                self.raw,
                k as c_int,
            )
        })
    }

    /// Posts the send of `buffer` to `dest` as request `k`.
    ///
    /// # Safety
    /// `buffer` stays valid and unchanged until request `k` is waited for.
    pub unsafe fn send(
        &mut self,
        comm: &Comm,
        buffer: &[f64],
        dest: usize,
        tag: usize,
        k: usize,
    ) -> CResult<()> {
        assert!(k < self.len);
        check("MPI_Isend", unsafe {
            ffi::fc3d_mpi_shim_isend(
                comm.raw(),
                buffer.as_ptr().cast(),
                buffer.len() as c_int,
                dest as c_int,
                tag as c_int,
                self.raw,
                k as c_int,
            )
        })
    }

    /// Waits for requests `range`.
    pub fn wait(&mut self, range: std::ops::Range<usize>) -> CResult<()> {
        assert!(range.end <= self.len);
        if range.is_empty() {
            return Ok(());
        }
        // SAFETY: in bounds.
        check("MPI_Waitall", unsafe {
            ffi::fc3d_mpi_shim_waitall(self.raw, range.start as c_int, range.len() as c_int)
        })
    }
}

impl Drop for Requests {
    fn drop(&mut self) {
        // SAFETY: allocated by the shim; every request was waited for by its owner.
        unsafe { ffi::fc3d_mpi_shim_requests_free(self.raw) }
    }
}
