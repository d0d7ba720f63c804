//! TrueMap / GelSight `.tmd` reader: the binary height maps of the TrueMap software (TrueGage,
//! GelSight).
//!
//! Layout, as read by Gwyddion's `rmitmd.c` and SurfaceTopography's `TMD.py`: the 32-byte
//! magic `Binary TrueMap Data File v2.0\r\n\0`, a NUL-terminated Latin-1 comment (Gwyddion reads
//! it to its NUL; every file seen holds `Created by TrueMap v6\r\n`), then little-endian
//! u32 columns and rows, f32 field width and height, f32 x and y offsets, and columns × rows
//! f32 heights, row by row. The format has no unit fields: lengths and heights are in
//! millimetres by definition (both references agree), so that is what the reader applies.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, header_text};
use std::path::Path;

pub(crate) const NAME: &str = "TrueMap TMD";

const MAGIC: &[u8] = b"Binary TrueMap Data File v2.0";
const MAGIC_SIZE: usize = 32;
/// Longest comment read before the header must have started.
const MAX_COMMENT: usize = 4096;
/// Metres per millimetre, the format's unit for lengths and heights.
const MM: f64 = 1e-3;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if !b.slice(0, MAGIC_SIZE, "magic")?.starts_with(MAGIC) {
        return Err(b.err("not a TrueMap file: magic 'Binary TrueMap Data File v2.0' missing"));
    }
    let tail = &bytes[MAGIC_SIZE..];
    let comment_len = tail
        .iter()
        .take(MAX_COMMENT)
        .position(|&c| c == 0)
        .ok_or_else(|| {
            b.err(format!(
                "the comment after the magic has no terminating NUL in its first {MAX_COMMENT} \
                 bytes: the file is truncated or not a TrueMap file"
            ))
        })?;
    let comment = header_text(&tail[..comment_len]);
    let header = MAGIC_SIZE + comment_len + 1;
    let nx = b.u32::<Le>(header, "number of columns")?;
    let ny = b.u32::<Le>(header + 4, "number of rows")?;
    let (nx, ny) = b.grid(i64::from(nx), i64::from(ny))?;
    let width = f64::from(b.f32::<Le>(header + 8, "field width")?) * MM;
    let height = f64::from(b.f32::<Le>(header + 12, "field height")?) * MM;
    let dx = b.spacing(width / nx as f64, "x spacing (m)")?;
    let dy = b.spacing(height / ny as f64, "y spacing (m)")?;
    let data = b.array(header + 24, nx * ny, 4, "heights")?;
    let heights = data
        .chunks_exact(4)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])) * MM)
        .collect();
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.instrument = Some("TrueMap".into());
    if !comment.is_empty() {
        map.meta.extra.push(("comment".into(), comment));
    }
    Ok(map)
}
