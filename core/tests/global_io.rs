//! The global `.dat` reader and writer on the Siconos files of `../shared/data/siconos` (never
//! copied into the repository): every global file reads to the sizes and storages Siconos'
//! reader gives, writing then reading gives back an equal problem in every storage (the file's
//! own, bit for bit), the reduction of TwoRods1 equals Siconos' own condensed problem, and
//! damaged input is a `Parse` error naming the token, never a panic.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use fc3d_core::io::dat::{
    parse_global_dat, read_dat_file, read_global_dat_file, read_global_rolling_dat,
    write_global_dat, write_global_rolling_dat, GlobalDat, GlobalDatProblem, GlobalStorage,
    MatrixStorage,
};
use fc3d_core::problem::{GlobalProblem, GlobalRollingProblem};
use fc3d_core::{CsrMatrix, Fc3dError};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

fn data(name: &str) -> PathBuf {
    Path::new(DATA_DIR).join(name)
}

/// The global files: name, dimension, contacts, size of M, storage code of M (and of H: the
/// same in every Siconos file), as Siconos' `globalFrictionContact_new_from_filename` reads
/// them (GFC3D) and as their headers declare (gfc2d, Siconos 4.5's).
const GLOBAL_FILES: &[(&str, usize, usize, usize, usize)] = &[
    ("GFC3D_Example0.dat", 3, 1, 9, 0),
    ("GFC3D_Example00.dat", 3, 1, 3, 0),
    ("GFC3D_Example00_badly_scaled.dat", 3, 1, 3, 0),
    ("GFC3D_Example0_SBM.dat", 3, 1, 9, 1),
    ("GFC3D_Example1.dat", 3, 1, 3, 1),
    ("GFC3D_OneContact.dat", 3, 1, 39, 1),
    ("GFC3D_TwoRods1.dat", 3, 3, 54, 1),
    ("gfc2d_granularflowonwall_00000_00117.dat", 2, 0, 900, 2),
    ("gfc2d_granularflowonwall_00069_00350.dat", 2, 69, 900, 2),
    ("gfc2d_granularflowonwall_00230_00206.dat", 2, 230, 9000, 2),
];

fn available() -> bool {
    let ok = data("GFC3D_TwoRods1.dat").is_file();
    if !ok {
        eprintln!("../shared/data/siconos missing: skipped");
    }
    ok
}

/// `(dimension, contacts, ndof)` of a read problem.
fn sizes(p: &GlobalDatProblem) -> (usize, usize, usize) {
    match p {
        GlobalDatProblem::Spatial(p) => (3, p.n_contacts(), p.ndof()),
        GlobalDatProblem::Planar(p) => (2, p.n_contacts(), p.ndof()),
    }
}

fn write(dat: &GlobalDat<GlobalDatProblem>, storage: &GlobalStorage) -> String {
    let mut out = Vec::new();
    match &dat.problem {
        GlobalDatProblem::Spatial(p) => write_global_dat(p, storage, &mut out),
        GlobalDatProblem::Planar(p) => write_global_dat(p, storage, &mut out),
    }
    .unwrap();
    String::from_utf8(out).unwrap()
}

/// The non-zero entries of a matrix.
fn entries(m: &CsrMatrix) -> BTreeMap<(usize, usize), u64> {
    let mut e = BTreeMap::new();
    m.for_each_entry(|i, j, v| {
        if v != 0.0 {
            e.insert((i, j), v.to_bits());
        }
    });
    e
}

/// The same problem up to the zeros a storage keeps or drops.
fn same_values(a: &GlobalDatProblem, b: &GlobalDatProblem) {
    fn check<const D: usize>(a: &GlobalProblem<'_, D>, b: &GlobalProblem<'_, D>) {
        assert_eq!(entries(a.m()), entries(b.m()));
        assert_eq!(entries(a.h()), entries(b.h()));
        assert_eq!((a.q(), a.b(), a.mu()), (b.q(), b.b(), b.mu()));
    }
    match (a, b) {
        (GlobalDatProblem::Spatial(a), GlobalDatProblem::Spatial(b)) => check(a, b),
        (GlobalDatProblem::Planar(a), GlobalDatProblem::Planar(b)) => check(a, b),
        _ => panic!("dimension changed"),
    }
}

fn cumulative(sizes: &[usize]) -> Vec<usize> {
    sizes
        .iter()
        .scan(0, |s, &k| {
            *s += k;
            Some(*s)
        })
        .collect()
}

