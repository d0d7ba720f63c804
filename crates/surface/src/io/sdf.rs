//! ISO 25178-71 / EU BCR surface data file (SDF), ASCII (`aBCR-1.0`, `aISO-1.0`) and binary
//! (`bBCR-1.0`, `bISO-1.0`).
//!
//! An ASCII file is a header of `Key = value` lines (ManufacID, CreateDate, ModDate, NumPoints,
//! NumProfiles, Xscale, Yscale, Zscale, Zresolution, Compression, DataType, CheckType) ended by
//! `*`, the NumPoints × NumProfiles values row by row ended by `*`, and an optional trailer of
//! `Key = value` or `< Key > value < /Key >` lines ended by `*`. A binary file has a fixed
//! 81-byte little-endian header with the same fields, the values, then the same optional
//! trailer. Heights are value × Zscale metres; the spacings are Xscale and Yscale metres.
//! DataType codes follow Gwyddion's `sdfile.c`: 0 uint8, 1 uint16, 2 uint32, 3 float32, 4 int8,
//! 5 int16, 6 int32, 7 float64. Binary integers at the extreme of their type (uint16/uint32
//! maximum, int16/int32 minimum) and NaN floats mark non-measured points; in ASCII files the
//! word `BAD` does (ISO 25178-71's marker for a non-measured point, which MountainsMap writes
//! whatever the DataType).

use super::common::{build_map, data_bytes, grid_points};
use crate::error::{Result, SurfaceError};
use crate::heightmap::{HeightMap, Metadata};
use std::path::Path;

pub(crate) const NAME: &str = "ISO 25178-71 SDF";

/// Size of the binary header: version 8, manufacturer 10, two dates of 12, two u16 sizes, four
/// f64 scales and three u8 codes.
const BINARY_HEADER: usize = 8 + 10 + 2 * 12 + 2 * 2 + 4 * 8 + 3;

/// `a` (ASCII) or `b` (binary), then `BCR-` or `ISO-` and a version.
pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.len() >= 8
        && matches!(bytes[0], b'a' | b'b')
        && matches!(&bytes[1..5], b"BCR-" | b"ISO-")
        && bytes[5].is_ascii_digit()
}

/// The fields both variants share.
struct Header {
    nx: u64,
    ny: u64,
    xscale: f64,
    yscale: f64,
    zscale: f64,
    data_type: u8,
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    if !sniff(bytes) {
        return Err(SurfaceError::format(
            path,
            NAME,
            "the file does not start with an SDF version (aBCR-1.0, bBCR-1.0, aISO-1.0, bISO-1.0)",
        ));
    }
    if bytes[0] == b'a' {
        parse_ascii(path, bytes)
    } else {
        parse_binary(path, bytes)
    }
}

