//! The FILE* and file-name readers and writers of the C ABI against inputs sized to hurt (issue
//! 13, item 3, and item 7 for readers), called as a C host calls them: `/dev/zero` as a path and
//! as a FILE*, pipes, headers declaring far more than the data holds, data after the problem,
//! streams that end early, a `numberOfContacts` whose triple does not fit a C int, a matrix
//! without blocks of size near `INT_MAX` written out, and calls from a thread with a 256 KiB
//! stack. Each gets an error code and NULL (or a clean result), never an abort.
//!
//! The tests named `under_memory_limit_*` are ignored in plain runs: they feed pipes with endless
//! valid values and expect `FC3D_ERR_OUT_OF_MEMORY`, which needs an address-space limit
//! (`scripts/test-memory-limit.sh` sets one with `ulimit -v`). They check the limit themselves
//! and return at once without one.

#![cfg(feature = "siconos-abi")]

use std::ffi::{c_char, CStr, CString};
use std::io::Write;
use std::os::fd::FromRawFd;
use std::os::raw::{c_double, c_int};
use std::path::PathBuf;
use std::ptr::{null_mut, NonNull};
use std::time::{Duration, Instant};

use fc3d::types::{FrictionContactProblem, NumericsMatrix, SparseBlockStructuredMatrix};
use fc3d::{
    FC3D_ERR_INVALID_SIZE, FC3D_ERR_IO, FC3D_ERR_NULL_POINTER, FC3D_ERR_OUT_OF_MEMORY,
    FC3D_ERR_PARSE,
};

mod siconos_api;
use siconos_api::*;

extern "C" {
    fn frictionContact_newFromFile(file: *mut libc::FILE) -> *mut FrictionContactProblem;
    fn frictionContact_printInFile(
        problem: *mut FrictionContactProblem,
        file: *mut libc::FILE,
    ) -> c_int;
    fn frictionContact_printInFilename(
        problem: *mut FrictionContactProblem,
        filename: *mut c_char,
    ) -> c_int;
    fn NM_new_from_file(file: *mut libc::FILE) -> *mut NumericsMatrix;
    fn NM_new_from_filename(filename: *const c_char) -> *mut NumericsMatrix;
    fn NM_write_in_file(m: *const NumericsMatrix, file: *mut libc::FILE);
    fn NM_free(m: *mut NumericsMatrix) -> *mut NumericsMatrix;
    fn SBM_new_from_file(file: *mut libc::FILE) -> *mut SparseBlockStructuredMatrix;
    fn SBM_clear(m: *mut SparseBlockStructuredMatrix);
}

const DATA_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/siconos");

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

fn cstring(s: &str) -> CString {
    CString::new(s).unwrap()
}

