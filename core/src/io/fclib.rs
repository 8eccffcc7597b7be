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
//! `M v = H r + f`, `u = H^T v + w`). M is factored once with faer's sparse Cholesky when it is
//! symmetric (to 1e-12 relative) and positive definite, with faer's sparse LU otherwise; every
//! solve is checked to be finite with a small normwise backward error, so a singular M is an
//! [`Fc3dError::InvalidStructure`], never NaNs in W. M must be stored in full (both triangles):
//! FCLIB has no symmetric-storage flag.
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
//! is rejected before it is allocated. The writer's errors are listed at [`write_fclib_file`].

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, MatMut, Side};
use hdf5_metno as hdf5;
use hdf5_metno::types::TypeDescriptor;

use crate::error::Fc3dError;
use crate::io::info::FclibInfo;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::problem::{FrictionProblem, DIMENSION};

mod info_group;
mod write;

pub use write::write_fclib_file;

/// The attribute of the W group in which [`write_fclib_file`] records W's storage.
const STORAGE_ATTRIBUTE: &str = "fc3d_storage";
/// Values of [`STORAGE_ATTRIBUTE`]: Siconos' `NM_types` codes.
const STORAGE_DENSE: i32 = 0;
const STORAGE_SPARSE_BLOCK: i32 = 1;
const STORAGE_SPARSE: i32 = 2;

/// Right-hand sides solved together when reducing a global problem.
const SOLVE_CHUNK: usize = 32;
/// Largest relative difference between `M[i][j]` and `M[j][i]` for M to count as symmetric.
const SYMMETRY_TOLERANCE: f64 = 1e-12;
/// Largest normwise backward error `|M x - b| / (|M| |x| + |b|)` (infinity norms) accepted from a
/// solve with M; Cholesky and LU of a non-singular M give about `ndof * 1e-16`.
const BACKWARD_ERROR_TOLERANCE: f64 = 1e-8;
/// A dataset may declare at most this many values per byte of the file (guards allocations
/// against corrupt headers while leaving room for compressed datasets).
const MAX_VALUES_PER_FILE_BYTE: u64 = 64;

