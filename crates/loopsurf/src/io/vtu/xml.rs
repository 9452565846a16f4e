//! Just enough XML for `.vtu` files: tags with their attributes, found one
//! after another by byte offset; comments and declarations skipped.

/// A parse error: the byte offset it refers to and what is wrong.
pub(super) type XmlError = (usize, String);

/// One XML tag.
pub(super) struct Tag<'a> {
    pub(super) name: &'a [u8],
    attrs: Vec<(&'a [u8], String)>,
    pub(super) closing: bool,
    pub(super) empty: bool,
    /// Offsets of `<` and just past `>`.
    pub(super) start: usize,
    pub(super) end: usize,
}

impl Tag<'_> {
    pub(super) fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| *n == name.as_bytes())
            .map(|(_, v)| v.as_str())
    }
}

pub(super) fn find(data: &[u8], from: usize, what: &[u8]) -> Option<usize> {
    data.get(from..)?
        .windows(what.len())
        .position(|w| w == what)
        .map(|k| from + k)
}

/// The next tag at or after `pos`, skipping text, the XML declaration,
/// comments and DOCTYPE-like declarations.
pub(super) fn next_tag(data: &[u8], mut pos: usize) -> Result<Option<Tag<'_>>, XmlError> {
    loop {
        let Some(start) = find(data, pos, b"<") else {
            return Ok(None);
        };
        let rest = &data[start..];
        let skip_to = |end: &[u8]| {
            find(data, start, end)
                .map(|k| k + end.len())
                .ok_or_else(|| (start, "an unterminated <? or <! construct".to_string()))
        };
        if rest.starts_with(b"<!--") {
            pos = skip_to(b"-->")?;
            continue;
        }
        if rest.starts_with(b"<?") {
            pos = skip_to(b"?>")?;
            continue;
        }
        if rest.starts_with(b"<!") {
            pos = skip_to(b">")?;
            continue;
        }
        let end = find(data, start, b">").ok_or((start, "a tag without its '>'".to_string()))?;
        let mut inner = &data[start + 1..end];
        let closing = inner.first() == Some(&b'/');
        if closing {
            inner = &inner[1..];
        }
        let empty = inner.last() == Some(&b'/');
        if empty {
            inner = &inner[..inner.len() - 1];
        }
        let name_end = inner
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(inner.len());
        let name = &inner[..name_end];
        if name.is_empty() {
            return Err((start, "a tag without a name".into()));
        }
        let attrs = attributes(&inner[name_end..]).map_err(|m| (start, m))?;
        return Ok(Some(Tag {
            name,
            attrs,
            closing,
            empty,
            start,
            end: end + 1,
        }));
    }
}

/// `name="value"` pairs (single or double quotes), entities decoded.
fn attributes(mut s: &[u8]) -> Result<Vec<(&[u8], String)>, String> {
    let mut out = Vec::new();
    loop {
        while s.first().is_some_and(u8::is_ascii_whitespace) {
            s = &s[1..];
        }
        if s.is_empty() {
            return Ok(out);
        }
        let eq = s
            .iter()
            .position(|&b| b == b'=')
            .ok_or_else(|| format!("attribute {} has no value", lossy(s)))?;
        let name = s[..eq].trim_ascii();
        let after = s[eq + 1..].trim_ascii_start();
        let quote = *after
            .first()
            .filter(|&&q| q == b'"' || q == b'\'')
            .ok_or_else(|| format!("attribute {} is not quoted", lossy(name)))?;
        let close = after[1..]
            .iter()
            .position(|&b| b == quote)
            .ok_or_else(|| format!("attribute {} has no closing quote", lossy(name)))?;
        out.push((name, unescape(&after[1..1 + close])));
        s = &after[close + 2..];
    }
}

pub(super) fn lossy(s: &[u8]) -> String {
    let s = String::from_utf8_lossy(s);
    let short: String = s.chars().take(40).collect();
    format!("{short:?}")
}

fn unescape(s: &[u8]) -> String {
    String::from_utf8_lossy(s)
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}
