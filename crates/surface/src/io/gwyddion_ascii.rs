//! Gwyddion's ASCII matrix export ("Text matrix of data values"): optional `#` comment lines,
//! then one line of whitespace-separated values per row. With "Add informational comment
//! header" Gwyddion writes `# Channel: name`, `# Width: 12.34 µm`, `# Height: 5678.9 nm` (the
//! physical size of the whole field) and `# Value units: m`.
//!
//! The matrix itself carries no spacing, so a file without the `# Width:` and `# Height:` lines
//! is an error that says how to re-export it. Width, height and value units may be m, mm, µm
//! (um), nm, pm or Å; values in any other unit are an error. Numbers may use a decimal comma;
//! `nan` marks a point that was not measured.

use super::common::{build_map, parse_number, unit_scale};
use super::text::{looks_like_gwyddion, matrix_rows, numbered_lines, utf8};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use std::path::Path;

pub(crate) const NAME: &str = "Gwyddion ASCII matrix";

/// A text file whose first non-blank line is a `#` comment.
pub(crate) fn sniff(bytes: &[u8]) -> bool {
    looks_like_gwyddion(bytes)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let text = utf8(path, NAME, bytes)?;
    let (mut width, mut height, mut z_unit, mut channel) = (None, None, "m", None);
    let mut lines = numbered_lines(text).peekable();
    while let Some((_, comment)) = lines.next_if(|(_, l)| l.starts_with('#')) {
        let Some((key, value)) = comment[1..].split_once(':') else {
            continue;
        };
        let value = value.trim();
        match key.trim() {
            "Width" => width = Some(length(path, "Width", value)?),
            "Height" => height = Some(length(path, "Height", value)?),
            "Value units" => z_unit = value,
            "Channel" => channel = Some(value),
            _ => {}
        }
    }
    let (mut heights, nx) = matrix_rows(path, NAME, lines)?;
    let (Some(width), Some(height)) = (width, height) else {
        return Err(fail(
            "no '# Width:' and '# Height:' lines state the field size, so the spacing is \
             unknown: export from Gwyddion with \"Add informational comment header\" checked"
                .into(),
        ));
    };
    let z_scale = unit_scale(path, NAME, "value", z_unit)?;
    for h in &mut heights {
        *h *= z_scale;
    }
    let ny = heights.len() / nx;
    let mut map = build_map(
        path,
        NAME,
        heights,
        (nx, ny),
        (width / nx as f64, height / ny as f64),
    )?;
    if let Some(channel) = channel {
        map.meta.extra.push(("channel".into(), channel.to_string()));
    }
    Ok(map)
}

/// A length such as `12.34 µm` in metres.
fn length(path: &Path, key: &str, value: &str) -> Result<f64> {
    let fail = || {
        SurfaceError::format(
            path,
            NAME,
            format!("'# {key}: {value}' is not a positive length with a unit"),
        )
    };
    let (number, unit) = value.split_once(char::is_whitespace).ok_or_else(fail)?;
    let number = parse_number(number)
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(fail)?;
    Ok(number * unit_scale(path, NAME, key, unit.trim())?)
}