/// Reads an FCLIB problem: `/fclib_local` when present, else `/fclib_global` reduced to
/// `W = H^T M^-1 H`, `q = H^T M^-1 f + w`. W comes back in the storage [`write_fclib_file`]
/// recorded (attribute `fc3d_storage`), else in 3x3 sparse-block storage. See the module
/// documentation for the layout and the errors.
pub fn read_fclib_file(path: &Path) -> Result<FrictionProblem<'static>, Fc3dError> {
    let (file, reader) = open(path)?;
    if file.link_exists("fclib_local") {
        reader.read_local(&reader.group(&file, "", "fclib_local")?)
    } else if file.link_exists("fclib_global") {
        reader.read_global(&reader.group(&file, "", "fclib_global")?)
    } else {
        Err(reader.not_fclib())
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

/// Opens an FCLIB file for reading, with the reader of its datasets.
fn open(path: &Path) -> Result<(hdf5::File, Reader), Fc3dError> {
    let label = path.display().to_string();
    let io_error = |message: String| Fc3dError::Io {
        file: label.clone(),
        message,
    };
    // The operating system's message (no such file, permission denied) is clearer than HDF5's.
    let meta = std::fs::metadata(path).map_err(|e| io_error(e.to_string()))?;
    if meta.is_dir() {
        return Err(io_error("is a directory, not an FCLIB file".into()));
    }
    std::fs::File::open(path).map_err(|e| io_error(e.to_string()))?;
    let file = hdf5::File::open(path)
        .map_err(|e| io_error(format!("cannot be opened as an HDF5 file: {e}")))?;
    let reader = Reader {
        label: label.clone(),
        max_values: meta
            .len()
            .saturating_mul(MAX_VALUES_PER_FILE_BYTE)
            .max(1 << 20),
    };
    Ok((file, reader))
}

/// A sparse matrix read from a file: its size and `(row, column, value)` entries (duplicates not
/// yet summed).
struct SparseEntries {
    nrows: usize,
    ncols: usize,
    entries: Vec<(usize, usize, f64)>,
}

/// Reads datasets of one file, turning every failure into a typed error that names the file.
struct Reader {
    label: String,
    max_values: u64,
}

impl Reader {
    fn invalid(&self, message: impl std::fmt::Display) -> Fc3dError {
        Fc3dError::InvalidStructure(format!("{}: {message}", self.label))
    }

    fn not_fclib(&self) -> Fc3dError {
        self.invalid("neither /fclib_local nor /fclib_global is present: not an FCLIB problem file")
    }

    fn hdf5_error(&self, object: &str, e: hdf5::Error) -> Fc3dError {
        Fc3dError::Io {
            file: self.label.clone(),
            message: format!("{object}: HDF5 read failed: {e}"),
        }
    }

    fn group(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<hdf5::Group, Fc3dError> {
        let path = format!("{ppath}/{name}");
        if !parent.link_exists(name) {
            return Err(self.invalid(format!("{path} is missing")));
        }
        parent
            .group(name)
            .map_err(|e| self.invalid(format!("{path} is not a group ({e})")))
    }

    /// A dataset of at most one dimension, its path, and its declared number of values (checked
    /// against the size of the file).
    fn dataset(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<(hdf5::Dataset, String), Fc3dError> {
        let path = format!("{ppath}/{name}");
        if !parent.link_exists(name) {
            return Err(self.invalid(format!("{path} is missing")));
        }
        let ds = parent
            .dataset(name)
            .map_err(|e| self.invalid(format!("{path} is not a dataset ({e})")))?;
        let shape = ds.shape();
        if shape.len() > 1 {
            return Err(self.invalid(format!(
                "{path} has shape {shape:?}, expected a one-dimensional array"
            )));
        }
        let size: u64 = shape.iter().map(|&d| d as u64).product();
        if size > self.max_values {
            return Err(self.invalid(format!(
                "{path} declares {size} values, more than the file could hold"
            )));
        }
        Ok((ds, path))
    }

    fn type_of(&self, ds: &hdf5::Dataset, path: &str) -> Result<TypeDescriptor, Fc3dError> {
        ds.dtype()
            .and_then(|t| t.to_descriptor())
            .map_err(|e| self.invalid(format!("{path} has an unreadable datatype ({e})")))
    }

    fn ints(&self, parent: &hdf5::Group, ppath: &str, name: &str) -> Result<Vec<i64>, Fc3dError> {
        let (ds, path) = self.dataset(parent, ppath, name)?;
        match self.type_of(&ds, &path)? {
            TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => {}
            other => {
                return Err(self.invalid(format!("{path} holds {other} values, expected integers")))
            }
        }
        ds.read_raw::<i64>().map_err(|e| self.hdf5_error(&path, e))
    }

    fn int_scalar(&self, parent: &hdf5::Group, ppath: &str, name: &str) -> Result<i64, Fc3dError> {
        let values = self.ints(parent, ppath, name)?;
        match values.as_slice() {
            [v] => Ok(*v),
            _ => Err(self.invalid(format!(
                "{ppath}/{name} holds {} values, expected one",
                values.len()
            ))),
        }
    }

    /// A size field (`m`, `n`), which must be >= 0.
    fn size(&self, parent: &hdf5::Group, ppath: &str, name: &str) -> Result<usize, Fc3dError> {
        let v = self.int_scalar(parent, ppath, name)?;
        usize::try_from(v)
            .ok()
            .filter(|&s| (s as u64) <= self.max_values)
            .ok_or_else(|| self.invalid(format!("{ppath}/{name} = {v} is not a valid size")))
    }

    /// A float array; every value must be finite.
    fn floats(&self, parent: &hdf5::Group, ppath: &str, name: &str) -> Result<Vec<f64>, Fc3dError> {
        let (ds, path) = self.dataset(parent, ppath, name)?;
        match self.type_of(&ds, &path)? {
            TypeDescriptor::Float(_) => {}
            other => {
                return Err(self.invalid(format!(
                    "{path} holds {other} values, expected floating-point numbers"
                )))
            }
        }
        let values = ds
            .read_raw::<f64>()
            .map_err(|e| self.hdf5_error(&path, e))?;
        self.check_finite(&path, &values)?;
        Ok(values)
    }

    fn check_finite(&self, what: &str, values: &[f64]) -> Result<(), Fc3dError> {
        match values.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(Fc3dError::NonFinite {
                what: format!("{}: {what}", self.label),
                index,
            }),
            None => Ok(()),
        }
    }

    fn spacedim(&self, group: &hdf5::Group, gpath: &str) -> Result<(), Fc3dError> {
        let d = self.int_scalar(group, gpath, "spacedim")?;
        if d == DIMENSION as i64 {
            return Ok(());
        }
        let what = if d == 2 {
            " (a 2D problem)".to_string()
        } else {
            String::new()
        };
        Err(Fc3dError::Unsupported(format!(
            "{}: {gpath}/spacedim = {d}{what}: fc3d solves 3D problems only",
            self.label
        )))
    }

    /// Converts a stored index to `usize`, checking `0 <= v < bound`.
    fn index(
        &self,
        path: &str,
        k: usize,
        v: i64,
        bound: usize,
        what: &str,
    ) -> Result<usize, Fc3dError> {
        usize::try_from(v)
            .ok()
            .filter(|&u| u < bound)
            .ok_or_else(|| {
                self.invalid(format!(
                    "{path}[{k}] = {v}: {what} index out of range 0..{bound}"
                ))
            })
    }

    /// Checks a compressed pointer array (`outer + 1` non-decreasing entries from 0, the last one
    /// within the index and value arrays) and returns it as `usize`.
    fn pointers(
        &self,
        path: &str,
        p: &[i64],
        outer: usize,
        n_idx: usize,
        n_x: usize,
    ) -> Result<Vec<usize>, Fc3dError> {
        if p.len() != outer + 1 {
            return Err(self.invalid(format!(
                "{path}/p has {} entries, expected {} for a compressed matrix",
                p.len(),
                outer + 1
            )));
        }
        if p[0] != 0 {
            return Err(self.invalid(format!("{path}/p[0] = {}, expected 0", p[0])));
        }
        if let Some(k) = p.windows(2).position(|w| w[1] < w[0]) {
            return Err(self.invalid(format!(
                "{path}/p decreases at {}: {} then {}",
                k + 1,
                p[k],
                p[k + 1]
            )));
        }
        let last = p[outer] as u64; // >= 0: starts at 0 and never decreases
        if last > n_idx as u64 || last > n_x as u64 {
            return Err(self.invalid(format!(
                "{path}/p ends at {last} but i has {n_idx} and x {n_x} entries"
            )));
        }
        Ok(p.iter().map(|&v| v as usize).collect())
    }

    /// Reads the sparse matrix group `ppath/name` (triplets, CSC or CSR; see the module doc).
    fn matrix(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<SparseEntries, Fc3dError> {
        let g = self.group(parent, ppath, name)?;
        let path = format!("{ppath}/{name}");
        let nrows = self.size(&g, &path, "m")?;
        let ncols = self.size(&g, &path, "n")?;
        let nz = self.int_scalar(&g, &path, "nz")?;
        // nzmax is informational (Siconos writes more or fewer values than it says).
        self.int_scalar(&g, &path, "nzmax")?;
        let p = self.ints(&g, &path, "p")?;
        let idx = self.ints(&g, &path, "i")?;
        let x = {
            let (ds, xpath) = self.dataset(&g, &path, "x")?;
            match self.type_of(&ds, &xpath)? {
                TypeDescriptor::Float(_) => {}
                other => {
                    return Err(self.invalid(format!(
                        "{xpath} holds {other} values, expected floating-point numbers"
                    )))
                }
            }
            ds.read_raw::<f64>()
                .map_err(|e| self.hdf5_error(&xpath, e))?
        };
        let mut entries = Vec::new();
        match nz {
            nz if nz >= 0 => {
                let count = nz as u64;
                for (field, len) in [("p", p.len()), ("i", idx.len()), ("x", x.len())] {
                    if (len as u64) < count {
                        return Err(self.invalid(format!(
                            "{path}/{field} has {len} entries, fewer than nz = {nz} triplets"
                        )));
                    }
                }
                let count = count as usize;
                entries.reserve(count);
                for k in 0..count {
                    let row = self.index(&format!("{path}/i"), k, idx[k], nrows, "row")?;
                    let col = self.index(&format!("{path}/p"), k, p[k], ncols, "column")?;
                    entries.push((row, col, x[k]));
                }
                self.check_finite(&format!("{path}/x"), &x[..count])?;
            }
            -1 | -2 => {
                let by_columns = nz == -1;
                let (outer, inner, inner_name) = if by_columns {
                    (ncols, nrows, "row")
                } else {
                    (nrows, ncols, "column")
                };
                let ptr = self.pointers(&path, &p, outer, idx.len(), x.len())?;
                entries.reserve(ptr[outer]);
                let ipath = format!("{path}/i");
                for o in 0..outer {
                    for k in ptr[o]..ptr[o + 1] {
                        let in_ = self.index(&ipath, k, idx[k], inner, inner_name)?;
                        entries.push(if by_columns {
                            (in_, o, x[k])
                        } else {
                            (o, in_, x[k])
                        });
                    }
                }
                self.check_finite(&format!("{path}/x"), &x[..ptr[outer]])?;
            }
            _ => {
                return Err(self.invalid(format!(
                    "{path}/nz = {nz}: expected a triplet count (>= 0), -1 (compressed columns) \
                     or -2 (compressed rows)"
                )))
            }
        }
        Ok(SparseEntries {
            nrows,
            ncols,
            entries,
        })
    }

    fn check_len(
        &self,
        path: &str,
        got: usize,
        expected: usize,
        why: &str,
    ) -> Result<(), Fc3dError> {
        if got == expected {
            Ok(())
        } else {
            Err(self.invalid(format!(
                "{path} has {got} entries, expected {expected} ({why})"
            )))
        }
    }

    /// `ncols` must be a multiple of 3; returns the number of contacts.
    fn contacts(&self, path: &str, n: usize) -> Result<usize, Fc3dError> {
        if !n.is_multiple_of(DIMENSION) {
            return Err(self.invalid(format!(
                "{path} has {n} columns, not a multiple of the space dimension 3"
            )));
        }
        Ok(n / DIMENSION)
    }

    fn read_local(&self, g: &hdf5::Group) -> Result<FrictionProblem<'static>, Fc3dError> {
        let gp = "/fclib_local";
        self.spacedim(g, gp)?;
        for extra in ["R", "V"] {
            if g.link_exists(extra) {
                return Err(Fc3dError::Unsupported(format!(
                    "{}: {gp}/{extra} present: local problems with extra constraints (R, V, s) \
                     are not supported",
                    self.label
                )));
            }
        }
        let w = self.matrix(g, gp, "W")?;
        if w.nrows != w.ncols {
            return Err(self.invalid(format!(
                "{gp}/W is {}x{}, expected a square matrix",
                w.nrows, w.ncols
            )));
        }
        let nc = self.contacts(&format!("{gp}/W"), w.ncols)?;
        let vp = format!("{gp}/vectors");
        let v = self.group(g, gp, "vectors")?;
        let q = self.floats(&v, &vp, "q")?;
        self.check_len(&format!("{vp}/q"), q.len(), w.nrows, "the size of W")?;
        let mu = self.floats(&v, &vp, "mu")?;
        self.check_len(&format!("{vp}/mu"), mu.len(), nc, "one per contact")?;
        match self.storage(&self.group(g, gp, "W")?, &format!("{gp}/W"))? {
            Some(storage) => self.problem_as_stored(storage, w.nrows, &w.entries, q, mu),
            None => self.problem(w.nrows, &w.entries, q, mu),
        }
    }

    /// The storage recorded by [`write_fclib_file`] in the attribute `fc3d_storage` of the W
    /// group `wg`, `None` without the attribute.
    fn storage(&self, wg: &hdf5::Group, wpath: &str) -> Result<Option<i32>, Fc3dError> {
        let names = wg
            .attr_names()
            .map_err(|e| self.hdf5_error(&format!("{wpath} attributes"), e))?;
        if !names.iter().any(|n| n == STORAGE_ATTRIBUTE) {
            return Ok(None);
        }
        let apath = format!("{wpath} attribute {STORAGE_ATTRIBUTE}");
        let value = self.int_attribute(wg, STORAGE_ATTRIBUTE, &apath)?;
        match i32::try_from(value) {
            Ok(v @ (STORAGE_DENSE | STORAGE_SPARSE_BLOCK | STORAGE_SPARSE)) => Ok(Some(v)),
            _ => Err(self.invalid(format!(
                "{apath} = {value}: expected {STORAGE_DENSE} (dense), {STORAGE_SPARSE_BLOCK} \
                 (sparse-block) or {STORAGE_SPARSE} (sparse)"
            ))),
        }
    }

    /// The integer attribute `name` of `object` (one value), named `apath` in messages.
    fn int_attribute(
        &self,
        object: &hdf5::Location,
        name: &str,
        apath: &str,
    ) -> Result<i64, Fc3dError> {
        let attr = object.attr(name).map_err(|e| self.hdf5_error(apath, e))?;
        match attr
            .dtype()
            .and_then(|t| t.to_descriptor())
            .map_err(|e| self.invalid(format!("{apath} has an unreadable datatype ({e})")))?
        {
            TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => {}
            other => {
                return Err(
                    self.invalid(format!("{apath} holds {other} values, expected an integer"))
                )
            }
        }
        if attr.size() != 1 {
            return Err(self.invalid(format!(
                "{apath} holds {} values, expected one",
                attr.size()
            )));
        }
        let values = attr
            .read_raw::<i64>()
            .map_err(|e| self.hdf5_error(apath, e))?;
        values
            .first()
            .copied()
            .ok_or_else(|| self.invalid(format!("{apath} holds no value")))
    }

    /// The info group `ig` (named `ipath`): its three strings and `numberOfDegreeOfFreedom`.
    fn read_info(&self, ig: &hdf5::Group, ipath: &str) -> Result<FclibInfo, Fc3dError> {
        let mut strings = [None, None, None];
        for (slot, name) in strings.iter_mut().zip(info_group::STRINGS) {
            if ig.link_exists(name) {
                let text = info_group::read_string(ig, name, self.max_values)
                    .map_err(|e| self.invalid(format!("{ipath}/{name}: {e}")))?;
                *slot = Some(text);
            }
        }
        let names = ig
            .attr_names()
            .map_err(|e| self.hdf5_error(&format!("{ipath} attributes"), e))?;
        let apath = format!("{ipath} attribute {}", info_group::NDOF_ATTRIBUTE);
        let ndof = if names.iter().any(|n| n == info_group::NDOF_ATTRIBUTE) {
            let v = self.int_attribute(ig, info_group::NDOF_ATTRIBUTE, &apath)?;
            Some(
                i32::try_from(v)
                    .map_err(|_| self.invalid(format!("{apath} = {v} does not fit a C int")))?,
            )
        } else {
            None
        };
        let [title, description, math_info] = strings;
        Ok(FclibInfo {
            title,
            description,
            math_info,
            number_of_degrees_of_freedom: ndof,
        })
    }

    /// Assembles the problem with W in the storage `storage` (an `fc3d_storage` code), from
    /// exactly the stored entries: the first value at a position is kept as it is (signed zeros
    /// included), duplicates are added to it.
    fn problem_as_stored(
        &self,
        storage: i32,
        n: usize,
        w_entries: &[(usize, usize, f64)],
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let w = match storage {
            STORAGE_DENSE => {
                let size = n
                    .checked_mul(n)
                    .filter(|&s| s as u64 <= self.max_values)
                    .ok_or_else(|| {
                        self.invalid(format!(
                            "/fclib_local/W is marked dense but {n}x{n} values are more than \
                             the file could describe"
                        ))
                    })?;
                let mut data = vec![0.0; size];
                let mut seen = vec![false; size];
                for &(i, j, v) in w_entries {
                    let k = i + j * n;
                    if seen[k] {
                        data[k] += v;
                    } else {
                        data[k] = v;
                        seen[k] = true;
                    }
                }
                Delassus::Dense(DenseMatrix::new(n, n, data)?)
            }
            STORAGE_SPARSE_BLOCK => {
                let nc = n / DIMENSION;
                let mut map = BTreeMap::<(usize, usize), ([f64; 9], [bool; 9])>::new();
                for c in 0..nc {
                    map.insert((c, c), ([0.0; 9], [false; 9]));
                }
                for &(i, j, v) in w_entries {
                    let (block, seen) = map
                        .entry((i / DIMENSION, j / DIMENSION))
                        .or_insert(([0.0; 9], [false; 9]));
                    let k = i % DIMENSION + DIMENSION * (j % DIMENSION);
                    if seen[k] {
                        block[k] += v;
                    } else {
                        block[k] = v;
                        seen[k] = true;
                    }
                }
                let mut row_ptr = vec![0usize; nc + 1];
                let mut col_idx = Vec::with_capacity(map.len());
                let mut blocks = Vec::with_capacity(map.len());
                for ((bi, bj), (block, _)) in map {
                    row_ptr[bi + 1] += 1;
                    col_idx.push(bj);
                    blocks.push(block);
                }
                for c in 0..nc {
                    row_ptr[c + 1] += row_ptr[c];
                }
                Delassus::SparseBlock(BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks)?)
            }
            _ => Delassus::Sparse(CsrMatrix::from_triplets(n, n, w_entries)?),
        };
        FrictionProblem::new(w, q, mu)
    }

    fn read_global(&self, g: &hdf5::Group) -> Result<FrictionProblem<'static>, Fc3dError> {
        let gp = "/fclib_global";
        self.spacedim(g, gp)?;
        if g.link_exists("G") {
            return Err(Fc3dError::Unsupported(format!(
                "{}: {gp}/G present: global problems with bilateral constraints (G, b) are not \
                 supported",
                self.label
            )));
        }
        let m = self.matrix(g, gp, "M")?;
        if m.nrows != m.ncols {
            return Err(self.invalid(format!(
                "{gp}/M is {}x{}, expected a square matrix",
                m.nrows, m.ncols
            )));
        }
        let ndof = m.nrows;
        let h = self.matrix(g, gp, "H")?;
        if h.nrows != ndof {
            return Err(self.invalid(format!("{gp}/H has {} rows but M has {ndof}", h.nrows)));
        }
        let nc = self.contacts(&format!("{gp}/H"), h.ncols)?;
        let vp = format!("{gp}/vectors");
        let v = self.group(g, gp, "vectors")?;
        let f = self.floats(&v, &vp, "f")?;
        self.check_len(&format!("{vp}/f"), f.len(), ndof, "the size of M")?;
        let w = self.floats(&v, &vp, "w")?;
        self.check_len(&format!("{vp}/w"), w.len(), h.ncols, "the columns of H")?;
        let mu = self.floats(&v, &vp, "mu")?;
        self.check_len(&format!("{vp}/mu"), mu.len(), nc, "one per contact")?;
        let (w_entries, q) = reduce_global(ndof, &m.entries, &h, &f, &w)
            .map_err(|e| self.invalid(format!("reducing the global problem: {e}")))?;
        self.problem(h.ncols, &w_entries, q, mu)
    }

    /// Assembles the problem with W in 3x3 sparse-block storage.
    fn problem(
        &self,
        n: usize,
        w_entries: &[(usize, usize, f64)],
        q: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<FrictionProblem<'static>, Fc3dError> {
        let csr = CsrMatrix::from_triplets(n, n, w_entries)?;
        let blocks = Delassus::Sparse(csr).to_block_sparse()?;
        FrictionProblem::new(Delassus::SparseBlock(blocks), q, mu)
    }
}

