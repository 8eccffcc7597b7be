// One fuzz case of the .dat reader, shared by fuzz/fuzz_targets/dat_parser.rs and
// tests/fuzz_regressions.rs (both include this file).

/// A stream handing out bytes in pieces of 1 to 5 bytes, so that the streaming readers meet
/// chunk boundaries everywhere.
struct DatPieces<'a> {
    data: &'a [u8],
    at: usize,
}

impl std::io::Read for DatPieces<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = (1 + self.at % 5).min(buf.len()).min(self.data.len() - self.at);
        buf[..n].copy_from_slice(&self.data[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

fn dat_pieces(data: &[u8]) -> DatPieces<'_> {
    DatPieces { data, at: 0 }
}

/// The streaming reader's result against the text reader's: the same success, value for value
/// (Debug shows -0.0), and, when `exact`, the same error.
fn assert_same_read<T: std::fmt::Debug>(
    text: &Result<T, fc3d_core::error::Fc3dError>,
    stream: &Result<T, fc3d_core::error::Fc3dError>,
    exact: bool,
    what: &str,
) {
    match (text, stream) {
        (Ok(a), Ok(b)) => assert_eq!(format!("{a:?}"), format!("{b:?}"), "{what}"),
        (Err(a), Err(b)) => {
            if exact {
                assert_eq!(a, b, "{what}")
            }
        }
        _ => panic!("{what}: text {text:?}, stream {stream:?}"),
    }
}

/// Parses arbitrary bytes; panics (assert) if a parsed problem does not survive a round trip,
/// or if a streaming reader (`read_dat`, `read_matrix`, `read_sbm`, fed the raw bytes in small
/// pieces, of known and of unknown length) disagrees with the text reader on the same input.
pub fn run_dat_case(data: &[u8]) {
    use fc3d_core::io::dat;

    let text = String::from_utf8_lossy(data);
    // Offsets and sizes agree between the bytes and the text only when nothing was replaced.
    let exact = matches!(text, std::borrow::Cow::Borrowed(_));
    let len = Some(data.len() as u64);

    let parsed = dat::parse_dat(&text, "fuzz");
    if let Ok(p) = &parsed {
        let mut out = Vec::new();
        dat::write_dat(p, &mut out).expect("writing to memory");
        let again = dat::parse_dat(std::str::from_utf8(&out).expect("utf-8"), "again")
            .expect("what we write, we read");
        assert_eq!(p.size(), again.size());
    }
    let known = dat::read_dat(dat_pieces(data), len, "fuzz").map(|(p, _)| p);
    assert_same_read(&parsed, &known, exact, "read_dat, known length");
    let unknown = dat::read_dat(dat_pieces(data), None, "fuzz").map(|(p, _)| p);
    assert_same_read(&parsed, &unknown, false, "read_dat, unknown length");

    // The same bytes as a lone matrix and as a sparse-block body.
    let matrix = dat::parse_matrix_prefix(&text, "fuzz").map(|(m, used)| (m, used as u64));
    let matrix_stream = dat::read_matrix(dat_pieces(data), len, "fuzz");
    if exact {
        assert_same_read(&matrix, &matrix_stream, true, "read_matrix");
    } else {
        assert_eq!(matrix.is_ok(), matrix_stream.is_ok(), "read_matrix");
    }
    let body = dat::parse_sbm_prefix(&text, "fuzz").map(|(m, used)| (m, used as u64));
    let body_stream = dat::read_sbm(dat_pieces(data), None, "fuzz");
    if exact {
        assert_same_read(&body, &body_stream, false, "read_sbm");
    } else {
        assert_eq!(body.is_ok(), body_stream.is_ok(), "read_sbm");
    }
}
