//! Gwyddion Simple Field (`.gsf`, gwyddion.net/documentation/user-guide-en/gsf.html): the line
//! `Gwyddion Simple Field 1.0`, UTF-8 `Key = Value` lines (XRes, YRes, XReal, YReal, XOffset,
//! YOffset, Title, XYUnits, ZUnits, and any others), 1 to 4 NUL bytes that pad the header to a
//! multiple of 4, then XRes × YRes little-endian float32 values row by row. NaN marks a point
//! that was not measured. gonio also writes `XSpacing` and `YSpacing`, the exact spacings, which
//! it prefers on reading when they agree with XReal / XRes. Units other than metres (mm, µm, nm, pm, Å) are converted; absent
//! units are taken as metres; XReal and YReal default to 1 as the specification says.

use super::common::{build_map, data_bytes, grid_points, unit_scale};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use std::path::Path;

pub(crate) const NAME: &str = "Gwyddion GSF";

const MAGIC: &[u8] = b"Gwyddion Simple Field 1.0\n";

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    if !sniff(bytes) {
        return Err(fail(
            "the file does not start with 'Gwyddion Simple Field 1.0'".into(),
        ));
    }
    let header_len = bytes
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| fail("no NUL byte ends the header: the file is truncated".into()))?;
    let header = std::str::from_utf8(&bytes[MAGIC.len()..header_len])
        .map_err(|e| fail(format!("the header is not UTF-8: {e}")))?;
    let data_start = (header_len / 4 + 1) * 4;
    if bytes.len() < data_start || bytes[header_len..data_start].iter().any(|&b| b != 0) {
        return Err(fail(format!(
            "the header must be padded with NUL bytes up to byte {data_start}"
        )));
    }

    let mut fields = Vec::new();
    for line in header.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let (key, value) = line
            .split_once('=')
            .ok_or_else(|| fail(format!("header line '{line}' is not 'Key = Value'")))?;
        fields.push((key.trim(), value.trim()));
    }
    let get = |key: &str| fields.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
    let count = |key: &str| -> Result<u64> {
        let v = get(key).ok_or_else(|| fail(format!("the header has no {key}")))?;
        v.parse()
            .map_err(|_| fail(format!("{key} '{v}' is not a count")))
    };
    let length = |key: &str| -> Result<f64> {
        let Some(v) = get(key) else { return Ok(1.0) };
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or_else(|| fail(format!("{key} '{v}' is not a positive length")))
    };
    let (nx, ny) = (count("XRes")?, count("YRes")?);
    let n = grid_points(path, NAME, nx, ny)?;
    let needed = data_bytes(path, NAME, n, 4, bytes.len() - data_start)?;
    if bytes.len() - data_start != needed {
        return Err(fail(format!(
            "{} bytes follow the header, XRes × YRes = {n} float32 values take {needed}",
            bytes.len() - data_start
        )));
    }
    let xy_scale = unit_scale(path, NAME, "XYUnits", get("XYUnits").unwrap_or("m"))?;
    let z_scale = unit_scale(path, NAME, "ZUnits", get("ZUnits").unwrap_or("m"))?;
    let (nx, ny) = (nx as usize, ny as usize);
    let dx = spacing(get("XSpacing"), length("XReal")? / nx as f64) * xy_scale;
    let dy = spacing(get("YSpacing"), length("YReal")? / ny as f64) * xy_scale;
    let mut heights = Vec::with_capacity(n);
    for (i, b) in bytes[data_start..].chunks_exact(4).enumerate() {
        let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        if v.is_infinite() {
            return Err(fail(format!(
                "value {i} is infinite (only NaN may mark a missing point)"
            )));
        }
        heights.push(f64::from(v) * z_scale);
    }
    let mut map = build_map(path, NAME, heights, (nx, ny), (dx, dy))?;
    for (key, value) in fields {
        if !matches!(
            key,
            "XRes" | "YRes" | "XReal" | "YReal" | "XYUnits" | "ZUnits"
        ) {
            map.meta.extra.push((key.to_string(), value.to_string()));
        }
    }
    Ok(map)
}

/// Write a map as GSF: heights as float32 metres (NaN where invalid), `XYUnits = m`,
/// `ZUnits = m`, and the spacings as the extra fields `XSpacing` and `YSpacing`, since
/// XReal / XRes in floating point may differ from dx in the last bit. Heights keep float32
/// precision.
pub(crate) fn to_bytes(map: &HeightMap) -> Vec<u8> {
    let mut header = String::from_utf8(MAGIC.to_vec()).expect("ASCII magic");
    let (nx, ny) = (map.nx(), map.ny());
    header += &format!("XRes = {nx}\nYRes = {ny}\n");
    header += &format!(
        "XReal = {:e}\nYReal = {:e}\n",
        map.dx() * nx as f64,
        map.dy() * ny as f64
    );
    header += &format!("XSpacing = {:e}\nYSpacing = {:e}\n", map.dx(), map.dy());
    header += "XYUnits = m\nZUnits = m\n";
    if let Some(source) = &map.meta.source {
        let title = source
            .display()
            .to_string()
            .replace(['\n', '\r', '\0'], " ");
        header += &format!("Title = {title}\n");
    }
    let mut out = header.into_bytes();
    let padding = 4 - out.len() % 4;
    out.resize(out.len() + padding, 0);
    out.reserve(map.heights().len() * 4);
    for &h in map.heights() {
        out.extend_from_slice(&(h as f32).to_le_bytes());
    }
    out
}

/// The spacing a `XSpacing`/`YSpacing` field states (written by gonio) when it agrees with
/// XReal / XRes to 1e-9, else XReal / XRes.
fn spacing(stated: Option<&str>, from_extent: f64) -> f64 {
    stated
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|s| (s - from_extent).abs() <= 1e-9 * from_extent)
        .unwrap_or(from_extent)
}
