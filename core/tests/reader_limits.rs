//! The `.dat` readers against inputs sized to hurt (issue 13, item 3, and item 7 for readers):
//! headers declaring far more than the data holds, headers whose sizes overflow, data after the
//! problem, `/dev/zero` as a path and as a stream, endless whitespace and lines, streams that end
//! early, and from a thread with a 256 KiB stack. Every case ends in a typed error after a
//! bounded read, never an abort, a hang or an allocation sized by the header.
//!
//! The streaming readers (`read_dat`, `read_matrix`, `read_sbm`, `read_dat_file`,
//! `read_matrix_file`) must read exactly what the text readers read: every shared file through
//! streams cut in small pieces gives the same problem, bit for bit.
//!
//! The tests named `under_memory_limit_*` are ignored in plain runs: they feed endless valid
//! values and expect `Fc3dError::OutOfMemory`, which needs an address-space limit
//! (`scripts/test-memory-limit.sh` runs them under `ulimit -v`). Without a limit they return at
//! once without reading anything.

use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use fc3d_core::io::{
    parse_dat, parse_matrix, parse_matrix_prefix, parse_sbm, parse_sbm_prefix, read_dat,
    read_dat_file, read_matrix, read_matrix_file, read_sbm, write_dat,
};
use fc3d_core::{Delassus, Fc3dError, FrictionProblem};

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

/// A stream handing out `data` in pieces of 1 to 7 bytes (chunk boundaries everywhere).
struct Pieces<'a> {
    data: &'a [u8],
    at: usize,
    k: usize,
}

impl<'a> Pieces<'a> {
    fn new(data: &'a [u8]) -> Self {
        Pieces { data, at: 0, k: 0 }
    }
}

impl Read for Pieces<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.k += 1;
        let n = (1 + self.k % 7)
            .min(buf.len())
            .min(self.data.len() - self.at);
        buf[..n].copy_from_slice(&self.data[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

/// Counts the bytes a reader takes from a stream.
struct Counted<R> {
    inner: R,
    taken: u64,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.taken += n as u64;
        Ok(n)
    }
}

fn counted<R: Read>(inner: R) -> Counted<R> {
    Counted { inner, taken: 0 }
}

fn shared_3d_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(DATA_DIR)
        .expect("the shared Siconos data directory")
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".dat")
                && ![
                    "GFC3D_",
                    "gfc2d_",
                    "fc2d_",
                    "FC2D_",
                    "FrictionContactProblem00",
                ]
                .iter()
                .any(|prefix| name.starts_with(prefix))
                && name != "ACinputs.dat"
        })
        .collect();
    files.sort();
    assert!(files.len() >= 30, "{} files", files.len());
    files
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

fn w_bits(w: &Delassus<'_>) -> Vec<u64> {
    let mut out = Vec::new();
    w.for_each_entry(|i, j, v| out.extend([i as u64, j as u64, v.to_bits()]));
    out
}

fn assert_same_problem(a: &FrictionProblem<'_>, b: &FrictionProblem<'_>, what: &str) {
    assert_eq!(a, b, "{what}");
    assert_eq!(a.w().storage_name(), b.w().storage_name(), "{what}");
    assert_eq!(w_bits(a.w()), w_bits(b.w()), "{what}: W");
    assert_eq!(bits(a.q()), bits(b.q()), "{what}: q");
    assert_eq!(bits(a.mu()), bits(b.mu()), "{what}: mu");
}

fn is_parse_error(e: &Fc3dError) -> bool {
    matches!(e, Fc3dError::Parse { .. })
}

/// A scratch file removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str, contents: &[u8]) -> Self {
        let path =
            std::env::temp_dir().join(format!("fc3d-reader-limits-{}-{name}", std::process::id()));
        std::fs::write(&path, contents).unwrap();
        Scratch(path)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Parses `text` every way a problem can be read: in memory, from a stream of known and of
/// unknown length, from a file. Returns the four results.
fn every_way(text: &str, name: &str) -> Vec<Result<FrictionProblem<'static>, Fc3dError>> {
    let file = Scratch::new(name, text.as_bytes());
    vec![
        parse_dat(text, name),
        read_dat(Pieces::new(text.as_bytes()), Some(text.len() as u64), name).map(|(p, _)| p),
        read_dat(Pieces::new(text.as_bytes()), None, name).map(|(p, _)| p),
        read_dat_file(&file.0),
    ]
}

