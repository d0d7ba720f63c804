//! Nanosurf `.nid` reader: the AFM files of Nanosurf's easyScan, FlexAFM and DriveAFM
//! controllers.
//!
//! Layout, as read by SurfaceTopography's `EZD.py` and Gwyddion's `nanosurf.c`: a UTF-8 INI
//! header (`[Section]` lines, `Key=Value` lines) ended by the two bytes `#!`, then the data
//! blocks of every data set one after the other. The `[DataSet]` section holds `GroupCount`
//! groups (scan forward, scan backward); group `i` lists `Gr{i}-Count` channel slots, of which
//! those present name their section in `Gr{i}-Ch{j}=DataSet-i:j`. Each such section gives the
//! grid (`Points` × `Lines`), the lateral ranges (`Dim0Range`, `Dim1Range` in `Dim0Unit`,
//! `Dim1Unit`), the channel (`Dim2Name`, `Dim2Unit`, `Dim2Min`, `Dim2Range`) and the storage
//! (`SaveMode=Binary`, `SaveBits` 16 or 32, `SaveSign`, `SaveOrder` Intel or Motorola). A raw
//! value `v` of `b` bits is `Dim2Min + (v − vmin) · Dim2Range / 2^b`, `vmin` the type's
//! minimum (−2^(b−1) for signed, 0 for unsigned). A channel is a height channel when its unit
//! is a length. Channels are named `Frame (Dim2Name)`, e.g. `Scan forward (Z-Axis)`.

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::Binary;
use crate::io::common::{metres_per_unit, parse_number, unit_scale};
use std::path::Path;

pub(crate) const NAME: &str = "Nanosurf NID";

const MAGIC: &[u8] = b"[DataSet]";
const DATA_MARK: &[u8] = b"#!";

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The INI header: sections of key/value pairs.
struct Ini(Vec<(String, Vec<(String, String)>)>);

impl Ini {
    fn parse(text: &str) -> Ini {
        let mut sections: Vec<(String, Vec<(String, String)>)> = Vec::new();
        for line in text.lines().map(str::trim) {
            if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
                sections.push((name.to_string(), Vec::new()));
            } else if let (Some((key, value)), Some(section)) =
                (line.split_once('='), sections.last_mut())
            {
                section
                    .1
                    .push((key.trim().to_string(), value.trim().to_string()));
            }
        }
        Ini(sections)
    }

    fn section(&self, name: &str) -> Option<&[(String, String)]> {
        self.0
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| e.as_slice())
    }
}

/// Look up `key` of the header section `name`, or an error naming both.
fn field<'s>(
    b: &Binary,
    section: &'s [(String, String)],
    name: &str,
    key: &str,
) -> Result<&'s str> {
    section
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .ok_or_else(|| b.err(format!("section [{name}] lacks '{key}'")))
}

fn number(b: &Binary, section: &[(String, String)], name: &str, key: &str) -> Result<f64> {
    let text = field(b, section, name, key)?;
    parse_number(text)
        .filter(|v| v.is_finite())
        .ok_or_else(|| b.err(format!("'{key}' of [{name}] is '{text}', not a number")))
}

/// One data set: its channel and where and how its values are stored.
struct DataSet {
    channel: Channel,
    offset: usize,
    grid: (usize, usize),
    bytes_per_point: usize,
    signed: bool,
    big_endian: bool,
    section: String,
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let end = bytes
        .windows(DATA_MARK.len())
        .position(|w| w == DATA_MARK)
        .ok_or_else(|| b.err("the data marker '#!' that ends the header is missing"))?;
    let ini = Ini::parse(&String::from_utf8_lossy(&bytes[..end]));
    let data_start = end + DATA_MARK.len();
    let top = ini
        .section("DataSet")
        .ok_or_else(|| b.err("the header lacks its [DataSet] section"))?;
    let count = |key: &str| -> Result<usize> {
        let n = number(&b, top, "DataSet", key)?;
        if (0.0..=1024.0).contains(&n) && n.fract() == 0.0 {
            Ok(n as usize)
        } else {
            Err(b.err(format!(
                "'{key}' of [DataSet] is {n}, not a count up to 1024"
            )))
        }
    };
    let mut sets = Vec::new();
    let mut offset = data_start;
    for group in 0..count("GroupCount")? {
        for slot in 0..count(&format!("Gr{group}-Count"))? {
            let key = format!("Gr{group}-Ch{slot}");
            let Some((_, name)) = top.iter().find(|(k, _)| *k == key) else {
                continue;
            };
            let section = ini
                .section(name)
                .ok_or_else(|| b.err(format!("{key} names the missing section [{name}]")))?;
            let set = data_set(&b, section, name, sets.len(), offset)?;
            offset = set
                .grid
                .0
                .checked_mul(set.grid.1)
                .and_then(|n| n.checked_mul(set.bytes_per_point))
                .and_then(|n| n.checked_add(offset))
                .ok_or_else(|| b.err("the data blocks overflow the address space"))?;
            sets.push(set);
        }
    }
    if sets.is_empty() {
        return Err(b.err("the header lists no data set"));
    }
    // All blocks must be present, not only the one read: a file cut short is damaged.
    if offset > bytes.len() {
        return Err(b.err(format!(
            "file truncated: the header's {} data sets end at byte {offset}, but the file has \
             only {} bytes",
            sets.len(),
            bytes.len()
        )));
    }
    let channels: Vec<Channel> = sets.iter().map(|s| s.channel.clone()).collect();
    let set = &sets[select(path, NAME, &channels, selector)?];
    let section = ini.section(&set.section).unwrap_or_default();
    let name = set.section.as_str();
    let (nx, ny) = set.grid;
    let what = format!("data of channel {}", set.channel);
    let data = b.array(set.offset, nx * ny, set.bytes_per_point, &what)?;

