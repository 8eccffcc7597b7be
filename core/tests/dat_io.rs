//! The `.dat` reader and writer against the Siconos data files in `../shared/data/siconos`
//! (never copied into the repository): every 3D file parses to what Siconos 4.4 reads from it,
//! writing and re-reading is bit-exact in every storage, and damaged input gives a `Parse` error
//! that names the file, never a panic.

use std::path::{Path, PathBuf};

use fc3d_core::io::{
    parse_dat, parse_matrix, parse_matrix_prefix, parse_sbm, parse_sbm_prefix, read_dat_file,
    write_dat, write_dat_file, write_matrix, write_sbm,
};
use fc3d_core::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix, Fc3dError, FrictionProblem};
use proptest::prelude::*;

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

/// Name, contacts, storage code, W[0,0], q[0], mu[0], hashes of W, q and mu.
type SiconosRead = (&'static str, usize, usize, f64, f64, f64, u64, u64, u64);

/// What Siconos 4.4 reads from each local 3D file (`frictionContact_new_from_filename`, W
/// densified with `NM_get_value`); the hashes are FNV-1a over the bits of dense W (column-major),
/// q and mu (-0 counted as +0). Produced by a throwaway C program linked with `-lsiconos_numerics`.
#[rustfmt::skip]
const SICONOS_READS: &[SiconosRead] = &[
    ("BoxesStack1-i100000-32.hdf5.dat", 52, 1, 100.0, -0.004905000002339639, 0.7, 0x1e68d45c10a68fb0, 0xc713520646ebb5c1, 0x9386e0fc07955345),
    ("Capsules-i100-1090.dat", 276, 1, 1.8960847104574132, -0.004904997696345398, 0.7, 0x224d14f7b322e81c, 0xc5e45ce592e16da8, 0x4952f6a95ce7ac45),
    ("Capsules-i100-889.dat", 276, 1, 1.896083270572581, -0.004905000011238311, 0.7, 0xb6e12e140e32d2c6, 0xa64ee7904010ad8d, 0x4952f6a95ce7ac45),
    ("Capsules-i101-404.dat", 225, 1, 1.8960832727845054, -0.004905000000074441, 0.7, 0x9b704fc5bb33201f, 0x831bd7b0bae50e02, 0x4359c0fdf8a70e1a),
    ("Capsules-i103-990.dat", 275, 1, 1.896083271498419, -0.00490499999880544, 0.7, 0xad3bb90c228727c3, 0xd4fec606e0190f63, 0xa8ac098414ab344a),
    ("Confeti-ex03-Fc3D-SBM.dat", 54, 1, 3.978874e-05, -0.1961647554406818, 0.4, 0xc86553279f752a7f, 0x507e618c737f15bb, 0x41612d8e6cbf0dc1),
    ("Confeti-ex13-4contact-Fc3D-SBM.dat", 4, 1, 5.220412e-05, 0.43898786629311703, 0.04, 0x7bef06e6851e9cf7, 0xe004e91333346d8a, 0x74dcecb05f4e90e5),
    ("Confeti-ex13-Fc3D-SBM.dat", 107, 1, 1.335327e-05, -29.666781889659433, 0.04, 0x52ea4a7e8e364bea, 0xa5c189ed75489d82, 0xd2aade1699024683),
    ("FC3D_Example1.dat", 3, 0, 1.0, -1.0, 0.1, 0xec1f75e96a5a8ab8, 0x1b8c8051872cc2fd, 0x9498a5daa33bad80),
    ("FC3D_Example1_SBM.dat", 3, 1, 1.0, -1.0, 0.1, 0xec1f75e96a5a8ab8, 0x1b8c8051872cc2fd, 0x9498a5daa33bad80),
    ("FrictionContact3D_1c.dat", 1, 0, 15.0, -1.0, 0.1, 0x3e971dae8116c7c7, 0x4e77aab06869d3f0, 0x4fa09cc0eec310c4),
    ("FrictionContact3D_RR_1c.dat", 1, 0, 0.01344, -0.1458, 0.6, 0xfe777e985e6e1c4b, 0xb467df52437a9052, 0x43f7b2c96727af99),
    ("NESpheres_10_1.dat", 9, 0, 0.2, -0.09809999999999792, 0.8, 0x11aa936d3dc883e2, 0xdaa2de751bf193c2, 0x88b19ce51ad299e4),
    ("NESpheres_30_1.dat", 44, 0, 0.4, 0.0, 0.8, 0x95b0ac7525d671dc, 0xcbe1bd58d6191f27, 0x0f6bdb51452364bd),
    ("OneObject-i100000-316.hdf5.dat", 25, 1, 3.6151272655237587, -5.988444166876716e-05, 0.3, 0xd96c3621f9c9e845, 0x84d4b4fb385c9dae, 0x8b0c0f2496dfc309),
    ("OneObject-i1028-138.hdf5.dat", 23, 1, 3.199203009793331, 0.0006539698698202479, 0.3, 0x7c1c0624051e8178, 0xca995ce3f493c469, 0x419c54cb04fc5169),
    ("RockPile_tob1.dat", 463, 1, 7.796024884104368, -1.3322676295501878e-15, 1.0, 0xe48cb07674a4c121, 0x6380d163cc1d74e1, 0x39a4fd16187dec98),
    ("Rover1039.dat", 4, 0, 0.013991323801233675, -0.0925587358343308, 0.7, 0x8bd8a64126d30ad3, 0xc6e032ef38946dc5, 0x079ddc82ebd989c5),
    ("Rover1040.dat", 5, 0, 0.013992195795588667, -0.0992303372500856, 0.7, 0xedd40b3e1c848662, 0x0ef78f9a4f1d01e1, 0x3859d0b52474ddba),
    ("Rover1041.dat", 5, 0, 0.013993070477515203, -0.09274297736985523, 0.7, 0x3199da50b36414b4, 0x165a42fa3727908c, 0x3859d0b52474ddba),
    ("Rover11035.dat", 1, 0, 0.013583095681423556, -0.0541770492217097, 0.7, 0x63b2fc1304eda2c8, 0x107956075dbc66e8, 0xd3edcf664362151a),
    ("Rover11211.dat", 1, 0, 0.0131139862028829, -57.0047768427723, 0.7, 0xbc1b599772bf3372, 0x61b5127baceb68d6, 0xd3edcf664362151a),
    ("Rover3865.dat", 5, 0, 0.013536436491572063, -0.07771527867915212, 0.7, 0xa3f080ecc690a75f, 0xd589ac9bebe56e2e, 0x3859d0b52474ddba),
    ("Rover4144.dat", 4, 0, 0.013360200353845665, -0.10194201122610648, 0.7, 0x4934a8023939402a, 0x6b006fe0037927d0, 0x079ddc82ebd989c5),
    ("Rover4396.dat", 2, 0, 0.012062654401707928, -0.07993436691636902, 0.7, 0xa9ef4bcb9718110c, 0x74f4b86c4ecd1c97, 0x28019c31405d34b5),
    ("Rover4493.dat", 4, 0, 0.01374036428786303, -0.08300326249946081, 0.7, 0x4d6730bb7989cc73, 0x78314f34e63c79a9, 0x079ddc82ebd989c5),
    ("Rover4516.dat", 4, 0, 0.013846716055977194, -0.08309890212753981, 0.7, 0xa794ac6fa4e85a27, 0x6a6e9829a041ba3d, 0x079ddc82ebd989c5),
    ("Rover4609.dat", 5, 0, 0.01407184234419233, -0.08677968871073319, 0.7, 0x2dbc54d90145653a, 0x9c514734da4b079d, 0x3859d0b52474ddba),
    ("Rover4613.dat", 5, 0, 0.014075433144897592, -0.08687219229741414, 0.7, 0xa80b8cac0a1a188b, 0xa40d7e7de065f66e, 0x3859d0b52474ddba),
    ("Rover4622.dat", 4, 0, 0.014083767148191045, -0.08653501160976144, 0.7, 0xf3d54d633bc5b0df, 0xad552afee71de305, 0x079ddc82ebd989c5),
];

/// The reduced-form (local) problem files: not global problems (`GFC3D_`, `gfc2d_`), not the 2D
/// local files written in another layout (`fc2d_`, `FC2D_`), not `ACinputs.dat`.
fn local_problem_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(DATA_DIR)
        .expect("the shared Siconos data directory")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".dat")
                && !["GFC3D_", "gfc2d_", "fc2d_", "FC2D_"]
                    .iter()
                    .any(|prefix| name.starts_with(prefix))
                && name != "ACinputs.dat"
        })
        .collect();
    files.sort();
    files
}

