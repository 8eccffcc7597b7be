//! Typed errors of the core. The C layer maps each variant to a return code and a message.

use thiserror::Error;

/// Everything that can be wrong with the input of a solve or a file, as a typed value.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Fc3dError {
    /// Two sizes that must agree do not.
    #[error("dimension mismatch: {what}: expected {expected}, got {got}")]
    DimensionMismatch {
        what: String,
        expected: usize,
        got: usize,
    },
    /// A NaN or an infinity in the data.
    #[error("non-finite value in {what} at index {index}")]
    NonFinite { what: String, index: usize },
    /// Friction coefficients must be >= 0.
    #[error("negative friction coefficient mu[{contact}] = {value}")]
    NegativeFriction { contact: usize, value: f64 },
    /// A sparse-block W lacks the 3x3 diagonal block of a contact.
    #[error("the diagonal 3x3 block of contact {contact} is missing from W")]
    MissingDiagonalBlock { contact: usize },
    /// Index arrays that do not describe a valid matrix.
    #[error("invalid matrix structure: {0}")]
    InvalidStructure(String),
    /// A problem of another dimension than 3 given to a 3D reader or solver (a 2D friction
    /// problem: read it with `io::dat::read_dat_file_any`, solve it with `solve_planar`).
    #[error(
        "{file}: problems of dimension {dimension} are not supported here (3D only; read a 2D \
         problem with read_dat_file_any and solve it with solve_planar, or fc2d_driver in C)"
    )]
    UnsupportedDimension { file: String, dimension: usize },
    /// A storage or problem shape the library does not handle.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// A solver id that is not implemented.
    #[error("solver id {id} ({name}) is not implemented in fc3d")]
    UnsupportedSolver { id: i32, name: String },
    /// An option value out of its documented range.
    #[error("invalid option: {0}")]
    InvalidOption(String),
    /// A setting outside its documented range. `setting` names it as a path into the
    /// configuration (`tolerance`, `nsgs.relaxation`, `local.tolerance`, ...), so that the C
    /// layer can name the iparam/dparam index it came from.
    #[error("invalid option: {setting} = {value} must be {requirement}")]
    InvalidSetting {
        setting: &'static str,
        value: String,
        requirement: &'static str,
    },
    /// A malformed problem file.
    #[error("{file}: {message} (token {token_index}: '{token}')")]
    Parse {
        file: String,
        token_index: usize,
        token: String,
        message: String,
    },
    /// Memory for data of the given size could not be allocated (sizes come from the input).
    #[error("out of memory: {what} needs {bytes} bytes")]
    OutOfMemory { what: String, bytes: usize },
    /// An operating-system level I/O failure.
    #[error("{file}: {message}")]
    Io { file: String, message: String },
}

impl Fc3dError {
    /// An option or setting out of range ([`Fc3dError::InvalidOption`] or
    /// [`Fc3dError::InvalidSetting`]).
    pub fn is_invalid_option(&self) -> bool {
        matches!(
            self,
            Fc3dError::InvalidOption(_) | Fc3dError::InvalidSetting { .. }
        )
    }

    pub(crate) fn dims(what: impl Into<String>, expected: usize, got: usize) -> Self {
        Fc3dError::DimensionMismatch {
            what: what.into(),
            expected,
            got,
        }
    }
}

/// `Ok` when `holds`, else the [`Fc3dError::InvalidSetting`] naming `setting`, its `value` and
/// the `requirement` it breaks.
pub(crate) fn require_setting(
    holds: bool,
    setting: &'static str,
    value: impl std::fmt::Display,
    requirement: &'static str,
) -> Result<(), Fc3dError> {
    if holds {
        Ok(())
    } else {
        Err(Fc3dError::InvalidSetting {
            setting,
            value: value.to_string(),
            requirement,
        })
    }
}

/// A vector of `len` copies of `value`, allocated fallibly: an impossible size (from the input) is
/// an [`Fc3dError::OutOfMemory`] naming `what`, never an abort.
pub fn try_vec<T: Clone>(len: usize, value: T, what: &str) -> Result<Vec<T>, Fc3dError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| Fc3dError::OutOfMemory {
            what: what.to_string(),
            bytes: len.saturating_mul(std::mem::size_of::<T>()),
        })?;
    v.resize(len, value);
    Ok(v)
}

/// A copy of `values`, allocated fallibly (see [`try_vec`]).
pub fn try_copy<T: Clone>(values: &[T], what: &str) -> Result<Vec<T>, Fc3dError> {
    let mut v = Vec::new();
    v.try_reserve_exact(values.len())
        .map_err(|_| Fc3dError::OutOfMemory {
            what: what.to_string(),
            bytes: std::mem::size_of_val(values),
        })?;
    v.extend_from_slice(values);
    Ok(v)
}

/// Checks that every value is finite, naming the first offender.
pub fn check_finite(what: &str, values: &[f64]) -> Result<(), Fc3dError> {
    if all_finite(values) {
        return Ok(());
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Fc3dError::NonFinite {
            what: what.to_string(),
            index,
        }),
        None => Ok(()),
    }
}

/// Whether every value is finite, in one pass at the pace of memory: `x * 0` is 0 for a finite
/// `x` and NaN otherwise, summed in eight independent lanes (a test per value, which stops at
/// the first offender, runs at a value per several cycles).
pub fn all_finite(values: &[f64]) -> bool {
    let chunks = values.chunks_exact(8);
    let remainder = chunks.remainder();
    all_finite_lanes(chunks.map(|c| c.first_chunk::<8>().expect("8 values")))
        && remainder.iter().all(|v| v.is_finite())
}

/// [`all_finite`] over groups of `L` values, each group's values summed in the `L` lanes (the
/// groups may lie apart in memory, as the blocks of a host's sparse-block W do).
pub fn all_finite_lanes<'v, const L: usize>(groups: impl Iterator<Item = &'v [f64; L]>) -> bool {
    let mut sums = [0.0_f64; L];
    for g in groups {
        for (s, x) in sums.iter_mut().zip(g) {
            *s += x * 0.0;
        }
    }
    sums.iter().all(|&s| s == 0.0)
}
