//! Wyko / Veeco Vision `.opd` reader: the little-endian block files of Wyko and Veeco (Bruker)
//! white-light interferometers.
//!
//! Layout, as read by Gwyddion's `opdfile.c` and SurfaceTopography's `OPD.py`: two bytes
//! `01 00`, then a directory of 24-byte entries (16-byte name, u16 type, u32 size, u16 flags)
//! whose first entry is the directory itself (`Directory`, type 1, flags 0xFFFF). The blocks'
//! contents follow the directory, in the order of the entries. The height data is the first
//! array block (type 3) named `OPD`, `SAMPLE_DATA`, `RAW_DATA`, `RAW DATA` or `Raw`: three u16
//! (nx, ny, element size) then the values column by column, each column from the last row to the
//! first. Element sizes: 1 (unsigned bytes), 2 (signed little-endian int16) or 4 (float32). Float
//! values of 1e10 or more in magnitude (Vision writes 1.7e38) mark points that were not measured,
//! as do 16-bit values of 32766 and 32767 (the two largest; negative values are real heights
//! below the reference, as Gwyddion's `opdfile.c` and SurfaceTopography's `OPD.py` read them). Scalars: `Wavelength` (nm), `Pixel_size`
//! (mm), optional `Mult` (counts per wavelength unit, default 1) and `Aspect` (dy / dx, default 1).

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, header_text};
use std::path::Path;

pub(crate) const NAME: &str = "Wyko OPD";

const MAGIC: &[u8] = b"\x01\x00Directory";
const ENTRY_SIZE: usize = 24;
const NAME_SIZE: usize = 16;

/// Block types of the directory.
const TYPE_DIRECTORY: u16 = 1;
const TYPE_ARRAY: u16 = 3;
const TYPE_TEXT: u16 = 5;
const TYPE_SHORT: u16 = 6;
const TYPE_FLOAT: u16 = 7;
const TYPE_DOUBLE: u16 = 8;
const TYPE_LONG: u16 = 12;
/// A serialised value; those holding a string start with `12 01` and a one-byte length.
const TYPE_VARIANT: u16 = 15;

/// Names of the blocks that hold heights, in the vocabulary of the Vision versions.
const HEIGHT_BLOCKS: [&str; 5] = ["OPD", "SAMPLE_DATA", "RAW_DATA", "RAW DATA", "Raw"];

/// Float values at or above this magnitude mark points that were not measured.
const BAD_FLOAT: f32 = 1e10;
/// Signed 16-bit values at or above this mark points that were not measured.
const BAD_INT16: i16 = 32766;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// One entry of the directory with the position of its content.
struct Block {
    name: String,
    kind: u16,
    offset: usize,
    size: usize,
}

