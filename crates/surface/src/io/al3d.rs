//! Alicona `.al3d` reader: the files of Alicona InfiniteFocus and MeasureSuite.
//!
//! Layout, as read by Gwyddion's `alicona.c` and SurfaceTopography's `AL3D.py`: the magic
//! `AliconaImaging\0\r\n`, then 52-byte text tags (20-byte key, 30-byte value, both
//! NUL-terminated, and CRLF): `Version`, `TagCount` and `TagCount` more (`Cols`, `Rows`,
//! `PixelSizeXMeter`, `PixelSizeYMeter`, `InvalidPixelValue`, `DepthImageOffset`,
//! `TextureImageOffset`, `NumberOfPlanes`, ...), then a 256-byte comment. The depth image at
//! `DepthImageOffset` holds little-endian f32 heights in metres, row by row, each row padded:
//! to a multiple of 8 columns in M. Baiker's MATLAB `AliconaReader` (2012), to a multiple of
//! 8 bytes in Gwyddion's. The padding is taken from the file itself: the one that makes the
//! depth image end where the texture image (or the file) starts, else 8 columns. NaN or
//! `InvalidPixelValue` marks points that were not measured.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, header_text};
use std::path::Path;

pub(crate) const NAME: &str = "Alicona AL3D";

const MAGIC: &[u8] = b"AliconaImaging\x00\r\n";
const KEY_SIZE: usize = 20;
const VALUE_SIZE: usize = 30;
const TAG_SIZE: usize = KEY_SIZE + VALUE_SIZE + 2;
const COMMENT_SIZE: usize = 256;
/// More tags than any Alicona file holds; a larger count is a corrupt header.
const MAX_TAGS: usize = 10_000;
/// Relative tolerance for matching `InvalidPixelValue`, whose text is rounded (as in
/// SurfaceTopography: f32 resolution).
const INVALID_RELTOL: f64 = 1.5e-7;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The header's key/value tags and its comment.
struct Header {
    tags: Vec<(String, String)>,
    comment: String,
    end: usize,
}

