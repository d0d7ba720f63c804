//! Bruker / Veeco / Digital Instruments Nanoscope reader (`.spm`, `.di`, `.000`, `.001`, ...):
//! the AFM files of the Nanoscope and Dimension controllers, version 4.3 and later.
//!
//! Layout, as read by SurfaceTopography's `DI.py` and Gwyddion's `nanoscope.c`: a Latin-1 text
//! header of lines `\Key: value`, grouped in sections opened by `\*Section name` and closed by
//! `\*File list end`. Each `\*Ciao image list` (also `AFM`, `STM`, `NCAFM image list`) section
//! describes one channel: `Data offset` and `Data length` of its block, `Bytes/pixel` (2 or 4),
//! `Samps/line` × `Number of lines`, `Scan Size: sx sy unit` (`~m` is µm), the channel name in
//! `@2:Image Data: S [Name] "Description"` and the scale in
//! `@2:Z scale: V [Sens. Zsens] (0.0050354 V/LSB) 2.910461 V`. The data are little-endian
//! signed integers, stored line after line; a value `v` is
//! `v · (Z scale value) / 256^(bytes per pixel) · (soft scale)`, the soft scale being the value
//! of the `@Sens. Zsens` key (bracketed name) in the scanner or scan list, e.g. `V 20.8 nm/V`:
//! its numerator (nm) is the unit of the channel, and its denominator is the unit of the Z scale
//! value, or another voltage it converts to (a Z scale in mV under a soft scale in nm/V, as an
//! amplitude-error channel writes it); a soft scale without a unit (`V 1.000000`) keeps the Z
//! scale's unit. A channel without a length unit (phase in º, amplitude in mV) is listed but is
//! not a height channel. A channel whose scale cannot be interpreted (a soft scale per a unit the
//! Z scale is not in, a missing Z scale) is listed with what is wrong with it, and only asking
//! for it is an error: the file's other channels read as usual. From version 9.2 the data may be int32 although `Bytes/pixel` says 2; such blocks
//! are refused (no test file). Lines are kept in their stored order (SurfaceTopography and
//! Gwyddion show them bottom-up, so their first row is the file's last line).

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, header_text};
use crate::io::common::{metres_per_unit, parse_number, unit_scale};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "Nanoscope";

const MAGIC: &[u8] = b"\\*File list";
/// First version that may store 32-bit data in blocks whose header says 2 bytes per pixel.
const VERSION_32BIT: u32 = 0x0920_0000;
const END: &[u8] = b"\\*File list end";
const IMAGE_SECTIONS: [&str; 4] = [
    "ciao image list",
    "afm image list",
    "stm image list",
    "ncafm image list",
];
const SCALE_SECTIONS: [&str; 6] = [
    "scanner list",
    "microscope list",
    "ciao scan list",
    "afm list",
    "stm list",
    "nc afm list",
];

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The header: sections (lower-case name) of (lower-case key, value) lines.
type Sections = Vec<(String, Vec<(String, String)>)>;

fn sections(b: &Binary, bytes: &[u8]) -> Result<Sections> {
    let end = bytes
        .windows(END.len())
        .position(|w| w == END)
        .ok_or_else(|| b.err("the header's end (\\*File list end) is missing"))?;
    let mut out: Sections = Vec::new();
    for line in header_text(&bytes[..end]).lines().map(str::trim) {
        if let Some(name) = line.strip_prefix("\\*") {
            out.push((name.trim().to_ascii_lowercase(), Vec::new()));
        } else if let Some(entry) = line.strip_prefix('\\') {
            // Keys may hold a colon themselves (`@2:Z scale`): the value follows ": ".
            let (key, value) = entry
                .split_once(": ")
                .unwrap_or((entry.trim_end_matches(':'), ""));
            let section = out
                .last_mut()
                .ok_or_else(|| b.err("a header key comes before the first section"))?;
            section
                .1
                .push((key.trim().to_ascii_lowercase(), value.trim().to_string()));
        } else if !line.is_empty() {
            return Err(b.err(format!("header line '{line}' does not start with '\\'")));
        }
    }
    Ok(out)
}

fn get<'s>(section: &'s [(String, String)], key: &str) -> Option<&'s str> {
    section
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

/// A scaled value `V [soft scale] (hard scale) number unit`: the soft scale's name and the
/// number with its unit.
struct Scaled<'a> {
    soft: Option<&'a str>,
    value: f64,
    unit: &'a str,
}

