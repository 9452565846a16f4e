//! The reader's cursor over a `.msh` file: whitespace-separated text tokens
//! with their line, or little-endian binary items with their byte offset,
//! and errors that name the place. The sections are read in `sections`.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;

use super::{Kind, MshPhysicalName};
use crate::error::{Error, Result};

/// A node as read, before tags become indices.
pub(super) struct RawNode {
    pub(super) tag: u64,
    pub(super) xyz: DVec3,
    pub(super) place: usize,
}

/// An element as read, before node tags become indices.
pub(super) struct RawElement {
    pub(super) tag: u64,
    pub(super) kind: Kind,
    /// (dim, entity tag) for MSH 4.1, (-1, elementary tag) for 2.2.
    pub(super) entity: (i32, i32),
    /// MSH 2.2's physical tag; MSH 4.1 looks it up in `$Entities`.
    pub(super) physical: i32,
    /// Range in `Parser::element_nodes`.
    pub(super) first: usize,
    pub(super) count: usize,
    pub(super) place: usize,
}

/// A `$NodeData` section as read.
pub(super) struct RawNodeData {
    pub(super) name: String,
    pub(super) time: f64,
    pub(super) time_step: i64,
    pub(super) components: usize,
    /// (node tag, place) per entry.
    pub(super) tags: Vec<(u64, usize)>,
    pub(super) values: Vec<f64>,
}

/// The MSH format families we read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Version {
    V2,
    V41,
}

/// A cursor over the file: whitespace-separated text tokens with their
/// line, or little-endian binary items with their offset.
pub(super) struct Parser<'a> {
    data: &'a [u8],
    path: &'a Path,
    pos: usize,
    /// The line `pos` is on (meaningful before binary data).
    line: usize,
    /// Where the last token or item started: its line and byte offset.
    item_line: usize,
    item_pos: usize,
    /// The file is binary: places are byte offsets, not lines.
    pub(super) binary: bool,
    /// Currently inside a binary payload.
    pub(super) in_binary: bool,
    pub(super) version: Version,
    /// The section being read and what in it, for messages.
    pub(super) section: &'static str,
    pub(super) context: String,

    pub(super) version_text: String,
    pub(super) physical_names: Vec<MshPhysicalName>,
    /// (dim, entity tag) → first physical tag.
    pub(super) entity_physical: HashMap<(i32, i32), i32>,
    pub(super) nodes: Vec<RawNode>,
    pub(super) elements: Vec<RawElement>,
    pub(super) element_nodes: Vec<u64>,
    pub(super) skipped: usize,
    pub(super) node_data: Vec<RawNodeData>,
}

/// Up to 40 characters of a token, for messages.
pub(super) fn shown(token: &[u8]) -> String {
    let s = String::from_utf8_lossy(token);
    if s.chars().count() > 40 {
        format!("{:?}...", s.chars().take(40).collect::<String>())
    } else {
        format!("{s:?}")
    }
}

impl<'a> Parser<'a> {
    pub(super) fn new(data: &'a [u8], path: &'a Path) -> Self {
        Parser {
            data,
            path,
            pos: 0,
            line: 1,
            item_line: 1,
            item_pos: 0,
            binary: false,
            in_binary: false,
            version: Version::V41,
            section: "the file",
            context: String::new(),
            version_text: String::new(),
            physical_names: Vec::new(),
            entity_physical: HashMap::new(),
            nodes: Vec::new(),
            elements: Vec::new(),
            element_nodes: Vec::new(),
            skipped: 0,
            node_data: Vec::new(),
        }
    }

    // ---- places and errors

    /// The place of the last item: a line (text files) or byte offset.
    pub(super) fn place(&self) -> usize {
        if self.binary {
            self.item_pos
        } else {
            self.item_line
        }
    }

    /// An error at a place [`Parser::place`] gave.
    pub(super) fn error_at(&self, place: usize, message: String) -> Error {
        if self.binary {
            Error::InvalidArgument(format!("byte {place}: {message}")).in_file(self.path, None)
        } else {
            Error::Malformed {
                line: place,
                message,
            }
            .in_file(self.path, Some(place))
        }
    }