fn is_2d(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.starts_with("FrictionContactProblem00"))
}

/// The local 3D files, checked to be exactly those of [`SICONOS_READS`].
fn files_3d() -> Vec<PathBuf> {
    let files: Vec<PathBuf> = local_problem_files()
        .into_iter()
        .filter(|p| !is_2d(p))
        .collect();
    let mut names: Vec<&str> = files.iter().map(|p| file_name(p)).collect();
    let mut expected: Vec<&str> = SICONOS_READS.iter().map(|r| r.0).collect();
    names.sort_unstable();
    expected.sort_unstable();
    assert_eq!(names, expected);
    files
}

fn file_name(path: &Path) -> &str {
    path.file_name()
        .and_then(|n| n.to_str())
        .expect("a UTF-8 file name")
}

/// FNV-1a over the bits of `values` (-0 as +0), as in the C program that produced the table.
fn fnv(values: impl IntoIterator<Item = f64>) -> u64 {
    let mut h: u64 = 0xcbf29ce484222325;
    for v in values {
        let v = if v == 0.0 { 0.0 } else { v };
        for byte in v.to_bits().to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x100000001b3);
        }
    }
    h
}

fn write_to_string(problem: &FrictionProblem<'_>) -> String {
    let mut bytes = Vec::new();
    write_dat(problem, &mut bytes).expect("writing to memory");
    String::from_utf8(bytes).expect("the writer emits UTF-8")
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// Equal storage, structure and value bits (`==` on f64 would let -0 pass for +0).
fn assert_bit_identical(a: &FrictionProblem<'_>, b: &FrictionProblem<'_>, what: &str) {
    assert_eq!(a, b, "{what}");
    assert_eq!(bits(a.q()), bits(b.q()), "{what}: q");
    assert_eq!(bits(a.mu()), bits(b.mu()), "{what}: mu");
    match (a.w(), b.w()) {
        (Delassus::Dense(x), Delassus::Dense(y)) => {
            assert_eq!(bits(x.values()), bits(y.values()), "{what}: W")
        }
        (Delassus::SparseBlock(x), Delassus::SparseBlock(y)) => {
            assert_eq!(x.blocks().len(), y.blocks().len(), "{what}: blocks");
            for (bx, by) in x.blocks().zip(y.blocks()) {
                assert_eq!(bits(bx), bits(by), "{what}: W block");
            }
        }
        (Delassus::Sparse(x), Delassus::Sparse(y)) => {
            assert_eq!(bits(x.values()), bits(y.values()), "{what}: W")
        }
        _ => panic!("{what}: the storage changed"),
    }
}

/// A sparse-block copy of W: every 3x3 block with a non-zero entry, and every diagonal block.
fn to_sparse_block(w: &Delassus<'_>) -> BlockSparseMatrix<'static> {
    let nc = w.nrows() / 3;
    let mut row_ptr = vec![0];
    let mut col_idx = Vec::new();
    let mut blocks = Vec::new();
    for bi in 0..nc {
        for bj in 0..nc {
            let mut block = [0.0; 9];
            for c in 0..3 {
                for r in 0..3 {
                    block[r + 3 * c] = w.get(3 * bi + r, 3 * bj + c);
                }
            }
            if bi == bj || block.iter().any(|&v| v != 0.0) {
                col_idx.push(bj);
                blocks.push(block);
            }
        }
        row_ptr.push(blocks.len());
    }
    BlockSparseMatrix::new(nc, nc, row_ptr, col_idx, blocks).expect("a valid block structure")
}

/// W as a CSparse compressed dump (origin 2: sections are columns, from the transpose's rows; origin
/// 3: sections are rows), with exact values instead of Siconos' `%g`.
fn compressed_dump_text(p: &FrictionProblem<'_>, origin: usize) -> String {
    let n = p.size();
    let csr = p.w().to_csr();
    let sections = if origin == 3 {
        csr
    } else {
        let mut transposed = Vec::new();
        csr.for_each_entry(|i, j, v| transposed.push((j, i, v)));
        CsrMatrix::from_triplets(n, n, &transposed).expect("in range")
    };
    let mut text = format!(
        "3\n{}\n2\n{n}\n{n}\n{origin}\nCSparse Version 3.1.9, May 4, 2016.  Copyright (c) T. Davis\n\
         {n}-by-{n}, nzmax: {} nnz: {}, 1-norm: 1\n",
        p.n_contacts(),
        sections.nnz() + 3,
        sections.nnz()
    );
    for s in 0..n {
        let (a, b) = (sections.row_ptr()[s], sections.row_ptr()[s + 1]);
        text += &format!("    col {s} : locations {a} to {}\n", b as i64 - 1);
        for k in a..b {
            text += &format!(
                "      {} : {:e}\n",
                sections.col_idx()[k],
                sections.values()[k]
            );
        }
    }
    for values in [p.q(), p.mu()] {
        let line: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
        text += &line.join(" ");
        text += "\n";
    }
    text
}

/// Byte ranges of the whitespace-separated tokens of `text`.
fn token_spans(text: &str) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices() {
        match (c.is_whitespace(), start) {
            (true, Some(s)) => {
                spans.push((s, i));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        spans.push((s, text.len()));
    }
    spans
}

fn assert_parse_error_in(
    result: Result<FrictionProblem<'static>, Fc3dError>,
    label: &str,
) -> (usize, String) {
    match result {
        Err(Fc3dError::Parse {
            file,
            token_index,
            token,
            ..
        }) => {
            assert_eq!(file, label);
            (token_index, token)
        }
        other => panic!("{label}: expected a parse error, got {other:?}"),
    }
}

#[test]
fn every_3d_file_reads_as_siconos_reads_it() {
    files_3d();
    for &(name, nc, storage, w00, q0, mu0, w_hash, q_hash, mu_hash) in SICONOS_READS {
        let p = read_dat_file(&Path::new(DATA_DIR).join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(p.n_contacts(), nc, "{name}");
        assert_eq!(p.size(), 3 * nc, "{name}");
        let expected_storage = ["dense", "sparse-block"][storage];
        assert_eq!(p.w().storage_name(), expected_storage, "{name}");
        assert_eq!(p.w().get(0, 0).to_bits(), w00.to_bits(), "{name}: W[0,0]");
        assert_eq!(p.q()[0].to_bits(), q0.to_bits(), "{name}: q[0]");
        assert_eq!(p.mu()[0].to_bits(), mu0.to_bits(), "{name}: mu[0]");
        let dense = p.w().to_dense();
        assert_eq!(fnv(dense.values().iter().copied()), w_hash, "{name}: W");
        assert_eq!(fnv(p.q().iter().copied()), q_hash, "{name}: q");
        assert_eq!(fnv(p.mu().iter().copied()), mu_hash, "{name}: mu");
    }
}

#[test]
fn spot_values_of_small_files() {
    let p = read_dat_file(&Path::new(DATA_DIR).join("FrictionContact3D_1c.dat")).unwrap();
    assert_eq!(p.w().get(0, 0), 15.0);
    assert_eq!(p.w().get(2, 0), -2.0);
    assert_eq!(p.w().get(1, 2), 1.0);
    assert_eq!(p.q(), &[-1.0, 2.0, 3.0]);
    assert_eq!(p.mu(), &[0.1]);

    let p = read_dat_file(&Path::new(DATA_DIR).join("FC3D_Example1_SBM.dat")).unwrap();
    let Delassus::SparseBlock(s) = p.w() else {
        panic!("expected a sparse-block W")
    };
    assert_eq!((s.n_block_rows(), s.n_blocks()), (3, 3));
    assert_eq!(s.row_ptr(), &[0, 1, 2, 3]);
    assert_eq!(s.col_idx(), &[0, 1, 2]);
    assert_eq!(p.q(), &[-1.0, 1.0, 3.0, -1.0, 1.0, 3.0, -1.0, 1.0, 3.0]);
    assert_eq!(p.mu(), &[0.1; 3]);
}

#[test]
fn write_then_read_is_bit_exact_in_every_storage() {
    for path in files_3d() {
        let name = file_name(&path);
        let original = read_dat_file(&path).unwrap();
        let sbm = match original.w() {
            Delassus::SparseBlock(s) => s.clone(),
            w => to_sparse_block(w),
        };
        let variants = [
            original.clone(),
            original
                .with_w(Delassus::Dense(original.w().to_dense()))
                .unwrap(),
            original
                .with_w(Delassus::Sparse(original.w().to_csr()))
                .unwrap(),
            original.with_w(Delassus::SparseBlock(sbm)).unwrap(),
        ];
        for p in &variants {
            let what = format!("{name} as {}", p.w().storage_name());
            let text = write_to_string(p);
            let back = parse_dat(&text, &what).unwrap_or_else(|e| panic!("{e}"));
            assert_bit_identical(&back, p, &what);
            // Writing is deterministic: the re-read problem writes the same text.
            assert_eq!(write_to_string(&back), text, "{what}");
        }
    }
}

#[test]
fn compressed_dumps_read_like_the_csr_they_print() {
    for path in files_3d() {
        let name = file_name(&path);
        let original = read_dat_file(&path).unwrap();
        let expected = original
            .with_w(Delassus::Sparse(original.w().to_csr()))
            .unwrap();
        for origin in [2, 3] {
            let what = format!("{name} as a compressed dump with origin {origin}");
            let back = parse_dat(&compressed_dump_text(&original, origin), &what)
                .unwrap_or_else(|e| panic!("{e}"));
            assert_bit_identical(&back, &expected, &what);
        }
    }
}

#[test]
fn write_dat_file_and_read_dat_file_agree() {
    let dir = std::env::temp_dir().join(format!("fc3d-dat-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let original = read_dat_file(&Path::new(DATA_DIR).join("Rover4396.dat")).unwrap();
    let out = dir.join("rover.dat");
    write_dat_file(&original, &out).unwrap();
    let back = read_dat_file(&out).unwrap();
    assert_bit_identical(&back, &original, "file round trip");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_files_are_io_errors_naming_the_file() {
    let path = Path::new(DATA_DIR).join("no-such-problem.dat");
    match read_dat_file(&path) {
        Err(Fc3dError::Io { file, .. }) => assert!(file.ends_with("no-such-problem.dat")),
        other => panic!("expected an I/O error, got {other:?}"),
    }
    let unwritable = Path::new(DATA_DIR).join("no-such-dir").join("out.dat");
    let p = read_dat_file(&Path::new(DATA_DIR).join("Rover11035.dat")).unwrap();
    assert!(matches!(
        write_dat_file(&p, &unwritable),
        Err(Fc3dError::Io { file, .. }) if file.ends_with("out.dat")
    ));
}

#[test]
fn two_dimensional_files_are_unsupported() {
    let mut seen = 0;
    for path in std::fs::read_dir(DATA_DIR)
        .unwrap()
        .map(|e| e.unwrap().path())
    {
        let name = file_name(&path).to_string();
        if !(is_2d(&path) || name.starts_with("fc2d_") || name.starts_with("FC2D_")) {
            continue;
        }
        match read_dat_file(&path) {
            Err(e @ Fc3dError::UnsupportedDimension { dimension: 2, .. }) => {
                let message = e.to_string();
                assert!(message.contains(&name), "{message}");
                assert!(
                    message.contains("dimension 2 are not supported"),
                    "{message}"
                );
            }
            other => panic!("{name}: expected UnsupportedDimension, got {other:?}"),
        }
        seen += 1;
    }
    assert!(seen >= 6, "only {seen} 2D files found");
}

/// The number of leading tokens the parser needs: the shortest token prefix that parses (a prefix
/// parses iff it holds every needed token, since what follows mu is ignored). Files end with at
/// most a few ignored tokens, so walking back from the end is cheap.
fn needed_tokens(text: &str, spans: &[(usize, usize)], label: &str) -> usize {
    let parses = |t: usize| {
        let end = if t == 0 { 0 } else { spans[t - 1].1 };
        parse_dat(&text[..end], label).is_ok()
    };
    assert!(parses(spans.len()), "{label}: the whole file must parse");
    let mut needed = spans.len();
    while needed > 0 && parses(needed - 1) {
        needed -= 1;
    }
    needed
}

#[test]
fn truncated_files_give_parse_errors_naming_the_file() {
    for path in files_3d() {
        let label = path.display().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let spans = token_spans(&text);
        let needed = needed_tokens(&text, &spans, &label);
        let full = parse_dat(&text, &label).unwrap();
        assert_eq!(
            parse_dat(&text[..spans[needed - 1].1], &label).unwrap(),
            full
        );

        // Cut right after a token: the parser runs out of input.
        let cuts = [
            0,
            1,
            2,
            3,
            4,
            5,
            6,
            9,
            needed / 3,
            needed / 2,
            needed - 2,
            needed - 1,
        ];
        for t in cuts.into_iter().filter(|&t| t < needed) {
            let end = if t == 0 { 0 } else { spans[t - 1].1 };
            let (index, token) = assert_parse_error_in(parse_dat(&text[..end], &label), &label);
            assert_eq!(
                (index, token.as_str()),
                (t, "<end of file>"),
                "{label} cut after {t} tokens"
            );
        }
        // Cut anywhere before the last needed token starts (possibly inside a token).
        let last_start = spans[needed - 1].0;
        for k in 0..16 {
            let mut end = last_start * k / 16 + k * 7 % 5;
            while end > 0 && !text.is_char_boundary(end) {
                end -= 1;
            }
            assert_parse_error_in(parse_dat(&text[..end.min(last_start)], &label), &label);
        }
    }
}

#[test]
fn garbage_tokens_are_reported_where_they_are() {
    for path in files_3d() {
        let label = path.display().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let spans = token_spans(&text);
        let needed = needed_tokens(&text, &spans, &label);
        // In dense and sparse-block files every needed token is a number the parser reads.
        for (k, garbage) in [
            (0, "x"),
            (1, "three"),
            (2, "1e999"),
            (5, "#"),
            (needed / 2, "nan"),
            (needed - 1, "-inf"),
            (needed - 2, "0x1p3"),
        ] {
            let (s, e) = spans[k];
            let damaged = format!("{}{garbage}{}", &text[..s], &text[e..]);
            let (index, token) = assert_parse_error_in(parse_dat(&damaged, &label), &label);
            assert_eq!(
                (index, token.as_str()),
                (k, garbage),
                "{label}: {garbage} at token {k}"
            );
        }
    }
}

#[test]
fn structural_damage_is_a_parse_error() {
    let text = std::fs::read_to_string(Path::new(DATA_DIR).join("FC3D_Example1_SBM.dat")).unwrap();
    let spans = token_spans(&text);
    let replace =
        |k: usize, by: &str| format!("{}{by}{}", &text[..spans[k].0], &text[spans[k].1..]);
    // Tokens: 0 dim, 1 nc, 2 storage, 3-4 sizes, 5 nbblocks, 6-7 block counts, 8-10 row sizes,
    // 11-13 column sizes, 14 filled1, 15 filled2, 16-19 index1_data, 20-22 index2_data, 23 first
    // block number.
    for (k, by, expected) in [
        (1, "4", 3),   // nc disagrees with the sizes
        (2, "7", 2),   // unknown storage
        (5, "2", 15),  // nbblocks disagrees with filled2
        (8, "0", 8),   // cumulative sizes must increase
        (6, "2", 9),   // the row blocks cover less than W
        (7, "4", 14),  // a fourth cumulative column size that does not increase
        (14, "9", 14), // filled1 too large
        (18, "0", 18), // index1_data decreasing
        (17, "0", 16), // no block in row 0: its diagonal block is missing
        (20, "1", 16), // the diagonal block of contact 0 is missing
        (21, "3", 21), // block column out of range
        (23, "1", 23), // wrong block number
    ] {
        let (index, _) = assert_parse_error_in(parse_dat(&replace(k, by), "sbm"), "sbm");
        assert_eq!(index, expected, "{by} at token {k}");
    }
    // Blocks of another size are a limitation, not a malformed file.
    let six = replace(8, "6");
    assert!(matches!(parse_dat(&six, "six"), Err(Fc3dError::Unsupported(m)) if m.contains("six")));
}

const VOCABULARY: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "4",
    "6",
    "9",
    "12",
    "-1",
    "0.5",
    "1e0",
    "-0",
    "1e-300",
    "18446744073709551615",
    "99999999999999999999",
    "nan",
    "inf",
    "x",
    ":",
    "col",
    "locations",
    "to",
    "CSparse",
    "Version",
    "triplet:",
    "3-by-3,",
    "6-by-6,",
    "nzmax:",
    "nnz:",
    "9,",
    "1-norm:",
];

fn token_text() -> impl Strategy<Value = String> {
    prop::collection::vec(
        (
            prop::sample::select(VOCABULARY),
            prop::sample::select(&[" ", "\n", "\t", "\n\n"][..]),
        ),
        0..80,
    )
    .prop_map(|tokens| tokens.into_iter().flat_map(|(t, sep)| [t, sep]).collect())
}

fn check_no_panic(text: &str) -> Result<(), TestCaseError> {
    match parse_dat(text, "fuzz") {
        Ok(p) => prop_assert_eq!(p.size(), 3 * p.n_contacts()),
        Err(Fc3dError::Parse {
            file,
            token_index,
            token,
            ..
        }) => {
            prop_assert_eq!(file, "fuzz");
            let tokens: Vec<&str> = text.split_whitespace().collect();
            match tokens.get(token_index) {
                Some(t) => prop_assert_eq!(token.as_str(), *t),
                None => prop_assert_eq!(token.as_str(), "<end of file>"),
            }
        }
        Err(Fc3dError::Unsupported(message)) => prop_assert!(message.contains("fuzz")),
        Err(Fc3dError::UnsupportedDimension { file, dimension }) => {
            prop_assert_eq!(file, "fuzz");
            prop_assert_eq!(dimension, 2)
        }
        Err(other) => prop_assert!(false, "unexpected error kind: {other:?}"),
    }
    Ok(())
}

proptest! {
    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        check_no_panic(&String::from_utf8_lossy(&bytes))?;
    }

    #[test]
    fn random_token_sequences_never_panic(
        header in prop::sample::select(&["3 1 0 3 3 ", "3 1 1 3 3 ", "3 1 2 3 3 ", "3 2 1 6 6 ", "3 1 2 3 3 1\nCSparse\n", ""][..]),
        body in token_text(),
    ) {
        check_no_panic(&format!("{header}{body}"))?;
    }

    #[test]
    fn mutated_real_files_never_panic(
        which in 0usize..3,
        edits in prop::collection::vec((any::<prop::sample::Index>(), prop::sample::select(VOCABULARY), 0u8..3), 1..4),
    ) {
        let base = match which {
            0 => std::fs::read_to_string(Path::new(DATA_DIR).join("FC3D_Example1_SBM.dat")).unwrap(),
            1 => std::fs::read_to_string(Path::new(DATA_DIR).join("Rover4396.dat")).unwrap(),
            _ => {
                let p = read_dat_file(&Path::new(DATA_DIR).join("FC3D_Example1.dat")).unwrap();
                write_to_string(&p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap())
            }
        };
        let mut text = base;
        for (at, token, kind) in edits {
            let spans = token_spans(&text);
            if spans.is_empty() {
                break;
            }
            let (s, e) = spans[at.index(spans.len())];
            text = match kind {
                0 => format!("{}{token}{}", &text[..s], &text[e..]),  // replace
                1 => format!("{}{}", &text[..s], &text[e..]),          // delete
                _ => format!("{}{token} {}", &text[..s], &text[s..]), // insert
            };
        }
        check_no_panic(&text)?;
    }
}

// ---------------------------------------------------------------------------------------------
// The matrix part alone (`NM_write_in_file` / `NM_new_from_file`, `SBM_new_from_file`)
// ---------------------------------------------------------------------------------------------

fn matrix_text(w: &Delassus<'_>) -> String {
    let mut bytes = Vec::new();
    write_matrix(w, &mut bytes).expect("writing to memory");
    String::from_utf8(bytes).expect("the writer emits UTF-8")
}

/// Same storage, shape, structure and value bits.
fn assert_matrix_bits(a: &Delassus<'_>, b: &Delassus<'_>, what: &str) {
    assert_eq!(a, b, "{what}");
    assert_eq!(
        (a.nrows(), a.ncols()),
        (b.nrows(), b.ncols()),
        "{what}: shape"
    );
    match (a, b) {
        (Delassus::Dense(x), Delassus::Dense(y)) => {
            assert_eq!(bits(x.values()), bits(y.values()), "{what}")
        }
        (Delassus::SparseBlock(x), Delassus::SparseBlock(y)) => {
            assert_eq!(
                (x.row_ptr(), x.col_idx()),
                (y.row_ptr(), y.col_idx()),
                "{what}"
            );
            for (bx, by) in x.blocks().zip(y.blocks()) {
                assert_eq!(bits(bx), bits(by), "{what}: block");
            }
        }
        (Delassus::Sparse(x), Delassus::Sparse(y)) => {
            assert_eq!(bits(x.values()), bits(y.values()), "{what}")
        }
        _ => panic!("{what}: the storage changed"),
    }
}

/// Writes, parses back, checks the bits, that writing is deterministic and that the prefix
/// reader stops right before what follows the matrix.
fn assert_matrix_round_trip(w: &Delassus<'_>, what: &str) {
    let text = matrix_text(w);
    let back = parse_matrix(&text, what).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_matrix_bits(&back, w, what);
    assert_eq!(matrix_text(&back), text, "{what}: rewrite");
    let followed = format!("{text} \n\n  next 1 2\n");
    let (again, len) = parse_matrix_prefix(&followed, what).unwrap();
    assert_matrix_bits(&again, w, what);
    assert_eq!(&followed[len..], "next 1 2\n", "{what}: prefix length");
}

fn sample_values(count: usize, seed: u64) -> Vec<f64> {
    let special = [
        1.0 / 3.0,
        -0.0,
        0.1,
        f64::MIN_POSITIVE,
        5e-324,
        -f64::MAX,
        123_456_789.123_456_79,
        -2.5e-10,
    ];
    (0..count)
        .map(|k| {
            let k = k as u64 + seed;
            special[(k % special.len() as u64) as usize] * (1.0 + k as f64 / 7.0)
        })
        .map(|v| if v.is_finite() { v } else { -1.5 })
        .collect()
}

#[test]
fn matrices_of_any_shape_round_trip_in_every_storage() {
    for (rows, cols) in [
        (0, 0),
        (1, 1),
        (2, 3),
        (3, 2),
        (4, 7),
        (6, 6),
        (0, 5),
        (5, 0),
    ] {
        let dense = DenseMatrix::new(rows, cols, sample_values(rows * cols, 3)).unwrap();
        let mut triplets = Vec::new();
        dense.for_each_entry(|i, j, v| {
            if (i + 2 * j) % 3 != 1 {
                triplets.push((i, j, v))
            }
        });
        let sparse = CsrMatrix::from_triplets(rows, cols, &triplets).unwrap();
        assert_matrix_round_trip(&Delassus::Dense(dense), &format!("dense {rows}x{cols}"));
        assert_matrix_round_trip(&Delassus::Sparse(sparse), &format!("sparse {rows}x{cols}"));
    }
    // Sparse-block: 3x3 blocks, non-square, empty rows, no block at all.
    for (nbr, nbc, row_ptr, col_idx) in [
        (2, 3, vec![0, 2, 3], vec![0, 2, 2]),
        (3, 1, vec![0, 1, 1, 2], vec![0, 0]),
        (2, 2, vec![0, 1, 2], vec![1, 0]),
        (2, 2, vec![0, 0, 0], vec![]),
        (0, 0, vec![0], vec![]),
    ] {
        let blocks: Vec<[f64; 9]> = (0..col_idx.len())
            .map(|k| sample_values(9, 11 * k as u64).try_into().unwrap())
            .collect();
        let sbm = BlockSparseMatrix::new(nbr, nbc, row_ptr, col_idx, blocks).unwrap();
        let what = format!("sparse-block {nbr}x{nbc} blocks");
        assert_matrix_round_trip(&Delassus::SparseBlock(sbm.clone()), &what);

        // The body alone, as SBM_write_in_file / SBM_new_from_file.
        let mut body = Vec::new();
        write_sbm(&sbm, &mut body).unwrap();
        let body = String::from_utf8(body).unwrap();
        let back = parse_sbm(&body, &what).unwrap();
        if sbm.n_blocks() == 0 {
            // A lone 0 does not say the size.
            assert_eq!((back.nrows(), back.ncols(), back.n_blocks()), (0, 0, 0));
        } else {
            assert_matrix_bits(
                &Delassus::SparseBlock(back),
                &Delassus::SparseBlock(sbm.clone()),
                &what,
            );
        }
        let followed = format!("{body}\t\nrest");
        let (_, len) = parse_sbm_prefix(&followed, &what).unwrap();
        assert_eq!(&followed[len..], "rest", "{what}");
        // The header plus the body is the NM_write_in_file text.
        assert!(
            matrix_text(&Delassus::SparseBlock(sbm)).ends_with(&body),
            "{what}"
        );
    }
}

#[test]
fn the_w_of_every_3d_file_round_trips_as_a_lone_matrix() {
    for path in files_3d() {
        let name = file_name(&path);
        let p = read_dat_file(&path).unwrap();
        let sbm = match p.w() {
            Delassus::SparseBlock(s) => s.clone(),
            w => to_sparse_block(w),
        };
        for w in [
            Delassus::Dense(p.w().to_dense()),
            Delassus::Sparse(p.w().to_csr()),
            Delassus::SparseBlock(sbm),
        ] {
            let what = format!("{name}: W as {}", w.storage_name());
            assert_matrix_round_trip(&w, &what);
            // In a .dat file the matrix follows `dim nc` and q follows it.
            let q = p.with_w(w.clone()).unwrap();
            let dat = write_to_string(&q);
            let after_header = dat.splitn(3, '\n').nth(2).unwrap();
            let (in_dat, len) = parse_matrix_prefix(after_header, &what).unwrap();
            assert_matrix_bits(&in_dat, &w, &what);
            let first_q: f64 = after_header[len..]
                .split_whitespace()
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert_eq!(first_q.to_bits(), p.q()[0].to_bits(), "{what}");
        }
    }
}

/// Verbatim `NM_write_in_file` output of Siconos 4.4 (a dense 2x3, a 3x4 triplet, the same as CSC
/// with an empty column, a 6x6 sparse-block of 3 blocks), each followed by the tail a host would
/// read next; produced by a throwaway C program linked with `-lsiconos_numerics`.
const SICONOS_DENSE_2X3: &str = "0\n2\n3\n2\t3\n  1.000000000000000055511151e-01   \
    2.000000000000000111022302e-01   3.000000000000000444089210e-01 \n  \
    4.000000000000000777156117e-01   5.000000000000000000000000e-01   \
    3.333333333333333148296163e-01 \nTAIL 42\n";
const SICONOS_TRIPLET_3X4: &str = "2\n3\n4\n1\n\
    CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
    triplet: 3-by-4, nzmax: 4 nnz: 3\n    0 0 : 0.333333\n    2 3 : -2.5e-10\n    1 1 : 123457\n\
    TAIL 42\n";
const SICONOS_CSC_3X4: &str = "2\n3\n4\n2\n\
    CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
    3-by-4, nzmax: 3 nnz: 3, 1-norm: 123457\n    col 0 : locations 0 to 0\n      0 : 0.333333\n\
    \x20   col 1 : locations 1 to 1\n      1 : 123457\n    col 2 : locations 2 to 1\n\
    \x20   col 3 : locations 2 to 2\n      2 : -2.5e-10\nTAIL 42\n";

/// `NM_write_in_file` of a 6x6 sparse-block matrix with blocks (0,0), (0,1), (1,1) whose entry
/// (i, j) is 10 (i + 1) + j + 1 + 1/8; without its first three lines it is `SBM_write_in_file`'s.
fn siconos_sbm_6x6() -> String {
    let mut text = String::from("1\n6\n6\n3\n2\n2\n3\t6\t\n3\t6\t\n3\n3\n0\t2\t3\t\n0\t1\t1\t\n");
    for (k, (bi, bj)) in [(0, 0), (0, 1), (1, 1)].into_iter().enumerate() {
        text += &format!("{k}\n");
        for c in 0..3 {
            for r in 0..3 {
                let v = (10 * (3 * bi + r + 1) + 3 * bj + c + 1) as f64 + 0.125;
                text += &format!("  {v:.24e}\n");
            }
        }
    }
    text + "TAIL 42\n"
}

#[test]
fn siconos_matrix_files_read_as_siconos_reads_them() {
    let (dense, len) = parse_matrix_prefix(SICONOS_DENSE_2X3, "dense").unwrap();
    assert_eq!(&SICONOS_DENSE_2X3[len..], "TAIL 42\n");
    let Delassus::Dense(d) = &dense else {
        panic!("expected dense")
    };
    assert_eq!((d.nrows(), d.ncols()), (2, 3));
    // Column-major: the second value is entry (1, 0).
    assert_eq!(d.get(1, 0), 0.2);
    assert_eq!(d.get(0, 1), 0.30000000000000004);
    assert_eq!(d.get(1, 2), 1.0 / 3.0);

    for (label, text) in [("triplet", SICONOS_TRIPLET_3X4), ("csc", SICONOS_CSC_3X4)] {
        let (w, len) = parse_matrix_prefix(text, label).unwrap();
        assert_eq!(&text[len..], "TAIL 42\n", "{label}");
        let Delassus::Sparse(s) = &w else {
            panic!("{label}: expected sparse")
        };
        assert_eq!((s.nrows(), s.ncols(), s.nnz()), (3, 4, 3), "{label}");
        // Siconos prints sparse values with %g.
        assert_eq!(w.get(0, 0), 0.333333, "{label}");
        assert_eq!(w.get(1, 1), 123457.0, "{label}");
        assert_eq!(w.get(2, 3), -2.5e-10, "{label}");
        assert_eq!(w.get(2, 2), 0.0, "{label}");
    }

    let text = siconos_sbm_6x6();
    let (w, len) = parse_matrix_prefix(&text, "sbm").unwrap();
    assert_eq!(&text[len..], "TAIL 42\n");
    let Delassus::SparseBlock(s) = &w else {
        panic!("expected sparse-block")
    };
    assert_eq!(
        (s.n_block_rows(), s.n_block_cols(), s.n_blocks()),
        (2, 2, 3)
    );
    for i in 0..6 {
        for j in 0..6 {
            let stored = i < 3 || j >= 3;
            let expected = if stored {
                (10 * (i + 1) + j + 1) as f64 + 0.125
            } else {
                0.0
            };
            assert_eq!(w.get(i, j), expected, "({i}, {j})");
        }
    }
    // SBM_new_from_file reads the body without the header.
    let body = text.splitn(4, '\n').nth(3).unwrap();
    let (b, len) = parse_sbm_prefix(body, "sbm body").unwrap();
    assert_eq!(&body[len..], "TAIL 42\n");
    assert_eq!(&b, s);
    // ... and is not a matrix file, nor is a matrix file a body.
    assert!(matches!(
        parse_matrix(body, "x"),
        Err(Fc3dError::Parse { .. })
    ));
    assert!(matches!(
        parse_sbm(&text, "x"),
        Err(Fc3dError::Parse { .. })
    ));
    // Siconos writes a sparse-block matrix without blocks as a lone 0.
    let empty = parse_matrix("1\n6\n9\n0\n", "empty").unwrap();
    assert_eq!((empty.nrows(), empty.ncols(), empty.get(5, 8)), (6, 9, 0.0));
}

#[test]
fn sparse_block_matrices_need_3x3_blocks() {
    // NM_write_in_file of a 4x4 matrix cut into 2x2 blocks by Siconos (SBM_from_csparse(2, ...)).
    let mut text =
        String::from("1\n4\n4\n4\n2\n2\n2\t4\t\n2\t4\t\n3\n4\n0\t2\t4\t\n0\t1\t0\t1\t\n");
    for k in 0..4 {
        text += &format!("{k}\n1\n2\n3\n4\n");
    }
    for (result, label) in [
        (parse_matrix(&text, "two.mat").map(|_| ()), "two.mat"),
        (
            parse_sbm(text.splitn(4, '\n').nth(3).unwrap(), "two.sbm").map(|_| ()),
            "two.sbm",
        ),
        (parse_matrix("1 4 4 0", "four.mat").map(|_| ()), "four.mat"),
    ] {
        match result {
            Err(Fc3dError::Unsupported(m)) => {
                assert!(m.contains(label) && m.contains("3x3"), "{m}")
            }
            other => panic!("{label}: expected Unsupported, got {other:?}"),
        }
    }
}

#[test]
fn damaged_matrix_files_are_parse_errors() {
    for (text, token_index) in [
        ("", 0),
        ("garbage", 0),
        ("7 3 3", 0),
        ("0 2 2 2 3 1 2 3 4", 4),     // the sizes are not repeated
        ("0 2 2 2 2 1 2 3", 8),       // truncated: the end of the text
        ("0 1 1 1 1 nan", 5),         // non-finite
        ("0 4294967296 0 4294967296 0", 1), // does not fit a C int
        ("2 1000000000000 1000000000000 1\nCSparse\ntriplet: 1000000000000-by-1000000000000, nzmax: 0 nnz: 0\n", 1),
        ("1 99999999 99999999 0", 1), // sparse-block too large to hold
        ("2 2 2 1\nCSparse\ntriplet: 2-by-3, nzmax: 1 nnz: 1\n 0 0 : 1\n", 6),
        ("2 2 2 1\nCSparse\ntriplet: 2-by-2, nzmax: 1 nnz: 1\n 0 2 : 1\n", 12),
    ] {
        match parse_matrix(text, "bad") {
            Err(Fc3dError::Parse {
                file,
                token_index: at,
                ..
            }) => {
                assert_eq!(file, "bad");
                assert_eq!(at, token_index, "{text:?}");
            }
            other => panic!("{text:?}: expected a parse error, got {other:?}"),
        }
    }
    assert!(matches!(parse_sbm("", "bad"), Err(Fc3dError::Parse { .. })));
    assert!(matches!(
        parse_sbm("1 1 1 3 3 2 1 0 1 0 0 1", "bad"),
        Err(Fc3dError::Parse { .. })
    ));
}

fn arbitrary_matrix() -> impl Strategy<Value = Delassus<'static>> {
    let value = prop_oneof![
        Just(0.0),
        any::<f64>().prop_filter("finite", |v| v.is_finite()),
        -1e3..1e3f64,
    ];
    let dense = (0usize..6, 0usize..6)
        .prop_flat_map(move |(r, c)| (Just((r, c)), prop::collection::vec(value.clone(), r * c)))
        .prop_map(|((r, c), v)| Delassus::Dense(DenseMatrix::new(r, c, v).unwrap()));
    let sparse = (1usize..7, 1usize..7)
        .prop_flat_map(|(r, c)| {
            (
                Just((r, c)),
                prop::collection::vec((0..r, 0..c, -1e6..1e6f64), 0..12),
            )
        })
        .prop_map(|((r, c), t)| Delassus::Sparse(CsrMatrix::from_triplets(r, c, &t).unwrap()));
    let sbm = (1usize..4, 1usize..4)
        .prop_flat_map(|(nbr, nbc)| {
            (
                Just((nbr, nbc)),
                prop::collection::vec(prop::collection::vec(any::<bool>(), nbc), nbr),
                prop::collection::vec(any::<f64>().prop_filter("finite", |v| v.is_finite()), 9),
            )
        })
        .prop_map(|((nbr, nbc), present, values)| {
            let mut row_ptr = vec![0];
            let mut col_idx = Vec::new();
            let mut blocks = Vec::new();
            for row in &present {
                for (j, &p) in row.iter().enumerate() {
                    if p {
                        col_idx.push(j);
                        let mut b: [f64; 9] = values.clone().try_into().unwrap();
                        b[0] = blocks.len() as f64;
                        blocks.push(b);
                    }
                }
                row_ptr.push(col_idx.len());
            }
            Delassus::SparseBlock(
                BlockSparseMatrix::new(nbr, nbc, row_ptr, col_idx, blocks).unwrap(),
            )
        });
    prop_oneof![dense, sparse, sbm]
}

proptest! {
    #[test]
    fn random_matrices_round_trip(w in arbitrary_matrix()) {
        assert_matrix_round_trip(&w, "random");
    }

    #[test]
    fn random_matrix_text_never_panics(
        header in prop::sample::select(&["0 2 3 ", "1 6 6 ", "1 3 6 ", "2 3 3 1\nCSparse\n", "2 3 4 2\nCSparse\n", ""][..]),
        body in token_text(),
    ) {
        let text = format!("{header}{body}");
        match parse_matrix_prefix(&text, "fuzz") {
            Ok((_, len)) => prop_assert!(len <= text.len()),
            Err(Fc3dError::Parse { file, .. }) => prop_assert_eq!(file, "fuzz"),
            Err(Fc3dError::Unsupported(m)) => prop_assert!(m.contains("fuzz")),
            Err(other) => prop_assert!(false, "unexpected error kind: {other:?}"),
        }
        let _ = parse_sbm_prefix(&body, "fuzz");
    }
}
