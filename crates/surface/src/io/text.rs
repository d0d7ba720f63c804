//! Helpers shared by the text readers (Gwyddion's ASCII export, the `h= w=` header matrix and
//! `x y z` point lists): decoding, numbered lines, rows of numbers, and the content tests that
//! tell the three layouts apart.
//!
//! The layouts are told apart by their first lines: a `#` comment starts Gwyddion's export,
//! leading `key=value` lines naming `h` and `w` start the header matrix, and lines of exactly three
//! numbers are a point list. A text file that matches none of them is read by extension as a
//! Gwyddion matrix, whose error then says what that layout needs.

use super::common::parse_number;
use crate::error::{Result, SurfaceError};
use std::path::Path;

/// The file as UTF-8 text, or an error naming the file and the layout.
pub(crate) fn utf8<'a>(path: &Path, format: &'static str, bytes: &'a [u8]) -> Result<&'a str> {
    std::str::from_utf8(bytes)
        .map_err(|e| SurfaceError::format(path, format, format!("not UTF-8 text: {e}")))
}

/// Lines with their 1-based numbers, trimmed, blank lines left out.
pub(crate) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty())
}

/// The numbers of one line, or `None` if a token is not a number.
pub(crate) fn numbers(line: &str) -> Option<Vec<f64>> {
    line.split_whitespace().map(parse_number).collect()
}

/// A matrix of numbers, one row per line, every row as long as the first: the values row by
/// row and the row length. Infinite values are errors; `nan` is kept (a point not measured).
pub(crate) fn matrix_rows<'a>(
    path: &Path,
    format: &'static str,
    lines: impl Iterator<Item = (usize, &'a str)>,
) -> Result<(Vec<f64>, usize)> {
    let fail = |m: String| SurfaceError::format(path, format, m);
    let mut values = Vec::new();
    let mut nx = 0;
    for (number, line) in lines {
        let start = values.len();
        for token in line.split_whitespace() {
            let v = parse_number(token)
                .ok_or_else(|| fail(format!("line {number}: '{token}' is not a number")))?;
            if v.is_infinite() {
                return Err(fail(format!("line {number}: infinite value")));
            }
            values.push(v);
        }
        let columns = values.len() - start;
        if start == 0 {
            nx = columns;
        } else if columns != nx {
            return Err(fail(format!(
                "line {number} holds {columns} values, the first data row {nx}: the file is \
                 truncated or not a matrix"
            )));
        }
    }
    if values.is_empty() {
        return Err(fail("the file holds no data rows".into()));
    }
    Ok((values, nx))
}

/// The non-blank lines at the start of a file, as far as it is UTF-8 text (only the first
/// 4 KiB are looked at, so the test is cheap on large binary files).
fn first_lines(bytes: &[u8]) -> impl Iterator<Item = &str> {
    let head = &bytes[..bytes.len().min(4096)];
    let text = match std::str::from_utf8(head) {
        Ok(t) => t,
        Err(e) => std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or_default(),
    };
    text.lines().map(str::trim).filter(|l| !l.is_empty())
}

/// Gwyddion's export: the first non-blank line is a `#` comment.
pub(crate) fn looks_like_gwyddion(bytes: &[u8]) -> bool {
    first_lines(bytes)
        .next()
        .is_some_and(|l| l.starts_with('#'))
}

/// The header matrix: the leading lines are `key=value` pairs among which are `h` and `w`.
pub(crate) fn looks_like_header_matrix(bytes: &[u8]) -> bool {
    let keys: Vec<&str> = first_lines(bytes)
        .take_while(|l| l.contains('='))
        .flat_map(str::split_whitespace)
        .filter_map(|t| t.split_once('=').map(|(k, _)| k))
        .collect();
    keys.contains(&"h") && keys.contains(&"w")
}

/// A point list: the first three non-blank lines (all of them if fewer, but at least two) are
/// three numbers each.
pub(crate) fn looks_like_xyz(bytes: &[u8]) -> bool {
    let lines: Vec<&str> = first_lines(bytes).take(3).collect();
    lines.len() >= 2
        && lines
            .iter()
            .all(|l| numbers(l).is_some_and(|v| v.len() == 3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_are_told_apart_by_their_first_lines() {
        let gwy = b"# Channel: Z\n# Width: 1 um\n1 2\n";
        let hw = b"h=2 w=3\npixel size=1 um\n1 2 3\n4 5 6\n";
        let xyz = b"0 0 1\n0 1 2\n1 0 3\n1 1 4\n";
        let bare = b"1 2 3 4\n5 6 7 8\n";
        for (bytes, expect) in [
            (&gwy[..], [true, false, false]),
            (&hw[..], [false, true, false]),
            (&xyz[..], [false, false, true]),
            (&bare[..], [false, false, false]),
        ] {
            let got = [
                looks_like_gwyddion(bytes),
                looks_like_header_matrix(bytes),
                looks_like_xyz(bytes),
            ];
            assert_eq!(got, expect, "{}", String::from_utf8_lossy(bytes));
        }
        // A binary file is none of them.
        assert!(!looks_like_xyz(&[0xff, 0xfe, 0, 1]));
    }

    #[test]
    fn ragged_rows_are_an_error() {
        let lines = numbered_lines("1 2\n\n3\n");
        let err = matrix_rows(Path::new("r.txt"), "t", lines).unwrap_err();
        assert!(err.to_string().contains("line 3"), "{err}");
        let (values, nx) =
            matrix_rows(Path::new("r.txt"), "t", numbered_lines("1 2\n3 nan\n")).unwrap();
        assert_eq!((values.len(), nx), (4, 2));
        assert!(values[3].is_nan());
    }
}
