//! Igor binary wave (`.ibw`) reader, version 5: the files in which Asylum Research (Oxford
//! Instruments) AFMs save their images, one layer per channel.
//!
//! Layout, as read by SurfaceTopography's `IBW.py` (through the `igor2` package) and Gwyddion's
//! `igorfile.c`, following WaveMetrics' Technical Note PTN003: a 64-byte binary header
//! (`version` 5 as an i16 whose byte order gives the file's, the size of the wave record, and
//! the sizes of the formula, note, extended units and dimension labels that follow it), then
//! the wave record: a 320-byte wave header (`npnts` at 12, data `type` at 16, the dimensions
//! `nDim[4]` at 68, the spacings `sfA[4]` and offsets `sfB[4]` as f64 at 84 and 116, the data
//! unit and the four dimension units as 4-character strings at 148 and 152), and the data in
//! Igor's column-major order (x fastest, then y, then layer). After the wave record come the
//! formula, the note, the extended data unit, the four extended dimension units and the four
//! dimension label blocks: 32-byte labels, the first naming the dimension, then one per index;
//! the labels of dimension 2 name the channels (`HeightTrace`, `AmplitudeRetrace`, ...).
//! A wave has one data unit, so every layer has it: Asylum writes `m` for all, and a phase
//! layer then counts as a height channel, as in SurfaceTopography.

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Be, Binary, Le, header_text};
use crate::io::common::{metres_per_unit, unit_scale};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "Igor binary wave";

const VERSION: i16 = 5;
const BIN_HEADER: usize = 64;
const WAVE_HEADER: usize = 320;
const LABEL: usize = 32;
/// Offset of `whVersion` in the wave header; 1 in version 5 files.
const WH_VERSION: usize = 26;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    let version = |at: usize| bytes.get(at..at + 2).map(|s| [s[0], s[1]]);
    let five = [Some([5, 0]), Some([0, 5])];
    let one = [Some([1, 0]), Some([0, 1])];
    bytes.len() >= BIN_HEADER + WAVE_HEADER
        && five.contains(&version(0))
        && one.contains(&version(BIN_HEADER + WH_VERSION))
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if b.i16::<Le>(0, "version")? == VERSION {
        read::<Le>(&b, selector)
    } else if b.i16::<Be>(0, "version")? == VERSION {
        read::<Be>(&b, selector)
    } else {
        Err(b.err(format!(
            "version {} is not 5: only version 5 waves (Igor Pro 3 and later) are read",
            b.i16::<Le>(0, "version")?
        )))
    }
}

