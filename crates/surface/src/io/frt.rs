//! FRT MicroProf `.frt` reader: the binary files of FRT (Fries Research & Technology) MicroProf
//! optical profilometers.
//!
//! Layout, as read by Gwyddion's `microprof.c` and SurfaceTopography's `FRT.py`: the magic
//! `FRTM_GLIDERV` and a version, `1.00` (block sizes u32) or `1.01` (u64), a u16 block count,
//! then that many blocks of a u16 type, the size and the content, all little-endian. Blocks
//! read:
//! - `0x0066`: columns, rows, bits per point (16: unsigned counts, 32: signed counts);
//! - `0x0067`: width and height of the field in metres (f64);
//! - `0x006c`: the measuring range (u32) and the metres per count (f64);
//! - `0x0070`: the smallest and largest valid count (u32), when present;
//! - `0x000b`: the counts of the topography, row by row, the first stored row the bottom line
//!   of the image (Gwyddion and SurfaceTopography both flip it to the top; so does this
//!   reader); when absent, the first height-like image (topography, thickness, sample
//!   thickness, AFM) of the multi-image block `0x007d` (four u16 buffer ids, then per image a
//!   u32 type, columns, rows and bits per point, and its counts);
//! - `0x0072`: start of the measurement (Unix time), `0x008e`: the sensor's serial number,
//!   `0x0065`: the description.
//!
//! Non-measured points: the count 1, which both references mask, and any count outside the
//! valid range of block `0x0070`. SurfaceTopography 1.27 masks only the 1; Gwyddion notes that
//! it does not use the valid range yet. The images of block `0x007d` other than the one read
//! are listed in the metadata under `channel`.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, header_text, unix_time_iso};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "FRT MicroProf";

const MAGIC: &[u8] = b"FRTM_GLIDERV";
/// The count that marks a point that was not measured.
const UNDEFINED: i64 = 1;
/// Image types of block 0x007d (bit flags, after the mask) that hold heights.
const TYPE_MASK: u32 = 0xffdf;
const HEIGHT_TYPES: u32 = 0x0004 | 0x0080 | 0x0800 | 0x1000;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// One image: its type flags, grid, bits per point and counts.
struct Image<'a> {
    kind: u32,
    nx: u32,
    ny: u32,
    bits: u32,
    data: &'a [u8],
}

