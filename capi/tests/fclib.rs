//! FCLIB through the C ABI, called as a C host calls it: `frictionContact_fclib_write` then
//! `frictionContact_fclib_read` (and `frictionContact_new_from_filename` on the `.hdf5` file)
//! give back the same problem, W in the same storage, every value bit for bit, on every shared
//! 3D problem in its own storage and on two in all three storages; invalid calls fail with the
//! documented codes and write nothing.
//!
//! When libfc3d is built without FCLIB support (`fc3d_core::io::FCLIB_AVAILABLE` false: neither
//! the `fclib` feature of fc3d nor that of fc3d-core), the same functions exist and fail cleanly:
//! NULL / `FC3D_ERR_IO` with a message naming the missing support, and no file. The test checks
//! whichever build it runs in (`cargo test -p fc3d --test fclib` with and without
//! `--features fclib`).

#![cfg(feature = "siconos-abi")]

use std::ffi::{c_char, CStr, CString};
use std::os::raw::c_int;
use std::path::{Path, PathBuf};
use std::ptr::{null, null_mut};

use fc3d::types::FrictionContactProblem;
use fc3d::{FC3D_ERR_INVALID_PROBLEM, FC3D_ERR_IO, FC3D_ERR_NULL_POINTER, FC3D_OK};

/// What `frictionContact_fclib_write` returns on success, as Siconos (fclib) does.
const SICONOS_FCLIB_SUCCESS: c_int = 1;
use fc3d_core::io::{read_problem_file, write_dat_file, FCLIB_AVAILABLE};
use fc3d_core::matrix::Delassus;

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn frictionContact_fclib_read(path: *const c_char) -> *mut FrictionContactProblem;
    fn frictionContact_fclib_write(
        problem: *mut FrictionContactProblem,
        title: *mut c_char,
        description: *mut c_char,
        mathInfo: *mut c_char,
        path: *const c_char,
        ndof: c_int,
    ) -> c_int;
    fn frictionContact_printInFilename(
        problem: *mut FrictionContactProblem,
        filename: *mut c_char,
    ) -> c_int;
}

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

fn cstr(path: &Path) -> CString {
    CString::new(path.to_str().unwrap()).unwrap()
}

fn last_error() -> (c_int, String) {
    // SAFETY: fc3d returns a valid NUL-terminated string it owns.
    unsafe {
        (
            fc3d_last_error_code(),
            CStr::from_ptr(fc3d_last_error_message())
                .to_string_lossy()
                .into_owned(),
        )
    }
}

/// A scratch directory removed at the end.
struct Scratch(PathBuf);

impl Scratch {
    fn new(tag: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("fc3d-capi-fclib-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
    fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A C problem read from a file by `frictionContact_new_from_filename`, released on drop.
struct CProblem(*mut FrictionContactProblem);

impl CProblem {
    fn from_file(path: &Path) -> Option<Self> {
        // SAFETY: a valid C string.
        let p = unsafe { frictionContact_new_from_filename(cstr(path).as_ptr()) };
        (!p.is_null()).then_some(CProblem(p))
    }

    fn from_fclib(path: &Path) -> Option<Self> {
        // SAFETY: a valid C string.
        let p = unsafe { frictionContact_fclib_read(cstr(path).as_ptr()) };
        (!p.is_null()).then_some(CProblem(p))
    }

    fn storage(&self) -> c_int {
        // SAFETY: fc3d filled the problem and its matrix.
        unsafe { (*(*self.0).M).storageType }
    }

    /// The problem as `.dat` text written by `frictionContact_printInFilename`: W in its
    /// storage and every number in its shortest exact form (signs of zeros included), so equal
    /// texts are equal problems bit for bit.
    fn dat(&self, scratch: &Scratch, name: &str) -> String {
        let path = scratch.path(name);
        let c = cstr(&path);
        // SAFETY: a valid problem and C string; fc3d does not keep the name.
        let rc = unsafe { frictionContact_printInFilename(self.0, c.as_ptr() as *mut c_char) };
        assert_eq!(rc, FC3D_OK, "{:?}", last_error());
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        text
    }

    /// `frictionContact_fclib_write(self, title, description, mathInfo, path, ndof)`.
    fn write_fclib(&self, path: &Path, title: Option<&str>) -> c_int {
        let title = title.map(|t| CString::new(t).unwrap());
        let description = CString::new("written through fc3d's C ABI").unwrap();
        let path = cstr(path);
        // SAFETY: valid problem and C strings (fc3d does not modify or keep them).
        unsafe {
            frictionContact_fclib_write(
                self.0,
                title
                    .as_ref()
                    .map_or(null_mut(), |t| t.as_ptr() as *mut c_char),
                description.as_ptr() as *mut c_char,
                null_mut(),
                path.as_ptr(),
                -1,
            )
        }
    }
}

impl Drop for CProblem {
    fn drop(&mut self) {
        // SAFETY: allocated by fc3d, released once.
        unsafe { frictionContactProblem_free(self.0) }
    }
}

/// The 3D local problems of the shared collection (global and 2D files excluded).
fn shared_3d_problems() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(DATA_DIR)
        .expect("../shared/data/siconos")
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_str().unwrap();
            n.ends_with(".dat")
                && ![
                    "GFC3D_",
                    "gfc2d_",
                    "fc2d_",
                    "FC2D_",
                    "FrictionContactProblem",
                    "ACinputs",
                ]
                .iter()
                .any(|pre| n.starts_with(pre))
        })
        .collect();
    files.sort();
    files
}