/// A scratch file removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str, contents: &[u8]) -> Self {
        let path =
            std::env::temp_dir().join(format!("fc3d-file-limits-{}-{name}", std::process::id()));
        std::fs::write(&path, contents).unwrap();
        Scratch(path)
    }

    fn c_path(&self) -> CString {
        cstring(self.0.to_str().unwrap())
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// A C stream, closed on drop.
struct CFile(NonNull<libc::FILE>);

impl CFile {
    fn open(path: &str, mode: &str) -> Self {
        let f = unsafe { libc::fopen(cstring(path).as_ptr(), cstring(mode).as_ptr()) };
        CFile(NonNull::new(f).expect("fopen"))
    }

    fn ptr(&self) -> *mut libc::FILE {
        self.0.as_ptr()
    }

    /// Everything left in the stream.
    fn rest(&self) -> String {
        let mut out = Vec::new();
        loop {
            let c = unsafe { libc::fgetc(self.ptr()) };
            if c == libc::EOF {
                break;
            }
            out.push(c as u8);
        }
        String::from_utf8_lossy(&out).into_owned()
    }
}

impl Drop for CFile {
    fn drop(&mut self) {
        unsafe { libc::fclose(self.ptr()) };
    }
}

/// The read end of a pipe as a C stream (it cannot seek) and a thread writing `write` into the
/// other end; the writer stops when the reader closes (EPIPE: Rust ignores SIGPIPE).
fn pipe_with(
    write: impl FnOnce(&mut std::fs::File) -> std::io::Result<()> + Send + 'static,
) -> (CFile, std::thread::JoinHandle<()>) {
    let mut fds = [0; 2];
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    let reader = unsafe { libc::fdopen(fds[0], cstring("r").as_ptr()) };
    let mut writer = unsafe { std::fs::File::from_raw_fd(fds[1]) };
    let handle = std::thread::spawn(move || {
        let _ = write(&mut writer);
    });
    (CFile(NonNull::new(reader).expect("fdopen")), handle)
}

/// A shared problem as fc3d writes it (nothing after mu).
fn problem_text(name: &str) -> String {
    let p = fc3d_core::io::read_dat_file(&PathBuf::from(format!("{DATA_DIR}/{name}"))).unwrap();
    let mut text = Vec::new();
    fc3d_core::io::write_dat(&p, &mut text).unwrap();
    String::from_utf8(text).unwrap()
}

/// Reads a problem with `frictionContact_newFromFile`, returns (is NULL, code).
fn read_problem(file: &CFile) -> (bool, c_int) {
    unsafe {
        fc3d_clear_last_error();
        let p = frictionContact_newFromFile(file.ptr());
        let code = fc3d_last_error_code();
        let null = p.is_null();
        frictionContactProblem_free(p);
        (null, code)
    }
}

fn read_matrix(file: &CFile) -> (bool, c_int) {
    unsafe {
        fc3d_clear_last_error();
        let m = NM_new_from_file(file.ptr());
        let code = fc3d_last_error_code();
        let null = m.is_null();
        NM_free(m);
        (null, code)
    }
}

fn read_sbm(file: &CFile) -> (bool, c_int) {
    unsafe {
        fc3d_clear_last_error();
        let m = SBM_new_from_file(file.ptr());
        let code = fc3d_last_error_code();
        let null = m.is_null();
        if !null {
            SBM_clear(m);
            libc::free(m.cast());
        }
        (null, code)
    }
}

/// `/dev/zero` (an endless token) as a FILE*, as a pipe and as a path: FC3D_ERR_PARSE after a
/// bounded read. Before, `read_rest` (FILE*) and `std::fs::read` (paths) grew a buffer until the
/// allocation failed: an abort.
#[test]
fn dev_zero_as_file_pipe_and_path_is_a_parse_error() {
    let start = Instant::now();
    let zero = CFile::open("/dev/zero", "r");
    assert_eq!(read_problem(&zero), (true, FC3D_ERR_PARSE));
    assert!(last_error().1.contains("longer than"), "{}", last_error().1);
    assert_eq!(read_matrix(&zero), (true, FC3D_ERR_PARSE));
    assert_eq!(read_sbm(&zero), (true, FC3D_ERR_PARSE));
    for reader in [read_problem, read_matrix, read_sbm] {
        let (pipe, writer) = pipe_with(|w| loop {
            w.write_all(&[0u8; 4096])?;
        });
        assert_eq!(reader(&pipe), (true, FC3D_ERR_PARSE));
        drop(pipe);
        writer.join().unwrap();
    }
    unsafe {
        let path = cstring("/dev/zero");
        assert!(frictionContact_new_from_filename(path.as_ptr()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_PARSE);
        assert!(NM_new_from_filename(path.as_ptr()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_PARSE);
    }
    assert!(start.elapsed() < Duration::from_secs(10));
}

/// Headers declaring 10^15 contacts, values or blocks with a few tokens after them, from a
/// regular file (whose size bounds what it can hold), `fmemopen` and a pipe: FC3D_ERR_PARSE
/// (the end of the input is named), fast.
#[test]
fn huge_headers_with_little_data_are_parse_errors() {
    let e15 = "1000000000000000";
    let n15 = "3000000000000000";
    let problems = [
        format!("3 {e15} 0 {n15} {n15} {n15} {n15} 1 2 3\n"),
        format!("3 1 2 3 3 1\nCSparse\ntriplet: 3-by-3, nzmax: {e15} nnz: {e15}\n 0 0 : 1\n"),
        format!("3 1 1 3 3 {e15} 1 1 3 3 2 {e15} 0 {e15} 0 0 0\n"),
        format!("3 {e15} 1 {n15} {n15} 1 {e15} {e15} 3 6 9\n"),
    ];
    for (k, text) in problems.iter().enumerate() {
        let start = Instant::now();
        let file = Scratch::new(&format!("huge{k}.dat"), text.as_bytes());
        unsafe {
            assert!(frictionContact_new_from_filename(file.c_path().as_ptr()).is_null());
        }
        assert_eq!(last_error().0, FC3D_ERR_PARSE, "{k}: {}", last_error().1);
        let f = CFile::open(file.0.to_str().unwrap(), "r");
        assert_eq!(read_problem(&f), (true, FC3D_ERR_PARSE), "{k}");
        // A failed read leaves a seekable stream where it was.
        assert_eq!(&f.rest(), text, "{k}");
        let owned = text.clone();
        let (pipe, writer) = pipe_with(move |w| w.write_all(owned.as_bytes()));
        assert_eq!(read_problem(&pipe), (true, FC3D_ERR_PARSE), "{k}");
        drop(pipe);
        writer.join().unwrap();
        assert!(start.elapsed() < Duration::from_secs(5), "{k}");
    }
    let matrix = format!("2 16777215 16777215 1\nCSparse\ntriplet: 16777215-by-16777215, nzmax: {e15} nnz: {e15}\n 0 0 : 1\n");
    let file = Scratch::new("huge.mat", matrix.as_bytes());
    let f = CFile::open(file.0.to_str().unwrap(), "r");
    assert_eq!(read_matrix(&f), (true, FC3D_ERR_PARSE));
    unsafe {
        assert!(NM_new_from_filename(file.c_path().as_ptr()).is_null());
    }
    assert_eq!(last_error().0, FC3D_ERR_PARSE);
}

/// A problem followed by more text, in a regular file and through a pipe: read up to the
/// problem, the stream left at the first token after it (the pipe too: the one byte read past
/// the problem is pushed back). Before, `frictionContact_newFromFile` read the stream to its end.
#[test]
fn trailing_data_stays_in_the_stream() {
    let text = problem_text("Rover4396.dat");
    let with_tail = format!("{}\ntail 7\n", text.trim_end());
    let file = Scratch::new("tail.dat", with_tail.as_bytes());
    let f = CFile::open(file.0.to_str().unwrap(), "r");
    assert_eq!(read_problem(&f), (false, 0));
    assert_eq!(f.rest(), "tail 7\n");

    let owned = with_tail.clone();
    let (pipe, writer) = pipe_with(move |w| w.write_all(owned.as_bytes()));
    assert_eq!(read_problem(&pipe), (false, 0));
    assert_eq!(pipe.rest(), "tail 7\n");
    writer.join().unwrap();

    // A problem followed by an endless stream: read, the rest left alone.
    let owned = text.clone();
    let (pipe, writer) = pipe_with(move |w| {
        w.write_all(owned.as_bytes())?;
        loop {
            w.write_all(&[b'9'; 4096])?;
        }
    });
    assert_eq!(read_problem(&pipe), (false, 0));
    drop(pipe);
    writer.join().unwrap();
}

/// A stream that ends early (the pipe's writer stops in the middle of W): FC3D_ERR_PARSE.
#[test]
fn a_stream_that_ends_early_is_a_parse_error() {
    let text = problem_text("Capsules-i101-404.dat");
    for cut in [3, text.len() / 4, text.len() / 2, text.len() - 40] {
        let owned = text[..cut].to_string();
        let (pipe, writer) = pipe_with(move |w| w.write_all(owned.as_bytes()));
        assert_eq!(read_problem(&pipe), (true, FC3D_ERR_PARSE), "cut at {cut}");
        writer.join().unwrap();
    }
}

/// `numberOfContacts` whose triple does not fit a C int, with an M whose size is that triple
/// truncated to a C int: FC3D_ERR_INVALID_SIZE naming the count. Before, `3 * nc` was compared
/// with M's size through `as c_int` (truncating), and q, mu were taken as slices of `3 nc` and
/// `nc` values over the host's short arrays.
#[test]
fn contact_counts_whose_triple_is_not_a_c_int_are_rejected() {
    let devnull = CFile::open("/dev/null", "w");
    for nc in [1_431_655_766, 715_827_883, c_int::MAX] {
        let n = (3 * nc as i64) as c_int; // truncated on purpose: what the old check compared
        let mut values = vec![1.0 as c_double; 16];
        let mut m = NumericsMatrix {
            storageType: 0,
            size0: n,
            size1: n,
            matrix0: values.as_mut_ptr(),
            matrix1: null_mut(),
            matrix2: null_mut(),
            internalData: null_mut(),
            version: unsafe { std::mem::zeroed() },
            destructible: null_mut(),
        };
        let mut q = [0.0 as c_double; 3];
        let mut mu = [0.5 as c_double; 1];
        let mut problem = FrictionContactProblem {
            dimension: 3,
            numberOfContacts: nc,
            M: &mut m,
            q: q.as_mut_ptr(),
            mu: mu.as_mut_ptr(),
        };
        let rc = unsafe { frictionContact_printInFile(&mut problem, devnull.ptr()) };
        let (code, message) = last_error();
        assert_eq!(
            (rc, code),
            (FC3D_ERR_INVALID_SIZE, FC3D_ERR_INVALID_SIZE),
            "{nc}"
        );
        assert!(message.contains("C int"), "{message}");
        let out = Scratch::new("never.dat", b"");
        let rc = unsafe {
            frictionContact_printInFilename(&mut problem, out.c_path().as_ptr() as *mut _)
        };
        assert_eq!(rc, FC3D_ERR_INVALID_SIZE);
    }
}

/// A sparse-block matrix without blocks of size near INT_MAX is written as Siconos writes it (a
/// lone 0) without allocating anything of its size. Before, a row-pointer array of
/// `size0 / 3 + 1` (5.7 GB here) was built first.
#[test]
fn an_empty_sparse_block_matrix_of_huge_size_is_written_without_allocating() {
    let mut sbm: SparseBlockStructuredMatrix = unsafe { std::mem::zeroed() };
    let size = 2_147_483_646; // a multiple of 3
    let m = NumericsMatrix {
        storageType: 1,
        size0: size,
        size1: size,
        matrix0: null_mut(),
        matrix1: &mut sbm,
        matrix2: null_mut(),
        internalData: null_mut(),
        version: unsafe { std::mem::zeroed() },
        destructible: null_mut(),
    };
    let out = Scratch::new("empty.mat", b"");
    {
        let f = CFile::open(out.0.to_str().unwrap(), "w");
        unsafe {
            fc3d_clear_last_error();
            NM_write_in_file(&m, f.ptr());
        }
        assert_eq!(last_error().0, 0, "{}", last_error().1);
    }
    assert_eq!(
        std::fs::read_to_string(&out.0).unwrap(),
        format!("1\n{size}\n{size}\n0\n")
    );
    // NULL stream: the code, nothing else.
    unsafe { NM_write_in_file(&m, null_mut()) };
    assert_eq!(last_error().0, FC3D_ERR_NULL_POINTER);
}

/// The readers and writers from a thread with a 256 KiB stack. Before, the FILE* reader put a
/// 64 KiB buffer on the stack.
#[test]
fn readers_run_on_a_256_kib_stack() {
    std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(|| {
            let path = cstring(&format!("{DATA_DIR}/RockPile_tob1.dat"));
            let p = unsafe { frictionContact_new_from_filename(path.as_ptr()) };
            assert!(!p.is_null(), "{}", last_error().1);
            let out = Scratch::new("rock.dat", b"");
            let rc = unsafe { frictionContact_printInFilename(p, out.c_path().as_ptr() as *mut _) };
            assert_eq!(rc, 0);
            let f = CFile::open(out.0.to_str().unwrap(), "r");
            assert_eq!(read_problem(&f), (false, 0));
            unsafe { frictionContactProblem_free(p) };
            let zero = CFile::open("/dev/zero", "r");
            assert_eq!(read_problem(&zero), (true, FC3D_ERR_PARSE));
        })
        .unwrap()
        .join()
        .unwrap();
}

/// Missing files and NULL streams keep their codes.
#[test]
fn missing_files_and_null_streams() {
    unsafe {
        let missing = cstring("/nonexistent/fc3d/x.dat");
        assert!(frictionContact_new_from_filename(missing.as_ptr()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_IO);
        assert!(NM_new_from_filename(missing.as_ptr()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_IO);
        assert!(frictionContact_newFromFile(null_mut()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_NULL_POINTER);
        assert!(NM_new_from_file(null_mut()).is_null());
        assert_eq!(fc3d_last_error_code(), FC3D_ERR_NULL_POINTER);
    }
}

/// The address-space limit of this process (None when unlimited).
fn address_space_limit() -> Option<u64> {
    let mut limit = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } != 0
        || limit.rlim_cur == libc::RLIM_INFINITY
    {
        return None;
    }
    Some(limit.rlim_cur)
}

fn no_memory_limit(test: &str) -> bool {
    match address_space_limit() {
        Some(limit) if limit <= 8 << 30 => false,
        _ => {
            eprintln!("{test}: no address-space limit (run scripts/test-memory-limit.sh): skipped");
            true
        }
    }
}

/// Reads with `read` from `pipe`, expecting FC3D_ERR_OUT_OF_MEMORY.
fn expect_out_of_memory(read: fn(&CFile) -> (bool, c_int), pipe: CFile, what: &str) {
    let got = read(&pipe);
    let (code, message) = last_error();
    assert_eq!(got, (true, FC3D_ERR_OUT_OF_MEMORY), "{what}: {message}");
    eprintln!("{what}: out of memory at: {message}");
    assert_eq!(code, FC3D_ERR_OUT_OF_MEMORY);
}

/// Endless `0 ` values after `header`, into a pipe.
fn endless_values(header: String) -> (CFile, std::thread::JoinHandle<()>) {
    pipe_with(move |w| {
        w.write_all(header.as_bytes())?;
        let zeros = b"0 ".repeat(32 * 1024);
        loop {
            w.write_all(&zeros)?;
        }
    })
}

/// Pipes going on with valid values after headers declaring 10^9 contacts / 10^15 entries:
/// FC3D_ERR_OUT_OF_MEMORY once the values read cannot be stored, never an abort. Before,
/// `read_rest` grew an infallible buffer with the whole stream.
#[test]
#[ignore = "needs an address-space limit: scripts/test-memory-limit.sh"]
fn under_memory_limit_pipes_with_endless_values_run_out_of_memory() {
    if no_memory_limit("pipes with endless values") {
        return;
    }
    let e15 = "1000000000000000";
    let (pipe, writer) =
        endless_values("3 1000000000 0 3000000000 3000000000 3000000000 3000000000 ".into());
    expect_out_of_memory(read_problem, pipe, "frictionContact_newFromFile");
    writer.join().unwrap();

    let (pipe, writer) = endless_values("0 2000000000 2000000000 2000000000 2000000000 ".into());
    expect_out_of_memory(read_matrix, pipe, "NM_new_from_file");
    writer.join().unwrap();

    let (pipe, writer) = endless_values(format!("{e15} 1 1 3 3 2 {e15} 0 {e15} "));
    expect_out_of_memory(read_sbm, pipe, "SBM_new_from_file");
    writer.join().unwrap();
}