/// Heights in metres: `value · λ / mult`, λ in metres (Gwyddion `opdfile.c`; the same scale
/// SurfaceTopography applies, in its units, as `wavelength / mult · 1e-6` mm).
fn height_per_unit(wavelength_nm: f64, mult: f64) -> f64 {
    wavelength_nm * 1e-9 / mult
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let blocks = directory(&b)?;
    let find = |name: &str| blocks.iter().find(|blk| blk.name == name);
    let scalar = |name: &str| -> Result<Option<f64>> {
        find(name).map(|blk| scalar_value(&b, blk)).transpose()
    };

    let wavelength_nm = scalar("Wavelength")?
        .ok_or_else(|| b.err("no 'Wavelength' block: heights cannot be scaled"))?;
    let pixel_mm = scalar("Pixel_size")?
        .ok_or_else(|| b.err("no 'Pixel_size' block: the lateral scale is unknown"))?;
    let mult = scalar("Mult")?.unwrap_or(1.0);
    let aspect = scalar("Aspect")?.unwrap_or(1.0);
    b.spacing(wavelength_nm, "Wavelength (nm)")?;
    b.spacing(mult, "Mult")?;
    let dx = b.spacing(pixel_mm * 1e-3, "Pixel_size (m)")?;
    let dy = b.spacing(dx * aspect, "Pixel_size × Aspect (m)")?;
    let q = height_per_unit(wavelength_nm, mult);

    let data = blocks
        .iter()
        .find(|blk| blk.kind == TYPE_ARRAY && HEIGHT_BLOCKS.contains(&blk.name.as_str()))
        .ok_or_else(|| b.err("no height array block (OPD, RAW_DATA or Raw) in the directory"))?;
    let what = format!("array block '{}'", data.name);
    let nx = usize::from(b.u16::<Le>(data.offset, &what)?);
    let ny = usize::from(b.u16::<Le>(data.offset + 2, &what)?);
    let elem = usize::from(b.u16::<Le>(data.offset + 4, &what)?);
    let (nx, ny) = b.grid(nx as i64, ny as i64)?;
    if !matches!(elem, 1 | 2 | 4) {
        return Err(b.err(format!(
            "{what}: element size {elem} is not 1, 2 or 4 bytes"
        )));
    }
    // The block's own size bounds its array, as the file's length bounds the block.
    let block = b.slice(data.offset, data.size, &what)?;
    let values = Binary::new(path, NAME, block).array(6, nx * ny, elem, &what)?;

    let mut heights = vec![f64::NAN; nx * ny];
    for (k, v) in values.chunks_exact(elem).enumerate() {
        let (ix, j) = (k / ny, k % ny);
        let at = (ny - 1 - j) * nx + ix;
        heights[at] = match elem {
            4 => {
                let v = f32::from_le_bytes([v[0], v[1], v[2], v[3]]);
                if v.is_nan() {
                    return Err(b.err(format!("{what}: NaN at column {ix}, row {}", ny - 1 - j)));
                }
                if v.abs() >= BAD_FLOAT {
                    f64::NAN
                } else {
                    q * f64::from(v)
                }
            }
            2 => {
                let v = i16::from_le_bytes([v[0], v[1]]);
                if v >= BAD_INT16 {
                    f64::NAN
                } else {
                    q * f64::from(v)
                }
            }
            _ => q * f64::from(v[0]),
        };
    }
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;

    let text = |name: &str| find(name).and_then(|blk| text_value(&b, blk));
    map.meta.date = match (text("Date"), text("Time")) {
        (Some(d), Some(t)) => Some(format!("{d} {t}")),
        (d, t) => d.or(t),
    };
    let meta = &mut map.meta.extra;
    meta.push(("wavelength_nm".into(), wavelength_nm.to_string()));
    if let Some(m) = scalar("Magnification")? {
        meta.push(("magnification".into(), m.to_string()));
    }
    for (key, name) in [
        ("title", "Title"),
        ("data_set", "DataSetName"),
        ("data_kind", "DataKind"),
    ] {
        if let Some(value) = text(name) {
            meta.push((key.into(), value));
        }
    }
    Ok(map)
}

/// The directory's entries with non-empty contents, each located and checked against the file.
fn directory(b: &Binary) -> Result<Vec<Block>> {
    let magic = b.slice(0, MAGIC.len(), "directory")?;
    if magic != MAGIC {
        return Err(b.err("not an OPD file: it does not start with the 'Directory' block"));
    }
    let kind = b.u16::<Le>(2 + NAME_SIZE, "directory entry")?;
    let dir_size = b.u32::<Le>(2 + NAME_SIZE + 2, "directory entry")? as usize;
    if kind != TYPE_DIRECTORY || dir_size < ENTRY_SIZE || !dir_size.is_multiple_of(ENTRY_SIZE) {
        return Err(b.err(format!(
            "directory entry has type {kind} and size {dir_size}: expected type 1 and a multiple \
             of {ENTRY_SIZE} bytes"
        )));
    }
    b.slice(2, dir_size, "directory")?;
    let mut offset = 2 + dir_size;
    let mut blocks = Vec::new();
    for entry in (2 + ENTRY_SIZE..2 + dir_size).step_by(ENTRY_SIZE) {
        let name = header_text(b.slice(entry, NAME_SIZE, "directory entry")?);
        let kind = b.u16::<Le>(entry + NAME_SIZE, "directory entry")?;
        let size = b.u32::<Le>(entry + NAME_SIZE + 2, "directory entry")? as usize;
        if size == 0 {
            continue;
        }
        if kind == TYPE_DIRECTORY {
            return Err(b.err(format!("block '{name}' is a nested directory")));
        }
        b.slice(offset, size, &format!("block '{name}'"))?;
        blocks.push(Block {
            name,
            kind,
            offset,
            size,
        });
        offset += size;
    }
    Ok(blocks)
}

/// A numeric block (short, long, float or double) as f64.
fn scalar_value(b: &Binary, blk: &Block) -> Result<f64> {
    let what = format!("block '{}'", blk.name);
    let (value, size) = match blk.kind {
        TYPE_SHORT => (f64::from(b.i16::<Le>(blk.offset, &what)?), 2),
        TYPE_LONG => (f64::from(b.i32::<Le>(blk.offset, &what)?), 4),
        TYPE_FLOAT => (f64::from(b.f32::<Le>(blk.offset, &what)?), 4),
        TYPE_DOUBLE => (b.f64::<Le>(blk.offset, &what)?, 8),
        other => return Err(b.err(format!("{what} has type {other}, not a number"))),
    };
    if blk.size != size {
        return Err(b.err(format!("{what} holds {} bytes, not {size}", blk.size)));
    }
    Ok(value)
}

