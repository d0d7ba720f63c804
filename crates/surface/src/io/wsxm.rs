//! WSxM reader (`.top`, `.stp` and the other image files of Nanotec's WSxM software).
//!
//! Layout, as read by SurfaceTopography's `WSXM.py` and Gwyddion's `wsxmfile.c`: three lines
//! `WSxM file copyright …`, `SxM Image file`, `Image header size: N`, then an INI-like header
//! (`[Section]` lines and indented `Key: value` lines) closed by `[Header end]`; the image
//! starts at byte N. `[General Info]` gives the grid (`Number of columns` × `Number of rows`),
//! the storage (`Image Data Type`: `short`/`integer` for little-endian int16, `float`, `double`
//! for little-endian f32, f64), the acquisition channel and the `Z Amplitude` with its unit;
//! `[Control]` gives the field (`X Amplitude`, `Y Amplitude`, with units; a missing y amplitude
//! means a square scan). Floating-point data are heights in the unit of the Z amplitude;
//! integer data are normalised: the Z amplitude is the span of the stored values, so a count is
//! `Z amplitude / (max − min)` over the image (computed from the data, as Gwyddion does;
//! SurfaceTopography takes max and min from the header's `[Miscellaneous]` section, where they
//! are rounded). A file holds one channel.

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le};
use crate::io::common::{metres_per_unit, parse_number, unit_scale};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "WSxM";

const MAGIC: &[u8] = b"WSxM file copyright";
const SIZE_KEY: &str = "Image header size:";
const END: &str = "[Header end]";

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if !bytes.starts_with(MAGIC) {
        return Err(b.err("not a WSxM file: 'WSxM file copyright' missing"));
    }
    // The third line states the header size; it lies within the first few hundred bytes.
    let start: String = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]).into_owned();
    let size_line = start
        .lines()
        .nth(2)
        .and_then(|l| l.trim().strip_prefix(SIZE_KEY))
        .ok_or_else(|| b.err(format!("the third line does not start with '{SIZE_KEY}'")))?;
    let header_size: usize = size_line.trim().parse().map_err(|_| {
        b.err(format!(
            "header size '{}' is not a number",
            size_line.trim()
        ))
    })?;
    let text = String::from_utf8_lossy(b.slice(0, header_size, "header")?);
    let end = text
        .find(END)
        .ok_or_else(|| b.err(format!("the header does not end with {END}")))?;
    let mut section = String::new();
    let mut entries: Vec<(String, String, String)> = Vec::new();
    for line in text[..end].lines().skip(3).map(str::trim) {
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = name.to_string();
        } else if let Some((key, value)) = line.split_once(':') {
            entries.push((section.clone(), key.trim().into(), value.trim().into()));
        }
    }
    let get = |s: &str, k: &str| {
        entries
            .iter()
            .find(|(es, ek, _)| es == s && ek == k)
            .map(|(_, _, v)| v.as_str())
    };
    let field = |s: &str, k: &str| {
        get(s, k).ok_or_else(|| b.err(format!("the header lacks '{k}' in [{s}]")))
    };
    // A value with its unit, "600 nm": the number and the unit.
    let quantity = |s: &str, k: &str| -> Result<(f64, &str)> {
        let text = field(s, k)?;
        let (number, unit) = text.split_once(' ').unwrap_or((text, ""));
        let value = parse_number(number)
            .filter(|v| v.is_finite())
            .ok_or_else(|| b.err(format!("'{k}' is '{text}', not a number with a unit")))?;
        Ok((value, unit.trim()))
    };
    let count = |k: &str| -> Result<i64> {
        let text = field("General Info", k)?;
        Ok(text.parse().unwrap_or(-1))
    };
    let (nx, ny) = b.grid(count("Number of columns")?, count("Number of rows")?)?;

    let (z_amplitude, z_unit) = quantity("General Info", "Z Amplitude")?;
    let channels = [Channel {
        index: 0,
        name: get("General Info", "Acquisition channel")
            .unwrap_or("Default")
            .to_string(),
        unit: (!z_unit.is_empty()).then(|| z_unit.to_string()),
        is_height: metres_per_unit(z_unit).is_some(),
        problem: None,
    }];
    select(path, NAME, &channels, selector)?;
    let z_scale = unit_scale(path, NAME, "height", z_unit)?;

    let data_type = field("General Info", "Image Data Type")?;
    let point_size = match data_type {
        "short" | "integer" => 2,
        "float" => 4,
        "double" => 8,
        other => return Err(b.err(format!("image data type '{other}' is not read"))),
    };
    let data = b.array(header_size, nx * ny, point_size, "image")?;
    let values: Vec<f64> = data
        .chunks_exact(point_size)
        .map(|c| match c.len() {
            2 => f64::from(Le::read_i16(c)),
            4 => f64::from(Le::read_f32(c)),
            _ => Le::read_f64(c),
        })
        .collect();
    let scale = if point_size == 2 {
        let (min, max) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        // A flat image has no span: its heights are all zero whatever the amplitude.
        if max > min {
            z_amplitude / (max - min) * z_scale
        } else {
            0.0
        }
    } else {
        z_scale
    };
    let heights = values.into_iter().map(|v| v * scale).collect();

    let (lx, x_unit) = quantity("Control", "X Amplitude")?;
    let (ly, y_unit) = match get("Control", "Y Amplitude") {
        Some(_) => quantity("Control", "Y Amplitude")?,
        None => (lx, x_unit),
    };
    let dx = lx * unit_scale(path, NAME, "x amplitude", x_unit)? / nx as f64;
    let dy = ly * unit_scale(path, NAME, "y amplitude", y_unit)? / ny as f64;
    let dx = b.spacing(dx, "x spacing (m)")?;
    let dy = b.spacing(dy, "y spacing (m)")?;
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.channels = channels.to_vec();
    map.meta.date = get("General Info", "Acquisition time").map(str::to_string);
    map.meta.instrument = get("General Info", "Head type").map(|h| format!("Nanotec {h}"));
    Ok(map)
}
