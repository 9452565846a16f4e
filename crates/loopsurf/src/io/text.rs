//! Line and token scanning shared by the text readers (OFF, OBJ, Cart3D).
//!
//! Files are scanned as bytes so that a stray non-UTF-8 byte in a comment
//! does not reject the file; a non-UTF-8 number still fails to parse and is
//! reported with its line.

use std::borrow::Cow;
use std::str::FromStr;

use crate::error::Error;

/// The lines of a file, numbered from 1, without their `\n` / `\r\n` ends.
pub(super) fn lines(data: &[u8]) -> impl Iterator<Item = (usize, Cow<'_, str>)> {
    data.split(|&b| b == b'\n').enumerate().map(|(i, line)| {
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        (i + 1, String::from_utf8_lossy(line))
    })
}

/// The part of a line before a `#` comment, trimmed.
pub(super) fn strip_comment(line: &str) -> &str {
    line.split('#').next().unwrap_or("").trim()
}

/// Parses one token, or says on which line which value was expected.
pub(super) fn parse<T: FromStr>(token: &str, line: usize, what: &str) -> Result<T, Error> {
    token.parse().map_err(|_| Error::Malformed {
        line,
        message: format!("expected {what}, found {token:?}"),
    })
}

/// Parses the next token of an iterator, or says it is missing.
pub(super) fn next<'a, T: FromStr>(
    tokens: &mut impl Iterator<Item = &'a str>,
    line: usize,
    what: &str,
) -> Result<T, Error> {
    match tokens.next() {
        Some(token) => parse(token, line, what),
        None => Err(Error::Malformed {
            line,
            message: format!("expected {what}, found end of line"),
        }),
    }
}

/// Whitespace-separated tokens with the line each starts on, for formats
/// (Cart3D) whose records may wrap across lines.
pub(super) struct Tokens<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
    last_line: usize,
}

impl<'a> Tokens<'a> {
    /// Scans `data`, whose first byte is on line `first_line`.
    pub(super) fn new(data: &'a [u8], first_line: usize) -> Self {
        Tokens {
            data,
            pos: 0,
            line: first_line,
            last_line: first_line.saturating_sub(1),
        }
    }

    /// The line of the last token read (the line before the first one if
    /// none was read yet), for saying where a file ended.
    pub(super) fn last_line(&self) -> usize {
        self.last_line
    }

    /// The next token as text (lossy if not UTF-8) and its line.
    pub(super) fn next_token(&mut self) -> Option<(usize, Cow<'a, str>)> {
        while self.pos < self.data.len() && self.data[self.pos].is_ascii_whitespace() {
            if self.data[self.pos] == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
        if self.pos == self.data.len() {
            return None;
        }
        let start = self.pos;
        self.last_line = self.line;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Some((
            self.line,
            String::from_utf8_lossy(&self.data[start..self.pos]),
        ))
    }
}
