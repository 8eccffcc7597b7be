//! The tokens of a `.dat` text and the cursor the readers walk them with.

use crate::error::Fc3dError;

/// The token text reported when the input ends too early.
pub(super) const END_OF_FILE: &str = "<end of file>";

/// A whitespace-separated token and the line it sits on (the CSparse dump is partly line-based).
struct Token<'t> {
    text: &'t str,
    line: usize,
}

/// A cursor over the tokens of the whole input.
pub(super) struct Reader<'t> {
    text: &'t str,
    pub(super) file: &'t str,
    /// What the matrix is called in messages ("W" in a problem file, "M" alone).
    pub(super) name: &'static str,
    tokens: Vec<Token<'t>>,
    pub(super) pos: usize,
}

impl<'t> Reader<'t> {
    pub(super) fn new(text: &'t str, file: &'t str, name: &'static str) -> Self {
        // Splitting lines on '\n' then each line on whitespace yields exactly the tokens of
        // `text.split_whitespace()`, so token indices are those of the whole text.
        let tokens = text
            .split('\n')
            .enumerate()
            .flat_map(|(line, l)| l.split_whitespace().map(move |text| Token { text, line }))
            .collect();
        Reader {
            text,
            file,
            name,
            tokens,
            pos: 0,
        }
    }

    /// The bytes of the text read so far and the whitespace after them: the offset of the first
    /// unread token, or the length of the text when every token has been read.
    pub(super) fn consumed_bytes(&self) -> usize {
        self.tokens.get(self.pos).map_or(self.text.len(), |t| {
            // Tokens are slices of `text`.
            t.text.as_ptr() as usize - self.text.as_ptr() as usize
        })
    }

    /// A parse error at token `index` (the end of the input if there is no such token).
    pub(super) fn error_at(&self, index: usize, message: impl Into<String>) -> Fc3dError {
        let token = self.tokens.get(index).map_or(END_OF_FILE, |t| t.text);
        Fc3dError::Parse {
            file: self.file.to_string(),
            token_index: index,
            token: token.to_string(),
            message: message.into(),
        }
    }

    pub(super) fn peek(&self) -> Option<&'t str> {
        self.tokens.get(self.pos).map(|t| t.text)
    }

    /// The next token and its index.
    pub(super) fn next(&mut self, what: &str) -> Result<(usize, &'t str), Fc3dError> {
        let index = self.pos;
        match self.tokens.get(index) {
            Some(t) => {
                self.pos += 1;
                Ok((index, t.text))
            }
            None => Err(self.error_at(index, format!("the file ends where {what} is expected"))),
        }
    }

    /// Fails unless at least `needed` tokens are left: called with the token count a declared size
    /// implies, before allocating for it.
    pub(super) fn ensure_remaining(&self, needed: usize, what: &str) -> Result<(), Fc3dError> {
        let left = self.tokens.len() - self.pos;
        if needed > left {
            return Err(self.error_at(
                self.tokens.len(),
                format!("{what} need {needed} more tokens but the file ends after {left}"),
            ));
        }
        Ok(())
    }

    pub(super) fn usize(&mut self, what: &str) -> Result<(usize, usize), Fc3dError> {
        let (index, text) = self.next(what)?;
        text.parse::<usize>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (a non-negative integer)")))
    }

    pub(super) fn integer(&mut self, what: &str) -> Result<(usize, i64), Fc3dError> {
        let (index, text) = self.next(what)?;
        text.parse::<i64>()
            .map(|v| (index, v))
            .map_err(|_| self.error_at(index, format!("expected {what} (an integer)")))
    }

    /// A finite real number (NaN and infinities are rejected here, where the token is known).
    pub(super) fn real(&mut self, what: &str) -> Result<(usize, f64), Fc3dError> {
        let (index, text) = self.next(what)?;
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((index, v)),
            Ok(_) => Err(self.error_at(index, format!("{what} must be finite"))),
            Err(_) => Err(self.error_at(index, format!("expected {what} (a real number)"))),
        }
    }

    /// `count` finite reals.
    pub(super) fn reals(&mut self, count: usize, what: &str) -> Result<Vec<f64>, Fc3dError> {
        self.ensure_remaining(count, what)?;
        let mut values = Vec::with_capacity(count);
        for _ in 0..count {
            values.push(self.real(&format!("a value of {what}"))?.1);
        }
        Ok(values)
    }

    /// Consumes a token that must be exactly `literal`.
    pub(super) fn literal(&mut self, literal: &str, context: &str) -> Result<usize, Fc3dError> {
        let (index, text) = self.next(&format!("'{literal}' ({context})"))?;
        if text != literal {
            return Err(self.error_at(index, format!("expected '{literal}' ({context})")));
        }
        Ok(index)
    }

    /// Skips the tokens that share the line of token `index` and follow the cursor.
    pub(super) fn skip_rest_of_line(&mut self, index: usize) {
        if let Some(line) = self.tokens.get(index).map(|t| t.line) {
            while self.tokens.get(self.pos).is_some_and(|t| t.line == line) {
                self.pos += 1;
            }
        }
    }
}

/// `count * per_item` tokens, saturating: an absurd count must fail the remaining-token check,
/// not overflow.
pub(super) fn token_count(count: usize, per_item: usize) -> usize {
    count.saturating_mul(per_item)
}