fn scaled<'a>(key: &str, text: &'a str) -> std::result::Result<Scaled<'a>, String> {
    let bad = || format!("cannot read the value of '{key}': '{text}'");
    let mut rest = text.get(1..).ok_or_else(bad)?.trim_start();
    let mut soft = None;
    if let Some(inner) = rest.strip_prefix('[') {
        let (name, after) = inner.split_once(']').ok_or_else(bad)?;
        soft = Some(name.trim());
        rest = after.trim_start();
    }
    if let Some(inner) = rest.strip_prefix('(') {
        rest = inner.split_once(')').ok_or_else(bad)?.1.trim_start();
    }
    let (number, unit) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
    let value = parse_number(number)
        .filter(|v| v.is_finite())
        .ok_or_else(bad)?;
    Ok(Scaled {
        soft,
        value,
        unit: unit.trim(),
    })
}

/// One image section: its channel and how to read it.
struct Image {
    channel: Channel,
    offset: usize,
    length: usize,
    bytes_per_pixel: usize,
    grid: (usize, usize),
    size: (f64, f64),
    /// Value of one count: metres for a height channel, the channel's unit for any other.
    scale: f64,
}

fn image(
    b: &Binary,
    index: usize,
    s: &[(String, String)],
    scales: &[(String, String)],
) -> Result<Image> {
    let field = |key: &str| {
        get(s, key).ok_or_else(|| b.err(format!("image section {index} lacks '{key}'")))
    };
    let integer = |key: &str| -> Result<i64> {
        let text = field(key)?;
        text.parse().map_err(|_| {
            b.err(format!(
                "'{key}' of image section {index} is '{text}', not an integer"
            ))
        })
    };
    let name_text = ["@2:image data", "@3:image data", "@4:image data"]
        .iter()
        .find_map(|k| get(s, k))
        .or_else(|| get(s, "image data"))
        .unwrap_or("");
    let name = match (name_text.find('['), name_text.find(']')) {
        (Some(a), Some(z)) if a < z => name_text[a + 1..z].trim(),
        // `S "Name"` without a bracket, or a bare name (`\Image data: Height`).
        _ => name_text
            .strip_prefix("S ")
            .unwrap_or(name_text)
            .trim()
            .trim_matches('"'),
    };
    let grid = b.grid(integer("samps/line")?, integer("number of lines")?)?;
    // Files that omit it store 2 bytes per pixel (SurfaceTopography's and Gwyddion's default).
    let bytes_per_pixel = match get(s, "bytes/pixel").map_or(Ok(2), |_| integer("bytes/pixel"))? {
        2 => 2,
        4 => 4,
        other => return Err(b.err(format!("{other} bytes per pixel is not 2 or 4"))),
    };
    let size_text = field("scan size")?;
    let words: Vec<&str> = size_text.split_whitespace().collect();
    let number = |w: Option<&&str>| w.and_then(|w| parse_number(w)).filter(|v| v.is_finite());
    let (sx, sy, unit) = match (number(words.first()), number(words.get(1))) {
        (Some(sx), Some(sy)) => (sx, sy, words.get(2..).unwrap_or_default().join(" ")),
        (Some(sx), None) => (sx, sx, words.get(1..).unwrap_or_default().join(" ")),
        _ => return Err(b.err(format!("cannot read the scan size '{size_text}'"))),
    };
    let lateral = unit_scale(b.path(), NAME, "scan size", &unit.replace('~', "µ"))?;
    // A scale that cannot be interpreted is this channel's problem: the file's other channels
    // read all the same.
    let (scale, unit, problem) = match value_scale(s, scales, bytes_per_pixel) {
        Ok((scale, unit)) => (scale, unit, None),
        Err(problem) => (f64::NAN, String::new(), Some(problem)),
    };
    let unit_metres = metres_per_unit(&unit.replace('~', "µ"));
    Ok(Image {
        channel: Channel {
            index,
            name: name.to_string(),
            unit: (!unit.is_empty()).then(|| unit.to_string()),
            is_height: unit_metres.is_some(),
            problem,
        },
        offset: integer("data offset")?
            .try_into()
            .map_err(|_| b.err("negative data offset"))?,
        length: integer("data length")?
            .try_into()
            .map_err(|_| b.err("negative data length"))?,
        bytes_per_pixel,
        grid,
        size: (sx * lateral, sy * lateral),
        scale: scale * unit_metres.unwrap_or(1.0),
    })
}