/// Headers declaring up to 10^18 values (contacts, nnz, blocks, block rows, sections) followed
/// by a few tokens: a parse error naming the end of the input, fast, in every reader. Before,
/// the text readers checked the token count but the whole input was read into memory first
/// (`std::fs::read`, `read_rest` on FILE*), so the same headers in front of a large or endless
/// stream were read to its end.
#[test]
fn huge_declared_sizes_with_little_data_are_parse_errors() {
    let e15 = "1000000000000000";
    let n15 = "3000000000000000";
    let problems = [
        // dense W of 10^15 contacts
        format!("3 {e15} 0 {n15} {n15} {n15} {n15} 1 2 3"),
        // q and mu of 10^15 contacts after a sparse-block W of no blocks... (diagonal missing)
        format!("3 {e15} 1 {n15} {n15} 0"),
        // sparse-block: 10^15 block rows
        format!("3 {e15} 1 {n15} {n15} 1 {e15} {e15} 3 6 9"),
        // sparse-block: nbblocks 10^15 with one block row
        format!("3 1 1 3 3 {e15} 1 1 3 3 2 {e15} 0 {e15} 0 0 0"),
        // triplets: nnz 10^15
        format!("3 1 2 3 3 1\nCSparse\ntriplet: 3-by-3, nzmax: {e15} nnz: {e15}\n 0 0 : 1\n"),
        // compressed: nnz 10^15
        format!("3 1 2 3 3 2\nCSparse\n3-by-3, nzmax: {e15} nnz: {e15}, 1-norm: 0\n"),
        // compressed: 3 * 10^15 sections, nothing stored
        format!(
            "3 {e15} 2 {n15} {n15} 2\nCSparse\n{n15}-by-{n15}, nzmax: 0 nnz: 0, 1-norm: 0\n \
             col 0 : locations 0 to -1\n"
        ),
        // triplets of a 3*10^15 matrix, none stored: q and mu are missing
        format!("3 {e15} 2 {n15} {n15} 1\nCSparse\ntriplet: {n15}-by-{n15}, nzmax: 0 nnz: 0\n"),
        // 18446744073709551615 everywhere
        "3 6148914691236517205 0 18446744073709551615 18446744073709551615 1".to_string(),
    ];
    for (k, text) in problems.iter().enumerate() {
        let start = Instant::now();
        for (way, result) in every_way(text, &format!("huge{k}.dat"))
            .into_iter()
            .enumerate()
        {
            match result {
                Err(e) => assert!(is_parse_error(&e), "case {k}, way {way}: {e:?}"),
                Ok(_) => panic!("case {k}, way {way}: accepted"),
            }
        }
        assert!(start.elapsed() < Duration::from_secs(5), "case {k}");
    }

    let matrices = [
        format!("0 2147483647 2147483647 2147483647 2147483647 1 2"),
        format!("2 16777215 16777215 1\nCSparse\ntriplet: 16777215-by-16777215, nzmax: {e15} nnz: {e15}\n"),
        format!("1 {n15} 3 0"),
        format!("1 16777215 16777215 {e15} 5592405 5592405 3 6"),
    ];
    for (k, text) in matrices.iter().enumerate() {
        let file = Scratch::new(&format!("huge{k}.mat"), text.as_bytes());
        let results = [
            parse_matrix(text, "m").map(|_| ()),
            read_matrix(Pieces::new(text.as_bytes()), Some(text.len() as u64), "m").map(|_| ()),
            read_matrix(Pieces::new(text.as_bytes()), None, "m").map(|_| ()),
            read_matrix_file(&file.0).map(|_| ()),
        ];
        for (way, result) in results.into_iter().enumerate() {
            assert!(
                matches!(&result, Err(e) if is_parse_error(e)),
                "matrix case {k}, way {way}: {result:?}"
            );
        }
    }
    let body = format!("{e15} 1 1 3 3 2 {e15} 0 {e15} 0 0 0");
    for result in [
        parse_sbm(&body, "b").map(|_| ()),
        read_sbm(Pieces::new(body.as_bytes()), None, "b").map(|_| ()),
        read_sbm(Pieces::new(body.as_bytes()), Some(body.len() as u64), "b").map(|_| ()),
    ] {
        assert!(matches!(&result, Err(e) if is_parse_error(e)), "{result:?}");
    }
}