#[test]
fn every_global_file_reads_and_round_trips_in_every_storage() {
    if !available() {
        return;
    }
    for &(name, dim, nc, ndof, storage) in GLOBAL_FILES {
        let dat = read_global_dat_file(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(sizes(&dat.problem), (dim, nc, ndof), "{name}");
        assert_eq!(dat.storage.m.code(), storage, "{name}: M's storage");
        assert_eq!(dat.storage.h.code(), storage, "{name}: H's storage");

        // In its own storages: the same problem, bit for bit, and the same storages.
        let text = write(&dat, &dat.storage);
        let again = parse_global_dat(&text, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(again, dat, "{name}: written in its storages");
        // Written again, the text is the same.
        assert_eq!(write(&again, &again.storage), text, "{name}");

        // In the other storages: the same values.
        let (n, m) = (ndof, dim * nc);
        let blocks = GlobalStorage {
            m: MatrixStorage::SparseBlock {
                row_sizes: vec![n],
                col_sizes: vec![n],
            },
            h: MatrixStorage::SparseBlock {
                row_sizes: cumulative(&[n]),
                col_sizes: cumulative(&vec![dim; nc]),
            },
        };
        let mut others = vec![GlobalStorage::default()];
        // One block, or dense: n^2 values written.
        if n * n <= 100_000 {
            others.push(blocks);
            others.push(GlobalStorage {
                m: MatrixStorage::Dense,
                h: MatrixStorage::Dense,
            });
        }
        for storage in others {
            if m == 0 && matches!(storage.h, MatrixStorage::SparseBlock { .. }) {
                continue;
            }
            let text = write(&dat, &storage);
            let again = parse_global_dat(&text, name)
                .unwrap_or_else(|e| panic!("{name} in {storage:?}: {e}"));
            same_values(&again.problem, &dat.problem);
            assert_eq!(again.storage.m.code(), storage.m.code());
        }
    }
}

#[test]
fn two_rods_mass_has_two_27x27_blocks_and_reduces_to_the_condensed_file() {
    if !available() {
        return;
    }
    let dat = read_global_dat_file(&data("GFC3D_TwoRods1.dat")).unwrap();
    assert_eq!(
        dat.storage.m,
        MatrixStorage::SparseBlock {
            row_sizes: vec![27, 54],
            col_sizes: vec![27, 54],
        }
    );
    assert_eq!(
        dat.storage.h,
        MatrixStorage::SparseBlock {
            row_sizes: vec![27, 54],
            col_sizes: vec![3, 6, 9],
        }
    );
    let GlobalDatProblem::Spatial(p) = dat.problem else {
        panic!("3D")
    };
    // The reduction W = H^T M^-1 H, q = H^T M^-1 q + b against Siconos' condensed problem
    // (printed with 6 significant digits in its sparse-block W).
    let mut operator = p.operator().unwrap();
    let local = p.reduce(&mut operator).unwrap();
    let condensed = read_dat_file(&data("GFC3D_TwoRods1-condensed.dat")).unwrap();
    assert_eq!(local.n_contacts(), condensed.n_contacts());
    let scale = (0..9)
        .map(|i| condensed.w().get(i, i).abs())
        .fold(0.0, f64::max);
    for i in 0..9 {
        for j in 0..9 {
            let (a, b) = (local.w().get(i, j), condensed.w().get(i, j));
            assert!(
                (a - b).abs() <= 1e-5 * scale,
                "W[{i}][{j}]: {a} reduced, {b} in the condensed file"
            );
        }
        let (a, b) = (local.q()[i], condensed.q()[i]);
        assert!(
            (a - b).abs() <= 1e-5 * (1.0 + b.abs()),
            "q[{i}]: {a} vs {b}"
        );
    }
    assert_eq!(local.mu(), condensed.mu());
}

#[test]
fn the_condensed_two_rods_file_is_a_local_problem() {
    if !available() {
        return;
    }
    let path = data("GFC3D_TwoRods1-condensed.dat");
    assert!(read_dat_file(&path).is_ok());
    match read_global_dat_file(&path) {
        Err(Fc3dError::Parse { file, .. }) => assert!(file.ends_with("condensed.dat")),
        other => panic!("read as a global problem: {other:?}"),
    }
}

/// A global rolling problem: 2 bodies of 6 unknowns, 2 contacts of dimension 5.
fn rolling() -> GlobalRollingProblem<'static> {
    let mut m = Vec::new();
    for i in 0..12 {
        m.push((i, i, 1.0 + i as f64));
    }
    m.push((0, 1, 0.25));
    m.push((1, 0, 0.25));
    let mut h = Vec::new();
    for c in 0..2 {
        for k in 0..5 {
            h.push((6 * c + k, 5 * c + k, 1.0));
            h.push((6 * c + k + 1, 5 * c + k, -0.5));
        }
    }
    let base = GlobalProblem::<5>::new(
        CsrMatrix::from_triplets(12, 12, &m).unwrap(),
        CsrMatrix::from_triplets(12, 10, &h).unwrap(),
        (0..12).map(|i| -(i as f64) * 0.1).collect::<Vec<_>>(),
        vec![0.5; 10],
        vec![0.3, 0.6],
    )
    .unwrap();
    GlobalRollingProblem::new(base, vec![0.05, 0.1]).unwrap()
}

#[test]
fn a_rolling_problem_round_trips_in_every_storage() {
    let p = rolling();
    for storage in [
        GlobalStorage::default(),
        GlobalStorage {
            m: MatrixStorage::Dense,
            h: MatrixStorage::Dense,
        },
        GlobalStorage {
            m: MatrixStorage::SparseBlock {
                row_sizes: vec![6, 12],
                col_sizes: vec![6, 12],
            },
            h: MatrixStorage::SparseBlock {
                row_sizes: vec![6, 12],
                col_sizes: vec![5, 10],
            },
        },
    ] {
        let mut out = Vec::new();
        write_global_rolling_dat(&p, &storage, &mut out).unwrap();
        let (again, used) =
            read_global_rolling_dat(&out[..], Some(out.len() as u64), "rolling").unwrap();
        assert_eq!(used as usize, out.len());
        assert_eq!(again.storage, storage);
        assert_eq!(entries(again.problem.base().m()), entries(p.base().m()));
        assert_eq!(entries(again.problem.base().h()), entries(p.base().h()));
        assert_eq!(again.problem.mu_r(), p.mu_r());
        assert_eq!(again.problem.base().q(), p.base().q());
        assert_eq!(again.problem.base().b(), p.base().b());
    }
    // A rolling file is not a plain global one.
    let mut out = Vec::new();
    write_global_rolling_dat(&p, &GlobalStorage::default(), &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(matches!(
        parse_global_dat(&text, "rolling"),
        Err(Fc3dError::Parse { token_index: 0, .. })
    ));
}

/// The text of Example1 with the `k`th token replaced (tokens separated by whitespace).
fn example1_with(k: usize, token: &str) -> String {
    let text = std::fs::read_to_string(data("GFC3D_Example1.dat")).unwrap();
    let mut tokens: Vec<String> = text.split_whitespace().map(String::from).collect();
    tokens[k] = token.to_string();
    tokens.join("\n")
}

#[test]
fn damaged_files_are_parse_errors_naming_the_token() {
    if !available() {
        return;
    }
    let text = std::fs::read_to_string(data("GFC3D_Example1.dat")).unwrap();
    let tokens: Vec<&str> = text.split_whitespace().collect();
    // Every truncation fails with a parse error (no panic), at the end of the text.
    for cut in 0..tokens.len() - 1 {
        let short = tokens[..cut].join(" ");
        match parse_global_dat(&short, "cut") {
            Err(Fc3dError::Parse { token, .. }) => assert_eq!(token, "<end of file>", "cut {cut}"),
            other => panic!("cut at {cut}: {other:?}"),
        }
    }
    // Tokens: 0 dim, 1 nc, 2 M's storage, 3 rows, 4 columns, then M's sparse-block body (10
    // structure tokens, the block number, 9 values), then H's header at 25.
    let h = 25;
    assert_eq!(&tokens[h..h + 3], ["1", "3", "3"]);
    for (k, token, says) in [
        (0, "4", "dimension"),
        (4, "4", "square"),
        (h + 1, "4", "rows of M"),
        (h + 2, "4", "columns"),
        (2, "7", "storage"),
        (tokens.len() - 2, "-0.5", ">= 0"),
        (tokens.len() - 3, "nan", "finite"),
    ] {
        match parse_global_dat(&example1_with(k, token), "bad") {
            Err(Fc3dError::Parse {
                token_index,
                token: t,
                message,
                ..
            }) => {
                assert_eq!((token_index, t.as_str()), (k, token), "{message}");
                assert!(message.contains(says), "{message}");
            }
            other => panic!("token {k} = {token}: {other:?}"),
        }
    }
}
