//! The FCLIB writer of local problems: `/fclib_local` as `fclib_write_local` lays it out (see the
//! module documentation of `io::fclib` for the layout and the storage attribute).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use hdf5_metno as hdf5;

use super::info_group::{strings, write_info};
use super::{STORAGE_ATTRIBUTE, STORAGE_DENSE, STORAGE_SPARSE, STORAGE_SPARSE_BLOCK};
use crate::alloc::reserve;
use crate::error::Fc3dError;
use crate::io::info::FclibInfo;
use crate::matrix::Delassus;
use crate::problem::{FrictionProblem, DIMENSION};

/// FCLIB's `nz` of a matrix in compressed rows.
const COMPRESSED_ROWS: i32 = -2;

/// Writes `problem` to `path` as an FCLIB local problem (`/fclib_local`: `spacedim` = 3, W in
/// compressed rows with every entry its storage holds, `vectors/q`, `vectors/mu`, and the
/// `info` group from `info`), replacing any file there. W's storage is recorded in the attribute
/// `fc3d_storage` of the W group, so that [`read_fclib_file`](super::read_fclib_file) gives back
/// an equal problem, bit for bit, in the same storage.
///
/// The file is written next to `path` under a temporary name and renamed over `path` once
/// complete: on any error `path` is left as it was (no file, or the old file untouched). A
/// symbolic link at `path` is replaced by the new file, not followed.
/// Errors: a W too large for FCLIB's 32-bit indices or an info string holding a NUL byte is an
/// [`Fc3dError::Unsupported`]; a file that cannot be created, written or renamed an
/// [`Fc3dError::Io`] naming `path`. Never a panic.
pub fn write_fclib_file(
    problem: &FrictionProblem<'_>,
    path: &Path,
    info: &FclibInfo,
) -> Result<(), Fc3dError> {
    let label = path.display().to_string();
    // Everything that can be refused is checked before a file is created.
    let w = CompressedRows::of(problem.w(), &label)?;
    string_checks(info, &label)?;
    replace_file(path, |file| write_local(file, problem, &w, info))
}

/// Refuses info strings a C string cannot hold (a NUL byte).
pub(super) fn string_checks(info: &FclibInfo, label: &str) -> Result<(), Fc3dError> {
    for (name, value) in strings(info) {
        if value.is_some_and(|v| v.contains('\0')) {
            return Err(Fc3dError::Unsupported(format!(
                "{label}: the FCLIB info string `{name}` contains a NUL byte, which a C string \
                 cannot hold"
            )));
        }
    }
    Ok(())
}

/// Creates an HDF5 file next to `path` under a temporary name, fills it with `fill` (whose
/// errors are messages naming the object that failed), closes it and renames it over `path`:
/// on any error `path` is left as it was (no file, or the old file untouched) and the
/// temporary file is removed. A symbolic link at `path` is replaced, not followed.
pub(super) fn replace_file(
    path: &Path,
    fill: impl FnOnce(&hdf5::File) -> Result<(), String>,
) -> Result<(), Fc3dError> {
    let label = path.display().to_string();
    let io_error = |message: String| Fc3dError::Io {
        file: label.clone(),
        message,
    };
    if path.is_dir() {
        return Err(io_error("is a directory, not a file name".into()));
    }
    let temporary = temporary_path(path).ok_or_else(|| io_error("is not a file name".into()))?;
    let written = hdf5::File::create(&temporary)
        .map_err(|e| format!("creating the file: {e}"))
        .and_then(|file| {
            fill(&file)?;
            file.close().map_err(|e| format!("closing the file: {e}"))
        })
        .map_err(|message| io_error(format!("cannot write FCLIB file: {message}")))
        .and_then(|()| {
            std::fs::rename(&temporary, path)
                .map_err(|e| io_error(format!("cannot replace the file: {e}")))
        });
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// A name in the directory of `path` that no other writer uses, or `None` if `path` has no file
/// name.
fn temporary_path(path: &Path) -> Option<PathBuf> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name()?.to_string_lossy();
    let k = COUNTER.fetch_add(1, Ordering::Relaxed);
    let temporary = format!(".{name}.fc3d-{}-{k}.tmp", std::process::id());
    Some(match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(temporary),
        _ => PathBuf::from(temporary),
    })
}

/// `v` as FCLIB's C `int`.
fn int(v: usize, label: &str, what: &str) -> Result<i32, Fc3dError> {
    i32::try_from(v).map_err(|_| {
        Fc3dError::Unsupported(format!(
            "{label}: {what} ({v}) does not fit FCLIB's 32-bit int indices"
        ))
    })
}

/// W as FCLIB's compressed-row matrix: row pointers `p` (`n + 1`), column indices `i` and values
/// `x` (one per stored entry), and the storage it came from.
struct CompressedRows {
    n: i32,
    storage: i32,
    p: Vec<i32>,
    i: Vec<i32>,
    x: Vec<f64>,
}