/// A number of contacts whose triple overflows usize: a parse error at that token (never a
/// wrapped size).
#[test]
fn contact_counts_whose_triple_overflows_are_parse_errors() {
    for nc in [
        "6148914691236517206",
        "18446744073709551615",
        "9223372036854775807",
    ] {
        let text = format!("3 {nc} 0 3 3 3 3 1 0 0 0 1 0 0 0 1 0 0 0 0.5");
        for (way, result) in every_way(&text, "overflow.dat").into_iter().enumerate() {
            match result {
                Err(Fc3dError::Parse {
                    token_index, token, ..
                }) => assert_eq!((token_index, token.as_str()), (1, nc), "way {way}"),
                other => panic!("{nc}, way {way}: {other:?}"),
            }
        }
    }
}

/// A header larger than the data (every shared file cut short): the same parse error at the end
/// of the input in every reader.
#[test]
fn a_stream_that_ends_early_is_a_parse_error_at_its_end() {
    for path in shared_3d_files().into_iter().step_by(3) {
        let text = std::fs::read_to_string(&path).unwrap();
        let tokens = text.split_whitespace().count();
        for cut in [1, 7, text.len() / 3, text.len() / 2, text.len() * 9 / 10] {
            let mut end = cut.min(text.len());
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            // Cut just after a token (at a separator) so the end is unambiguous.
            let end = text[..end].rfind(char::is_whitespace).unwrap_or(0);
            let cut_text = &text[..end];
            if cut_text.split_whitespace().count() >= tokens - 2 {
                continue;
            }
            let expected = parse_dat(cut_text, "cut").unwrap_err();
            let Fc3dError::Parse { token, .. } = &expected else {
                panic!("{expected:?}")
            };
            assert_eq!(token, "<end of file>", "{}", path.display());
            let known = read_dat(
                Pieces::new(cut_text.as_bytes()),
                Some(cut_text.len() as u64),
                "cut",
            )
            .unwrap_err();
            assert_eq!(known, expected, "{} cut at {end}", path.display());
            // Of unknown length, the values are read until the end: the end is named too.
            match read_dat(Pieces::new(cut_text.as_bytes()), None, "cut") {
                Err(Fc3dError::Parse { token, .. }) => assert_eq!(token, "<end of file>"),
                other => panic!("{other:?}"),
            }
        }
    }
}

/// Data after the problem is not read: text, an endless stream of junk, `/dev/zero` after the
/// problem. Before, `frictionContact_newFromFile` and the matrix stream readers read to the end
/// of the stream.
#[test]
fn trailing_data_is_not_read() {
    let path = Path::new(DATA_DIR).join("Capsules-i100-889.dat");
    let original = read_dat_file(&path).unwrap();
    let mut text = Vec::new();
    write_dat(&original, &mut text).unwrap();
    let len = text.len() as u64;
    for tail in [&b"tail 7\n"[..], b"\0\0\0", b"x"] {
        let mut input = counted(text.as_slice().chain(io::repeat(tail[0]).take(1 << 40)));
        let (p, used) = read_dat(&mut input, None, "tail").unwrap();
        assert_same_problem(&p, &original, "with a tail");
        assert_eq!(used, len);
        // One chunk past the problem at most.
        assert!(
            input.taken <= len + (64 << 10),
            "{} bytes taken",
            input.taken
        );
    }
    // A regular file with a long tail: read up to the problem.
    let mut long = text.clone();
    long.extend(std::iter::repeat_n(b'9', 1 << 20));
    let file = Scratch::new("tail.dat", &long);
    assert_same_problem(&read_dat_file(&file.0).unwrap(), &original, "file");
    // A matrix followed by more: the next token's offset.
    let matrix = "0 1 1 1 1 2.5\n  next";
    let (w, used) = read_matrix(Pieces::new(matrix.as_bytes()), None, "m").unwrap();
    assert_eq!((w.get(0, 0), used), (2.5, 16));
    assert_eq!(parse_matrix_prefix(matrix, "m").unwrap().1, 16);
    let sbm = "0 \t rest";
    assert_eq!(
        read_sbm(Pieces::new(sbm.as_bytes()), None, "b").unwrap().1,
        4
    );
    assert_eq!(parse_sbm_prefix(sbm, "b").unwrap().1, 4);
}

