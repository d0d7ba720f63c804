//! Agilent / Molecular Imaging PicoView `.mi` reader: the image files of PicoScan and
//! PicoView (AFM).
//!
//! Layout, as read by SurfaceTopography's `MI.py` and Gwyddion's `pnifile.c`/`mifile.c`: a
//! text header of lines whose first 14 characters are the key and the rest the value
//! (`xPixels       256`), starting with `fileType      Image`. File-wide keys come first
//! (`xPixels`, `yPixels`, and the field `xLength`, `yLength` in metres); each `bufferLabel`
//! line then opens one channel, described by the keys that follow it (`bufferUnit`,
//! `bufferRange`, `direction`). The line with the key `data` ends the header; its value is the
//! encoding of the buffers that follow it, one after the other in the order of the labels:
//! `BINARY` (or empty) for little-endian int16, `BINARY_32` for int32 (`ASCII` is not read).
//! A value `v` is `v / 2^(bits − 1) · bufferRange`, in `bufferUnit`; a channel is a height
//! channel when that unit is a length.

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le};
use crate::io::common::{metres_per_unit, parse_number};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "PicoView";

const MAGIC: &[u8] = b"fileType      Image";
/// Width of the key column of a header line.
const KEY_WIDTH: usize = 14;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

type Entries = Vec<(String, String)>;

fn get<'e>(entries: &'e Entries, key: &str) -> Option<&'e str> {
    entries
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if !bytes.starts_with(MAGIC) {
        return Err(
            b.err("not a PicoView image: the file does not start with 'fileType      Image'")
        );
    }
    let mut header = Entries::new();
    let mut buffers: Vec<Entries> = Vec::new();
    let mut at = 0;
    let (encoding, data_start) = loop {
        let rest = bytes
            .get(at..)
            .filter(|r| !r.is_empty())
            .ok_or_else(|| b.err("the header ends without its 'data' line"))?;
        let len = rest
            .iter()
            .position(|&c| c == b'\n')
            .ok_or_else(|| b.err("file truncated: the header ends without its 'data' line"))?;
        let line: String = rest[..len].iter().map(|&c| char::from(c)).collect();
        at += len + 1;
        let line = line.trim_end_matches('\r');
        let split = line
            .char_indices()
            .nth(KEY_WIDTH)
            .map_or(line.len(), |(i, _)| i);
        let (key, value) = (line[..split].trim(), line[split..].trim());
        match key {
            "data" => break (value.to_string(), at),
            "bufferLabel" => buffers.push(vec![(key.into(), value.into())]),
            _ => match buffers.last_mut() {
                Some(buffer) => buffer.push((key.into(), value.into())),
                None => header.push((key.into(), value.into())),
            },
        }
    };
    let bytes_per_point = match encoding.as_str() {
        "BINARY" | "" => 2,
        "BINARY_32" => 4,
        other => {
            return Err(b.err(format!(
                "data encoded as '{other}'; only BINARY and BINARY_32 are read"
            )));
        }
    };
    let number = |entries: &Entries, key: &str| -> Result<f64> {
        let text = get(entries, key).ok_or_else(|| b.err(format!("the header lacks '{key}'")))?;
        parse_number(text)
            .filter(|v| v.is_finite())
            .ok_or_else(|| b.err(format!("'{key}' is '{text}', not a number")))
    };
    let pixels = |key: &str| -> Result<i64> {
        let n = number(&header, key)?;
        Ok(if n.fract() == 0.0 && n.abs() < 1e15 {
            n as i64
        } else {
            -1
        })
    };
    let (nx, ny) = b.grid(pixels("xPixels")?, pixels("yPixels")?)?;
    if buffers.is_empty() {
        return Err(b.err("the header describes no buffer (no 'bufferLabel' line)"));
    }
    let channels: Vec<Channel> = buffers
        .iter()
        .enumerate()
        .map(|(index, buffer)| {
            let unit = get(buffer, "bufferUnit").filter(|u| !u.is_empty());
            Channel {
                index,
                name: get(buffer, "bufferLabel").unwrap_or_default().to_string(),
                unit: unit.map(str::to_string),
                is_height: unit.and_then(metres_per_unit).is_some(),
                problem: None,
            }
        })
        .collect();
    // All buffers must be present, not only the one read: a file cut short is damaged.
    let block = nx * ny * bytes_per_point;
    b.array(
        data_start,
        nx * ny * buffers.len(),
        bytes_per_point,
        "data of all buffers",
    )?;
    let index = select(path, NAME, &channels, selector)?;
    let buffer = &buffers[index];
    let unit = get(buffer, "bufferUnit")
        .and_then(metres_per_unit)
        .unwrap_or(1.0);
    let range = number(buffer, "bufferRange")? * unit;
    let step = range / 2f64.powi(8 * bytes_per_point as i32 - 1);
    let what = format!("data of channel {}", channels[index]);
    let data = b.array(data_start + index * block, nx * ny, bytes_per_point, &what)?;
    let heights = data
        .chunks_exact(bytes_per_point)
        .map(|c| {
            let v = match c.len() {
                2 => f64::from(Le::read_i16(c)),
                _ => f64::from(Le::read_i32(c)),
            };
            v * step
        })
        .collect();
    let dx = b.spacing(number(&header, "xLength")? / nx as f64, "x spacing (m)")?;
    let dy = b.spacing(number(&header, "yLength")? / ny as f64, "y spacing (m)")?;
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.channel = index;
    map.meta.channels = channels;
    map.meta.instrument = get(&header, "version").map(str::to_string);
    map.meta.date = get(&header, "dateAcquired").map(str::to_string);
    if let Some(mode) = get(&header, "mode") {
        map.meta.extra.push(("mode".into(), mode.to_string()));
    }
    Ok(map)
}