impl CompressedRows {
    /// Every entry `w` stores, row by row: all `n * n` of a dense W (as Siconos' writer), the nine
    /// of every 3x3 block of a sparse-block W (in block order within a row), those of a CSR W.
    fn of(w: &Delassus<'_>, label: &str) -> Result<Self, Fc3dError> {
        let n = w.nrows();
        let stored = match w {
            Delassus::Dense(_) => n.saturating_mul(n),
            Delassus::SparseBlock(b) => b.n_blocks().saturating_mul(DIMENSION * DIMENSION),
            Delassus::Sparse(s) => s.nnz(),
        };
        int(n + 1, label, "the size of W plus one")?;
        int(stored, label, "the number of stored entries of W")?;
        // Sized by the problem (all n^2 entries of a dense W): allocated fallibly.
        let mut p = Vec::new();
        let mut i = Vec::new();
        let mut x = Vec::new();
        reserve(&mut p, n + 1, "the row pointers of W")?;
        reserve(&mut i, stored, "the column indices of W")?;
        reserve(&mut x, stored, "the values of W")?;
        p.push(0);
        // Indices are below n + 1 and counts at most `stored`, both checked to fit an i32.
        let storage = match w {
            Delassus::Dense(d) => {
                for row in 0..n {
                    for col in 0..n {
                        i.push(col as i32);
                        x.push(d.values()[row + col * n]);
                    }
                    p.push(x.len() as i32);
                }
                STORAGE_DENSE
            }
            Delassus::SparseBlock(b) => {
                for block_row in 0..b.n_block_rows() {
                    let blocks = b.row_ptr()[block_row]..b.row_ptr()[block_row + 1];
                    for r in 0..DIMENSION {
                        for k in blocks.clone() {
                            let block = b.block(k);
                            for c in 0..DIMENSION {
                                i.push((DIMENSION * b.col_idx()[k] + c) as i32);
                                x.push(block[r + DIMENSION * c]);
                            }
                        }
                        p.push(x.len() as i32);
                    }
                }
                STORAGE_SPARSE_BLOCK
            }
            Delassus::Sparse(s) => {
                p.extend(s.row_ptr()[1..].iter().map(|&v| v as i32));
                i.extend(s.col_idx().iter().map(|&v| v as i32));
                x.extend_from_slice(s.values());
                STORAGE_SPARSE
            }
        };
        Ok(CompressedRows {
            n: n as i32,
            storage,
            p,
            i,
            x,
        })
    }
}

/// Writes `/fclib_local` into a new file. Errors are messages naming the object that failed.
fn write_local(
    file: &hdf5::File,
    problem: &FrictionProblem<'_>,
    w: &CompressedRows,
    info: &FclibInfo,
) -> Result<(), String> {
    let at = |what: &'static str| move |e: hdf5::Error| format!("{what}: {e}");
    let local = file
        .create_group("fclib_local")
        .map_err(at("/fclib_local"))?;
    ints(&local, "spacedim", &[DIMENSION as i32]).map_err(at("/fclib_local/spacedim"))?;

    let wg = local.create_group("W").map_err(at("/fclib_local/W"))?;
    let nnz = w.x.len() as i32;
    for (name, value) in [
        ("nzmax", nnz),
        ("m", w.n),
        ("n", w.n),
        ("nz", COMPRESSED_ROWS),
    ] {
        ints(&wg, name, &[value]).map_err(|e| format!("/fclib_local/W/{name}: {e}"))?;
    }
    ints(&wg, "p", &w.p).map_err(at("/fclib_local/W/p"))?;
    ints(&wg, "i", &w.i).map_err(at("/fclib_local/W/i"))?;
    floats(&wg, "x", &w.x).map_err(at("/fclib_local/W/x"))?;
    wg.new_attr::<i32>()
        .shape(1)
        .create(STORAGE_ATTRIBUTE)
        .and_then(|a| a.write_raw(&[w.storage]))
        .map_err(|e| format!("/fclib_local/W attribute {STORAGE_ATTRIBUTE}: {e}"))?;

    let vectors = local
        .create_group("vectors")
        .map_err(at("/fclib_local/vectors"))?;
    floats(&vectors, "q", problem.q()).map_err(at("/fclib_local/vectors/q"))?;
    floats(&vectors, "mu", problem.mu()).map_err(at("/fclib_local/vectors/mu"))?;

    let info_group = local
        .create_group("info")
        .map_err(at("/fclib_local/info"))?;
    write_info(&info_group, info).map_err(|e| format!("/fclib_local/{e}"))?;

    Ok(())
}

/// A one-dimensional dataset of C `int`s (`H5LTmake_dataset_int`).
pub(super) fn ints(group: &hdf5::Group, name: &str, values: &[i32]) -> hdf5::Result<()> {
    group
        .new_dataset_builder()
        .with_data(values)
        .create(name)
        .map(drop)
}

/// A one-dimensional dataset of doubles (`H5LTmake_dataset_double`).
pub(super) fn floats(group: &hdf5::Group, name: &str, values: &[f64]) -> hdf5::Result<()> {
    group
        .new_dataset_builder()
        .with_data(values)
        .create(name)
        .map(drop)
}