fn read<E: ByteOrder>(b: &Binary, selector: Option<&ChannelSelector>) -> Result<HeightMap> {
    let size = |offset: usize, what: &str| -> Result<usize> {
        let v = b.i32::<E>(offset, what)?;
        usize::try_from(v).map_err(|_| b.err(format!("{what} {v} is negative")))
    };
    let wave_size = size(4, "wave record size")?;
    let formula_size = size(8, "formula size")?;
    let note_size = size(12, "note size")?;
    let data_units_size = size(16, "extended data unit size")?;
    let dim_units_sizes = (0..4)
        .map(|d| size(20 + 4 * d, "extended dimension unit size"))
        .collect::<Result<Vec<_>>>()?;
    let label_sizes = (0..4)
        .map(|d| size(36 + 4 * d, "dimension label size"))
        .collect::<Result<Vec<_>>>()?;
    let w = BIN_HEADER;
    b.slice(w, WAVE_HEADER, "wave header")?;
    let kind = b.i16::<E>(w + 16, "data type")?;
    let (point_size, decode): (usize, fn(&[u8]) -> f64) = match kind {
        0x02 => (4, |c| f64::from(E::read_f32(c))),
        0x04 => (8, |c| E::read_f64(c)),
        0x08 => (1, |c| f64::from(c[0] as i8)),
        0x48 => (1, |c| f64::from(c[0])),
        0x10 => (2, |c| f64::from(E::read_i16(c))),
        0x50 => (2, |c| f64::from(E::read_u16(c))),
        0x20 => (4, |c| f64::from(E::read_i32(c))),
        0x60 => (4, |c| f64::from(E::read_u32(c))),
        other => {
            return Err(b.err(format!(
                "data type {other:#x} is not a real number type (complex and text waves are not \
                 read)"
            )));
        }
    };
    let dims = (0..4)
        .map(|d| b.i32::<E>(w + 68 + 4 * d, "dimension size"))
        .collect::<Result<Vec<_>>>()?;
    if dims[3] > 1 {
        return Err(b.err("four-dimensional waves are not read"));
    }
    let (nx, ny) = b.grid(i64::from(dims[0]), i64::from(dims[1].max(1)))?;
    let layers =
        usize::try_from(dims[2].max(1)).map_err(|_| b.err(format!("{} layers", dims[2])))?;
    let layer = nx * ny;
    let npnts = b.i32::<E>(w + 12, "number of points")?;
    if layer.checked_mul(layers) != usize::try_from(npnts).ok() {
        return Err(b.err(format!(
            "the wave holds {npnts} points, not the {nx} × {ny} × {layers} of its dimensions"
        )));
    }
    let data_start = w + WAVE_HEADER;
    let data = b.array(data_start, layer * layers, point_size, "wave data")?;
    if WAVE_HEADER + data.len() > wave_size {
        return Err(b.err(format!(
            "the wave's {} data bytes do not fit its {wave_size}-byte record",
            data.len()
        )));
    }

    // The sections after the wave record, in order.
    let mut at = w
        .checked_add(wave_size)
        .and_then(|a| a.checked_add(formula_size))
        .ok_or_else(|| b.err("section sizes overflow"))?;
    let note = b.slice(at, note_size, "note")?;
    at += note_size;
    let data_units = match data_units_size {
        0 => b.text(w + 148, 4, "data unit")?,
        n => header_text(b.slice(at, n, "extended data unit")?),
    };
    at += data_units_size;
    let mut dim_units = Vec::new();
    for (d, &n) in dim_units_sizes.iter().enumerate() {
        dim_units.push(match n {
            0 => b.text(w + 152 + 4 * d, 4, "dimension unit")?,
            n => header_text(b.slice(at, n, "extended dimension unit")?),
        });
        at += n;
    }
    for &n in &label_sizes[..2] {
        at = at
            .checked_add(n)
            .ok_or_else(|| b.err("label sizes overflow"))?;
    }
    let labels = b.slice(at, label_sizes[2], "layer labels")?;
    // Label 0 names the dimension; label k + 1 names layer k.
    let name = |k: usize| {
        labels
            .get((k + 1) * LABEL..(k + 2) * LABEL)
            .map(header_text)
            .filter(|l| !l.is_empty())
            .unwrap_or_else(|| format!("Layer {k}"))
    };
    let is_height = metres_per_unit(&data_units).is_some();
    let channels: Vec<Channel> = (0..layers)
        .map(|index| Channel {
            index,
            name: name(index),
            unit: (!data_units.is_empty()).then(|| data_units.clone()),
            is_height,
            problem: None,
        })
        .collect();
    let index = select(b.path(), NAME, &channels, selector)?;
    let z = unit_scale(b.path(), NAME, "data", &data_units)?;
    let heights = data[index * layer * point_size..(index + 1) * layer * point_size]
        .chunks_exact(point_size)
        .map(|c| {
            let v = decode(c) * z;
            // Igor marks missing points with NaN; infinities are missing too.
            if v.is_finite() { v } else { f64::NAN }
        })
        .collect();
    let spacing = |d: usize| -> Result<f64> {
        let value = b.f64::<E>(w + 84 + 8 * d, "spacing")?;
        let unit = unit_scale(b.path(), NAME, "dimension", &dim_units[d])?;
        b.spacing(
            value * unit,
            if d == 0 {
                "x spacing (m)"
            } else {
                "y spacing (m)"
            },
        )
    };
    let mut map = b.height_map(heights, (nx, ny), (spacing(0)?, spacing(1)?))?;
    map.meta.channel = index;
    map.meta.channels = channels;
    let note = String::from_utf8_lossy(note);
    for line in note.split(['\r', '\n']) {
        if let Some((key, value)) = line.split_once(':') {
            match key.trim() {
                "ImagingMode" => map.meta.extra.push(("mode".into(), value.trim().into())),
                "Date" => map.meta.date = Some(value.trim().into()),
                "MicroscopeModel" => map.meta.instrument = Some(value.trim().into()),
                _ => {}
            }
        }
    }
    Ok(map)
}
