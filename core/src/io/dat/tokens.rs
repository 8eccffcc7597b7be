//! The tokens of a `.dat` input and the cursor the readers walk them with.
//!
//! Tokens are what `str::split_whitespace` gives on the input decoded as UTF-8 with invalid bytes
//! replaced (U+FFFD), and they are numbered as it numbers them; but they are scanned one at a
//! time, from memory or from a stream read in chunks (`scan`), never all at once. The reader
//! keeps the token it last read, the few tokens it has looked ahead at, and the texts of the
//! tokens a later error may have to name ([`Reader::remember`]).
//!
//! Sizes declared by the input are never trusted for allocation: vectors start at a capacity
//! bounded by what the rest of the input can hold ([`Reader::vec_for`]) and grow fallibly as
//! values actually arrive ([`try_push`]), so a header declaring 10^15 values with little data
//! fails with a parse error (or, for a stream that goes on long enough, with
//! [`Fc3dError::OutOfMemory`]), never an abort.

use std::collections::VecDeque;
use std::io::Read;

use super::scan::{Bytes, ScanError, MAX_GAP_BYTES, MAX_TOKEN_BYTES};
use super::store::ReadArray;
pub(super) use crate::alloc::{reserve, try_push};
use crate::error::Fc3dError;

/// The token text reported when the input ends too early.
pub(super) const END_OF_FILE: &str = "<end of file>";
/// Longest line [`Reader::skip_rest_of_line`] skips (the free-text CSparse banner).
const MAX_SKIPPED_LINE_BYTES: u64 = 1 << 20;
/// First capacity of a vector whose declared length the input's size cannot bound (a stream).
const UNBOUNDED_START_CAPACITY: usize = 4096;

/// A token: its number, text, line and byte offset in the input.
struct Token {
    index: usize,
    text: String,
    line: usize,
    start: u64,
}

/// A cursor over the tokens of an input.
pub(super) struct Reader<'t> {
    bytes: Bytes<'t>,
    pub(super) file: &'t str,
    /// What the matrix is called in messages ("W" in a problem file, "M" alone).
    pub(super) name: &'static str,
    /// Length in bytes of the whole input, when known (memory, a regular file).
    size: Option<u64>,
    /// The last token read.
    current: Option<Token>,
    /// Tokens scanned but not read yet (usually at most one).
    ahead: VecDeque<Token>,
    /// Texts kept for later messages ([`Reader::remember`]).
    kept: Vec<(usize, String)>,
    /// Scratch: the bytes of a run and spent token texts.
    run: Vec<u8>,
    spare: Vec<String>,
    /// Index of the next token to read.
    pub(super) pos: usize,
    /// Number of tokens scanned (read or ahead).
    scanned: usize,
    /// The number of tokens of the input, once its end has been seen.
    end: Option<usize>,
}

impl<'t> Reader<'t> {
    /// A reader over text in memory.
    pub(super) fn new(text: &'t str, file: &'t str, name: &'static str) -> Self {
        Self::with_bytes(
            Bytes::from_slice(text.as_bytes()),
            Some(text.len() as u64),
            file,
            name,
        )
    }

    /// A reader over a stream; `size`: its length in bytes when known (a regular file), which
    /// lets an impossible declared size fail before the stream is read to its end.
    pub(super) fn from_stream(
        stream: &'t mut dyn Read,
        size: Option<u64>,
        file: &'t str,
        name: &'static str,
    ) -> Self {
        Self::with_bytes(Bytes::from_stream(stream), size, file, name)
    }

    fn with_bytes(bytes: Bytes<'t>, size: Option<u64>, file: &'t str, name: &'static str) -> Self {
        Reader {
            bytes,
            file,
            name,
            size,
            current: None,
            ahead: VecDeque::new(),
            kept: Vec::new(),
            run: Vec::new(),
            spare: Vec::new(),
            pos: 0,
            scanned: 0,
            end: None,
        }
    }

