//! Lexing shared by the readers: lines, tokens and numbers, with errors that name the line.

use super::{ErrorKind, Format, MeshFileError};
use alloc::string::String;
use alloc::vec::Vec;
use glam::DVec3;

/// The text of a file without its UTF-8 byte-order mark, or an error if the bytes are not
/// text: a UTF-16 or UTF-32 byte-order mark, or a control byte other than tab, line feed,
/// carriage return and form feed (NUL bytes are what UTF-16 without a mark and binary files
/// show first). Bytes from 0x80 up pass, so Latin-1 comments still load.
pub(super) fn text(src: &[u8]) -> Result<&[u8], MeshFileError> {
    if let Some(rest) = src.strip_prefix(b"\xEF\xBB\xBF") {
        return text(rest);
    }
    if src.starts_with(b"\xFF\xFE") || src.starts_with(b"\xFE\xFF") {
        return Err(MeshFileError::new(
            Some(1),
            ErrorKind::NotText { byte: None },
        ));
    }
    let bad = |&b: &u8| (b < 0x20 && !b"\t\n\r\x0C".contains(&b)) || b == 0x7F;
    match src.iter().position(bad) {
        None => Ok(src),
        Some(at) => Err(MeshFileError::new(
            Some(line_at(src, at)),
            ErrorKind::NotText {
                byte: Some(src[at]),
            },
        )),
    }
}

/// The 1-based line of byte `at`, counting line ends as [`lines`] does.
fn line_at(src: &[u8], at: usize) -> usize {
    lines(&src[..at]).count()
}

/// The lines of `src` without their ends: `\n`, `\r\n` or a bare `\r` (old Mac files).
/// As `split`, the text after the last line end is a line, even if empty.
fn lines(src: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut rest = Some(src);
    core::iter::from_fn(move || {
        let s = rest?;
        match s.iter().position(|&b| b == b'\n' || b == b'\r') {
            None => {
                rest = None;
                Some(s)
            }
            Some(i) => {
                let end = if s[i..].starts_with(b"\r\n") { 2 } else { 1 };
                rest = Some(&s[i + end..]);
                Some(&s[..i])
            }
        }
    })
}

/// Calls `f(line_number, line)` for every line of `src` (see [`lines`]), without the
/// comment (from `#`) and with OBJ-style continuations (a trailing `\`) joined; the number
/// is that of the first physical line. Allocates only for continued lines.
pub(super) fn for_each_line<F>(
    src: &[u8],
    continuation: bool,
    mut f: F,
) -> Result<(), MeshFileError>
where
    F: FnMut(usize, &[u8]) -> Result<(), MeshFileError>,
{
    let mut joined: Vec<u8> = Vec::new();
    let mut joined_start = 0;
    for (i, mut line) in lines(src).enumerate() {
        if let Some(h) = line.iter().position(|&b| b == b'#') {
            line = &line[..h];
        }
        let trimmed = trim_end(line);
        if continuation && trimmed.last() == Some(&b'\\') {
            if joined.is_empty() {
                joined_start = i + 1;
            }
            joined.extend_from_slice(&trimmed[..trimmed.len() - 1]);
            joined.push(b' ');
            continue;
        }
        if joined.is_empty() {
            f(i + 1, line)?;
        } else {
            joined.extend_from_slice(line);
            f(joined_start, &joined)?;
            joined.clear();
        }
    }
    if !joined.is_empty() {
        f(joined_start, &joined)?;
    }
    Ok(())
}

fn trim_end(mut s: &[u8]) -> &[u8] {
    while let [rest @ .., last] = s {
        if last.is_ascii_whitespace() {
            s = rest;
        } else {
            break;
        }
    }
    s
}

/// Whitespace-separated tokens of a line.
pub(super) struct Tokens<'a>(pub(super) &'a [u8]);

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a [u8];

    #[inline]
    fn next(&mut self) -> Option<&'a [u8]> {
        let s = self.0;
        let start = s.iter().position(|b| !b.is_ascii_whitespace())?;
        let len = s[start..]
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(s.len() - start);
        self.0 = &s[start + len..];
        Some(&s[start..start + len])
    }
}

pub(super) fn bad_number(line: usize, expected: &'static str, tok: &[u8]) -> MeshFileError {
    MeshFileError::new(
        Some(line),
        ErrorKind::BadNumber {
            expected,
            found: written(tok),
        },
    )
}

/// A token as the file writes it, for a message: at most 40 bytes, then `...`.
pub(super) fn written(tok: &[u8]) -> String {
    let mut s = String::from_utf8_lossy(&tok[..tok.len().min(40)]).into_owned();
    if tok.len() > 40 {
        s.push_str("...");
    }
    s
}

/// A face's index `tok` (value `index`) that is not one of the file's `vertices`.
pub(super) fn out_of_range(
    line: usize,
    index: i64,
    tok: &[u8],
    vertices: usize,
    format: Format,
) -> MeshFileError {
    MeshFileError::new(
        Some(line),
        ErrorKind::IndexOutOfRange {
            index,
            written: written(tok),
            vertices,
            format,
        },
    )
}

pub(super) fn missing_number(line: usize, expected: &'static str) -> MeshFileError {
    MeshFileError::new(Some(line), ErrorKind::MissingNumber { expected })
}

/// A finite coordinate.
#[inline]
pub(super) fn parse_coord(tok: Option<&[u8]>, line: usize) -> Result<f64, MeshFileError> {
    const WHAT: &str = "a vertex coordinate (a finite number)";
    let tok = tok.ok_or_else(|| missing_number(line, WHAT))?;
    core::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|x| x.is_finite())
        .ok_or_else(|| bad_number(line, WHAT, tok))
}

/// Three coordinates from the next tokens (anything after them is left unread).
#[inline]
pub(super) fn parse_position(toks: &mut Tokens<'_>, line: usize) -> Result<DVec3, MeshFileError> {
    let x = parse_coord(toks.next(), line)?;
    let y = parse_coord(toks.next(), line)?;
    let z = parse_coord(toks.next(), line)?;
    Ok(DVec3::new(x, y, z))
}

/// A decimal integer with optional sign; values beyond 10^18 saturate (they are out of
/// range for any index anyway). `None` if `tok` is not an integer.
#[inline]
pub(super) fn parse_int(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first() {
        Some(b'-') => (true, &tok[1..]),
        Some(b'+') => (false, &tok[1..]),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut n: i64 = 0;
    for &b in digits {
        if !b.is_ascii_digit() {
            return None;
        }
        n = n.saturating_mul(10).saturating_add(i64::from(b - b'0'));
    }
    n = n.min(1_000_000_000_000_000_000);
    Some(if neg { -n } else { n })
}
