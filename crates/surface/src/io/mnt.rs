//! Digital Surf MountainsMap document (`.mnt`) reader: the measured surfaces stored in a
//! Mountains document.
//!
//! Layout, as read by SurfaceTopography's `MNT.py`: a compound (OLE2) file (see [`super::cfb`])
//! whose stream `ScopedContents` holds, after its u64 size, a tree of little-endian TLV entries
//! (u16 tag, u64 size, content). The document's objects sit at main (1) → contents (0x2bd) →
//! document (2) → objects (1), each entry there preceded by one more u64 size; an object holds
//! its class (1 → 1: u32), body (2) and GUID (3). A measured surface is class 9012, whose body
//! holds a header (0xffff; title at 4) and the measurement object (1, class 9062): grid
//! (0xffff → 0xffff: header with the channel name at 0xffff → 0xffff → 1; 1 and 2: the x and
//! y axes, each 0xffff → {0xffff scale, 1 point count}; 3: the mask), the heights (1, class 9049)
//! and the height axis (2 → 0xffff scale). A scale holds the step (1, f64) and its unit (2), the
//! display unit (3) and the origin in the display unit (5). Text is the byte 4 and UTF-16LE.
//!
//! Arrays (heights, mask) hold their element count (1) and data (2): the total byte size (u64),
//! then zlib blocks, each with its first element (u64), element count and compressed size (u32).
//! `height = count · step + origin`; counts are 16- or 32-bit signed integers row by row. The
//! mask (class 9056) is an image with a one-point border, 9 marking a measured point.
//!
//! Derived layers are not stored (Mountains recomputes them); the first measured surface whose
//! heights are lengths is read, and the names of the others are listed under `channel`.

use super::cfb::{Compound, SIGNATURE};
use super::common::metres_per_unit;
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, MAX_ZLIB_RATIO};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "MountainsMap document";

const CLASS_SURFACE: u32 = 9012;
const CLASS_MEASUREMENT: u32 = 9062;
const CLASS_HEIGHTS: u32 = 9049;
const CLASS_MASK: u32 = 9056;
const MASK_MEASURED: u8 = 9;
const TEXT_MARKER: u8 = 4;
const HEADER: u16 = 0xffff;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    // A compound file that names the stream ScopedContents (in UTF-16 in its directory).
    let name: Vec<u8> = "ScopedContents"
        .encode_utf16()
        .flat_map(u16::to_le_bytes)
        .collect();
    bytes.starts_with(SIGNATURE) && bytes.windows(name.len()).any(|w| w == name)
}

/// The TLV entries of one level of the tree.
struct Level<'a>(Vec<(u16, &'a [u8])>);

impl<'a> Level<'a> {
    /// The entries of `data`, each preceded by a u64 size when `prefixed`.
    fn of(b: &Binary, data: &'a [u8], prefixed: bool, what: &str) -> Result<Self> {
        let mut entries = Vec::new();
        let mut at = 0;
        let head = if prefixed { 18 } else { 10 };
        while at < data.len() {
            let fail = || b.err(format!("{what}: entry at {at} runs past its parent"));
            let h = data.get(at..at + head).ok_or_else(fail)?;
            let h = &h[head - 10..];
            let size = usize::try_from(Le::read_u64(&h[2..])).map_err(|_| fail())?;
            let start = at + head;
            let content = start
                .checked_add(size)
                .and_then(|end| data.get(start..end))
                .ok_or_else(fail)?;
            entries.push((Le::read_u16(h), content));
            at = start + size;
        }
        Ok(Level(entries))
    }

    fn get(&self, tag: u16) -> Option<&'a [u8]> {
        self.0.iter().find(|(t, _)| *t == tag).map(|(_, c)| *c)
    }

    fn need(&self, b: &Binary, tag: u16, what: &str) -> Result<&'a [u8]> {
        self.get(tag)
            .ok_or_else(|| b.err(format!("{what}: entry 0x{tag:04x} missing")))
    }

    /// The child `tag` as a level of its own.
    fn level(&self, b: &Binary, tag: u16, what: &str) -> Result<Level<'a>> {
        Level::of(b, self.need(b, tag, what)?, false, what)
    }

    fn u32(&self, b: &Binary, tag: u16, what: &str) -> Result<u32> {
        match self.need(b, tag, what)? {
            v if v.len() == 4 => Ok(Le::read_u32(v)),
            v => Err(b.err(format!("{what}: {} bytes, not a u32", v.len()))),
        }
    }

    fn f64(&self, b: &Binary, tag: u16, what: &str) -> Result<f64> {
        match self.need(b, tag, what)? {
            v if v.len() == 8 => Ok(Le::read_f64(v)),
            v => Err(b.err(format!("{what}: {} bytes, not an f64", v.len()))),
        }
    }

    fn text(&self, tag: u16) -> Option<String> {
        let v = self.get(tag)?;
        (v.first() == Some(&TEXT_MARKER) && v.len() % 2 == 1).then(|| {
            let units: Vec<u16> = v[1..].chunks_exact(2).map(Le::read_u16).collect();
            String::from_utf16_lossy(&units)
                .trim_end_matches('\0')
                .to_string()
        })
    }
}

