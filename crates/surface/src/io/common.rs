//! Helpers shared by the format readers: length units to metres, sizes computed with checked
//! arithmetic before any allocation, and the construction of a [`HeightMap`] whose errors name
//! the file.

use crate::error::{Result, SurfaceError};
use crate::heightmap::{HeightMap, MAX_POINTS};
use ndarray::Array2;
use std::path::Path;

/// Metres per unit for the length units a height-map file may state: `m`, `mm`, `µm` (also
/// written `um`, `μm` or `micron`), `nm`, `pm` and `Å` (also `A`, `Angstrom`). `None` for
/// anything else.
pub(crate) fn metres_per_unit(unit: &str) -> Option<f64> {
    Some(match unit.trim() {
        "m" => 1.0,
        "mm" => 1e-3,
        "\u{b5}m" | "\u{3bc}m" | "um" | "micron" | "microns" => 1e-6,
        "nm" => 1e-9,
        "pm" => 1e-12,
        "\u{c5}" | "\u{212b}" | "A" | "Angstrom" | "angstrom" => 1e-10,
        _ => return None,
    })
}

/// [`metres_per_unit`], or an error for `path` naming the unit and what it was the unit of.
pub(crate) fn unit_scale(path: &Path, format: &'static str, what: &str, unit: &str) -> Result<f64> {
    metres_per_unit(unit).ok_or_else(|| {
        SurfaceError::format(
            path,
            format,
            format!("unknown {what} unit '{unit}' (expected a length: m, mm, µm, nm, pm or Å)"),
        )
    })
}

/// Number of points of an `nx × ny` grid, or an error when a dimension is zero or the grid is
/// larger than [`MAX_POINTS`].
pub(crate) fn grid_points(path: &Path, format: &'static str, nx: u64, ny: u64) -> Result<usize> {
    if nx == 0 || ny == 0 {
        return Err(SurfaceError::format(
            path,
            format,
            format!("the header states an empty grid of {nx} × {ny} points"),
        ));
    }
    nx.checked_mul(ny)
        .and_then(|n| usize::try_from(n).ok())
        .filter(|&n| n <= MAX_POINTS)
        .ok_or_else(|| {
            SurfaceError::format(
                path,
                format,
                format!("the header states a grid of {nx} × {ny} points, more than gonio reads"),
            )
        })
}

/// Bytes needed by `points` values of `bytes_per_point` bytes each, checked against the
/// `available` bytes of the file before anything is allocated.
pub(crate) fn data_bytes(
    path: &Path,
    format: &'static str,
    points: usize,
    bytes_per_point: usize,
    available: usize,
) -> Result<usize> {
    let needed = points.checked_mul(bytes_per_point).ok_or_else(|| {
        SurfaceError::format(
            path,
            format,
            format!("{points} points overflow the address space"),
        )
    })?;
    if needed > available {
        return Err(SurfaceError::format(
            path,
            format,
            format!(
                "the header claims {points} points ({needed} bytes of data) but the file holds \
                 only {available} bytes there: the file is truncated or its header is corrupt"
            ),
        ));
    }
    Ok(needed)
}

/// A height map of `ny` rows of `nx` heights in metres (NaN where not measured) whose errors name
/// the file.
pub(crate) fn build_map(
    path: &Path,
    format: &'static str,
    heights: Vec<f64>,
    (nx, ny): (usize, usize),
    (dx, dy): (f64, f64),
) -> Result<HeightMap> {
    let grid = Array2::from_shape_vec((ny, nx), heights)
        .map_err(|e| SurfaceError::format(path, format, format!("grid {nx} × {ny}: {e}")))?;
    HeightMap::with_invalid(grid, dx, dy).map_err(|e| match e {
        SurfaceError::Invalid(message) => SurfaceError::format(path, format, message),
        other => other,
    })
}

/// Lower-case hexadecimal MD5 digest of `bytes`.
pub(crate) fn md5_hex(bytes: &[u8]) -> String {
    use md5::{Digest, Md5};
    Md5::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Parse a decimal number the way text exports write it: with a decimal point, or with a
/// decimal comma when the file was written in a locale that uses one.
pub(crate) fn parse_number(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().or_else(|| {
        token
            .contains(',')
            .then(|| token.replacen(',', ".", 1).parse().ok())?
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_convert_to_metres() {
        assert_eq!(metres_per_unit("m"), Some(1.0));
        assert_eq!(metres_per_unit("mm"), Some(1e-3));
        assert_eq!(metres_per_unit("\u{b5}m"), Some(1e-6));
        assert_eq!(metres_per_unit("um"), Some(1e-6));
        assert_eq!(metres_per_unit(" nm "), Some(1e-9));
        assert_eq!(metres_per_unit("pm"), Some(1e-12));
        assert_eq!(metres_per_unit("\u{c5}"), Some(1e-10));
        assert_eq!(metres_per_unit("V"), None);
        let err = unit_scale(Path::new("f.txt"), "test", "height", "furlong").unwrap_err();
        let text = err.to_string();
        assert!(text.contains("f.txt") && text.contains("furlong"), "{text}");
    }

    #[test]
    fn sizes_are_checked_before_allocating() {
        let p = Path::new("f.bin");
        assert_eq!(grid_points(p, "t", 3, 4).unwrap(), 12);
        assert!(grid_points(p, "t", 0, 4).is_err());
        assert!(grid_points(p, "t", u64::MAX, 2).is_err());
        assert!(grid_points(p, "t", 1 << 20, 1 << 20).is_err());
        assert_eq!(data_bytes(p, "t", 12, 4, 48).unwrap(), 48);
        assert!(data_bytes(p, "t", 12, 4, 47).is_err());
        assert!(data_bytes(p, "t", usize::MAX, 8, usize::MAX).is_err());
    }

    #[test]
    fn numbers_with_decimal_comma() {
        assert_eq!(parse_number("1.5e-3"), Some(1.5e-3));
        assert_eq!(parse_number("1,5"), Some(1.5));
        assert_eq!(parse_number("1,5,2"), None);
        assert_eq!(parse_number("x"), None);
    }

    #[test]
    fn md5_of_known_text() {
        // RFC 1321, appendix A.5.
        assert_eq!(md5_hex(b"abc"), "900150983cd24fb0d6963f7d28e17f72");
    }
}
