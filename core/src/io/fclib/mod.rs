//! FCLIB problem files (`.hdf5`), read and written through the system libhdf5 with `hdf5-metno`
//! (cargo feature `fclib`, off by default: it needs Debian's `libhdf5-dev` and `pkg-config`).
//!
//! # Layout
//!
//! An FCLIB file holds one of two groups (FCLIB 3, as written by `fclib_write_local/global` and by
//! Siconos' own writers):
//!
//! ```text
//! /fclib_local   spacedim            int[1]  (3 for fc3d)
//!                W/                  sparse matrix, 3nc x 3nc
//!                vectors/q           f64[3nc]
//!                vectors/mu          f64[nc]
//!                (R/, V/, vectors/s  optional equality constraints: rejected as Unsupported)
//!                info/title, description, math_info   strings (read by [`read_fclib_info`])
//! /fclib_global  spacedim            int[1]
//!                M/                  sparse matrix, ndof x ndof
//!                H/                  sparse matrix, ndof x 3nc
//!                vectors/f           f64[ndof]
//!                vectors/w           f64[3nc]
//!                vectors/mu          f64[nc]
//!                (G/, vectors/b      optional bilateral constraints: rejected as Unsupported)
//! /solution, /guesses                optional, ignored here
//! ```
//!
//! A sparse matrix is a group of CSparse fields: `nzmax`, `m` (rows), `n` (columns), `nz` (each an
//! int dataset of one element), `p`, `i` (int arrays) and `x` (f64 array), all indices 0-based.
//! `nz` tells the form:
//!
//! * `nz >= 0`: triplets, `nz` entries: row `i[k]`, column `p[k]`, value `x[k]`;
//! * `nz == -1`: compressed columns, `p` of length `n + 1`, row indices in `i`;
//! * `nz == -2`: compressed rows, `p` of length `m + 1`, column indices in `i`.
//!
//! `i` and `x` may be longer than the entries they hold (FCLIB writes `nzmax` of them); only the
//! first `nz` (triplets) or `p[last]` (compressed) are read. Duplicate entries are summed.
//! Attributes (`cond`, `rank`, `numberOfDegreeOfFreedom`, ...) are informational and ignored.
//!
//! The two shared Siconos files show both cases: `Box_Stacks-i0122-82-5.hdf5` is global only
//! (M 450x450 diagonal, H 450x246 as 1284 triplets, nc = 82); `LMGC_100_PR_PerioBox-i00361-60-03000.hdf5`
//! is local only (W 180x180 in compressed rows, 9576 entries, nc = 60).
//!
//! # Writing
//!
//! [`write_fclib_file`] writes a local problem as FCLIB's `fclib_write_local` does (the file is
//! replaced; FCLIB would refuse a file that already holds `/fclib_local`):
//!
//! ```text
//! /fclib_local   spacedim            int[1] = 3
//!                W/                  nzmax, m, n, nz = -2 (int[1] each), p int[m+1], i int[nzmax],
//!                                    x f64[nzmax]: compressed rows holding every entry W stores
//!                                    (all n^2 of a dense W, as Siconos' writer; the 9 of every
//!                                    3x3 block of a sparse-block W; those of a CSR W)
//!                W@fc3d_storage      int[1] attribute: W's storage, Siconos' NM_types code
//!                                    (0 dense, 1 sparse-block, 2 sparse)
//!                vectors/q, mu       f64[3nc], f64[nc]
//!                info/               title, description, math_info: scalar fixed-length
//!                                    NUL-terminated strings (H5LTmake_dataset_string), each only
//!                                    when given; attribute numberOfDegreeOfFreedom int[1] (as
//!                                    Siconos' frictionContact_fclib_write) when given
//! ```
//!
//! Readers that do not know `fc3d_storage` (FCLIB, Siconos) ignore it, as they ignore every
//! attribute. [`read_fclib_file`] uses it: a local problem with the attribute is rebuilt in that
//! storage from exactly the stored entries (a dense W from all its entries, a sparse-block W from
//! every 3x3 block that has a stored entry, zeros and signed zeros included, plus any missing
//! diagonal block; a CSR W as stored), so that writing then reading gives back an equal problem,
//! bit for bit, in the same storage. Without the attribute the rule below applies.
//!
//! # What is returned
//!
//! [`read_fclib_file`] reads `/fclib_local` when present, else reduces `/fclib_global` to the local
//! (Delassus) form `W = H^T M^-1 H`, `q = H^T M^-1 f + w` (the global problem being
//! `M v = H r + f`, `u = H^T v + w`) by the global problem's own reduction
//! ([`GlobalProblem::reduce`]: M factored once, block by block when it is block diagonal, and
//! checked with a small normwise backward error), so a singular M is an
//! [`Fc3dError::InvalidStructure`], never NaNs in W. M must be stored in full (both triangles):
//! FCLIB has no symmetric-storage flag. [`read_fclib_global_file`] returns the global problem
//! itself, and [`write_fclib_global_file`] writes one as Siconos does (M and H as triplets).
//!
//! Unless the file says otherwise (`fc3d_storage`, above), W is returned in the sparse-block
//! storage ([`Delassus::SparseBlock`], 3x3 blocks): every block with a non-zero entry plus every
//! diagonal block (Siconos' reader also gives a sparse-block W). A reduced W is dense within groups of contacts
//! that share a body and exactly zero elsewhere (the solves keep the zeros of M^-1 H exact), so
//! for block-diagonal M this storage keeps only the couplings that exist.
//!
//! # Errors
//!
//! Never a panic: a file that cannot be opened or read (missing, unreadable, not HDF5) is an
//! [`Fc3dError::Io`] naming the file; `spacedim != 3` and the optional constraint blocks are
//! [`Fc3dError::Unsupported`]; missing or mistyped datasets, inconsistent sizes and out-of-range
//! indices are [`Fc3dError::InvalidStructure`] naming the file and the dataset; NaN or infinite
//! values are [`Fc3dError::NonFinite`] naming them; an `fc3d_storage` or
//! `numberOfDegreeOfFreedom` attribute that is not one integer of the expected range is an
//! [`Fc3dError::InvalidStructure`]. A dataset declaring more values than 64 per byte of the file
//! is rejected before it is allocated, and memory sized by the file is allocated fallibly (or
//! probed first where a library allocates it): too much of it is an [`Fc3dError::OutOfMemory`],
//! never an abort. The writer's errors are listed at [`write_fclib_file`].