/// A text block, or a serialised string (`12 01`, length, bytes); `None` for anything else.
fn text_value(b: &Binary, blk: &Block) -> Option<String> {
    let content = b.slice(blk.offset, blk.size, "text block").ok()?;
    let text = match (blk.kind, content) {
        (TYPE_TEXT, _) => header_text(content),
        (TYPE_VARIANT, [0x12, 0x01, len, rest @ ..]) => header_text(rest.get(..usize::from(*len))?),
        _ => return None,
    };
    (!text.is_empty()).then_some(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A minimal OPD file: directory, Wavelength, Pixel_size and a 2 × 3 float array.
    fn tiny(values: [f32; 6]) -> Vec<u8> {
        tiny_array(4, &values.map(f32::to_le_bytes).concat())
    }

    /// A minimal OPD file whose 2 × 3 array has elements of `elem` bytes, given as `raw` bytes.
    fn tiny_array(elem: u16, raw: &[u8]) -> Vec<u8> {
        let entry = |name: &str, kind: u16, size: u32| {
            let mut e = vec![0u8; NAME_SIZE];
            e[..name.len()].copy_from_slice(name.as_bytes());
            e.extend(kind.to_le_bytes());
            e.extend(size.to_le_bytes());
            e.extend(0u16.to_le_bytes());
            e
        };
        let mut f = vec![1u8, 0];
        f.extend(entry("Directory", 1, 4 * ENTRY_SIZE as u32));
        f[2 + NAME_SIZE + 6..2 + ENTRY_SIZE].copy_from_slice(&0xffffu16.to_le_bytes());
        f.extend(entry("Wavelength", 7, 4));
        f.extend(entry("Pixel_size", 7, 4));
        f.extend(entry("RAW_DATA", 3, 6 + raw.len() as u32));
        f.extend(600.0f32.to_le_bytes());
        f.extend(0.002f32.to_le_bytes());
        for n in [2u16, 3, elem] {
            f.extend(n.to_le_bytes());
        }
        f.extend(raw);
        f
    }

    #[test]
    fn int16_heights_are_signed_and_only_the_two_largest_values_are_invalid() {
        // Two columns from the last row up: (-5, 32766, -32768) and (32767, 100, 32765).
        let raw: Vec<u8> = [-5i16, 32766, -32768, 32767, 100, 32765]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let map = parse(Path::new("t.opd"), &tiny_array(2, &raw)).unwrap();
        let h = |ix, iy| map.get(ix, iy).map(|v| (v / 600e-9).round() as i32);
        assert_eq!(h(0, 2), Some(-5));
        assert_eq!(h(0, 1), None);
        assert_eq!(h(0, 0), Some(-32768));
        assert_eq!(h(1, 2), None);
        assert_eq!(h(1, 1), Some(100));
        assert_eq!(h(1, 0), Some(32765));
        assert_eq!(map.valid_count(), 4);
    }

    #[test]
    fn columns_run_from_the_last_row_and_bad_pixels_are_invalid() {
        let map = parse(Path::new("t.opd"), &tiny([1.0, 2.0, 3.0, 4.0, 1.7e38, 6.0])).unwrap();
        assert_eq!((map.nx(), map.ny()), (2, 3));
        // 0.002 mm stored as f32: exact to its 24-bit mantissa.
        assert!((map.dx() / 2e-6 - 1.0).abs() < 1e-7 && map.dy() == map.dx());
        let h = |ix, iy| map.get(ix, iy).map(|v| v / 600e-9);
        // Column 0 holds 1, 2, 3 from the last row (iy = 2) up to the first.
        assert!((h(0, 2).unwrap() - 1.0).abs() < 1e-6);
        assert!((h(0, 0).unwrap() - 3.0).abs() < 1e-6);
        assert!((h(1, 2).unwrap() - 4.0).abs() < 1e-6);
        assert_eq!(h(1, 1), None);
        assert!((h(1, 0).unwrap() - 6.0).abs() < 1e-6);
    }

    #[test]
    fn nan_and_truncation_are_errors() {
        let p = Path::new("t.opd");
        let e = parse(p, &tiny([1.0, f32::NAN, 3.0, 4.0, 5.0, 6.0]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.opd") && e.contains("NaN"), "{e}");
        let full = tiny([0.0; 6]);
        for len in [0, 10, 30, 100, full.len() - 1] {
            assert!(parse(p, &full[..len]).is_err(), "length {len}");
        }
    }
}