/// `/dev/zero` (one endless token) as a path and as a stream: a parse error after reading at
/// most a few chunks. Before, `read_dat_file`, `NM_new_from_filename` (`std::fs::read`) and the
/// FILE* readers (`read_rest`) grew a buffer until the allocation failed: an abort.
#[test]
fn dev_zero_is_rejected_after_a_bounded_read() {
    let start = Instant::now();
    for result in [
        read_dat_file(Path::new("/dev/zero")).map(|_| ()),
        read_matrix_file(Path::new("/dev/zero")).map(|_| ()),
    ] {
        match result {
            Err(Fc3dError::Parse {
                token_index,
                message,
                ..
            }) => {
                assert_eq!(token_index, 0);
                assert!(message.contains("longer than"), "{message}");
            }
            other => panic!("{other:?}"),
        }
    }
    let mut zeros = counted(io::repeat(0));
    assert!(matches!(
        read_dat(&mut zeros, None, "zeros"),
        Err(Fc3dError::Parse { .. })
    ));
    assert!(zeros.taken <= 3 * 64 * 1024, "{} bytes taken", zeros.taken);
    let mut zeros = counted(io::repeat(0));
    assert!(read_sbm(&mut zeros, None, "zeros").is_err());
    // After a valid header, in the middle of the values.
    let mut input = counted(b"3 1 0 3 3 3 3 1 0 ".chain(io::repeat(0)));
    match read_dat(&mut input, None, "header then zeros") {
        Err(Fc3dError::Parse { token_index, .. }) => assert_eq!(token_index, 9),
        other => panic!("{other:?}"),
    }
    assert!(input.taken <= 3 * 64 * 1024);
    assert!(start.elapsed() < Duration::from_secs(10));
}

