//! The bytes of a `.dat` input, read lazily: from memory, or from a stream in chunks of
//! [`CHUNK_BYTES`] (on the heap), so that a reader holds only what it has parsed plus one chunk,
//! whatever the stream holds after that (a huge file, `/dev/zero`, a pipe that never ends).
//!
//! Tokens are runs of bytes between ASCII whitespace (the tokenizer in `tokens` splits a run that
//! is not ASCII further, on Unicode whitespace). Every wait for input is bounded: a run longer
//! than [`MAX_TOKEN_BYTES`] or more than [`MAX_GAP_BYTES`] of whitespace between two tokens is
//! an error, so a stream that never ends (`/dev/zero` is one endless token, `yes ''` endless
//! whitespace) is rejected after a bounded amount of reading.

use std::io::{self, Read};

/// Bytes read from a stream at a time (a heap buffer: readers run on small thread stacks). The
/// buffer starts at [`FIRST_CHUNK_BYTES`] and doubles while reads fill it.
const CHUNK_BYTES: usize = 64 * 1024;
const FIRST_CHUNK_BYTES: usize = 4 * 1024;
/// Longest token: no number or keyword of the format comes near it, and a stream of bytes that
/// are not whitespace (`/dev/zero`) is rejected after reading this much.
pub(super) const MAX_TOKEN_BYTES: usize = 64 * 1024;
/// Longest run of whitespace between two tokens (a stream of blank lines that never ends is
/// rejected after reading this much).
pub(super) const MAX_GAP_BYTES: u64 = 16 * 1024 * 1024;

/// ASCII whitespace as `char::is_whitespace` (and `str::split_whitespace`) sees it: unlike
/// `u8::is_ascii_whitespace`, it includes the vertical tab.
pub(super) fn is_ascii_space(b: u8) -> bool {
    matches!(b, b'\t' | b'\n' | 0x0B | 0x0C | b'\r' | b' ')
}

/// Why scanning stopped early.
pub(super) enum ScanError {
    /// The stream failed.
    Io(io::Error),
    /// A run of more than [`MAX_TOKEN_BYTES`] bytes; its first bytes.
    TokenTooLong(Vec<u8>),
    /// More than [`MAX_GAP_BYTES`] of whitespace.
    GapTooLong,
}

/// The input: a byte slice, or a stream read in chunks.
pub(super) struct Bytes<'t> {
    /// The whole input (memory), or nothing (stream).
    text: &'t [u8],
    stream: Option<&'t mut dyn Read>,
    /// The current chunk of a stream.
    buf: Vec<u8>,
    /// Next unread byte of the window (`text`, or `buf[..len]`).
    at: usize,
    /// Length of the window.
    len: usize,
    /// Offset in the input of the window's first byte.
    base: u64,
    /// The stream has ended.
    eof: bool,
    /// Number of '\n' before `at`.
    pub(super) line: usize,
}

impl<'t> Bytes<'t> {
    pub(super) fn from_slice(text: &'t [u8]) -> Self {
        Bytes {
            text,
            stream: None,
            buf: Vec::new(),
            at: 0,
            len: text.len(),
            base: 0,
            eof: true,
            line: 0,
        }
    }

    pub(super) fn from_stream(stream: &'t mut dyn Read) -> Self {
        Bytes {
            text: &[],
            stream: Some(stream),
            buf: vec![0; FIRST_CHUNK_BYTES],
            at: 0,
            len: 0,
            base: 0,
            eof: false,
            line: 0,
        }
    }

    /// Offset in the input of the next unread byte (for a stream: the bytes taken from it, less
    /// those of the current chunk not scanned yet).
    pub(super) fn offset(&self) -> u64 {
        self.base + self.at as u64
    }

    fn window(&self) -> &[u8] {
        if self.stream.is_some() {
            &self.buf[..self.len]
        } else {
            self.text
        }
    }

    /// Makes an unread byte available; false at the end of the input.
    fn fill(&mut self) -> Result<bool, ScanError> {
        if self.at < self.len {
            return Ok(true);
        }
        if self.eof {
            return Ok(false);
        }
        let Some(stream) = self.stream.as_mut() else {
            return Ok(false);
        };
        if self.len == self.buf.len() && self.buf.len() < CHUNK_BYTES {
            self.buf.resize(2 * self.buf.len(), 0);
        }
        self.base += self.len as u64;
        self.at = 0;
        self.len = 0;
        loop {
            match stream.read(&mut self.buf) {
                Ok(0) => {
                    self.eof = true;
                    return Ok(false);
                }
                Ok(n) => {
                    self.len = n.min(self.buf.len());
                    return Ok(true);
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(ScanError::Io(e)),
            }
        }
    }

    /// Skips whitespace; true when a token starts at [`Bytes::offset`], false at the end.
    pub(super) fn skip_space(&mut self) -> Result<bool, ScanError> {
        let mut skipped: u64 = 0;
        loop {
            if !self.fill()? {
                return Ok(false);
            }
            let (start, len) = (self.at, self.len);
            let mut at = start;
            let mut newlines = 0;
            {
                let w = self.window();
                while at < len && is_ascii_space(w[at]) {
                    newlines += usize::from(w[at] == b'\n');
                    at += 1;
                }
            }
            self.at = at;
            self.line += newlines;
            skipped += (at - start) as u64;
            if skipped > MAX_GAP_BYTES {
                return Err(ScanError::GapTooLong);
            }
            if at < len {
                return Ok(true);
            }
        }
    }

    /// The byte at the cursor, if any (after [`Bytes::skip_space`]: the first of a run).
    pub(super) fn peek_byte(&self) -> Option<u8> {
        (self.at < self.len).then(|| self.window()[self.at])
    }

    /// Reads the run of non-whitespace bytes that starts at the cursor into `out`.
    pub(super) fn read_run(&mut self, out: &mut Vec<u8>) -> Result<(), ScanError> {
        out.clear();
        loop {
            if !self.fill()? {
                return Ok(());
            }
            let (start, len) = (self.at, self.len);
            let room = MAX_TOKEN_BYTES + 1 - out.len();
            let mut at = start;
            {
                let w = self.window();
                while at < len && at - start < room && !is_ascii_space(w[at]) {
                    at += 1;
                }
                out.extend_from_slice(&w[start..at]);
            }
            self.at = at;
            if out.len() > MAX_TOKEN_BYTES {
                out.truncate(40);
                return Err(ScanError::TokenTooLong(std::mem::take(out)));
            }
            if at < len {
                return Ok(());
            }
        }
    }
}