    /// An error about the last item read, naming the section.
    pub(super) fn bad(&self, message: impl std::fmt::Display) -> Error {
        let context = if self.context.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.context)
        };
        self.error_at(
            self.place(),
            format!("{}{context}: {message}", self.section),
        )
    }

    /// The file ends before `what`.
    pub(super) fn truncated(&self, what: &str) -> Error {
        let context = if self.context.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.context)
        };
        if self.binary {
            Error::Truncated {
                message: format!(
                    "{}{context}: the file ends at byte {} before {what}",
                    self.section,
                    self.data.len()
                ),
            }
            .in_file(self.path, None)
        } else {
            Error::Truncated {
                message: format!("{}{context}: the file ends before {what}", self.section),
            }
            // The last line with data on it.
            .in_file(self.path, Some(self.item_line))
        }
    }

    /// Bytes left: what bounds any announced count.
    pub(super) fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    // ---- text

    fn skip_whitespace(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    pub(super) fn token(&mut self) -> Option<&'a [u8]> {
        self.skip_whitespace();
        if self.pos == self.data.len() {
            return None;
        }
        let start = self.pos;
        (self.item_line, self.item_pos) = (self.line, start);
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        Some(&self.data[start..self.pos])
    }

    /// The next text token parsed as a `T`.
    pub(super) fn text<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let token = self.token().ok_or_else(|| self.truncated(what))?;
        std::str::from_utf8(token)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| self.bad(format!("expected {what}, found {}", shown(token))))
    }

    /// The rest of the current line (without its end), consuming the end.
    pub(super) fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        let end = self.data[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(self.data.len(), |k| start + k);
        self.pos = (end + 1).min(self.data.len());
        if end < self.data.len() {
            self.line += 1;
        }
        let line = &self.data[start..end];
        line.strip_suffix(b"\r").unwrap_or(line)
    }

    /// Ends a text line before binary data: only blanks may remain on it.
    pub(super) fn end_line(&mut self) -> Result<()> {
        let rest = self.rest_of_line();
        if rest.iter().all(u8::is_ascii_whitespace) {
            Ok(())
        } else {
            Err(self.bad(format!("unexpected {} before binary data", shown(rest))))
        }
    }

    /// A quoted string tag on its own line (quotes optional).
    pub(super) fn string_line(&mut self, what: &str) -> Result<String> {
        self.skip_whitespace();
        if self.pos == self.data.len() {
            return Err(self.truncated(what));
        }
        (self.item_line, self.item_pos) = (self.line, self.pos);
        let line = String::from_utf8_lossy(self.rest_of_line())
            .trim()
            .to_string();
        let unquoted = line
            .strip_prefix('"')
            .and_then(|s| s.strip_suffix('"'))
            .unwrap_or(&line);
        Ok(unquoted.to_string())
    }

    /// Expects `$End<name>` next.
    pub(super) fn expect_end(&mut self, name: &str) -> Result<()> {
        let want = format!("$End{name}");
        match self.token() {
            Some(t) if t == want.as_bytes() => Ok(()),
            Some(t) if self.pos == self.data.len() && want.as_bytes().starts_with(t) => {
                Err(self.truncated(&want))
            }
            Some(t) => Err(self.bad(format!(
                "expected {want}, found {} (more data than announced?)",
                shown(t)
            ))),
            None => Err(self.truncated(&want)),
        }
    }

    /// Skips a section we do not use, up to its `$End` line.
    pub(super) fn skip_section(&mut self, name: &[u8]) -> Result<()> {
        let mut end = b"$End".to_vec();
        end.extend_from_slice(name);
        let found = self.data[self.pos..]
            .windows(end.len())
            .position(|w| w == end.as_slice());
        let Some(k) = found else {
            return Err(self.truncated(&format!("${}", String::from_utf8_lossy(&end[1..]))));
        };
        let stop = self.pos + k + end.len();
        self.line += self.data[self.pos..stop]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = stop;
        Ok(())
    }

    // ---- binary

    pub(super) fn bytes<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        self.item_pos = self.pos;
        let Some(b) = self.data.get(self.pos..self.pos + N) else {
            return Err(self.truncated(what));
        };
        let mut a = [0; N];
        a.copy_from_slice(b);
        self.pos += N;
        Ok(a)
    }

    // ---- items, text or binary as the section is

    pub(super) fn size(&mut self, what: &str) -> Result<u64> {
        if self.in_binary {
            self.bytes::<8>(what).map(u64::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    pub(super) fn int(&mut self, what: &str) -> Result<i32> {
        if self.in_binary {
            self.bytes::<4>(what).map(i32::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    pub(super) fn real(&mut self, what: &str) -> Result<f64> {
        if self.in_binary {
            self.bytes::<8>(what).map(f64::from_le_bytes)
        } else {
            self.text(what)
        }
    }

    /// A count or index as usize, refusing what does not fit.
    pub(super) fn count(&mut self, what: &str) -> Result<usize> {
        let n = self.size(what)?;
        usize::try_from(n).map_err(|_| self.bad(format!("{what} {n} is too large")))
    }

    /// An MSH 2.2 tag or count: an int in binary files, text otherwise;
    /// negative ones are refused.
    pub(super) fn int_count(&mut self, what: &str) -> Result<usize> {
        let n: i64 = if self.in_binary {
            self.int(what)? as i64
        } else {
            self.text(what)?
        };
        usize::try_from(n).map_err(|_| self.bad(format!("{what} {n} is negative")))
    }

    /// Starts the payload of a section that is binary in binary files.
    pub(super) fn begin_payload(&mut self) -> Result<()> {
        if self.binary {
            self.end_line()?;
            self.in_binary = true;
        }
        Ok(())
    }

    pub(super) fn end_payload(&mut self, name: &str) -> Result<()> {
        self.in_binary = false;
        self.context.clear();
        self.expect_end(name)
    }
}
