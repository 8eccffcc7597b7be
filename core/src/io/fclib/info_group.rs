//! The `info` group of an FCLIB problem: the strings `title`, `description`, `math_info` and the
//! integer attribute `numberOfDegreeOfFreedom`.
//!
//! FCLIB writes each string with `H5LTmake_dataset_string`: a scalar dataset whose type is a copy
//! of `H5T_C_S1` (ASCII, NUL-terminated) sized to the string plus its NUL, and reads it back with
//! the dataset's own type into a buffer of that size. hdf5-metno's typed API only knows string
//! types whose length is a compile-time constant, so these datasets are written and read here
//! through the raw bindings (`hdf5-metno-sys`), under hdf5-metno's library lock. Variable-length
//! strings (what h5py writes by default) are read too.

use std::ffi::{c_char, c_void, CStr, CString};

use hdf5_metno as hdf5;
use hdf5_metno_sys::h5::{herr_t, H5free_memory};
use hdf5_metno_sys::h5d::H5Dwrite;
use hdf5_metno_sys::h5d::{H5Dclose, H5Dcreate2, H5Dget_space, H5Dget_type, H5Dopen2, H5Dread};
use hdf5_metno_sys::h5i::hid_t;
use hdf5_metno_sys::h5p::H5P_DEFAULT;
use hdf5_metno_sys::h5s::{
    H5S_class_t, H5Sclose, H5Screate, H5Sget_simple_extent_npoints, H5S_ALL,
};
use hdf5_metno_sys::h5t::{
    H5T_class_t, H5T_str_t, H5Tclose, H5Tcopy, H5Tget_class, H5Tget_cset, H5Tget_size,
    H5Tget_strpad, H5Tis_variable_str, H5Tset_cset, H5Tset_size, H5T_C_S1, H5T_VARIABLE,
};

use crate::io::info::FclibInfo;

/// The three FCLIB strings of the info group, in the order FCLIB writes them.
pub(super) const STRINGS: [&str; 3] = ["title", "description", "math_info"];

/// The attribute Siconos' `frictionContact_fclib_write` adds to the info group.
pub(super) const NDOF_ATTRIBUTE: &str = "numberOfDegreeOfFreedom";

