//! Lexing shared by the readers: lines, tokens and numbers, with errors that name the line.

use super::{ErrorKind, MeshFileError};
use alloc::string::String;
use alloc::vec::Vec;
use glam::DVec3;

/// Calls `f(line_number, line)` for every line of `src`, without the line break, the
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
    for (i, raw) in src.split(|&b| b == b'\n').enumerate() {
        let mut line = raw.strip_suffix(b"\r").unwrap_or(raw);
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
    let cut = &tok[..tok.len().min(40)];
    MeshFileError::new(
        Some(line),
        ErrorKind::BadNumber {
            expected,
            found: String::from_utf8_lossy(cut).into_owned(),
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