    fn scan_error(&self, e: ScanError) -> Fc3dError {
        match e {
            ScanError::Io(e) => Fc3dError::Io {
                file: self.file.to_string(),
                message: format!("cannot read: {e}"),
            },
            ScanError::TokenTooLong(head) => Fc3dError::Parse {
                file: self.file.to_string(),
                token_index: self.scanned,
                token: format!("{}...", String::from_utf8_lossy(&head)),
                message: format!(
                    "a token longer than {MAX_TOKEN_BYTES} bytes: not a number of the format \
                     (is the input a text file?)"
                ),
            },
            ScanError::GapTooLong => Fc3dError::Parse {
                file: self.file.to_string(),
                token_index: self.scanned,
                token: "<whitespace>".to_string(),
                message: format!(
                    "more than {MAX_GAP_BYTES} bytes of whitespace: the input does not go on \
                     with tokens"
                ),
            },
        }
    }

    fn token(&mut self, text: &str, line: usize, start: u64) {
        let mut owned = self.spare.pop().unwrap_or_default();
        owned.clear();
        owned.push_str(text);
        self.ahead.push_back(Token {
            index: self.scanned,
            text: owned,
            line,
            start,
        });
        self.scanned += 1;
    }

    /// Scans until a token is ahead; false at the end of the input.
    fn scan(&mut self) -> Result<bool, Fc3dError> {
        while self.ahead.is_empty() {
            if self.end.is_some() {
                return Ok(false);
            }
            let found = self.bytes.skip_space().map_err(|e| self.scan_error(e))?;
            if !found {
                self.end = Some(self.scanned);
                return Ok(false);
            }
            let (line, start) = (self.bytes.line, self.bytes.offset());
            let mut run = std::mem::take(&mut self.run);
            let read = self.bytes.read_run(&mut run);
            if let Err(e) = read {
                self.run = run;
                return Err(self.scan_error(e));
            }
            match std::str::from_utf8(&run) {
                Ok(text) if text.is_ascii() => self.token(text, line, start),
                _ => self.split_run(&run, line, start),
            }
            self.run = run;
        }
        Ok(true)
    }

    /// A run that is not ASCII: decoded with U+FFFD for invalid bytes (as
    /// `String::from_utf8_lossy` does; ASCII bytes end every invalid sequence, so decoding run by
    /// run gives the same text as decoding the whole input) and split on Unicode whitespace.
    fn split_run(&mut self, run: &[u8], line: usize, start: u64) {
        let mut decoded = String::new();
        // (offset in `decoded`, offset in `run`) where each piece starts.
        let mut pieces: Vec<(usize, usize)> = Vec::new();
        let mut raw = 0;
        for chunk in run.utf8_chunks() {
            pieces.push((decoded.len(), raw));
            decoded.push_str(chunk.valid());
            raw += chunk.valid().len();
            if !chunk.invalid().is_empty() {
                pieces.push((decoded.len(), raw));
                decoded.push(char::REPLACEMENT_CHARACTER);
                raw += chunk.invalid().len();
            }
        }
        let raw_offset = |d: usize| {
            let (pd, pr) = pieces
                .iter()
                .rev()
                .find(|&&(pd, _)| pd <= d)
                .copied()
                .unwrap_or((0, 0));
            pr + (d - pd)
        };
        let mut token_start = None;
        for (d, c) in decoded.char_indices().chain([(decoded.len(), ' ')]) {
            match (c.is_whitespace(), token_start) {
                (true, Some(s)) => {
                    self.token(&decoded[s..d], line, start + raw_offset(s) as u64);
                    token_start = None;
                }
                (false, None) => token_start = Some(d),
                _ => {}
            }
        }
    }

    /// Keeps the text of token `index`, the token just read, for a later message about it.
    pub(super) fn remember(&mut self, index: usize) {
        if let Some(t) = self.current.as_ref().filter(|t| t.index == index) {
            self.kept.push((index, t.text.clone()));
        }
    }

