//! A .dat problem read through the C API lands in the host's structures as the core reads it:
//! the readers fill C arrays directly (no core copy converted afterwards), so this checks, bit
//! for bit, that the SBM's index arrays, blocks and block sizes, a
//! dense W's values, q and mu are those of `fc3d_core::io::dat::read_dat_file_any`, read by file
//! name (length known: arrays allocated once) and from a pipe (length unknown: arrays grown as
//! values arrive).

#![cfg(feature = "siconos-abi")]

use std::ffi::CString;
use std::io::Write;
use std::os::fd::FromRawFd;
use std::path::{Path, PathBuf};

use fc3d::types::FrictionContactProblem;
use fc3d_core::io::dat::{read_dat_file_any, DatProblem};
use fc3d_core::Delassus;

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn frictionContact_newFromFile(file: *mut libc::FILE) -> *mut FrictionContactProblem;
}

fn shared(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/siconos")
        .join(name)
}

/// `name` read from a pipe fed by a thread (a stream of unknown length).
fn read_from_pipe(path: &Path) -> *mut FrictionContactProblem {
    let text = std::fs::read(path).unwrap();
    let mut fds = [0; 2];
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    let writer = std::thread::spawn(move || {
        let mut w = unsafe { std::fs::File::from_raw_fd(fds[1]) };
        // The reader stops after mu: a write to a closed pipe may fail, which is fine.
        let _ = w.write_all(&text);
    });
    let file = unsafe { libc::fdopen(fds[0], c"r".as_ptr()) };
    assert!(!file.is_null());
    let p = unsafe { frictionContact_newFromFile(file) };
    unsafe { libc::fclose(file) };
    writer.join().unwrap();
    p
}

unsafe fn slice<'a, T>(p: *const T, len: usize) -> &'a [T] {
    assert!(!p.is_null() || len == 0);
    if len == 0 {
        &[]
    } else {
        std::slice::from_raw_parts(p, len)
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Checks the C problem `c` against the core's reading of `path`.
unsafe fn check_same(c: *mut FrictionContactProblem, path: &Path, how: &str) {
    assert!(!c.is_null(), "{how}: {} not read", path.display());
    let c = &*c;
    let (dim, nc, w, q, mu) = match read_dat_file_any(path).unwrap() {
        DatProblem::Spatial(p) => (
            3,
            p.n_contacts(),
            p.w().clone(),
            p.q().to_vec(),
            p.mu().to_vec(),
        ),
        DatProblem::Planar(p) => (
            2,
            p.n_contacts(),
            p.w().clone(),
            p.q().to_vec(),
            p.mu().to_vec(),
        ),
    };
    assert_eq!(
        (c.dimension, c.numberOfContacts as usize),
        (dim, nc),
        "{how}"
    );
    assert_eq!(bits(slice(c.q, dim as usize * nc)), bits(&q), "{how}: q");
    assert_eq!(bits(slice(c.mu, nc)), bits(&mu), "{how}: mu");
    let m = &*c.M;
    assert_eq!(
        (m.size0 as usize, m.size1 as usize),
        (w.nrows(), w.ncols()),
        "{how}"
    );
    match &w {
        Delassus::Dense(d) => {
            assert_eq!(m.storageType, 0, "{how}");
            assert_eq!(
                bits(slice(m.matrix0, d.values().len())),
                bits(d.values()),
                "{how}: W"
            );
        }
        Delassus::SparseBlock(b) => {
            assert_eq!(m.storageType, 1, "{how}");
            let s = &*m.matrix1;
            let (nbr, nb) = (b.n_block_rows(), b.n_blocks());
            assert_eq!(s.nbblocks as usize, nb, "{how}");
            assert_eq!(
                (s.blocknumber0 as usize, s.blocknumber1 as usize),
                (nbr, b.n_block_cols())
            );
            assert_eq!((s.filled1, s.filled2), (nbr + 1, nb), "{how}");
            assert_eq!(
                slice(s.index1_data, nbr + 1),
                b.row_ptr(),
                "{how}: index1_data"
            );
            assert_eq!(slice(s.index2_data, nb), b.col_idx(), "{how}: index2_data");
            let sizes: Vec<u32> = (1..=nbr as u32).map(|k| 3 * k).collect();
            assert_eq!(slice(s.blocksize0, nbr), &sizes[..], "{how}: blocksize0");
            for (k, block) in b.blocks().enumerate() {
                let cb = slice(*s.block.add(k), 9);
                assert_eq!(bits(cb), bits(block), "{how}: block {k}");
            }
            // Left to be computed on demand, as Siconos' reader leaves it.
            assert!(s.diagonal_blocks.is_null(), "{how}: diagonal_blocks");
        }
        // A sparse W (and a 2D problem's) is built by the core and copied: compared by the
        // solver tests.
        Delassus::Sparse(_) => assert_eq!(m.storageType, 2, "{how}"),
    }
}

#[test]
fn problems_read_into_c_are_the_core_reading_bit_for_bit() {
    for name in [
        "Capsules-i100-889.dat",
        "Confeti-ex13-Fc3D-SBM.dat",
        "FC3D_Example1_SBM.dat",
        "Rover1039.dat",
        "NESpheres_10_1.dat",
        "FC2D_SliderCrankLagrangian00000.dat",
    ] {
        let path = shared(name);
        let c_path = CString::new(path.to_str().unwrap()).unwrap();
        unsafe {
            let by_name = frictionContact_new_from_filename(c_path.as_ptr());
            check_same(by_name, &path, &format!("{name} by name"));
            frictionContactProblem_free(by_name);
            let piped = read_from_pipe(&path);
            check_same(piped, &path, &format!("{name} from a pipe"));
            frictionContactProblem_free(piped);
        }
    }
}
