//! The global problems' files, copies, velocities and reformulations through the C ABI (issue 26):
//! what is written reads back the same, a copy writes the same text, the global velocity solves
//! the balance, the reformulations are exact both ways, FCLIB files go through the C functions.

use std::ffi::{c_char, c_int};
use std::ptr::null_mut;

use fc3d::types::FrictionContactProblem;
use fc3d_core::io::dat::{read_dat_file, read_global_dat_file};

mod siconos_api;
use siconos_api::*;
mod global_api;
use global_api::*;

#[test]
fn files_copies_and_velocities_keep_the_problem() {
    if !available() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("fc3d-global-c-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for &name in GLOBAL_FILES {
        let p = CProblem::read(name);
        let copy = CProblem(unsafe { globalFrictionContact_copy(p.0) });
        assert!(!copy.0.is_null(), "{name}: {}", last_message());
        assert_eq!(
            unsafe { ((*p.get().M).storageType, (*copy.get().M).storageType) },
            unsafe { ((*p.get().M).storageType, (*p.get().M).storageType) }
        );
        let (a, b) = (dir.join("a.dat"), dir.join("b.dat"));
        for (problem, path) in [(&p, &a), (&copy, &b)] {
            let c = c_path(path);
            assert_eq!(
                unsafe { globalFrictionContact_printInFileName(problem.0, c.as_ptr()) },
                0
            );
        }
        let text = std::fs::read_to_string(&a).unwrap();
        assert_eq!(text, std::fs::read_to_string(&b).unwrap(), "{name}: copy");
        // The file written reads back to the same problem.
        let again = read_global_dat_file(&a).unwrap();
        let original = read_global_dat_file(&data(name)).unwrap();
        assert_eq!(again, original, "{name}");

        // v = M^-1 (q + H r) for a reaction.
        let core = core_problem(name);
        let r: Vec<f64> = (0..core.size()).map(|k| (k as f64 * 0.37).sin()).collect();
        let mut v = vec![0.0; core.ndof()];
        let mut rr = r.clone();
        let code = unsafe {
            globalFrictionContact_computeGlobalVelocity(p.0, rr.as_mut_ptr(), v.as_mut_ptr())
        };
        assert_eq!(code, 0, "{name}: {}", last_message());
        let mut mv = vec![0.0; core.ndof()];
        core.m().mul_add(&v, &mut mv);
        let mut rhs = core.q().to_vec();
        core.h().mul_add(&r, &mut rhs);
        let diff: Vec<f64> = mv.iter().zip(&rhs).map(|(a, b)| a - b).collect();
        assert!(norm(&diff) <= 1e-12 * norm(&rhs).max(1.0), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn reformulations_are_exact() {
    if !available() {
        return;
    }
    // Global -> local: TwoRods1 reduces to Siconos' condensed problem.
    let p = CProblem::read("GFC3D_TwoRods1.dat");
    let local = unsafe { globalFrictionContact_reformulation_FrictionContact(p.0) };
    assert!(!local.is_null(), "{}", last_message());
    let condensed = read_dat_file(&data("GFC3D_TwoRods1-condensed.dat")).unwrap();
    let w = unsafe { &*(*local).M };
    assert_eq!((w.size0, w.size1), (9, 9));
    // Local -> global -> local: the same W and q.
    let path = c_path(&data("FC3D_Example1_SBM.dat"));
    let fc = unsafe { frictionContact_new_from_filename(path.as_ptr()) };
    assert!(!fc.is_null());
    let g = unsafe { fc3d_reformulation_global_problem(fc) };
    assert!(!g.is_null(), "{}", last_message());
    let back = unsafe { globalFrictionContact_reformulation_FrictionContact(g) };
    assert!(!back.is_null(), "{}", last_message());
    let original = read_dat_file(&data("FC3D_Example1_SBM.dat")).unwrap();
    let dir = std::env::temp_dir().join(format!("fc3d-reform-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (problem, file, expected) in [
        (local, "local.dat", &condensed),
        (back, "back.dat", &original),
    ] {
        let out = c_path(&dir.join(file));
        extern "C" {
            fn frictionContact_printInFilename(
                problem: *mut FrictionContactProblem,
                filename: *const c_char,
            ) -> c_int;
        }
        assert_eq!(
            unsafe { frictionContact_printInFilename(problem, out.as_ptr()) },
            0
        );
        let got = read_dat_file(&dir.join(file)).unwrap();
        let n = expected.size();
        let scale = (0..n)
            .map(|i| expected.w().get(i, i).abs())
            .fold(0.0, f64::max);
        // The condensed file has 6 significant digits.
        let tolerance = if file == "local.dat" { 1e-5 } else { 1e-13 };
        for i in 0..n {
            for j in 0..n {
                let (a, b) = (got.w().get(i, j), expected.w().get(i, j));
                assert!(
                    (a - b).abs() <= tolerance * scale,
                    "{file} W[{i}][{j}] {a} {b}"
                );
            }
            let (a, b) = (got.q()[i], expected.q()[i]);
            assert!(
                (a - b).abs() <= tolerance * (1.0 + b.abs()),
                "{file} q[{i}] {a} {b}"
            );
        }
        assert_eq!(got.mu(), expected.mu());
        unsafe { frictionContactProblem_free(problem) };
    }
    unsafe {
        frictionContactProblem_free(fc);
        globalFrictionContact_free(g);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Box_Stacks' global problem through the FCLIB functions: read (by name and with
/// `globalFrictionContact_fclib_read`), solved, written and read back the same. Without FCLIB
/// support every call fails with `FC3D_ERR_IO`, writing nothing.
#[test]
fn fclib_global_files_through_the_c_api() {
    if !available() {
        return;
    }
    let path = c_path(&data("Box_Stacks-i0122-82-5.hdf5"));
    let dir = std::env::temp_dir().join(format!("fc3d-global-fclib-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = c_path(&dir.join("box.hdf5"));
    let mut title = *b"Box stacks\0";
    if !fc3d_core::io::FCLIB_AVAILABLE {
        let p = unsafe { globalFrictionContact_new_from_filename(path.as_ptr()) };
        assert!(p.is_null());
        assert_eq!(unsafe { fc3d_last_error_code() }, fc3d::FC3D_ERR_IO);
        assert!(last_message().contains("FCLIB"), "{}", last_message());
        assert!(unsafe { globalFrictionContact_fclib_read(path.as_ptr()) }.is_null());
        return;
    }
    let p = CProblem::read("Box_Stacks-i0122-82-5.hdf5");
    assert_eq!(
        (p.get().numberOfContacts, unsafe { (*p.get().M).size0 }),
        (82, 450)
    );
    let o = Options::new(600, 1e-5, 10000);
    let (n, m) = (450, 246);
    let (mut r, mut u, mut v) = (vec![0.0; m], vec![0.0; m], vec![0.0; n]);
    let info = unsafe { gfc3d_driver(p.0, r.as_mut_ptr(), u.as_mut_ptr(), v.as_mut_ptr(), o.0) };
    assert_eq!(info, 0, "{}", last_message());
    assert!(o.dparam(1) <= 1e-5);
    let written = unsafe {
        globalFrictionContact_fclib_write(
            p.0,
            title.as_mut_ptr().cast(),
            null_mut(),
            null_mut(),
            out.as_ptr(),
        )
    };
    assert_eq!(written, 1, "{}", last_message());
    let again = CProblem(unsafe { globalFrictionContact_fclib_read(out.as_ptr()) });
    assert!(!again.0.is_null(), "{}", last_message());
    let (a, b) = (dir.join("a.dat"), dir.join("b.dat"));
    for (problem, file) in [(&p, &a), (&again, &b)] {
        let c = c_path(file);
        assert_eq!(
            unsafe { globalFrictionContact_printInFileName(problem.0, c.as_ptr()) },
            0
        );
    }
    assert_eq!(
        std::fs::read_to_string(&a).unwrap(),
        std::fs::read_to_string(&b).unwrap()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
