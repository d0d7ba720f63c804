//! Text matrices with a `key=value` header such as
//!
//! ```text
//! h=305 w=75
//! pixel size=3.69862e-007 m
//! data unit=rad
//! height conversion factor (-> m)=2.91818e-008
//! ```
//!
//! followed by `h` lines of `w` whitespace-separated values (the first line is the top row,
//! y = 0). This is the layout of SurfaceTopography's `matrix-4.txt` example, which its `Text.py`
//! reads with the keys `h`, `w`, `pixel size` and `height conversion factor (-> unit)`.
//!
//! Read: `h` rows and `w` columns (both required; the matrix must have exactly that shape),
//! `pixel size` (required: value and length unit, the same spacing along x and y), and the
//! height scale: `height conversion factor (-> unit)` multiplies the stored values into the
//! length unit it names (for data stored in another quantity, such as a phase in `rad`);
//! without it, `data unit` must be a length unit. A header line holds one `key=value` pair, or
//! several when every word of the line is one (`h=305 w=75`). Other keys go to the metadata.

use super::common::{build_map, grid_points, metres_per_unit, parse_number, unit_scale};
use super::text::{looks_like_header_matrix, matrix_rows, numbered_lines, numbers, utf8};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use std::path::Path;

pub(crate) const NAME: &str = "text matrix with h= w= header";

const CONVERSION: &str = "height conversion factor (->";

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    looks_like_header_matrix(bytes)
}

/// The `key=value` pairs of one header line.
fn pairs(line: &str) -> Vec<(&str, &str)> {
    let words: Vec<&str> = line.split_whitespace().collect();
    if words.len() > 1 && words.iter().all(|w| w.contains('=')) {
        words.iter().filter_map(|w| w.split_once('=')).collect()
    } else {
        line.split_once('=')
            .map(|(k, v)| (k.trim(), v.trim()))
            .into_iter()
            .collect()
    }
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let text = utf8(path, NAME, bytes)?;
    let mut lines = numbered_lines(text).peekable();
    let mut header: Vec<(&str, &str)> = Vec::new();
    while let Some((number, line)) = lines.next_if(|(_, l)| numbers(l).is_none()) {
        let found = pairs(line);
        if found.is_empty() {
            return Err(fail(format!(
                "line {number}: '{line}' is neither a key=value header line nor a row of numbers"
            )));
        }
        header.extend(found);
    }
    let get = |key: &str| header.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
    let count = |key: &str| -> Result<u64> {
        let value =
            get(key).ok_or_else(|| fail(format!("the header lacks '{key}=' (the grid size)")))?;
        value
            .parse()
            .map_err(|_| fail(format!("'{key}={value}' is not a number of points")))
    };
    let (ny, nx) = (count("h")?, count("w")?);
    let points = grid_points(path, NAME, nx, ny)?;
    let pixel = get("pixel size").ok_or_else(|| {
        fail("the header lacks 'pixel size=' (value and unit), so the spacing is unknown".into())
    })?;
    let bad_pixel = || {
        fail(format!(
            "'pixel size={pixel}' is not a positive length with a unit"
        ))
    };
    let (value, unit) = pixel
        .split_once(char::is_whitespace)
        .ok_or_else(bad_pixel)?;
    let spacing = parse_number(value)
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(bad_pixel)?
        * unit_scale(path, NAME, "pixel size", unit.trim())?;

    let z_scale = height_scale(path, &header)?;
    let (mut heights, columns) = matrix_rows(path, NAME, lines)?;
    if columns as u64 != nx || heights.len() != points {
        return Err(fail(format!(
            "the header states h={ny} rows of w={nx} values, but the file holds {} rows of \
             {columns}: the file is truncated or its header is wrong",
            heights.len() / columns
        )));
    }
    for h in &mut heights {
        *h *= z_scale;
    }
    let (nx, ny) = (nx as usize, ny as usize);
    let mut map = build_map(path, NAME, heights, (nx, ny), (spacing, spacing))?;
    for (key, value) in &header {
        if !matches!(*key, "h" | "w" | "pixel size") && !key.starts_with(CONVERSION) {
            map.meta.extra.push((key.to_string(), value.to_string()));
        }
    }
    Ok(map)
}

/// Metres per stored value: the conversion factor into the length unit it names, or else the
/// data unit when that is a length.
fn height_scale(path: &Path, header: &[(&str, &str)]) -> Result<f64> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    if let Some((key, value)) = header.iter().find(|(k, _)| k.starts_with(CONVERSION)) {
        let unit = key[CONVERSION.len()..].trim().trim_end_matches(')').trim();
        let factor = parse_number(value)
            .filter(|v| v.is_finite() && *v != 0.0)
            .ok_or_else(|| fail(format!("'{key}={value}' is not a finite, non-zero factor")))?;
        return Ok(factor * unit_scale(path, NAME, "height conversion", unit)?);
    }
    match header.iter().find(|(k, _)| *k == "data unit") {
        Some((_, unit)) if metres_per_unit(unit).is_some() => unit_scale(path, NAME, "data", unit),
        Some((_, unit)) => Err(fail(format!(
            "'data unit={unit}' is not a length and no 'height conversion factor (-> unit)=' \
             line converts it, so the height scale is unknown"
        ))),
        None => Err(fail(
            "the header has neither 'height conversion factor (-> unit)=' nor a length \
             'data unit=', so the height scale is unknown"
                .into(),
        )),
    }
}
