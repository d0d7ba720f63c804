//! Zygo MetroPro `.dat` reader: the big-endian binary files written by MetroPro for Zygo
//! interferometers (header formats 1, 2 and 3).
//!
//! Layout, from the MetroPro Reference Guide (Zygo OMP-0347) as read by Gwyddion's `metropro.c`
//! and SurfaceTopography's `MetroPro.py`: a header of `header_size` bytes (834 for formats 1
//! and 2, 4096 for format 3), then `n_buckets` frames of 16-bit intensity data of
//! `ac_width × ac_height`, then the phase data: `cn_width × cn_height` signed 32-bit counts,
//! row by row. Counts of 2147483640 or more mark points that were not measured.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Be, Binary, unix_time_iso};
use std::path::Path;

pub(crate) const NAME: &str = "Zygo MetroPro";

/// Magic numbers of header formats 1, 2 and 3.
const MAGICS: [[u8; 4]; 3] = [
    [0x88, 0x1b, 0x03, 0x6f],
    [0x88, 0x1b, 0x03, 0x70],
    [0x88, 0x1b, 0x03, 0x71],
];

/// Smallest header: format 1 and 2 headers hold 834 bytes and every field read below.
const MIN_HEADER_SIZE: usize = 834;

/// Phase counts at or above this value mark invalid points.
const INVALID_PHASE: i32 = 2_147_483_640;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    MAGICS.iter().any(|m| bytes.starts_with(m))
}