/// The value of one count of an image section and the unit it is in: the Z scale's value over
/// `256^bytes_per_pixel`, times the soft scale it names (module docs). `Err` says, without the
/// file's name, why the channel's values cannot be interpreted.
fn value_scale(
    s: &[(String, String)],
    scales: &[(String, String)],
    bytes_per_pixel: usize,
) -> std::result::Result<(f64, String), String> {
    let key = ["@2:z scale", "@4:z scale"]
        .into_iter()
        .find(|k| get(s, k).is_some())
        .ok_or("it lacks '@2:Z scale' (files before version 4.3 are not read)")?;
    let z = scaled(key, get(s, key).unwrap_or_default())?;
    let hard = z.value / 256f64.powi(bytes_per_pixel as i32);
    // The soft scale turns the hard scale's unit (V) into the channel's (nm); without one the
    // channel stays in the hard scale's unit.
    let Some(text) = z
        .soft
        .and_then(|name| get(scales, &format!("@{}", name.to_ascii_lowercase())))
    else {
        return Ok((hard, z.unit.to_string()));
    };
    let soft = scaled("soft scale", text)?;
    match soft.unit.split_once('/') {
        Some((num, den)) => {
            let den = den.trim();
            // Per V under a Z scale in mV (an amplitude channel's sensitivity, say) is a unit
            // conversion: the hard scale's value in the soft scale's denominator.
            let conversion = if den == z.unit {
                Some(1.0)
            } else {
                volts(z.unit).zip(volts(den)).map(|(z, d)| z / d)
            };
            match conversion {
                Some(c) => Ok((hard * c * soft.value, num.trim().to_string())),
                None => Err(format!(
                    "its soft scale '{text}' is per {den}, but its Z scale is in {}",
                    z.unit
                )),
            }
        }
        // A bare factor (`V 1.000000`) keeps the Z scale's unit.
        None if soft.unit.is_empty() => Ok((hard * soft.value, z.unit.to_string())),
        None => Ok((hard * soft.value, soft.unit.to_string())),
    }
}

/// Volts in one `unit` of voltage as the headers write it (`~V` is µV, as `~m` is µm).
fn volts(unit: &str) -> Option<f64> {
    Some(match unit {
        "V" => 1.0,
        "mV" => 1e-3,
        "~V" | "\u{b5}V" | "\u{3bc}V" | "uV" => 1e-6,
        "nV" => 1e-9,
        "kV" => 1e3,
        _ => return None,
    })
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let sections = sections(&b, bytes)?;
    let scales: Vec<(String, String)> = sections
        .iter()
        .filter(|(name, _)| SCALE_SECTIONS.contains(&name.as_str()))
        .flat_map(|(_, entries)| entries.iter().cloned())
        .collect();
    let images = sections
        .iter()
        .filter(|(name, _)| IMAGE_SECTIONS.contains(&name.as_str()))
        .enumerate()
        .map(|(index, (_, s))| image(&b, index, s, &scales))
        .collect::<Result<Vec<_>>>()?;
    if images.is_empty() {
        return Err(b.err("the header describes no image"));
    }
    let file_list = sections
        .first()
        .map(|(_, e)| e.as_slice())
        .unwrap_or_default();
    let version = get(file_list, "version")
        .and_then(|v| u32::from_str_radix(v.trim_start_matches("0x"), 16).ok())
        .unwrap_or(0);
    // Every channel's block must be in the file, not only the one read: a file cut short is
    // damaged, whichever channel is asked for.
    for image in &images {
        let (nx, ny) = image.grid;
        let what = format!("data block of channel {}", image.channel);
        b.slice(image.offset, image.length, &what)?;
        if nx * ny * image.bytes_per_pixel > image.length {
            return Err(b.err(format!(
                "{what}: {nx} × {ny} points of {} bytes do not fit its {} bytes",
                image.bytes_per_pixel, image.length
            )));
        }
        // From version 9.2 the data may be stored as int32 whatever Bytes/pixel says; how such
        // values are scaled has not been checked on a file, so they are refused, not guessed.
        if version >= VERSION_32BIT && image.bytes_per_pixel == 2 && image.length >= 4 * nx * ny {
            return Err(b.err(format!(
                "{what} holds 4 bytes per point although Bytes/pixel is 2 (the 32-bit storage of \
                 version 9.2 and later), which is not read"
            )));
        }
    }
    let channels: Vec<Channel> = images.iter().map(|i| i.channel.clone()).collect();
    let chosen = &images[select(path, NAME, &channels, selector)?];
    let (nx, ny) = chosen.grid;
    let what = format!("data of channel {}", chosen.channel);
    let data = b.array(chosen.offset, nx * ny, chosen.bytes_per_pixel, &what)?;
    let heights = data
        .chunks_exact(chosen.bytes_per_pixel)
        .map(|c| {
            let v = match c.len() {
                2 => f64::from(Le::read_i16(c)),
                _ => f64::from(Le::read_i32(c)),
            };
            v * chosen.scale
        })
        .collect();
    let dx = b.spacing(chosen.size.0 / nx as f64, "x spacing (m)")?;
    let dy = b.spacing(chosen.size.1 / ny as f64, "y spacing (m)")?;
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.channel = chosen.channel.index;
    map.meta.channels = channels;
    map.meta.instrument = Some("Bruker Nanoscope".into());
    let file_list = sections
        .first()
        .map(|(_, e)| e.as_slice())
        .unwrap_or_default();
    map.meta.date = get(file_list, "date").map(str::to_string);
    if let Some(version) = get(file_list, "version") {
        map.meta.extra.push(("version".into(), version.to_string()));
    }
    Ok(map)
}