/// Name of an image type of block 0x007d, as Gwyddion's `microprof.c` names them.
fn type_name(kind: u32) -> String {
    let names = [
        (0x0001, "Piezo"),
        (0x0002, "Intensity"),
        (0x0004, "Topography"),
        (0x0008, "Real part"),
        (0x0010, "Imaginary part"),
        (0x0040, "Camera"),
        (0x0080, "Thickness"),
        (0x0100, "DIB from file"),
        (0x0200, "Absolute value"),
        (0x0400, "Phase"),
        (0x0800, "Sample thickness"),
        (0x1000, "AFM"),
        (0x2000, "Quality"),
    ];
    let kind = kind & TYPE_MASK;
    names
        .iter()
        .find(|(k, _)| *k == kind)
        .map_or_else(|| format!("type 0x{kind:04x}"), |(_, n)| (*n).to_string())
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if b.slice(0, MAGIC.len(), "magic")? != MAGIC {
        return Err(b.err("not an FRT file: magic FRTM_GLIDERV missing"));
    }
    let version = b.text(12, 4, "version")?;
    let size_bytes = match version.as_str() {
        "1.00" => 4,
        "1.01" => 8,
        other => return Err(b.err(format!("version '{other}' is not 1.00 or 1.01"))),
    };
    let count = b.u16::<Le>(16, "block count")?;
    let mut blocks = Vec::new();
    let mut at = 18;
    for k in 0..count {
        let what = format!("block {k} header");
        let kind = b.u16::<Le>(at, &what)?;
        let size = if size_bytes == 4 {
            u64::from(b.u32::<Le>(at + 2, &what)?)
        } else {
            Le::read_u64(b.slice(at + 2, 8, &what)?)
        };
        let start = at + 2 + size_bytes;
        let size = usize::try_from(size)
            .ok()
            .filter(|&s| s <= b.len())
            .ok_or_else(|| {
                b.err(format!(
                    "block 0x{kind:04x} at offset {at} claims {size} bytes, more than the file"
                ))
            })?;
        blocks.push((kind, b.slice(start, size, &format!("block 0x{kind:04x}"))?));
        at = start + size;
    }
    let block = |kind: u16, min: usize| -> Result<Option<&[u8]>> {
        match blocks.iter().find(|(k, _)| *k == kind) {
            None => Ok(None),
            Some((_, data)) if data.len() < min => Err(b.err(format!(
                "block 0x{kind:04x} holds {} bytes, fewer than its {min} fields need",
                data.len()
            ))),
            Some((_, data)) => Ok(Some(data)),
        }
    };
    let required = |kind: u16, min: usize, what: &str| {
        block(kind, min)?.ok_or_else(|| b.err(format!("block 0x{kind:04x} ({what}) missing")))
    };
    // Blocks are checked above to be long enough for the fields read from them.
    let u32_at = |d: &[u8], o: usize| Le::read_u32(&d[o..]);
    let f64_at = |d: &[u8], o: usize| Le::read_f64(&d[o..]);

    let range = required(0x0067, 16, "field size")?;
    let zscale = f64_at(required(0x006c, 12, "height scale")?, 4);
    if !(zscale.is_finite() && zscale != 0.0) {
        return Err(b.err(format!(
            "metres per count {zscale} must be finite and non-zero"
        )));
    }
    let (mut image, others) = if let Some(data) = block(0x000b, 0)? {
        let grid = required(0x0066, 12, "grid")?;
        let image = Image {
            kind: 0x0004,
            nx: u32_at(grid, 0),
            ny: u32_at(grid, 4),
            bits: u32_at(grid, 8),
            data,
        };
        (image, multi_images(&b, block(0x007d, 0)?)?)
    } else {
        let mut images = multi_images(&b, block(0x007d, 0)?)?;
        let first = images
            .iter()
            .position(|i| i.kind & TYPE_MASK & HEIGHT_TYPES != 0)
            .ok_or_else(|| b.err("no topography: neither block 0x000b nor a height image"))?;
        (images.remove(first), images)
    };
    let (nx, ny) = b.grid(i64::from(image.nx), i64::from(image.ny))?;
    let point = match image.bits {
        16 => 2,
        32 => 4,
        other => return Err(b.err(format!("{other} bits per point is not 16 or 32"))),
    };
    let what = "topography counts (within their block)";
    let data = Binary::new(path, NAME, image.data).array(0, nx * ny, point, what)?;
    image.data = data;
    let (first_valid, last_valid) = match block(0x0070, 8)? {
        Some(d) => (i64::from(u32_at(d, 0)), i64::from(u32_at(d, 4))),
        None => (i64::MIN, i64::MAX),
    };
    let mut heights = vec![0.0; nx * ny];
    for (i, c) in image.data.chunks_exact(point).enumerate() {
        let count = match point {
            2 => i64::from(u16::from_le_bytes([c[0], c[1]])),
            _ => i64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])),
        };
        // The first stored row is the bottom line: it becomes the last row of the map.
        let (row, column) = (ny - 1 - i / nx, i % nx);
        heights[row * nx + column] =
            if count == UNDEFINED || count < first_valid || count > last_valid {
                f64::NAN
            } else {
                count as f64 * zscale
            };
    }
    let dx = b.spacing(f64_at(range, 0).abs() / nx as f64, "x spacing (m)")?;
    let dy = b.spacing(f64_at(range, 8).abs() / ny as f64, "y spacing (m)")?;
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;

    let meta = &mut map.meta;
    meta.instrument = Some("FRT MicroProf".into());
    if let Some(serial) = block(0x008e, 4)? {
        let len = (u32_at(serial, 0) as usize).min(serial.len() - 4);
        let serial = header_text(&serial[4..4 + len]);
        if !serial.is_empty() {
            meta.instrument = Some(format!("FRT MicroProf, sensor {serial}"));
        }
    }
    if let Some(time) = block(0x0072, 4)? {
        let started = u32_at(time, 0);
        if started != 0 && started != u32::MAX {
            meta.date = unix_time_iso(i64::from(started));
        }
    }
    if let Some(text) = block(0x0065, 0)? {
        let text = header_text(text);
        if !text.is_empty() {
            meta.extra.push(("description".into(), text));
        }
    }
    for other in others {
        if !(other.kind & TYPE_MASK == 0x0004 && other.data == data) {
            meta.extra.push(("channel".into(), type_name(other.kind)));
        }
    }
    Ok(map)
}

/// The images of the multi-image block 0x007d (none when the block is absent).
fn multi_images<'a>(b: &Binary, block: Option<&'a [u8]>) -> Result<Vec<Image<'a>>> {
    let Some(block) = block else {
        return Ok(Vec::new());
    };
    let mut images = Vec::new();
    let mut at = 8;
    while at + 16 <= block.len() {
        let field = |o: usize| Le::read_u32(&block[at + o..]);
        let (kind, nx, ny, bits) = (field(0), field(4), field(8), field(12));
        let bytes = u64::from(nx) * u64::from(ny) * u64::from(bits / 8);
        let size = usize::try_from(bytes)
            .ok()
            .filter(|&s| s <= block.len() - at - 16)
            .ok_or_else(|| {
                b.err(format!(
                    "block 0x007d: image {} of {nx} × {ny} points at {bits} bits does not fit in \
                     the block",
                    images.len()
                ))
            })?;
        images.push(Image {
            kind,
            nx,
            ny,
            bits,
            data: &block[at + 16..at + 16 + size],
        });
        at += 16 + size;
    }
    Ok(images)
}