    let unit = field(&b, section, name, "Dim2Unit")?;
    let z_unit = unit_scale(path, NAME, "height", unit)?;
    let range = number(&b, section, name, "Dim2Range")? * z_unit;
    let min = number(&b, section, name, "Dim2Min")? * z_unit;
    let bits = 8 * set.bytes_per_point as i32;
    let step = range / 2f64.powi(bits);
    let type_min = if set.signed {
        -(2f64.powi(bits - 1))
    } else {
        0.0
    };
    let heights = data
        .chunks_exact(set.bytes_per_point)
        .map(|c| {
            let mut word = [0u8; 4];
            word[..c.len()].copy_from_slice(c);
            if set.big_endian {
                word[..c.len()].reverse();
            }
            let raw = u32::from_le_bytes(word);
            let v = match (set.bytes_per_point, set.signed) {
                (2, true) => f64::from(raw as u16 as i16),
                (2, false) => f64::from(raw as u16),
                (_, true) => f64::from(raw as i32),
                (_, false) => f64::from(raw),
            };
            min + (v - type_min) * step
        })
        .collect();
    let lateral = |axis: u8| -> Result<f64> {
        let unit = field(&b, section, name, &format!("Dim{axis}Unit"))?;
        let range = number(&b, section, name, &format!("Dim{axis}Range"))?;
        Ok(range * unit_scale(path, NAME, "lateral", unit)?)
    };
    let dx = b.spacing(lateral(0)? / nx as f64, "x spacing (m)")?;
    let dy = b.spacing(lateral(1)? / ny as f64, "y spacing (m)")?;
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.channel = set.channel.index;
    map.meta.channels = channels;
    let info = ini.section("DataSet-Info").unwrap_or_default();
    let info_field = |key: &str| info.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
    map.meta.instrument = Some(match info_field("Head type") {
        Some(head) => format!("Nanosurf {head}"),
        None => "Nanosurf".into(),
    });
    map.meta.date = match (info_field("Date"), info_field("Time")) {
        (Some(date), Some(time)) => Some(format!("{date} {time}")),
        (date, _) => date,
    };
    Ok(map)
}

fn data_set(
    b: &Binary,
    section: &[(String, String)],
    name: &str,
    index: usize,
    offset: usize,
) -> Result<DataSet> {
    let mode = field(b, section, name, "SaveMode")?;
    if mode != "Binary" {
        return Err(b.err(format!(
            "[{name}] is saved as '{mode}'; only Binary is read"
        )));
    }
    let integer = |key: &str| -> Result<i64> {
        let n = number(b, section, name, key)?;
        Ok(if n.fract() == 0.0 && n.abs() < 1e15 {
            n as i64
        } else {
            -1
        })
    };
    let grid = b.grid(integer("Points")?, integer("Lines")?)?;
    let bytes_per_point = match integer("SaveBits")? {
        16 => 2,
        32 => 4,
        other => return Err(b.err(format!("[{name}]: {other} bits per value is not 16 or 32"))),
    };
    let signed = match field(b, section, name, "SaveSign")? {
        "Signed" => true,
        "Unsigned" => false,
        other => {
            return Err(b.err(format!(
                "[{name}]: SaveSign '{other}' is not Signed or Unsigned"
            )));
        }
    };
    let big_endian = match field(b, section, name, "SaveOrder")? {
        "Intel" => false,
        "Motorola" => true,
        other => {
            return Err(b.err(format!(
                "[{name}]: SaveOrder '{other}' is not Intel or Motorola"
            )));
        }
    };
    let unit = field(b, section, name, "Dim2Unit")?;
    let frame = field(b, section, name, "Frame").unwrap_or("");
    let quantity = field(b, section, name, "Dim2Name")?;
    Ok(DataSet {
        channel: Channel {
            index,
            name: format!("{frame} ({quantity})"),
            unit: Some(unit.to_string()),
            is_height: metres_per_unit(unit).is_some(),
            problem: None,
        },
        offset,
        grid,
        bytes_per_point,
        signed,
        big_endian,
        section: name.to_string(),
    })
}