/// Heights in metres from phase counts (MetroPro Reference Guide, "Phase data"):
/// `h = counts · S · O · λ / R`, with `S` the interferometric scale factor, `O` the obliquity
/// factor, `λ` the wavelength in metres and `R` the phase resolution (4096, 32768 or 131072
/// counts per wave for `phase_res` 0, 1, 2).
fn height_per_count(scale: f64, obliquity: f64, wavelength: f64, resolution: f64) -> f64 {
    scale * obliquity * wavelength / resolution
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    let magic = b.slice(0, 4, "magic number")?;
    let format = MAGICS
        .iter()
        .position(|m| m == magic)
        .ok_or_else(|| b.err("not a MetroPro file: magic number 0x881B036F/70/71 missing"))?
        + 1;
    let header_format = usize::from(b.u16::<Be>(4, "header format")?);
    if header_format != format {
        return Err(b.err(format!(
            "header format {header_format} does not match the magic number of format {format}"
        )));
    }
    let header_size = b.u32::<Be>(6, "header size")? as usize;
    if header_size < MIN_HEADER_SIZE {
        return Err(b.err(format!(
            "header size {header_size} is smaller than the {MIN_HEADER_SIZE} bytes of a MetroPro \
             header"
        )));
    }
    b.slice(0, header_size, "header")?;

    let ac_width = usize::from(b.u16::<Be>(52, "intensity width")?);
    let ac_height = usize::from(b.u16::<Be>(54, "intensity height")?);
    let n_buckets = usize::from(b.u16::<Be>(56, "intensity buckets")?);
    let ac_n_bytes = b.u32::<Be>(60, "intensity byte count")? as usize;
    let cn_width = usize::from(b.u16::<Be>(68, "phase width")?);
    let cn_height = usize::from(b.u16::<Be>(70, "phase height")?);
    let cn_n_bytes = b.u32::<Be>(72, "phase byte count")? as usize;

    let intensity_bytes = n_buckets
        .checked_mul(ac_width)
        .and_then(|n| n.checked_mul(ac_height))
        .and_then(|n| n.checked_mul(2))
        .filter(|&n| n == ac_n_bytes)
        .ok_or_else(|| {
            b.err(format!(
                "intensity data: header claims {ac_n_bytes} bytes, which is not {n_buckets} × \
                 {ac_width} × {ac_height} 16-bit values"
            ))
        })?;
    let (nx, ny) = b.grid(cn_width as i64, cn_height as i64)?;
    if nx * ny * 4 != cn_n_bytes {
        return Err(b.err(format!(
            "phase data: header claims {cn_n_bytes} bytes, which is not {nx} × {ny} 32-bit counts"
        )));
    }
    let phase_offset = header_size
        .checked_add(intensity_bytes)
        .ok_or_else(|| b.err("intensity data size overflows"))?;
    let phase = b.array(phase_offset, nx * ny, 4, "phase data")?;

    let scale = f64::from(b.f32::<Be>(164, "interferometric scale factor")?);
    let wavelength = f64::from(b.f32::<Be>(168, "wavelength")?);
    let obliquity = f64::from(b.f32::<Be>(176, "obliquity factor")?);
    let lateral_res = f64::from(b.f32::<Be>(184, "lateral resolution")?);
    let phase_res = b.i16::<Be>(218, "phase resolution")?;
    let inverted = b.i16::<Be>(232, "data sign")? != 0;
    let resolution = match phase_res {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131072.0,
        other => return Err(b.err(format!("phase resolution code {other} is not 0, 1 or 2"))),
    };
    for (name, value) in [
        ("interferometric scale factor", scale),
        ("obliquity factor", obliquity),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(b.err(format!(
                "{name} = {value} must be a positive, finite number"
            )));
        }
    }
    b.spacing(wavelength, "wavelength (m)")?;
    let dx = b.spacing(lateral_res, "lateral resolution (m per pixel)")?;
    let sign = if inverted { -1.0 } else { 1.0 };
    let q = sign * height_per_count(scale, obliquity, wavelength, resolution);

    let heights = phase
        .chunks_exact(4)
        .map(|c| {
            let counts = i32::from_be_bytes([c[0], c[1], c[2], c[3]]);
            if counts >= INVALID_PHASE {
                f64::NAN
            } else {
                q * f64::from(counts)
            }
        })
        .collect();
    let mut map = b.height_map(heights, (nx, ny), (dx, dx))?;

    let meta = &mut map.meta;
    let time_stamp = b.i32::<Be>(76, "time stamp")?;
    meta.date = unix_time_iso(i64::from(time_stamp));
    let system_type = b.i16::<Be>(238, "system type")?;
    let serial = b.u16::<Be>(242, "system serial number")?;
    meta.instrument = Some(format!("Zygo (system type {system_type}, serial {serial})"));
    let version = (
        b.i16::<Be>(42, "software version")?,
        b.i16::<Be>(44, "software version")?,
        b.i16::<Be>(46, "software version")?,
    );
    meta.extra.push((
        "software".into(),
        format!("MetroPro {}.{}.{}", version.0, version.1, version.2),
    ));
    meta.extra
        .push(("wavelength_nm".into(), format!("{}", wavelength * 1e9)));
    meta.extra
        .push(("header_format".into(), format.to_string()));
    for (key, offset, len) in [
        ("comment", 80, 82),
        ("objective", 246, 12),
        ("part", 258, 40),
        ("part_serial", 320, 40),
    ] {
        let value = b.text(offset, len, key)?;
        if !value.is_empty() {
            meta.extra.push((key.into(), value));
        }
    }
    Ok(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_convert_with_the_reference_guide_formula() {
        // One wave of phase (R counts) at S = 0.5 (reflection), O = 1 is half a wavelength.
        let q = height_per_count(0.5, 1.0, 632.8e-9, 32768.0);
        assert!((q * 32768.0 - 316.4e-9).abs() < 1e-18);
    }

    #[test]
    fn rejects_foreign_and_short_files() {
        let p = Path::new("a.dat");
        assert!(parse(p, b"not a zygo file").is_err());
        let mut short = vec![0u8; 100];
        short[..4].copy_from_slice(&MAGICS[0]);
        let e = parse(p, &short).unwrap_err().to_string();
        assert!(e.contains("a.dat"), "{e}");
    }
}