/// `.dat` -> C problem -> `frictionContact_fclib_write` -> `frictionContact_fclib_read` and
/// `frictionContact_new_from_filename`: the same storage and the same text.
fn round_trip(scratch: &Scratch, dat: &Path, label: &str) {
    let original =
        CProblem::from_file(dat).unwrap_or_else(|| panic!("{label}: {:?}", last_error()));
    let hdf5 = scratch.path(&format!("{label}.hdf5"));
    assert_eq!(
        original.write_fclib(&hdf5, Some(label)),
        SICONOS_FCLIB_SUCCESS,
        "{label}: {:?}",
        last_error()
    );
    let expected = original.dat(scratch, "expected.dat");
    for (reader, back) in [
        ("frictionContact_fclib_read", CProblem::from_fclib(&hdf5)),
        (
            "frictionContact_new_from_filename",
            CProblem::from_file(&hdf5),
        ),
    ] {
        let back = back.unwrap_or_else(|| panic!("{label}: {reader}: {:?}", last_error()));
        assert_eq!(back.storage(), original.storage(), "{label}: {reader}");
        assert_eq!(back.dat(scratch, "back.dat"), expected, "{label}: {reader}");
    }
    // The Rust reader sees the same problem as the C host.
    let rust = read_problem_file(&hdf5).unwrap();
    assert_eq!(
        rust,
        fc3d_core::io::parse_dat(&expected, label).unwrap(),
        "{label}"
    );
    std::fs::remove_file(&hdf5).unwrap();
}

#[test]
fn write_then_read_gives_back_the_same_problem() {
    if !FCLIB_AVAILABLE {
        return; // see without_fclib_support_the_functions_fail_cleanly
    }
    let s = Scratch::new("roundtrip");
    let files = shared_3d_problems();
    assert_eq!(files.len(), 30);
    for path in &files {
        round_trip(&s, path, path.file_name().unwrap().to_str().unwrap());
    }
    // Every storage a C host can hand over: dense (0), sparse-block (1), sparse (2, CSC).
    for name in ["Confeti-ex13-4contact-Fc3D-SBM.dat", "Rover4396.dat"] {
        let p = read_problem_file(&data(name)).unwrap();
        for (storage, w) in [
            ("dense", Delassus::Dense(p.w().to_dense())),
            (
                "sparse-block",
                Delassus::SparseBlock(p.w().to_block_sparse().unwrap()),
            ),
            ("csr", Delassus::Sparse(p.w().to_csr())),
        ] {
            let dat = s.path(&format!("{storage}-{name}"));
            write_dat_file(&p.with_w(w).unwrap(), &dat).unwrap();
            round_trip(&s, &dat, &format!("{storage}-{name}"));
            std::fs::remove_file(&dat).unwrap();
        }
    }
    assert!(s.files().is_empty(), "{:?}", s.files());
}

#[test]
fn foreign_fclib_files_are_read_as_siconos_reads_them() {
    if !FCLIB_AVAILABLE {
        return;
    }
    // A local problem written by Siconos (W in compressed rows) and a global one (reduced).
    for (name, nc) in [
        ("LMGC_100_PR_PerioBox-i00361-60-03000.hdf5", 60),
        ("Box_Stacks-i0122-82-5.hdf5", 82),
    ] {
        for p in [
            CProblem::from_fclib(&data(name)),
            CProblem::from_file(&data(name)),
        ] {
            let p = p.unwrap_or_else(|| panic!("{name}: {:?}", last_error()));
            // SAFETY: filled by fc3d.
            let (dim, n) = unsafe { ((*p.0).dimension, (*p.0).numberOfContacts) };
            assert_eq!((dim, n), (3, nc), "{name}");
            assert_eq!(p.storage(), 1, "{name}: sparse-block, as Siconos' reader");
        }
    }
}

