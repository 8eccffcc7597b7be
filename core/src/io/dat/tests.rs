use super::csparse::parse_sparse;
use super::tokens::{Reader, END_OF_FILE};
use super::*;
use crate::error::Fc3dError;
use crate::matrix::{BlockSparseMatrix, CsrMatrix, Delassus, DenseMatrix};
use crate::problem::FrictionProblem;

fn data_file(name: &str) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos/");
    std::fs::read_to_string(format!("{path}{name}")).expect("shared data file")
}

/// `FrictionContact3D_1c.dat` re-written by Siconos 4.4 (`frictionContact_printInFilename`)
/// with W converted to CSC (`NM_csc`): same lines and tokens, indentation not kept.
const SICONOS_CSC_1C: &str = "3\n1\n2\n3\n3\n2\n\
CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
3-by-3, nzmax: 9 nnz: 9, 1-norm: 19\n\
    col 0 : locations 0 to 2\n      0 : 15\n      1 : -1\n      2 : -2\n\
    col 1 : locations 3 to 5\n      0 : -1\n      1 : 14\n      2 : 1\n\
    col 2 : locations 6 to 8\n      0 : -2\n      1 : 1\n      2 : 16\n \
-1.000000000000000000000000e+00   2.000000000000000000000000e+00   3.000000000000000000000000e+00 \n  \
1.000000000000000055511151e-01 \n";

/// The same problem with W converted to triplets (`NM_triplet`), verbatim.
const SICONOS_TRIPLET_1C: &str = "3\n1\n2\n3\n3\n1\n\
CSparse Version 3.2.0, Sept 12, 2017.  Copyright (c) Timothy A. Davis, 2006-2016\n\
triplet: 3-by-3, nzmax: 16 nnz: 9\n\
    0 0 : 15\n    0 1 : -1\n    0 2 : -2\n    1 0 : -1\n    1 1 : 14\n    1 2 : 1\n\
    2 0 : -2\n    2 1 : 1\n    2 2 : 16\n \
-1.000000000000000000000000e+00   2.000000000000000000000000e+00   3.000000000000000000000000e+00 \n  \
1.000000000000000055511151e-01 \n";

#[test]
fn siconos_sparse_dumps_read_like_the_dense_original() {
    let dense = parse_dat(&data_file("FrictionContact3D_1c.dat"), "1c").unwrap();
    for (label, text) in [("csc", SICONOS_CSC_1C), ("triplet", SICONOS_TRIPLET_1C)] {
        let p = parse_dat(text, label).unwrap();
        assert!(matches!(p.w(), Delassus::Sparse(_)), "{label}");
        assert_eq!(p.w().to_dense(), dense.w().to_dense(), "{label}");
        assert_eq!(p.q(), dense.q());
        assert_eq!(p.mu(), dense.mu());
    }
}

#[test]
fn csr_origin_reads_sections_as_rows() {
    // An upper-triangular W makes the orientation visible.
    let text = "3\n1\n2\n3\n3\n3\nCSparse Version x\n3-by-3, nzmax: 4 nnz: 4, 1-norm: 3\n\
        col 0 : locations 0 to 1\n 0 : 1\n 2 : 5\n col 1 : locations 2 to 2\n 1 : 1\n\
        col 2 : locations 3 to 3\n 2 : 1\n 0 0 0\n 0.5\n";
    let p = parse_dat(text, "csr").unwrap();
    assert_eq!(p.w().get(0, 2), 5.0);
    assert_eq!(p.w().get(2, 0), 0.0);
}

/// Parses the W of a (2D) file whose header is `dim nc storage n n`, to exercise the CSparse
/// readers on the real dumps Siconos wrote.
fn matrix_of(text: &str) -> Delassus<'static> {
    let mut r = Reader::new(text, "2d", "W");
    let header: Vec<usize> = (0..5).map(|_| r.usize("header").unwrap().1).collect();
    assert_eq!(header[2], STORAGE_SPARSE);
    parse_sparse(&mut r, header[3], header[4])
        .unwrap()
        .finish(&r)
        .unwrap()
}

#[test]
fn real_csc_dump_of_a_2d_file() {
    let w = matrix_of(&data_file("fc2d_granularflowonwall_00667_00000.dat"));
    let Delassus::Sparse(s) = &w else {
        panic!("expected a sparse W")
    };
    assert_eq!((s.nrows(), s.nnz()), (1334, 3822));
    assert_eq!(w.get(0, 0), 856.713);
    assert_eq!(w.get(649, 0), -454.43);
    assert_eq!(w.get(648, 1), 454.43);
}

#[test]
fn real_triplet_dump_of_a_2d_file() {
    let w = matrix_of(&data_file("gfc2d_granularflowonwall_00069_00350.dat"));
    let Delassus::Sparse(s) = &w else {
        panic!("expected a sparse W")
    };
    assert_eq!((s.nrows(), s.nnz()), (900, 900));
    assert_eq!(w.get(2, 2), 1.46527e-10);
    assert_eq!(w.get(3, 3), 0.00149261);
}