/// `(row, column, value)` entries of a sparse matrix.
type Entries = Vec<(usize, usize, f64)>;

/// A factorization of M.
enum MassFactor {
    Cholesky(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
}

impl MassFactor {
    fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        match self {
            MassFactor::Cholesky(f) => f.solve_in_place(rhs),
            MassFactor::Lu(f) => f.solve_in_place(rhs),
        }
    }
}

/// M (square, `ndof`) with duplicates summed, factored, and what the backward-error check needs.
struct MassSolver {
    ndof: usize,
    /// Summed entries `(row, col, value)`.
    entries: Vec<(usize, usize, f64)>,
    /// Infinity norm of M (largest absolute row sum).
    norm_inf: f64,
    factor: MassFactor,
}

impl MassSolver {
    fn new(ndof: usize, raw: &[(usize, usize, f64)]) -> Result<Self, String> {
        let mut summed = BTreeMap::<(usize, usize), f64>::new();
        for &(i, j, v) in raw {
            *summed.entry((i, j)).or_insert(0.0) += v;
        }
        let entries: Vec<(usize, usize, f64)> = summed
            .iter()
            .filter(|(_, &v)| v != 0.0)
            .map(|(&(i, j), &v)| (i, j, v))
            .collect();
        let mut row_sums = vec![0.0; ndof];
        let mut amax = 0.0_f64;
        for &(i, _, v) in &entries {
            row_sums[i] += v.abs();
            amax = amax.max(v.abs());
        }
        let norm_inf = row_sums.iter().copied().fold(0.0, f64::max);
        let symmetric = entries.iter().all(|&(i, j, v)| {
            let t = summed.get(&(j, i)).copied().unwrap_or(0.0);
            (v - t).abs() <= SYMMETRY_TOLERANCE * amax
        });
        let triplets: Vec<Triplet<usize, usize, f64>> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let mat = SparseColMat::<usize, f64>::try_new_from_triplets(ndof, ndof, &triplets)
            .map_err(|e| format!("M cannot be stored by faer: {e:?}"))?;
        let cholesky = if symmetric {
            mat.sp_cholesky(Side::Lower).ok()
        } else {
            None
        };
        let factor = match cholesky {
            Some(llt) => MassFactor::Cholesky(llt),
            None => MassFactor::Lu(Box::new(
                mat.sp_lu()
                    .map_err(|e| format!("M is singular (sparse LU: {e:?})"))?,
            )),
        };
        Ok(MassSolver {
            ndof,
            entries,
            norm_inf,
            factor,
        })
    }