/// The string fields of `info`, by dataset name.
pub(super) fn strings(info: &FclibInfo) -> [(&'static str, Option<&str>); 3] {
    [
        (STRINGS[0], info.title.as_deref()),
        (STRINGS[1], info.description.as_deref()),
        (STRINGS[2], info.math_info.as_deref()),
    ]
}

/// Writes the fields of `info` that are set into the (new, empty) group `group`. Errors are
/// messages naming the dataset or attribute.
pub(super) fn write_info(group: &hdf5::Group, info: &FclibInfo) -> Result<(), String> {
    for (name, value) in strings(info) {
        if let Some(value) = value {
            write_string(group, name, value).map_err(|e| format!("info/{name}: {e}"))?;
        }
    }
    if let Some(ndof) = info.number_of_degrees_of_freedom {
        group
            .new_attr::<i32>()
            .shape(1)
            .create(NDOF_ATTRIBUTE)
            .and_then(|a| a.write_raw(&[ndof]))
            .map_err(|e| format!("info attribute {NDOF_ATTRIBUTE}: {e}"))?;
    }
    Ok(())
}

/// A raw HDF5 identifier, closed when dropped (always inside the library lock: every `Id` lives
/// within one `hdf5::sync::sync` call).
struct Id {
    id: hid_t,
    close: unsafe extern "C" fn(hid_t) -> herr_t,
}

impl Id {
    /// Wraps `id`, or fails with `what` when the call that made it failed (negative id).
    fn new(
        id: hid_t,
        close: unsafe extern "C" fn(hid_t) -> herr_t,
        what: &str,
    ) -> Result<Self, String> {
        if id < 0 {
            Err(format!("{what} failed"))
        } else {
            Ok(Id { id, close })
        }
    }
}

impl Drop for Id {
    fn drop(&mut self) {
        // SAFETY: `id` is a valid identifier of the kind `close` releases, closed once.
        unsafe {
            (self.close)(self.id);
        }
    }
}

fn check(status: herr_t, what: &str) -> Result<(), String> {
    if status < 0 {
        Err(format!("{what} failed"))
    } else {
        Ok(())
    }
}

/// Writes `value` as FCLIB does: a scalar dataset of a fixed-length, NUL-terminated ASCII string
/// type of `value.len() + 1` bytes. `value` must not contain a NUL byte.
fn write_string(group: &hdf5::Group, name: &str, value: &str) -> Result<(), String> {
    let cname = CString::new(name).map_err(|_| "the name contains a NUL byte".to_string())?;
    let cvalue = CString::new(value).map_err(|_| "the string contains a NUL byte".to_string())?;
    let bytes = cvalue.as_bytes_with_nul();
    let parent = group.id();
    hdf5::sync::sync(|| {
        // SAFETY: every identifier passed to the library comes from it and is still open (the
        // `Id` guards close them after use); the buffer holds exactly the type's size in bytes.
        unsafe {
            let string_type = Id::new(H5Tcopy(*H5T_C_S1), H5Tclose, "H5Tcopy(H5T_C_S1)")?;
            check(H5Tset_size(string_type.id, bytes.len()), "H5Tset_size")?;
            let space = Id::new(H5Screate(H5S_class_t::H5S_SCALAR), H5Sclose, "H5Screate")?;
            let dataset = Id::new(
                H5Dcreate2(
                    parent,
                    cname.as_ptr(),
                    string_type.id,
                    space.id,
                    H5P_DEFAULT,
                    H5P_DEFAULT,
                    H5P_DEFAULT,
                ),
                H5Dclose,
                "H5Dcreate2",
            )?;
            check(
                H5Dwrite(
                    dataset.id,
                    string_type.id,
                    H5S_ALL,
                    H5S_ALL,
                    H5P_DEFAULT,
                    bytes.as_ptr().cast::<c_void>(),
                ),
                "H5Dwrite",
            )
        }
    })
}

/// Reads the string dataset `name` of `group`: fixed-length (FCLIB, ended by its first NUL,
/// trailing blanks of a space-padded type removed) or variable-length. The dataset must hold one
/// string of at most `max_bytes` bytes. Invalid UTF-8 is replaced by U+FFFD.
pub(super) fn read_string(
    group: &hdf5::Group,
    name: &str,
    max_bytes: u64,
) -> Result<String, String> {
    let cname = CString::new(name).map_err(|_| "the name contains a NUL byte".to_string())?;
    let parent = group.id();
    let bytes = hdf5::sync::sync(|| -> Result<Vec<u8>, String> {
        // SAFETY: as in `write_string`; a fixed-length read fills exactly `size` bytes, and a
        // variable-length read stores one pointer that the library allocated.
        unsafe {
            let dataset = Id::new(
                H5Dopen2(parent, cname.as_ptr(), H5P_DEFAULT),
                H5Dclose,
                "H5Dopen2",
            )?;
            let file_type = Id::new(H5Dget_type(dataset.id), H5Tclose, "H5Dget_type")?;
            if H5Tget_class(file_type.id) != H5T_class_t::H5T_STRING {
                return Err("is not a string dataset".into());
            }
            let space = Id::new(H5Dget_space(dataset.id), H5Sclose, "H5Dget_space")?;
            let count = H5Sget_simple_extent_npoints(space.id);
            if count != 1 {
                return Err(format!("holds {count} strings, expected one"));
            }
            let variable = H5Tis_variable_str(file_type.id);
            check(variable, "H5Tis_variable_str")?;
            if variable > 0 {
                let memory_type = Id::new(H5Tcopy(*H5T_C_S1), H5Tclose, "H5Tcopy(H5T_C_S1)")?;
                check(H5Tset_size(memory_type.id, H5T_VARIABLE), "H5Tset_size")?;
                check(
                    H5Tset_cset(memory_type.id, H5Tget_cset(file_type.id)),
                    "H5Tset_cset",
                )?;
                let mut text: *mut c_char = std::ptr::null_mut();
                check(
                    H5Dread(
                        dataset.id,
                        memory_type.id,
                        H5S_ALL,
                        H5S_ALL,
                        H5P_DEFAULT,
                        (&mut text as *mut *mut c_char).cast::<c_void>(),
                    ),
                    "H5Dread",
                )?;
                if text.is_null() {
                    return Ok(Vec::new());
                }
                let bytes = CStr::from_ptr(text).to_bytes().to_vec();
                H5free_memory(text.cast::<c_void>());
                Ok(bytes)
            } else {
                let size = H5Tget_size(file_type.id);
                if size == 0 || size as u64 > max_bytes {
                    return Err(format!("declares a string of {size} bytes"));
                }
                let mut buffer = Vec::new();
                buffer
                    .try_reserve_exact(size)
                    .map_err(|_| format!("cannot allocate {size} bytes for the string"))?;
                buffer.resize(size, 0u8);
                check(
                    H5Dread(
                        dataset.id,
                        file_type.id,
                        H5S_ALL,
                        H5S_ALL,
                        H5P_DEFAULT,
                        buffer.as_mut_ptr().cast::<c_void>(),
                    ),
                    "H5Dread",
                )?;
                if let Some(end) = buffer.iter().position(|&b| b == 0) {
                    buffer.truncate(end);
                }
                if H5Tget_strpad(file_type.id) == H5T_str_t::H5T_STR_SPACEPAD {
                    while buffer.last() == Some(&b' ') {
                        buffer.pop();
                    }
                }
                Ok(buffer)
            }
        }
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}