#[test]
fn empty_problem_round_trips_in_every_storage() {
    let dense = DenseMatrix::new(0, 0, Vec::new()).unwrap();
    let sbm = BlockSparseMatrix::new(0, 0, vec![0], Vec::new(), Vec::new()).unwrap();
    let csr = CsrMatrix::from_triplets(0, 0, &[]).unwrap();
    for w in [
        Delassus::Dense(dense),
        Delassus::SparseBlock(sbm),
        Delassus::Sparse(csr),
    ] {
        let p = FrictionProblem::new(w, Vec::new(), Vec::new()).unwrap();
        let mut text = Vec::new();
        write_dat(&p, &mut text).unwrap();
        let back = parse_dat(std::str::from_utf8(&text).unwrap(), "empty").unwrap();
        assert_eq!(back, p);
    }
}

#[test]
fn extreme_values_round_trip_bit_for_bit() {
    let values = [
        f64::MIN_POSITIVE,
        5e-324,
        -f64::MAX,
        f64::MAX,
        -0.0,
        0.1,
        1.0 / 3.0,
        -2.5e-308,
        123_456_789.123_456_79,
    ];
    let w = DenseMatrix::new(3, 3, values.to_vec()).unwrap();
    let p =
        FrictionProblem::new(Delassus::Dense(w), vec![-0.0, 1e300, -1e-300], vec![0.0]).unwrap();
    let mut text = Vec::new();
    write_dat(&p, &mut text).unwrap();
    let back = parse_dat(std::str::from_utf8(&text).unwrap(), "x").unwrap();
    let Delassus::Dense(d) = back.w() else {
        panic!("expected a dense W")
    };
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(d.values()), bits(&values));
    assert_eq!(bits(back.q()), bits(p.q()));
}

#[test]
fn errors_name_the_offending_token() {
    let err = parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 0 x", "f.dat").unwrap_err();
    assert_eq!(
        err,
        Fc3dError::Parse {
            file: "f.dat".into(),
            token_index: 15,
            token: "x".into(),
            message: "expected a value of the dense W (a real number)".into(),
        }
    );
    let Fc3dError::Parse {
        token, token_index, ..
    } = parse_dat("3 1 0 3 3 3 3 1 0", "f.dat").unwrap_err()
    else {
        panic!("expected a parse error")
    };
    assert_eq!((token.as_str(), token_index), (END_OF_FILE, 9));
    let Fc3dError::Parse { token, .. } =
        parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 0 1 0 0 0 -0.5", "f.dat").unwrap_err()
    else {
        panic!("expected a parse error")
    };
    assert_eq!(token, "-0.5");
    let Fc3dError::Parse { token, message, .. } =
        parse_dat("3 1 0 3 3 3 3 1 0 0 0 1 0 0 inf 1", "f.dat").unwrap_err()
    else {
        panic!("expected a parse error")
    };
    assert_eq!(token, "inf");
    assert!(message.contains("finite"), "{message}");
}

#[test]
fn huge_declared_sizes_fail_before_allocating() {
    for text in [
        "3 6148914691236517205 0 18446744073709551615 18446744073709551615",
        "3 1000000000 0 3000000000 3000000000 3000000000 3000000000 1",
        "3 1000000 1 3000000 3000000 1000000000000",
        "3 1 2 3 3 1\nCSparse\ntriplet: 3-by-3, nzmax: 99999999999 nnz: 99999999999\n",
        "3 1 2 3 3 2\nCSparse\n3-by-3, nzmax: 999999999999 nnz: 999999999999, 1-norm: 0\n",
        "3 1000000000000 2 3000000000000 3000000000000 1\nCSparse\n\
         triplet: 3000000000000-by-3000000000000, nzmax: 0 nnz: 0\n",
    ] {
        assert!(
            matches!(parse_dat(text, "big"), Err(Fc3dError::Parse { .. })),
            "{text}"
        );
    }
}

#[test]
fn non_3x3_blocks_and_2d_files_are_unsupported() {
    let text = "3 2 1 6 6 1 1 1 6 6 2 1 0 1 0 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 \
                19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 0 0 0 0 0 0 1 1";
    match parse_dat(text, "six.dat") {
        Err(Fc3dError::Unsupported(m)) => assert!(m.contains("six.dat") && m.contains("3x3")),
        other => panic!("{other:?}"),
    }
    match parse_dat("2 1 0 2 2 2 2 1 0 0 1 0 0 0.5", "flat.dat") {
        Err(e @ Fc3dError::UnsupportedDimension { dimension: 2, .. }) => {
            let m = e.to_string();
            assert!(m.contains("flat.dat") && m.contains("dimension 2 are not supported"))
        }
        other => panic!("{other:?}"),
    }
}