#[test]
fn invalid_calls_fail_with_their_codes_and_write_nothing() {
    let s = Scratch::new("invalid");
    let out = s.path("out.hdf5");
    let out_c = cstr(&out);
    let p = CProblem::from_file(&data("FC3D_Example1.dat")).unwrap();
    // SAFETY: every pointer is valid or NULL, as each case says.
    unsafe {
        fc3d_clear_last_error();
        assert!(frictionContact_fclib_read(null()).is_null());
        assert_eq!(last_error().0, FC3D_ERR_NULL_POINTER);
        assert!(
            last_error().1.contains("path is NULL"),
            "{:?}",
            last_error()
        );

        let rc = frictionContact_fclib_write(
            null_mut(),
            null_mut(),
            null_mut(),
            null_mut(),
            out_c.as_ptr(),
            0,
        );
        assert_eq!((rc, last_error().0), (0, FC3D_ERR_NULL_POINTER));
        let rc = frictionContact_fclib_write(p.0, null_mut(), null_mut(), null_mut(), null(), 0);
        assert_eq!((rc, last_error().0), (0, FC3D_ERR_NULL_POINTER));

        // A 2D problem is refused before any file is touched.
        (*p.0).dimension = 2;
        let rc =
            frictionContact_fclib_write(p.0, null_mut(), null_mut(), null_mut(), out_c.as_ptr(), 0);
        (*p.0).dimension = 3;
        assert_eq!((rc, last_error().0), (0, FC3D_ERR_INVALID_PROBLEM));

        // Missing files and directories.
        let missing = cstr(&s.path("missing.hdf5"));
        assert!(frictionContact_fclib_read(missing.as_ptr()).is_null());
        assert_eq!(last_error().0, FC3D_ERR_IO, "{:?}", last_error());
        assert!(
            last_error().1.contains("missing.hdf5"),
            "{:?}",
            last_error()
        );
        assert!(frictionContact_new_from_filename(missing.as_ptr()).is_null());
        assert_eq!(last_error().0, FC3D_ERR_IO, "{:?}", last_error());
        let nowhere = cstr(&s.path("no/such/dir/out.hdf5"));
        let rc = frictionContact_fclib_write(
            p.0,
            null_mut(),
            null_mut(),
            null_mut(),
            nowhere.as_ptr(),
            0,
        );
        assert_eq!((rc, last_error().0), (0, FC3D_ERR_IO));
    }
    assert!(s.files().is_empty(), "{:?}", s.files());

    if FCLIB_AVAILABLE {
        // A text file named .hdf5 is not an FCLIB file: an I/O error naming it, not a crash.
        let text = s.path("text.hdf5");
        std::fs::write(&text, "3\n1\n0\n3\n3\n").unwrap();
        assert!(CProblem::from_fclib(&text).is_none());
        let (code, message) = last_error();
        assert_eq!(code, FC3D_ERR_IO, "{message}");
        assert!(message.contains("text.hdf5"), "{message}");
        // An existing file is replaced, atomically.
        assert_eq!(
            p.write_fclib(&text, None),
            SICONOS_FCLIB_SUCCESS,
            "{:?}",
            last_error()
        );
        assert_eq!(
            CProblem::from_fclib(&text).unwrap().dat(&s, "a.dat"),
            p.dat(&s, "b.dat")
        );
        assert_eq!(s.files(), ["text.hdf5"]);
    }
}

#[test]
fn without_fclib_support_the_functions_fail_cleanly() {
    if FCLIB_AVAILABLE {
        return; // see write_then_read_gives_back_the_same_problem
    }
    let s = Scratch::new("nofclib");
    let p = CProblem::from_file(&data("FC3D_Example1.dat")).unwrap();
    let out = s.path("out.hdf5");
    assert_eq!(p.write_fclib(&out, Some("title")), 0);
    assert_eq!(last_error().0, FC3D_ERR_IO);
    let (code, message) = last_error();
    assert_eq!(code, FC3D_ERR_IO);
    assert!(message.contains("frictionContact_fclib_write"), "{message}");
    assert!(message.contains("out.hdf5"), "{message}");
    assert!(message.contains("without FCLIB support"), "{message}");
    assert!(s.files().is_empty(), "{:?}", s.files());

    let shared = data("LMGC_100_PR_PerioBox-i00361-60-03000.hdf5");
    assert!(CProblem::from_fclib(&shared).is_none());
    let (code, message) = last_error();
    assert_eq!(code, FC3D_ERR_IO);
    assert!(message.contains("frictionContact_fclib_read"), "{message}");
    assert!(message.contains("without FCLIB support"), "{message}");
    assert!(CProblem::from_file(&shared).is_none());
    let (code, message) = last_error();
    assert_eq!(code, FC3D_ERR_IO);
    assert!(
        message.contains("frictionContact_new_from_filename"),
        "{message}"
    );
    assert!(message.contains("without FCLIB support"), "{message}");
    // .dat files are read as before, even those named *.hdf5.dat.
    assert!(CProblem::from_file(&data("BoxesStack1-i100000-32.hdf5.dat")).is_some());
}