/// Endless whitespace, an endless CSparse banner line, an endless stream of short junk tokens
/// after the problem: bounded reads, parse errors (or success for data after the problem).
#[test]
fn endless_whitespace_and_lines_are_rejected() {
    let mut blank = counted(io::repeat(b'\n'));
    match read_dat(&mut blank, None, "blank") {
        Err(Fc3dError::Parse { message, .. }) => assert!(message.contains("whitespace")),
        other => panic!("{other:?}"),
    }
    assert!(blank.taken <= (16 << 20) + (64 << 10));
    let mut header_then_blank = b"3 1 0 3".chain(io::repeat(b' '));
    assert!(matches!(
        read_dat(&mut header_then_blank, None, "blank"),
        Err(Fc3dError::Parse { .. })
    ));
    // A banner line of words that never ends.
    let words = b" a".repeat(1 << 20);
    let mut banner = counted(
        b"3 1 2 3 3 1\nCSparse"
            .chain(io::Cursor::new(words))
            .chain(io::repeat(b'a')),
    );
    match read_dat(&mut banner, None, "banner") {
        Err(Fc3dError::Parse { message, .. }) => {
            assert!(message.contains("line longer"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    assert!(banner.taken <= (1 << 21) + (64 << 10), "{}", banner.taken);
}

/// Every shared 3D file read from streams in small pieces, of known and unknown length, and from
/// its path, gives the problem the text reader gives, bit for bit, and the same matrix through
/// the matrix readers.
#[test]
fn streams_read_exactly_what_text_reads() {
    for path in shared_3d_files() {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(&path).unwrap();
        let expected = parse_dat(&text, &name).unwrap();
        for len in [Some(text.len() as u64), None] {
            let (p, _) = read_dat(Pieces::new(text.as_bytes()), len, &name).unwrap();
            assert_same_problem(&p, &expected, &name);
        }
        assert_same_problem(&read_dat_file(&path).unwrap(), &expected, &name);
        // The matrix part: after `dim nc`.
        let after = text
            .split_whitespace()
            .skip(2)
            .collect::<Vec<_>>()
            .join(" ");
        let (w, used) = parse_matrix_prefix(&after, &name).unwrap();
        let (ws, used_s) = read_matrix(Pieces::new(after.as_bytes()), None, &name).unwrap();
        assert_eq!(w_bits(&w), w_bits(&ws), "{name}");
        assert_eq!(used as u64, used_s, "{name}");
    }
}

/// The readers run on a thread with a 256 KiB stack (hosts call from small worker threads):
/// their buffers are on the heap. Before, the FILE* reader put a 64 KiB buffer on the stack.
#[test]
fn readers_run_on_a_256_kib_stack() {
    std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(|| {
            let path = Path::new(DATA_DIR).join("RockPile_tob1.dat");
            let p = read_dat_file(&path).unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            let (q, _) = read_dat(Pieces::new(text.as_bytes()), None, "rock").unwrap();
            assert_same_problem(&p, &q, "rock");
            assert!(read_dat_file(Path::new("/dev/zero")).is_err());
            let mut csr = Vec::new();
            write_dat(
                &p.with_w(Delassus::Sparse(p.w().to_csr())).unwrap(),
                &mut csr,
            )
            .unwrap();
            let (r, _) = read_dat(csr.as_slice(), None, "csr").unwrap();
            assert_eq!(r.n_contacts(), p.n_contacts());
        })
        .unwrap()
        .join()
        .unwrap();
}

/// The address-space limit of this process in bytes, from `/proc/self/limits` (None when
/// unlimited or unknown).
fn address_space_limit() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line.split_whitespace().nth(3)?.parse().ok()
}

/// True (and a note) when no address-space limit of at most 8 GiB is set: the endless-stream
/// tests would then take the machine's memory.
fn no_memory_limit(test: &str) -> bool {
    match address_space_limit() {
        Some(limit) if limit <= 8 << 30 => false,
        _ => {
            eprintln!("{test}: no address-space limit (run scripts/test-memory-limit.sh): skipped");
            true
        }
    }
}

fn expect_out_of_memory<T: std::fmt::Debug>(result: Result<T, Fc3dError>, what: &str) {
    match result {
        Err(Fc3dError::OutOfMemory { bytes, .. }) => {
            eprintln!("{what}: out of memory at {bytes} bytes, as expected")
        }
        other => panic!("{what}: expected OutOfMemory, got {other:?}"),
    }
}

/// A header declaring 10^9 contacts (a dense W of 9 10^18 values), then valid values without end, from a stream of unknown
/// length (a pipe): the values are stored as they arrive until an allocation fails, which is an
/// `OutOfMemory` error. Before, `Vec::with_capacity`/`push` aborted the process.
#[test]
#[ignore = "needs an address-space limit: scripts/test-memory-limit.sh"]
fn under_memory_limit_endless_values_run_out_of_memory() {
    if no_memory_limit("endless values") {
        return;
    }
    let e15 = "1000000000000000";
    // 10^9 contacts: (3 * 10^9)^2 values still fit a usize.
    let dense = "3 1000000000 0 3000000000 3000000000 3000000000 3000000000 ";
    expect_out_of_memory(
        read_dat(dense.as_bytes().chain(ZeroValues), None, "dense"),
        "dense W",
    );
    let triplets = format!(
        "2 16777215 16777215 1\nCSparse\ntriplet: 16777215-by-16777215, nzmax: {e15} nnz: {e15}\n"
    );
    expect_out_of_memory(
        read_matrix(triplets.as_bytes().chain(Triplets), None, "triplets"),
        "triplets",
    );
    let sbm = format!("{e15} 1 1 3 3 2 {e15} 0 {e15} ");
    expect_out_of_memory(
        read_sbm(sbm.as_bytes().chain(ZeroValues), None, "sbm"),
        "block columns",
    );
}

/// A regular file whose header declares a sparse matrix of 2^24 - 1 rows and no entry: its
/// row pointers (128 MiB) are probed before `CsrMatrix::from_triplets` allocates them. Under a
/// limit of 1 GiB it fits; the test checks it reads or fails cleanly either way.
#[test]
#[ignore = "needs an address-space limit: scripts/test-memory-limit.sh"]
fn under_memory_limit_declared_rows_are_probed() {
    if no_memory_limit("declared rows") {
        return;
    }
    let text = "2 16777215 16777215 1\nCSparse\ntriplet: 16777215-by-16777215, nzmax: 0 nnz: 0\n";
    match parse_matrix(text, "rows") {
        Ok(w) => assert_eq!(w.nrows(), 16777215),
        Err(e) => assert!(matches!(e, Fc3dError::OutOfMemory { .. }), "{e:?}"),
    }
}

/// Endless `0 ` values.
struct ZeroValues;

impl Read for ZeroValues {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        for pair in buf.chunks_mut(2) {
            pair[0] = b'0';
            if pair.len() > 1 {
                pair[1] = b' ';
            }
        }
        Ok(buf.len() & !1)
    }
}

/// Endless `0 0 : 1` triplet lines.
struct Triplets;

impl Read for Triplets {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        const LINE: &[u8] = b"0 0 : 1\n";
        let n = buf.len() / LINE.len() * LINE.len();
        for line in buf[..n].chunks_mut(LINE.len()) {
            line.copy_from_slice(LINE);
        }
        Ok(n)
    }
}

mod differential {
    //! The streaming readers against the text readers on random input: the same result, and the
    //! same error when the length is known.

    use super::*;
    use proptest::prelude::*;

    const VOCABULARY: &[&str] = &[
        "0",
        "1",
        "2",
        "3",
        "4",
        "6",
        "9",
        "-1",
        "0.5",
        "-0",
        "1e-300",
        "nan",
        "x",
        ":",
        "col",
        "locations",
        "to",
        "CSparse",
        "triplet:",
        "3-by-3,",
        "6-by-6,",
        "nzmax:",
        "nnz:",
        "9,",
        "1-norm:",
        "+3",
        "\u{a0}",
        "\u{85}",
        "é",
    ];

    fn token_text() -> impl Strategy<Value = String> {
        prop::collection::vec(
            (
                prop::sample::select(VOCABULARY),
                prop::sample::select(&[" ", "\n", "\t", "\r\n", "\u{b}"][..]),
            ),
            0..80,
        )
        .prop_map(|tokens| tokens.into_iter().flat_map(|(t, sep)| [t, sep]).collect())
    }

    fn check(bytes: &[u8]) -> Result<(), TestCaseError> {
        let text = String::from_utf8_lossy(bytes);
        let exact = matches!(text, std::borrow::Cow::Borrowed(_));
        let len = Some(bytes.len() as u64);
        let dbg = |r: &Result<FrictionProblem<'static>, Fc3dError>| match r {
            Ok(p) => Ok(format!("{p:?}")),
            Err(e) => Err(e.clone()),
        };
        let parsed = dbg(&parse_dat(&text, "f"));
        let known = dbg(&read_dat(Pieces::new(bytes), len, "f").map(|(p, _)| p));
        let unknown = dbg(&read_dat(Pieces::new(bytes), None, "f").map(|(p, _)| p));
        if exact {
            prop_assert_eq!(&parsed, &known);
        }
        prop_assert_eq!(parsed.is_ok(), known.is_ok());
        prop_assert_eq!(parsed.is_ok(), unknown.is_ok());
        if let (Ok(a), Ok(b)) = (&parsed, &unknown) {
            prop_assert_eq!(a, b);
        }
        let m = parse_matrix_prefix(&text, "m").map(|(w, used)| (format!("{w:?}"), used as u64));
        let ms =
            read_matrix(Pieces::new(bytes), len, "m").map(|(w, used)| (format!("{w:?}"), used));
        if exact {
            prop_assert_eq!(m, ms);
        } else {
            prop_assert_eq!(m.is_ok(), ms.is_ok());
        }
        let b = parse_sbm_prefix(&text, "b").map(|(s, used)| (format!("{s:?}"), used as u64));
        let bs = read_sbm(Pieces::new(bytes), None, "b").map(|(s, used)| (format!("{s:?}"), used));
        prop_assert_eq!(b.is_ok(), bs.is_ok());
        if exact {
            if let (Ok(x), Ok(y)) = (b, bs) {
                prop_assert_eq!(x, y);
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn random_tokens_read_alike(
            header in prop::sample::select(&["3 1 0 3 3 ", "3 1 1 3 3 ", "3 2 1 6 6 ", "3 1 2 3 3 1\nCSparse x y\n", "3 1 2 3 3 2 \nCSparse\n", "0 2 3 ", "1 6 6 ", "2 3 3 1\nCSparse\n", ""][..]),
            body in token_text(),
        ) {
            check(format!("{header}{body}").as_bytes())?;
        }

        #[test]
        fn random_bytes_read_alike(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
            check(&bytes)?;
        }

        #[test]
        fn mutated_files_read_alike(which in 0usize..4, at in any::<prop::sample::Index>(), by in prop::sample::select(&["", "0", "99999999999", "\u{a0}", "\u{fffd}", "\n", "x"][..])) {
            let name = ["FC3D_Example1_SBM.dat", "FrictionContact3D_1c.dat", "Rover4396.dat", "FC3D_Example1.dat"][which];
            let text = std::fs::read_to_string(Path::new(DATA_DIR).join(name)).unwrap();
            let mut k = at.index(text.len());
            while !text.is_char_boundary(k) {
                k -= 1;
            }
            check(format!("{}{by}{}", &text[..k], &text[k..]).as_bytes())?;
            check(&text.as_bytes()[..k])?;
        }
    }
}

/// An FCLIB file whose W is marked dense (`fc3d_storage` = 0) with 12000 rows and no entry,
/// padded to 3 MB so that 12000^2 values pass the "64 values per byte of file" guard: the dense
/// W (1.2 GB) cannot be allocated under a 1 GiB limit and is an `OutOfMemory` error. Before,
/// `vec![0.0; n * n]` aborted the process.
#[cfg(feature = "fclib")]
#[test]
#[ignore = "needs an address-space limit: scripts/test-memory-limit.sh"]
fn under_memory_limit_fclib_dense_w_runs_out_of_memory() {
    use hdf5_metno as hdf5;
    if no_memory_limit("fclib dense W") {
        return;
    }
    let n: i32 = 12_000;
    let file = Scratch::new("dense.hdf5", b"");
    {
        let f = hdf5::File::create(&file.0).unwrap();
        let g = f.create_group("fclib_local").unwrap();
        g.new_dataset_builder()
            .with_data(&[3i32])
            .create("spacedim")
            .unwrap();
        let w = g.create_group("W").unwrap();
        for (field, v) in [("nzmax", 0), ("m", n), ("n", n), ("nz", 0)] {
            w.new_dataset_builder()
                .with_data(&[v])
                .create(field)
                .unwrap();
        }
        let none: [i32; 0] = [];
        w.new_dataset_builder()
            .with_data(&none)
            .create("p")
            .unwrap();
        w.new_dataset_builder()
            .with_data(&none)
            .create("i")
            .unwrap();
        w.new_dataset_builder()
            .with_data(&[0.0f64; 0])
            .create("x")
            .unwrap();
        w.new_attr::<i32>()
            .shape(1)
            .create("fc3d_storage")
            .unwrap()
            .write_raw(&[0i32])
            .unwrap();
        let v = g.create_group("vectors").unwrap();
        let q = vec![-1.0f64; n as usize];
        v.new_dataset_builder()
            .with_data(q.as_slice())
            .create("q")
            .unwrap();
        let mu = vec![0.5f64; n as usize / 3];
        v.new_dataset_builder()
            .with_data(mu.as_slice())
            .create("mu")
            .unwrap();
        // Incompressible padding.
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let pad: Vec<u64> = (0..(3 << 20) / 8)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                x
            })
            .collect();
        f.new_dataset_builder()
            .with_data(pad.as_slice())
            .create("padding")
            .unwrap();
    }
    expect_out_of_memory(fc3d_core::io::read_fclib_file(&file.0), "FCLIB dense W");
}

/// Where a matrix ends when Unicode whitespace follows it: the offset of the next token, as the
/// text reader gives it.
#[test]
fn the_end_of_a_matrix_before_unicode_whitespace() {
    for text in [
        "0 1 1 1 1 2.5 \u{a0}next",
        "0 1 1 1 1 2.5\n\u{a0}\u{85}",
        "0 1 1 1 1 2.5 \u{a0}\u{a0}",
        "0 1 1 1 1 2.5 é",
    ] {
        let (_, used) = parse_matrix_prefix(text, "m").unwrap();
        let expected = text
            .char_indices()
            .skip_while(|&(i, _)| i < 13)
            .find(|(_, c)| !c.is_whitespace())
            .map_or(text.len(), |(i, _)| i);
        assert_eq!(used, expected, "{text:?}");
        let (_, streamed) = read_matrix(Pieces::new(text.as_bytes()), None, "m").unwrap();
        assert_eq!(streamed, used as u64, "{text:?}");
    }
}
