//! The reader of one FCLIB file's datasets: opening the file, typed reads of groups, datasets
//! and attributes that turn every failure into an error naming the file, and the info group.

use std::path::Path;

use hdf5_metno as hdf5;
use hdf5_metno::types::TypeDescriptor;

use super::info_group;
use crate::alloc::{bytes_of, ensure_headroom};
use crate::error::Fc3dError;
use crate::io::info::FclibInfo;
use crate::problem::DIMENSION;

/// A dataset may declare at most this many values per byte of the file (guards allocations
/// against corrupt headers while leaving room for compressed datasets).
const MAX_VALUES_PER_FILE_BYTE: u64 = 64;

/// Opens an FCLIB file for reading, with the reader of its datasets.
pub(super) fn open(path: &Path) -> Result<(hdf5::File, Reader), Fc3dError> {
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

/// Reads datasets of one file, turning every failure into a typed error that names the file.
pub(super) struct Reader {
    pub(super) label: String,
    pub(super) max_values: u64,
}

impl Reader {
    pub(super) fn invalid(&self, message: impl std::fmt::Display) -> Fc3dError {
        Fc3dError::InvalidStructure(format!("{}: {message}", self.label))
    }

    pub(super) fn not_fclib(&self) -> Fc3dError {
        self.invalid("neither /fclib_local nor /fclib_global is present: not an FCLIB problem file")
    }

    pub(super) fn hdf5_error(&self, object: &str, e: hdf5::Error) -> Fc3dError {
        Fc3dError::Io {
            file: self.label.clone(),
            message: format!("{object}: HDF5 read failed: {e}"),
        }
    }

    pub(super) fn group(
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
    pub(super) fn dataset(
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
        // The hdf5 crate allocates the values it reads without a fallible path: probe first
        // (8 bytes a value: every read here is of i64 or f64).
        ensure_headroom(
            bytes_of(usize::try_from(size).unwrap_or(usize::MAX), 8),
            &format!("{}: {path}", self.label),
        )?;
        Ok((ds, path))
    }

    pub(super) fn type_of(
        &self,
        ds: &hdf5::Dataset,
        path: &str,
    ) -> Result<TypeDescriptor, Fc3dError> {
        ds.dtype()
            .and_then(|t| t.to_descriptor())
            .map_err(|e| self.invalid(format!("{path} has an unreadable datatype ({e})")))
    }

    pub(super) fn ints(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<Vec<i64>, Fc3dError> {
        let (ds, path) = self.dataset(parent, ppath, name)?;
        match self.type_of(&ds, &path)? {
            TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => {}
            other => {
                return Err(self.invalid(format!("{path} holds {other} values, expected integers")))
            }
        }
        ds.read_raw::<i64>().map_err(|e| self.hdf5_error(&path, e))
    }

    pub(super) fn int_scalar(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<i64, Fc3dError> {
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
    pub(super) fn size(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<usize, Fc3dError> {
        let v = self.int_scalar(parent, ppath, name)?;
        usize::try_from(v)
            .ok()
            .filter(|&s| (s as u64) <= self.max_values)
            .ok_or_else(|| self.invalid(format!("{ppath}/{name} = {v} is not a valid size")))
    }

    /// A float array; every value must be finite.
    pub(super) fn floats(
        &self,
        parent: &hdf5::Group,
        ppath: &str,
        name: &str,
    ) -> Result<Vec<f64>, Fc3dError> {
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

    pub(super) fn check_finite(&self, what: &str, values: &[f64]) -> Result<(), Fc3dError> {
        match values.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(Fc3dError::NonFinite {
                what: format!("{}: {what}", self.label),
                index,
            }),
            None => Ok(()),
        }
    }

    pub(super) fn spacedim(&self, group: &hdf5::Group, gpath: &str) -> Result<(), Fc3dError> {
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

    pub(super) fn check_len(
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
    pub(super) fn contacts(&self, path: &str, n: usize) -> Result<usize, Fc3dError> {
        if !n.is_multiple_of(DIMENSION) {
            return Err(self.invalid(format!(
                "{path} has {n} columns, not a multiple of the space dimension 3"
            )));
        }
        Ok(n / DIMENSION)
    }

    /// The integer attribute `name` of `object` (one value), named `apath` in messages.
    pub(super) fn int_attribute(
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
    pub(super) fn read_info(&self, ig: &hdf5::Group, ipath: &str) -> Result<FclibInfo, Fc3dError> {
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
}