use std::path::Path;

use crate::error::Fc3dError;
use crate::io::info::FclibInfo;
use crate::problem::{FrictionProblem, GlobalProblem};

mod global;
mod info_group;
mod local;
mod reader;
mod sparse;
#[cfg(test)]
mod tests;
mod write;

use reader::open;

pub use global::{write_fclib_global_file, write_fclib_global_rolling_file};
pub use write::write_fclib_file;

/// The attribute of the W group in which [`write_fclib_file`] records W's storage.
const STORAGE_ATTRIBUTE: &str = "fc3d_storage";
/// Values of [`STORAGE_ATTRIBUTE`]: Siconos' `NM_types` codes.
const STORAGE_DENSE: i32 = 0;
const STORAGE_SPARSE_BLOCK: i32 = 1;
const STORAGE_SPARSE: i32 = 2;

/// Reads an FCLIB problem: `/fclib_local` when present, else `/fclib_global` reduced to
/// `W = H^T M^-1 H`, `q = H^T M^-1 f + w`. W comes back in the storage [`write_fclib_file`]
/// recorded (attribute `fc3d_storage`), else in 3x3 sparse-block storage. See the module
/// documentation for the layout and the errors.
pub fn read_fclib_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    let (file, reader) = open(path)?;
    if file.link_exists("fclib_local") {
        reader.read_local(&reader.group(&file, "", "fclib_local")?)
    } else if file.link_exists("fclib_global") {
        reader.read_global_reduced(&reader.group(&file, "", "fclib_global")?)
    } else {
        Err(reader.not_fclib())
    }
}

/// Reads the global problem `/fclib_global` of an FCLIB file (M and H in compressed rows,
/// duplicates summed; FCLIB's `f` is q, `w` is b). A file without it is an
/// [`Fc3dError::InvalidStructure`]; other errors as [`read_fclib_file`]'s.
pub fn read_fclib_global_file(path: &Path) -> Result<GlobalProblem<'static>, Fc3dError> {
    let (file, reader) = open(path)?;
    if file.link_exists("fclib_global") {
        reader.read_global(&reader.group(&file, "", "fclib_global")?)
    } else {
        Err(reader.invalid("no /fclib_global group: not an FCLIB global problem file"))
    }
}

/// Reads the info group of an FCLIB file: that of `/fclib_local` when present, else that of
/// `/fclib_global`; every field `None` when the group (or a field) is absent. The strings may be
/// fixed-length (FCLIB) or variable-length (h5py); invalid UTF-8 is replaced by U+FFFD. Errors
/// as [`read_fclib_file`]'s.
pub fn read_fclib_info(path: &Path) -> Result<FclibInfo, Fc3dError> {
    let (file, reader) = open(path)?;
    let name = if file.link_exists("fclib_local") {
        "fclib_local"
    } else if file.link_exists("fclib_global") {
        "fclib_global"
    } else {
        return Err(reader.not_fclib());
    };
    let group = reader.group(&file, "", name)?;
    if !group.link_exists("info") {
        return Ok(FclibInfo::default());
    }
    let gpath = format!("/{name}");
    reader.read_info(
        &reader.group(&group, &gpath, "info")?,
        &format!("{gpath}/info"),
    )
}