fn parse_ascii(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let text =
        std::str::from_utf8(bytes).map_err(|e| fail(format!("an ASCII SDF must be text: {e}")))?;
    let mut sections = text.splitn(3, '*');
    let (header, data) = match (sections.next(), sections.next()) {
        (Some(h), Some(d)) => (h, d),
        _ => return Err(fail("no '*' ends the header".into())),
    };
    let trailer = sections
        .next()
        .ok_or_else(|| fail("no '*' ends the data: the file is truncated".into()))?;
    let mut fields = Vec::new();
    for line in header
        .lines()
        .skip(1)
        .map(str::trim)
        .filter(|l| !l.is_empty())
    {
        if line.starts_with(';') {
            continue;
        }
        let (key, value) = line
            .split_once('=')
            .ok_or_else(|| fail(format!("header line '{line}' is not 'Key = value'")))?;
        fields.push((key.trim(), value.trim()));
    }
    let get = |key: &str| -> Result<&str> {
        fields
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(key))
            .map(|(_, v)| *v)
            .ok_or_else(|| fail(format!("the header has no {key}")))
    };
    let count = |key: &str| -> Result<u64> {
        let v = get(key)?;
        v.parse()
            .map_err(|_| fail(format!("{key} '{v}' is not a count")))
    };
    let scale = |key: &str| -> Result<f64> {
        let v = get(key)?;
        v.parse::<f64>()
            .ok()
            .filter(|s| s.is_finite() && *s > 0.0)
            .ok_or_else(|| fail(format!("{key} '{v}' is not a positive number")))
    };
    let code = |key: &str| -> Result<u8> {
        let v = get(key)?;
        v.parse()
            .map_err(|_| fail(format!("{key} '{v}' is not a code")))
    };
    let head = Header {
        nx: count("NumPoints")?,
        ny: count("NumProfiles")?,
        xscale: scale("Xscale")?,
        yscale: scale("Yscale")?,
        zscale: scale("Zscale")?,
        data_type: code("DataType")?,
    };
    check_codes(path, code("Compression")?, head.data_type)?;
    let n = grid_points(path, NAME, head.nx, head.ny)?;
    // Each value takes at least one character and one separator.
    data_bytes(path, NAME, n, 2, data.len() + 1)?;
    let mut heights = Vec::with_capacity(n);
    for token in data.split_ascii_whitespace() {
        if heights.len() == n {
            return Err(fail(format!(
                "the data holds more than the {n} values the header states"
            )));
        }
        if token.eq_ignore_ascii_case("BAD") {
            heights.push(f64::NAN);
            continue;
        }
        let value: f64 = token
            .parse()
            .map_err(|_| fail(format!("value {} '{token}' is not a number", heights.len())))?;
        if value.is_infinite() {
            return Err(fail(format!("value {} is infinite", heights.len())));
        }
        heights.push(value * head.zscale);
    }
    if heights.len() != n {
        return Err(fail(format!(
            "the data holds {} values, the header states {} × {} = {n}",
            heights.len(),
            head.nx,
            head.ny
        )));
    }
    let trailer = trailer.trim();
    if !trailer.is_empty() && !trailer.ends_with('*') {
        return Err(fail(
            "no '*' ends the trailer: the file is truncated".into(),
        ));
    }
    let mut map = finish(path, heights, &head)?;
    set_dates(&mut map.meta, get("ManufacID").ok(), get("CreateDate").ok());
    for (key, value) in fields
        .iter()
        .filter(|(k, _)| k.eq_ignore_ascii_case("Zresolution"))
    {
        map.meta.extra.push((key.to_string(), value.to_string()));
    }
    read_trailer(trailer.trim_end_matches('*'), &mut map.meta);
    Ok(map)
}

fn parse_binary(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    if bytes.len() < BINARY_HEADER {
        return Err(fail(format!(
            "the file holds {} bytes, less than the {BINARY_HEADER}-byte binary header",
            bytes.len()
        )));
    }
    let u16_at = |o: usize| u64::from(u16::from_le_bytes([bytes[o], bytes[o + 1]]));
    let f64_at = |o: usize| f64::from_le_bytes(bytes[o..o + 8].try_into().expect("8 bytes"));
    let head = Header {
        nx: u16_at(42),
        ny: u16_at(44),
        xscale: f64_at(46),
        yscale: f64_at(54),
        zscale: f64_at(62),
        data_type: bytes[81 - 2],
    };
    for (name, s) in [
        ("Xscale", head.xscale),
        ("Yscale", head.yscale),
        ("Zscale", head.zscale),
    ] {
        if !(s.is_finite() && s > 0.0) {
            return Err(fail(format!("{name} {s} is not a positive number")));
        }
    }
    check_codes(path, bytes[81 - 3], head.data_type)?;
    let n = grid_points(path, NAME, head.nx, head.ny)?;
    let size = value_size(head.data_type);
    let mut start = BINARY_HEADER;
    let needed = data_bytes(path, NAME, n, size, bytes.len() - start)?;
    // Olympus writes `bISO-1.0` files with two extra u32 fields after the header (Gwyddion's
    // sdfile.c): recognised by the file being exactly 8 bytes longer than header and data.
    if &bytes[..8] == b"bISO-1.0" && bytes.len() == BINARY_HEADER + needed + 8 {
        start += 8;
    }
    let data = &bytes[start..start + needed];
    let heights = data
        .chunks_exact(size)
        .map(|b| decode(head.data_type, b).map_or(f64::NAN, |v| v * head.zscale))
        .collect();
    let mut map = finish(path, heights, &head)?;
    let text = |r: std::ops::Range<usize>| String::from_utf8_lossy(&bytes[r]).trim().to_string();
    let (maker, created) = (text(8..18), text(18..30));
    set_dates(&mut map.meta, Some(&maker), Some(&created));
    map.meta
        .extra
        .push(("Zresolution".into(), f64_at(70).to_string()));
    let rest = String::from_utf8_lossy(&bytes[start + needed..]);
    read_trailer(rest.trim().trim_matches('*'), &mut map.meta);
    Ok(map)
}