    /// Offset in bytes of the first token not read, or the length of the input when none is
    /// left: the length of what was read and the whitespace after it. Looks ahead at most to the
    /// first byte of the next token (for a stream; the whole next run when it is not ASCII); a
    /// stream that fails or ends in endless whitespace counts as ending where scanning stopped.
    pub(super) fn consumed_bytes(&mut self) -> u64 {
        if let Some(t) = self.ahead.front() {
            return t.start;
        }
        if let Ok(true) = self.bytes.skip_space() {
            // A run that is not ASCII may start with Unicode whitespace (or be nothing else):
            // scan it to find where its first token starts.
            if !self.bytes.peek_byte().is_some_and(|b| b.is_ascii()) {
                if let Ok(true) = self.scan() {
                    return self.ahead.front().map_or(0, |t| t.start);
                }
            }
        }
        self.bytes.offset()
    }

    /// A parse error at token `index`: the token just read, one looked ahead at, one kept with
    /// [`Reader::remember`], or the end of the input.
    pub(super) fn error_at(&self, index: usize, message: impl Into<String>) -> Fc3dError {
        let token = if self.end.is_some_and(|end| index >= end) {
            END_OF_FILE
        } else {
            self.current
                .iter()
                .chain(self.ahead.iter())
                .find(|t| t.index == index)
                .map(|t| t.text.as_str())
                .or_else(|| {
                    self.kept
                        .iter()
                        .find(|(i, _)| *i == index)
                        .map(|(_, t)| t.as_str())
                })
                .unwrap_or("<not kept>")
        };
        self.error_with_token(index, token, message)
    }

    /// A parse error at token `index` whose text the caller knows.
    pub(super) fn error_with_token(
        &self,
        index: usize,
        token: &str,
        message: impl Into<String>,
    ) -> Fc3dError {
        Fc3dError::Parse {
            file: self.file.to_string(),
            token_index: index,
            token: token.to_string(),
            message: message.into(),
        }
    }

    /// The next token, not read yet (None at the end of the input).
    pub(super) fn peek(&mut self) -> Result<Option<&str>, Fc3dError> {
        self.scan()?;
        Ok(self.ahead.front().map(|t| t.text.as_str()))
    }

    /// Reads the next token and returns its index; its text is [`Reader::text`].
    pub(super) fn next(&mut self, what: &str) -> Result<usize, Fc3dError> {
        if !self.scan()? {
            return Err(self.error_at(self.pos, format!("the file ends where {what} is expected")));
        }
        let token = self.ahead.pop_front().expect("scanned");
        if let Some(old) = self.current.replace(token) {
            self.spare.push(old.text);
        }
        self.pos += 1;
        Ok(self.pos - 1)
    }

    /// The text of the token last read.
    pub(super) fn text(&self) -> &str {
        self.current.as_ref().map_or("", |t| t.text.as_str())
    }

    /// An upper bound on the tokens left, when the input's size is known: `k` tokens take at
    /// least `2k - 1` bytes.
    fn remaining_bound(&self) -> Option<usize> {
        let size = self.size?;
        let bytes_left = size.saturating_sub(self.bytes.offset());
        let bound = usize::try_from(bytes_left.saturating_add(1) / 2).unwrap_or(usize::MAX);
        Some(bound.saturating_add(self.ahead.len()))
    }

    /// Fails unless `needed` more tokens can be left: called with the token count a declared size
    /// implies, before reading and allocating for it. When the input's size shows it cannot hold
    /// them, the rest is counted (bounded by that size, nothing kept) to name its end;
    /// otherwise (a stream of unknown length, or a size that fits) nothing is read here, and the
    /// values are read and stored as they arrive.
    pub(super) fn ensure_remaining(&mut self, needed: usize, what: &str) -> Result<(), Fc3dError> {
        match self.remaining_bound() {
            Some(bound) if needed > bound => {}
            _ => return Ok(()),
        }
        let mut left = self.ahead.len();
        self.ahead.clear();
        while self.scan()? {
            left += self.ahead.len();
            self.ahead.clear();
        }
        if needed > left {
            return Err(self.error_at(
                self.pos + left,
                format!("{what} need {needed} more tokens but the file ends after {left}"),
            ));
        }
        Err(Fc3dError::Io {
            file: self.file.to_string(),
            message: "the file grew while it was read".into(),
        })
    }

