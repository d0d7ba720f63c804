//! Digital Surf `.sur` reader: the little-endian files of MountainsMap and of the instruments
//! that write its format, plain (`DIGITAL SURF`) or zlib-compressed (`DSCOMPRESSED`).
//!
//! Layout, as read by Gwyddion's `surffile.c`, SurfaceTopography's `SUR.py` and RosettaSciIO's
//! `digitalsurf`: a 512-byte header (signature, object type, names, point size 16 or 32 bits,
//! z range, grid, spacings as f32 with their unit strings, date, sizes of the comment and
//! private zones, offsets), then the comment zone, the private zone and the points: signed
//! integers row by row, `height = value · dz + z_offset` in the unit of dz. Compressed files
//! hold a u32 stream count, (raw size, compressed size) u32 pairs and the zlib streams instead.
//! When the header's "special points" flag is set, the value `zmin − 2` (where MountainsMap
//! writes them) and the type's minimum + 1 mark points that were not measured.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, MAX_ZLIB_RATIO};
use crate::io::common::unit_scale;
use std::borrow::Cow;
use std::path::Path;

pub(crate) const NAME: &str = "Digital Surf";

const PLAIN: &[u8] = b"DIGITAL SURF";
const COMPRESSED: &[u8] = b"DSCOMPRESSED";
const HEADER_SIZE: usize = 512;
/// Format code of files written with Macintosh (big-endian) byte order.
const FORMAT_MACINTOSH: u16 = 257;
/// Object types: a profile (one line) or a surface.
const TYPE_PROFILE: u16 = 1;
const TYPE_SURFACE: u16 = 2;
/// Most zlib streams a compressed file may hold (RosettaSciIO writes 1 to 8).
const MAX_STREAMS: usize = 64;

/// Acquisition types (header offset 82), from Gwyddion's `surffile.c`.
const ACQUISITION: [&str; 11] = [
    "",
    "contact stylus",
    "scanning optical gauge",
    "thermocouple",
    "",
    "contact stylus with skid",
    "AFM",
    "STM",
    "video",
    "interferometer",
    "structured light projection",
];

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(PLAIN) || bytes.starts_with(COMPRESSED)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let signature = b.slice(0, 12, "signature")?;
    let compressed = signature == COMPRESSED;
    if !compressed && signature != PLAIN {
        return Err(b.err("not a Digital Surf file: signature DIGITAL SURF missing"));
    }
    b.slice(0, HEADER_SIZE, "header")?;
    if b.u16::<Le>(12, "format")? == FORMAT_MACINTOSH {
        return Err(b.err("Macintosh (big-endian) .sur files are not supported"));
    }
    let kind = b.u16::<Le>(18, "object type")?;
    if kind != TYPE_PROFILE && kind != TYPE_SURFACE {
        return Err(b.err(format!(
            "object type {kind} is not a profile (1) or surface (2): series, images and spectra \
             are not read"
        )));
    }
    let special_points = b.i16::<Le>(86, "special points flag")? != 0;
    let point_bits = b.i16::<Le>(98, "point size")?;
    let point_size = match point_bits {
        16 => 2,
        32 => 4,
        other => return Err(b.err(format!("point size {other} bits is not 16 or 32"))),
    };
    let zmin = b.i32::<Le>(100, "zmin")?;
    let nx = b.i32::<Le>(108, "points per line")?;
    let ny = b.i32::<Le>(112, "number of lines")?;
    let total = b.i32::<Le>(116, "total number of points")?;
    let (nx, ny) = b.grid(i64::from(nx), i64::from(ny))?;
    if i64::from(total) != (nx * ny) as i64 {
        return Err(b.err(format!(
            "total number of points {total} is not {nx} × {ny}: the header is inconsistent"
        )));
    }
    let unit = |offset, what| -> Result<f64> {
        let text = b.text(offset, 16, what)?;
        unit_scale(path, NAME, what, &text)
    };
    let dx = f64::from(b.f32::<Le>(120, "x spacing")?) * unit(180, "x spacing")?;
    let dy = f64::from(b.f32::<Le>(124, "y spacing")?) * unit(196, "y spacing")?;
    let dz = f64::from(b.f32::<Le>(128, "z spacing")?) * unit(212, "z spacing")?;
    let dx = b.spacing(dx, "x spacing (m)")?;
    // A profile has no line spacing; any positive value stands in for it.
    let dy = if ny == 1 && !(dy.is_finite() && dy > 0.0) {
        dx
    } else {
        b.spacing(dy, "y spacing (m)")?
    };
    if !(dz.is_finite() && dz != 0.0) {
        return Err(b.err(format!(
            "z spacing {dz} m must be a finite, non-zero number"
        )));
    }
    let z_offset = f64::from(b.f32::<Le>(474, "z offset")?) * unit(212, "z spacing")?;
    if !z_offset.is_finite() {
        return Err(b.err("z offset is not finite"));
    }
    let comment_size = usize::from(b.u16::<Le>(334, "comment size")?);
    let private_size = usize::from(b.u16::<Le>(336, "private zone size")?);
    let comment = b.text(HEADER_SIZE, comment_size, "comment zone")?;
    let data_offset = HEADER_SIZE + comment_size + private_size;
    let points = if compressed {
        Cow::Owned(inflate(&b, data_offset, nx * ny * point_size)?)
    } else {
        Cow::Borrowed(b.array(data_offset, nx * ny, point_size, "points")?)
    };

    let invalid = |v: i32| {
        special_points && (Some(v) == zmin.checked_sub(2) || v == type_min(point_size) + 1)
    };
    let heights = points
        .chunks_exact(point_size)
        .map(|c| {
            let v = match point_size {
                2 => i32::from(i16::from_le_bytes([c[0], c[1]])),
                _ => i32::from_le_bytes([c[0], c[1], c[2], c[3]]),
            };
            if invalid(v) {
                f64::NAN
            } else {
                f64::from(v) * dz + z_offset
            }
        })
        .collect();
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    if kind == TYPE_PROFILE && ny == 1 {
        map = map.into_profile()?;
    }

    let meta = &mut map.meta;
    let inversion = b.u16::<Le>(290, "inversion")?;
    if inversion != 0 {
        meta.warn(format!(
            "the header's inversion flag is {inversion}; heights are read as stored, not inverted"
        ));
    }
    let acquisition = usize::from(b.u16::<Le>(82, "acquisition type")?);
    meta.instrument = ACQUISITION
        .get(acquisition)
        .filter(|s| !s.is_empty())
        .map(|s| (*s).to_string());
    let date: Vec<u16> = (0..6)
        .map(|k| b.u16::<Le>(306 + 2 * k, "date"))
        .collect::<Result<_>>()?;
    if date[5] != 0 {
        meta.date = Some(format!(
            "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}",
            date[5], date[4], date[3], date[2], date[1], date[0]
        ));
    }
    for (key, offset) in [("object", 20), ("operator", 50)] {
        let value = b.text(offset, 30, key)?;
        if !value.is_empty() {
            meta.extra.push((key.into(), value));
        }
    }
    if !comment.is_empty() {
        meta.extra.push(("comment".into(), comment));
    }
    let objects = b.u16::<Le>(14, "number of objects")?;
    if objects > 1 {
        meta.warn(format!(
            "the file holds {objects} objects; only the first is read"
        ));
    }
    Ok(map)
}