/// Class number and body of a document object.
fn object<'a>(b: &Binary, data: &'a [u8], what: &str) -> Result<(u32, Level<'a>)> {
    let o = Level::of(b, data, false, what)?;
    let class = o.level(b, 1, what)?.u32(b, 1, what)?;
    Ok((
        class,
        Level::of(b, o.get(2).unwrap_or_default(), false, what)?,
    ))
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let stream = Compound::open(&b)?.stream("ScopedContents")?;
    let tree = stream
        .get(8..)
        .ok_or_else(|| b.err("stream ScopedContents is shorter than its size field"))?;
    let what = "document";
    let objects = Level::of(&b, tree, false, what)?
        .level(&b, 1, what)?
        .level(&b, 0x2bd, what)?
        .level(&b, 2, what)?;
    let objects = Level::of(&b, objects.need(&b, 1, what)?, true, "document objects")?;
    let mut map: Option<HeightMap> = None;
    let mut others = Vec::new();
    for (k, &(_, data)) in objects.0.iter().enumerate() {
        let what = format!("object {k}");
        let (class, body) = object(&b, data, &what)?;
        if class != CLASS_SURFACE {
            continue;
        }
        let title = body
            .get(HEADER)
            .and_then(|h| Level::of(&b, h, false, &what).ok().and_then(|h| h.text(4)));
        let (class, inner) = object(&b, body.need(&b, 1, &what)?, &what)?;
        if class != CLASS_MEASUREMENT {
            continue;
        }
        let surface = surface(&b, &inner.level(&b, HEADER, &what)?, &what)?;
        let name = surface
            .name
            .clone()
            .or(title)
            .unwrap_or_else(|| format!("surface {k}"));
        match (surface.map, &map) {
            (Some(m), None) => map = Some(m),
            _ => others.push(name),
        }
    }
    let mut map = map.ok_or_else(|| b.err("the document holds no measured surface of heights"))?;
    for name in others {
        map.meta.extra.push(("channel".into(), name));
    }
    Ok(map)
}

/// A measured surface: its channel name, and its map when its heights are lengths.
struct Surface {
    name: Option<String>,
    map: Option<HeightMap>,
}

fn surface(b: &Binary, m: &Level, what: &str) -> Result<Surface> {
    let grid = m.level(b, HEADER, what)?;
    let name = grid
        .get(HEADER)
        .and_then(|h| Level::of(b, h, false, what).ok())
        .and_then(|h| {
            h.get(HEADER)
                .and_then(|d| Level::of(b, d, false, what).ok())
        })
        .and_then(|d| d.text(1));
    let z = m.level(b, 2, what)?.level(b, HEADER, "height axis")?;
    let z_unit = z.text(2).unwrap_or_default();
    let Some(z_scale) = metres_per_unit(&z_unit) else {
        return Ok(Surface { name, map: None });
    };
    let step = z.f64(b, 1, "height step")? * z_scale;
    let display = z.text(3).unwrap_or_else(|| z_unit.clone());
    let origin = match z.get(5) {
        Some(_) => {
            let scale = metres_per_unit(&display)
                .ok_or_else(|| b.err(format!("height display unit '{display}' is not a length")))?;
            z.f64(b, 5, "height origin")? * scale
        }
        None => 0.0,
    };
    if !(step.is_finite() && step != 0.0 && origin.is_finite()) {
        return Err(b.err(format!(
            "height step {step} m and origin {origin} m must be finite, the step non-zero"
        )));
    }
    let axis = |tag: u16, name: &str| -> Result<(u32, f64)> {
        let a = grid.level(b, tag, name)?.level(b, HEADER, name)?;
        let scale = a.level(b, HEADER, name)?;
        let unit = scale.text(2).unwrap_or_default();
        let metres = metres_per_unit(&unit)
            .ok_or_else(|| b.err(format!("{name} unit '{unit}' is not a length")))?;
        let step = b.spacing(scale.f64(b, 1, name)? * metres, &format!("{name} (m)"))?;
        Ok((a.u32(b, 1, name)?, step))
    };
    let (nx, dx) = axis(1, "x spacing")?;
    let (ny, dy) = axis(2, "y spacing")?;
    let (nx, ny) = b.grid(i64::from(nx), i64::from(ny))?;

    let (class, heights) = object(b, m.need(b, 1, "heights")?, "heights")?;
    if class != CLASS_HEIGHTS {
        return Err(b.err(format!("heights: class {class}, not {CLASS_HEIGHTS}")));
    }
    let (counts, size) = array(b, &heights, nx * ny, &[2, 4], "heights")?;
    let mut values: Vec<f64> = counts
        .chunks_exact(size)
        .map(|c| {
            let count = if size == 2 {
                f64::from(Le::read_i16(c))
            } else {
                f64::from(Le::read_i32(c))
            };
            count * step + origin
        })
        .collect();
    if let Some(mask) = grid.get(3) {
        let (class, body) = object(b, mask, "mask")?;
        if class == CLASS_MASK {
            let (_, image) = object(b, body.need(b, 5, "mask")?, "mask image")?;
            let (image, _) = array(b, &image, (nx + 2) * (ny + 2), &[1], "mask")?;
            for (i, v) in values.iter_mut().enumerate() {
                if image[(i / nx + 1) * (nx + 2) + i % nx + 1] != MASK_MEASURED {
                    *v = f64::NAN;
                }
            }
        }
    }
    let mut map = b.height_map(values, (nx, ny), (dx, dy))?;
    if let Some(name) = &name {
        map.meta.extra.push(("surface".into(), name.clone()));
    }
    Ok(Surface {
        name,
        map: Some(map),
    })
}