    /// An empty vector for `declared` items of `tokens_per_item` tokens each, with a capacity
    /// that the rest of the input can fill (at most [`UNBOUNDED_START_CAPACITY`] when its size
    /// is unknown), allocated fallibly. Fill it with [`try_push`].
    pub(super) fn vec_for<T>(
        &self,
        declared: usize,
        tokens_per_item: usize,
        what: &str,
    ) -> Result<Vec<T>, Fc3dError> {
        let mut v = Vec::new();
        reserve(&mut v, self.capacity_for(declared, tokens_per_item), what)?;
        Ok(v)
    }

    /// The capacity [`Reader::vec_for`] gives: `declared`, bounded by what the rest of the
    /// input can hold (at most [`UNBOUNDED_START_CAPACITY`] when its size is unknown).
    pub(super) fn capacity_for(&self, declared: usize, tokens_per_item: usize) -> usize {
        let bound = self
            .remaining_bound()
            .map_or(UNBOUNDED_START_CAPACITY, |b| b / tokens_per_item.max(1));
        declared.min(bound)
    }

    pub(super) fn usize(&mut self, what: &str) -> Result<(usize, usize), Fc3dError> {
        let index = self.next(what)?;
        self.text()
            .parse::<usize>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (a non-negative integer)")))
    }

    pub(super) fn integer(&mut self, what: &str) -> Result<(usize, i64), Fc3dError> {
        let index = self.next(what)?;
        self.text()
            .parse::<i64>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (an integer)")))
    }

    /// A finite real number (NaN and infinities are rejected here, where the token is known).
    pub(super) fn real(&mut self, what: &str) -> Result<(usize, f64), Fc3dError> {
        let index = self.next(what)?;
        match self.text().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((index, v)),
            Ok(_) => Err(self.error_at(index, format!("{what} must be finite"))),
            Err(_) => Err(self.error_at(index, format!("expected {what} (a real number)"))),
        }
    }

    /// `count` finite reals, in an array of the caller's storage.
    pub(super) fn reals<A: ReadArray<f64>>(
        &mut self,
        count: usize,
        what: &str,
    ) -> Result<A, Fc3dError> {
        self.ensure_remaining(count, what)?;
        let mut values = A::with_capacity(self.capacity_for(count, 1), what)?;
        let item = format!("a value of {what}");
        for _ in 0..count {
            let v = self.real(&item)?.1;
            values.push(v, what)?;
        }
        Ok(values)
    }

    /// Reads a token that must be exactly `literal`.
    pub(super) fn literal(&mut self, literal: &str, context: &str) -> Result<usize, Fc3dError> {
        let index = self.next(&format!("'{literal}' ({context})"))?;
        if self.text() != literal {
            return Err(self.error_at(index, format!("expected '{literal}' ({context})")));
        }
        Ok(index)
    }

    /// Skips the tokens that share the line of token `index` (the token just read) and follow
    /// it; a line longer than 1 MiB is an error (a stream that never ends the line).
    pub(super) fn skip_rest_of_line(&mut self, index: usize) -> Result<(), Fc3dError> {
        let Some((line, from)) = self
            .current
            .as_ref()
            .filter(|t| t.index == index)
            .map(|t| (t.line, t.start))
        else {
            return Ok(());
        };
        while self.scan()? {
            let next = self.ahead.front().expect("scanned");
            if next.line != line {
                break;
            }
            if next.start - from > MAX_SKIPPED_LINE_BYTES {
                return Err(self.error_at(
                    next.index,
                    format!("a line longer than {MAX_SKIPPED_LINE_BYTES} bytes"),
                ));
            }
            self.next("")?;
        }
        Ok(())
    }
}

/// `count * per_item` tokens, saturating: an absurd count must fail the remaining-token check,
/// not overflow.
pub(super) fn token_count(count: usize, per_item: usize) -> usize {
    count.saturating_mul(per_item)
}