impl Header {
    fn get(&self, key: &str) -> Option<&str> {
        self.tags
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let header = header(&b)?;
    let required = |key: &str| {
        header
            .get(key)
            .ok_or_else(|| b.err(format!("tag '{key}' missing from the header")))
    };
    let integer = |key: &str| -> Result<usize> {
        let text = required(key)?;
        text.parse()
            .map_err(|_| b.err(format!("tag '{key}' = '{text}' is not a whole number")))
    };
    let float = |key: &str| -> Result<f64> {
        let text = required(key)?;
        text.parse()
            .map_err(|_| b.err(format!("tag '{key}' = '{text}' is not a number")))
    };
    let (nx, ny) = b.grid(integer("Cols")? as i64, integer("Rows")? as i64)?;
    let dx = b.spacing(float("PixelSizeXMeter")?, "PixelSizeXMeter")?;
    let dy = b.spacing(float("PixelSizeYMeter")?, "PixelSizeYMeter")?;
    let depth = integer("DepthImageOffset")?;
    if depth == 0 {
        return Err(b.err("DepthImageOffset is 0: the file holds no depth image"));
    }
    if depth < header.end {
        return Err(b.err(format!(
            "DepthImageOffset {depth} points into the header, which ends at {}",
            header.end
        )));
    }
    let texture = match header.get("TextureImageOffset") {
        Some(_) => integer("TextureImageOffset")?,
        None => 0,
    };
    let invalid_value = match header.get("InvalidPixelValue") {
        Some(_) => float("InvalidPixelValue")?,
        None => f64::NAN,
    };

    let depth_end = if texture > depth { texture } else { b.len() };
    let stride = row_stride(nx, ny, depth_end - depth.min(depth_end));
    let values = b.array(depth, stride * ny, 4, "depth image")?;
    if texture > 0 {
        let planes = match header.get("NumberOfPlanes") {
            Some(_) => integer("NumberOfPlanes")?.max(1),
            None => 1,
        };
        if texture < depth + values.len() {
            return Err(b.err(format!(
                "TextureImageOffset {texture} lies inside the depth image ({depth} to {})",
                depth + values.len()
            )));
        }
        b.array(texture, nx * ny, planes, "texture image")?;
    }

    let mut heights = Vec::with_capacity(nx * ny);
    for (iy, row) in values.chunks_exact(4 * stride).enumerate() {
        for (ix, v) in row.chunks_exact(4).take(nx).enumerate() {
            let v = f64::from(f32::from_le_bytes([v[0], v[1], v[2], v[3]]));
            if v.is_infinite() {
                return Err(b.err(format!("infinite height at column {ix}, row {iy}")));
            }
            let marked = (v - invalid_value).abs() <= INVALID_RELTOL * invalid_value.abs();
            heights.push(if marked { f64::NAN } else { v });
        }
    }
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;

    let meta = &mut map.meta;
    let application = header.get("CreatingApplication").unwrap_or("");
    meta.instrument = Some(format!("Alicona {application}").trim().to_string());
    if !header.comment.is_empty() {
        meta.extra.push(("comment".into(), header.comment.clone()));
    }
    for key in [
        "Version",
        "Magnification",
        "WorkingDistance",
        "DepthResMinVal",
    ] {
        if let Some(value) = header.get(key) {
            meta.extra.push((key.into(), value.into()));
        }
    }
    Ok(map)
}

/// Columns stored per row of the depth image: `nx` rounded up to 8 columns, or to 8 bytes (2
/// columns), whichever makes `ny` rows fill exactly `available` bytes; 8 columns otherwise.
fn row_stride(nx: usize, ny: usize, available: usize) -> usize {
    let by_columns = nx.div_ceil(8) * 8;
    let by_bytes = nx.div_ceil(2) * 2;
    [by_columns, by_bytes]
        .into_iter()
        .find(|&s| s.checked_mul(4 * ny) == Some(available))
        .unwrap_or(by_columns)
}

/// Reads and checks the tags and the comment.
fn header(b: &Binary) -> Result<Header> {
    if b.slice(0, MAGIC.len(), "magic")? != MAGIC {
        return Err(b.err("not an AL3D file: magic 'AliconaImaging' missing"));
    }
    let tag = |k: usize| -> Result<(String, String)> {
        let at = MAGIC.len() + k * TAG_SIZE;
        let raw = b.slice(at, TAG_SIZE, &format!("header tag {k}"))?;
        let key = header_text(&raw[..KEY_SIZE]);
        if raw[TAG_SIZE - 2..] != *b"\r\n" || key.is_empty() {
            return Err(b.err(format!(
                "header tag {k} ('{key}') is corrupt: empty key or no CRLF terminator"
            )));
        }
        Ok((key, header_text(&raw[KEY_SIZE..KEY_SIZE + VALUE_SIZE])))
    };
    let version = tag(0)?;
    let count = tag(1)?;
    if version.0 != "Version" || count.0 != "TagCount" {
        return Err(b.err("the header must start with the tags Version and TagCount"));
    }
    let n: usize = count
        .1
        .parse()
        .ok()
        .filter(|&n| n <= MAX_TAGS)
        .ok_or_else(|| {
            b.err(format!(
                "TagCount '{}' is not a plausible number of tags",
                count.1
            ))
        })?;
    let comment_at = MAGIC.len() + (n + 2) * TAG_SIZE;
    let comment = header_text(b.slice(comment_at, COMMENT_SIZE, "comment")?);
    let mut tags = vec![version];
    for k in 0..n {
        tags.push(tag(k + 2)?);
    }
    Ok(Header {
        tags,
        comment,
        end: comment_at + COMMENT_SIZE,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stride_follows_the_space_the_file_gives() {
        assert_eq!(row_stride(200, 3, 200 * 3 * 4), 200);
        assert_eq!(row_stride(5, 3, 8 * 3 * 4), 8);
        assert_eq!(row_stride(5, 3, 6 * 3 * 4), 6);
        assert_eq!(row_stride(5, 3, 1), 8);
    }
}