/// The inflated data of an array object's body (element count at 1, data at 2), which must
/// hold `count` elements of one of the `sizes`; returns the bytes and the element size.
fn array(
    b: &Binary,
    body: &Level,
    count: usize,
    sizes: &[usize],
    what: &str,
) -> Result<(Vec<u8>, usize)> {
    let stated = body.u32(b, 1, what)? as usize;
    if stated != count {
        return Err(b.err(format!(
            "{what}: {stated} elements, but the grid needs {count}"
        )));
    }
    let data = body.need(b, 2, what)?;
    let total = data
        .get(..8)
        .map(Le::read_u64)
        .ok_or_else(|| b.err(format!("{what}: data shorter than its size field")))?;
    let size = sizes
        .iter()
        .copied()
        .find(|&s| total == (count * s) as u64)
        .ok_or_else(|| {
            b.err(format!(
                "{what}: {total} bytes for {count} elements is not {sizes:?} bytes each"
            ))
        })?;
    if total > (data.len() as u64).saturating_mul(MAX_ZLIB_RATIO as u64) {
        return Err(b.err(format!(
            "{what}: {} compressed bytes cannot inflate to the {total} bytes claimed",
            data.len()
        )));
    }
    let mut blocks = Vec::new();
    let mut at = 8;
    while at < data.len() {
        let head = data
            .get(at..at + 16)
            .ok_or_else(|| b.err(format!("{what}: block header at {at} truncated")))?;
        let first = usize::try_from(Le::read_u64(head)).unwrap_or(usize::MAX);
        let elements = Le::read_u32(&head[8..]) as usize;
        let zipped = Le::read_u32(&head[12..]) as usize;
        let input = data
            .get(at + 16..(at + 16).saturating_add(zipped))
            .ok_or_else(|| b.err(format!("{what}: block at {at} runs past the data")))?;
        if first.saturating_add(elements) > count {
            return Err(b.err(format!(
                "{what}: block of elements {first} to {} lies outside the {count} elements",
                first.saturating_add(elements)
            )));
        }
        blocks.push((first, elements, input));
        at += 16 + zipped;
    }
    blocks.sort_by_key(|&(first, ..)| first);
    let mut out = Vec::with_capacity(count * size);
    for (first, elements, input) in blocks {
        if first * size != out.len() {
            return Err(b.err(format!(
                "{what}: the blocks leave a gap or overlap at element {first}"
            )));
        }
        b.inflate(input, elements * size, &mut out, &format!("{what} block"))?;
    }
    if out.len() != count * size {
        return Err(b.err(format!(
            "{what}: the blocks hold {} bytes, not {}",
            out.len(),
            count * size
        )));
    }
    Ok((out, size))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn tlv(tag: u16, content: &[u8]) -> Vec<u8> {
        let mut out = tag.to_le_bytes().to_vec();
        out.extend((content.len() as u64).to_le_bytes());
        out.extend(content);
        out
    }

    fn level(entries: &[(u16, Vec<u8>)]) -> Vec<u8> {
        entries.iter().flat_map(|(t, c)| tlv(*t, c)).collect()
    }

    fn text(s: &str) -> Vec<u8> {
        let mut out = vec![TEXT_MARKER];
        out.extend(s.encode_utf16().flat_map(u16::to_le_bytes));
        out
    }

    fn zlib(bytes: &[u8]) -> Vec<u8> {
        let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        e.write_all(bytes).unwrap();
        e.finish().unwrap()
    }

    /// An array object of class `class`: `count` elements of `size` bytes in the given blocks
    /// (first element, bytes).
    fn array_object(class: u32, count: u32, size: u64, blocks: &[(u64, &[u8])]) -> Vec<u8> {
        let mut data = (u64::from(count) * size).to_le_bytes().to_vec();
        for (first, bytes) in blocks {
            let z = zlib(bytes);
            data.extend(first.to_le_bytes());
            data.extend(((bytes.len() as u64 / size) as u32).to_le_bytes());
            data.extend((z.len() as u32).to_le_bytes());
            data.extend(z);
        }
        let body = level(&[(1, count.to_le_bytes().to_vec()), (2, data)]);
        level(&[(1, level(&[(1, class.to_le_bytes().to_vec())])), (2, body)])
    }

    fn axis(step: f64, unit: &str, n: u32) -> Vec<u8> {
        let scale = level(&[(1, step.to_le_bytes().to_vec()), (2, text(unit))]);
        let axis = level(&[(HEADER, scale), (1, n.to_le_bytes().to_vec())]);
        level(&[(HEADER, axis)])
    }

    /// A 3 × 2 measurement with 32-bit counts 0..6 in two blocks stored out of order, height
    /// step 2 nm, origin 1 µm, and a mask that leaves point (1, 1) unmeasured.
    fn measurement(blocks: &[(u64, &[u8])]) -> Vec<u8> {
        let mut mask = vec![MASK_MEASURED; 5 * 4];
        mask[2 * 5 + 2] = 22;
        let mask_body = level(&[
            (1, 3u32.to_le_bytes().to_vec()),
            (2, 2u32.to_le_bytes().to_vec()),
            (5, array_object(9048, 20, 1, &[(0, &mask)])),
        ]);
        let mask_object = level(&[
            (1, level(&[(1, CLASS_MASK.to_le_bytes().to_vec())])),
            (2, mask_body),
        ]);
        let grid = level(&[
            (1, axis(0.5, "µm", 3)),
            (2, axis(0.25, "mm", 2)),
            (3, mask_object),
        ]);
        let z = level(&[
            (1, 2.0f64.to_le_bytes().to_vec()),
            (2, text("nm")),
            (3, text("µm")),
            (5, 1.0f64.to_le_bytes().to_vec()),
        ]);
        level(&[
            (HEADER, grid),
            (1, array_object(CLASS_HEIGHTS, 6, 4, blocks)),
            (2, level(&[(HEADER, z)])),
        ])
    }

    fn counts(range: std::ops::Range<i32>) -> Vec<u8> {
        range.flat_map(i32::to_le_bytes).collect()
    }

    #[test]
    fn measurement_with_mask_and_blocks_out_of_order() {
        let (first, second) = (counts(0..2), counts(2..6));
        let bytes = measurement(&[(2, &second), (0, &first)]);
        let b = Binary::new(Path::new("m.mnt"), NAME, &bytes);
        let m = Level::of(&b, &bytes, false, "test").unwrap();
        let map = surface(&b, &m, "test").unwrap().map.unwrap();
        assert_eq!((map.nx(), map.ny()), (3, 2));
        assert_eq!((map.dx(), map.dy()), (0.5e-6, 0.25e-3));
        // count · 2 nm + 1 µm
        assert!((map.get(2, 0).unwrap() - (2.0 * 2e-9 + 1e-6)).abs() < 1e-18);
        assert!((map.get(0, 1).unwrap() - (3.0 * 2e-9 + 1e-6)).abs() < 1e-18);
        assert!(!map.is_valid(1, 1));
        assert_eq!(map.valid_count(), 5);
    }

    #[test]
    fn blocks_that_leave_a_gap_are_an_error() {
        let bytes = measurement(&[(0, &counts(0..2)), (3, &counts(3..6))]);
        let b = Binary::new(Path::new("gap.mnt"), NAME, &bytes);
        let m = Level::of(&b, &bytes, false, "test").unwrap();
        let err = surface(&b, &m, "test").err().unwrap().to_string();
        assert!(
            err.contains("gap.mnt") && err.contains("gap or overlap"),
            "{err}"
        );
    }
}