    /// Solves `M X = B` in place (`x` holds B on entry), checking every column is finite and has
    /// a small normwise backward error.
    fn solve(&self, x: &mut Mat<f64>) -> Result<(), String> {
        let b = x.clone();
        self.factor.solve_in_place(x.as_mut());
        let k = x.ncols();
        let mut residual = b.clone();
        for &(i, j, v) in &self.entries {
            for c in 0..k {
                residual[(i, c)] -= v * x[(j, c)];
            }
        }
        for c in 0..k {
            let xc = x.col_as_slice(c);
            if let Some(i) = xc.iter().position(|v| !v.is_finite()) {
                return Err(format!(
                    "M is singular: solving with it gave x[{i}] = {}",
                    xc[i]
                ));
            }
            let inf = |s: &[f64]| s.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            let r = inf(residual.col_as_slice(c));
            let scale = self.norm_inf * inf(xc) + inf(b.col_as_slice(c));
            if r > BACKWARD_ERROR_TOLERANCE * scale {
                return Err(format!(
                    "M is numerically singular: a solve with it left a residual {r:e} for a \
                     scale {scale:e}"
                ));
            }
        }
        Ok(())
    }
}

/// `W = H^T M^-1 H` as `(row, col, value)` entries (exact zeros left out) and
/// `q = H^T M^-1 f + w`. Errors are messages about M.
fn reduce_global(
    ndof: usize,
    m_entries: &[(usize, usize, f64)],
    h: &SparseEntries,
    f: &[f64],
    w: &[f64],
) -> Result<(Entries, Vec<f64>), String> {
    let n = h.ncols;
    let solver = MassSolver::new(ndof, m_entries)?;
    debug_assert_eq!(solver.ndof, ndof);
    let mut h_cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut h_rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); ndof];
    for &(i, j, v) in &h.entries {
        if v != 0.0 {
            h_cols[j].push((i, v));
            h_rows[i].push((j, v));
        }
    }
    // y = H^T x for a dense x, visiting only the rows of H where x is non-zero.
    let mut acc = vec![0.0; n];
    let mut touched = BTreeSet::new();
    let mut transpose_product = |x: &[f64], out: &mut dyn FnMut(usize, f64)| {
        touched.clear();
        for (r, &xr) in x.iter().enumerate() {
            if xr != 0.0 {
                for &(c, v) in &h_rows[r] {
                    acc[c] += v * xr;
                    touched.insert(c);
                }
            }
        }
        for &c in touched.iter() {
            out(c, acc[c]);
            acc[c] = 0.0;
        }
    };

    let mut w_entries = Vec::new();
    let mut start = 0;
    while start < n {
        let k = SOLVE_CHUNK.min(n - start);
        let mut x = Mat::<f64>::zeros(ndof, k);
        for jj in 0..k {
            for &(r, v) in &h_cols[start + jj] {
                x[(r, jj)] += v;
            }
        }
        solver.solve(&mut x)?;
        for jj in 0..k {
            let j = start + jj;
            transpose_product(x.col_as_slice(jj), &mut |c, v| {
                if v != 0.0 {
                    w_entries.push((c, j, v));
                }
            });
        }
        start += k;
    }

    let mut y = Mat::<f64>::zeros(ndof, 1);
    y.col_as_slice_mut(0).copy_from_slice(f);
    solver.solve(&mut y)?;
    let mut q = w.to_vec();
    transpose_product(y.col_as_slice(0), &mut |c, v| q[c] += v);
    Ok((w_entries, q))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn h_of(ndof: usize, n: usize, entries: Vec<(usize, usize, f64)>) -> SparseEntries {
        SparseEntries {
            nrows: ndof,
            ncols: n,
            entries,
        }
    }

    fn dense(n: usize, entries: &[(usize, usize, f64)]) -> Vec<f64> {
        let mut d = vec![0.0; n * n];
        for &(i, j, v) in entries {
            d[i * n + j] += v;
        }
        d
    }

    #[test]
    fn reduction_matches_a_hand_computation() {
        // M = [[2, 1], [1, 2]] (SPD), M^-1 = [[2, -1], [-1, 2]] / 3; H = [[1, 0, 0], [0, 1, 1]].
        let m = [(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 2.0)];
        let h = h_of(2, 3, vec![(0, 0, 1.0), (1, 1, 1.0), (1, 2, 1.0)]);
        let (w, q) = reduce_global(2, &m, &h, &[3.0, 0.0], &[1.0, 2.0, 3.0]).unwrap();
        let wd = dense(3, &w);
        let expected = [2.0, -1.0, -1.0, -1.0, 2.0, 2.0, -1.0, 2.0, 2.0].map(|v| v / 3.0);
        for (a, b) in wd.iter().zip(expected) {
            assert!((a - b).abs() < 1e-14, "{wd:?}");
        }
        // M^-1 f = (2, -1); q = H^T (2, -1) + w = (3, 1, 2).
        for (a, b) in q.iter().zip([3.0, 1.0, 2.0]) {
            assert!((a - b).abs() < 1e-14, "{q:?}");
        }
    }

    #[test]
    fn unsymmetric_mass_uses_lu_and_duplicates_are_summed() {
        // M = [[2, 1], [0, 4]] given with the 2 split in two triplets.
        let m = [(0, 0, 1.0), (0, 0, 1.0), (0, 1, 1.0), (1, 1, 4.0)];
        let solver = MassSolver::new(2, &m).unwrap();
        assert!(matches!(solver.factor, MassFactor::Lu(_)));
        let mut x = Mat::<f64>::zeros(2, 1);
        x[(0, 0)] = 3.0;
        x[(1, 0)] = 4.0;
        solver.solve(&mut x).unwrap();
        assert!((x[(0, 0)] - 1.0).abs() < 1e-15 && (x[(1, 0)] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn indefinite_symmetric_mass_falls_back_to_lu() {
        let m = [(0, 1, 1.0), (1, 0, 1.0)];
        let solver = MassSolver::new(2, &m).unwrap();
        assert!(matches!(solver.factor, MassFactor::Lu(_)));
    }

    #[test]
    fn singular_mass_is_an_error_not_nans() {
        let h = h_of(2, 3, vec![(0, 0, 1.0), (1, 1, 1.0)]);
        for m in [
            vec![(0, 0, 1.0)],                                        // structurally singular
            vec![(0, 0, 1.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 1.0)], // numerically singular
        ] {
            let err = reduce_global(2, &m, &h, &[0.0, 0.0], &[0.0; 3]).unwrap_err();
            assert!(err.contains("singular"), "{err}");
        }
    }
}