/// Smallest value of a signed integer of `size` bytes.
fn type_min(size: usize) -> i32 {
    if size == 2 {
        i32::from(i16::MIN)
    } else {
        i32::MIN
    }
}

/// The points of a compressed file: the zlib streams at `offset`, inflated, which must give
/// exactly `expected` bytes. Sizes are checked before inflating, and inflation stops there.
fn inflate(b: &Binary, offset: usize, expected: usize) -> Result<Vec<u8>> {
    let streams = b.u32::<Le>(offset, "compressed stream count")? as usize;
    if streams == 0 || streams > MAX_STREAMS {
        return Err(b.err(format!(
            "{streams} compressed streams (expected 1 to {MAX_STREAMS})"
        )));
    }
    let mut sizes = Vec::with_capacity(streams);
    let mut raw_total = 0usize;
    for k in 0..streams {
        let raw = b.u32::<Le>(offset + 4 + 8 * k, "stream sizes")? as usize;
        let zipped = b.u32::<Le>(offset + 8 + 8 * k, "stream sizes")? as usize;
        raw_total = raw_total.saturating_add(raw);
        sizes.push((raw, zipped));
    }
    if raw_total != expected {
        return Err(b.err(format!(
            "compressed streams hold {raw_total} bytes, but the grid needs {expected}"
        )));
    }
    let start = offset + 4 + 8 * streams;
    let zipped_total = sizes
        .iter()
        .try_fold(0usize, |acc, &(_, z)| acc.checked_add(z));
    let zipped_total = zipped_total.ok_or_else(|| b.err("compressed stream sizes overflow"))?;
    let input = b.slice(start, zipped_total, "compressed streams")?;
    if expected > zipped_total.saturating_mul(MAX_ZLIB_RATIO) {
        return Err(b.err(format!(
            "{zipped_total} compressed bytes cannot inflate to the {expected} bytes of the grid"
        )));
    }
    let mut out = Vec::with_capacity(expected);
    let mut at = 0;
    for (k, (raw, zipped)) in sizes.into_iter().enumerate() {
        b.inflate(
            &input[at..at + zipped],
            raw,
            &mut out,
            &format!("compressed stream {k}"),
        )?;
        at += zipped;
    }
    Ok(out)
}