fn check_codes(path: &Path, compression: u8, data_type: u8) -> Result<()> {
    if compression != 0 {
        return Err(SurfaceError::format(
            path,
            NAME,
            format!("compression {compression} is not supported (only 0, uncompressed)"),
        ));
    }
    if data_type > 7 {
        return Err(SurfaceError::format(
            path,
            NAME,
            format!("DataType {data_type} is not one of 0 to 7"),
        ));
    }
    Ok(())
}

fn value_size(data_type: u8) -> usize {
    match data_type {
        0 | 4 => 1,
        1 | 5 => 2,
        7 => 8,
        _ => 4,
    }
}

/// A binary value, or `None` for the codes that mark non-measured points.
fn decode(data_type: u8, b: &[u8]) -> Option<f64> {
    let v = match data_type {
        0 => f64::from(b[0]),
        1 => f64::from(u16::from_le_bytes([b[0], b[1]])),
        2 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        3 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        4 => f64::from(b[0] as i8),
        5 => f64::from(i16::from_le_bytes([b[0], b[1]])),
        6 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        _ => f64::from_le_bytes(b[..8].try_into().expect("8 bytes")),
    };
    let marker = match data_type {
        1 => f64::from(u16::MAX),
        2 => f64::from(u32::MAX),
        5 => f64::from(i16::MIN),
        6 => f64::from(i32::MIN),
        _ => f64::NAN,
    };
    (v != marker && !v.is_nan()).then_some(v)
}

fn finish(path: &Path, heights: Vec<f64>, head: &Header) -> Result<HeightMap> {
    if heights.iter().any(|h| h.is_infinite()) {
        return Err(SurfaceError::format(path, NAME, "a height is infinite"));
    }
    build_map(
        path,
        NAME,
        heights,
        (head.nx as usize, head.ny as usize),
        (head.xscale, head.yscale),
    )
}

/// Manufacturer into the instrument, and the creation date `DDMMYYYYhhmm` as
/// `YYYY-MM-DDThh:mm` (or as written when it has another shape).
fn set_dates(meta: &mut Metadata, maker: Option<&str>, created: Option<&str>) {
    meta.instrument = maker
        .map(str::trim)
        .filter(|m| !m.is_empty())
        .map(str::to_string);
    meta.date = created.map(str::trim).filter(|d| !d.is_empty()).map(|d| {
        if d.len() == 12 && d.bytes().all(|b| b.is_ascii_digit()) {
            format!(
                "{}-{}-{}T{}:{}",
                &d[4..8],
                &d[2..4],
                &d[0..2],
                &d[8..10],
                &d[10..12]
            )
        } else {
            d.to_string()
        }
    });
}

/// Trailer lines `Key = value` or `< Key > value < /Key >` into the metadata.
fn read_trailer(trailer: &str, meta: &mut Metadata) {
    for line in trailer.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let pair = if let Some(rest) = line.strip_prefix('<') {
            rest.split_once('>').map(|(key, rest)| {
                let value = rest.rsplit_once('<').map_or(rest, |(v, _)| v);
                (key.trim(), value.trim())
            })
        } else {
            line.split_once('=').map(|(k, v)| (k.trim(), v.trim()))
        };
        if let Some((key, value)) = pair.filter(|(k, _)| !k.is_empty()) {
            meta.extra.push((key.to_string(), value.to_string()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_markers_are_invalid() {
        assert_eq!(decode(5, &i16::MIN.to_le_bytes()), None);
        assert_eq!(decode(5, &(-3i16).to_le_bytes()), Some(-3.0));
        assert_eq!(decode(1, &u16::MAX.to_le_bytes()), None);
        assert_eq!(decode(7, &f64::NAN.to_le_bytes()), None);
        assert_eq!(decode(3, &1.5f32.to_le_bytes()), Some(1.5));
    }

    #[test]
    fn trailer_pairs() {
        let mut meta = Metadata::default();
        read_trailer(
            "< OperatorName > Tom Jones < / OperatorName >\nLens = 50x\n",
            &mut meta,
        );
        assert_eq!(meta.extra[0], ("OperatorName".into(), "Tom Jones".into()));
        assert_eq!(meta.extra[1], ("Lens".into(), "50x".into()));
    }
}
