//! Sensofar `.plu` reader: the little-endian SensoSCAN files of Sensofar PLu confocal and
//! interferometric profilers (format versions 2000 and later).
//!
//! Layout, as read by Gwyddion's `sensofar.c` and SurfaceTopography's `PLU.py`: a 500-byte header
//! (128-byte date text, u32 Unix time, 256-byte comment, the axes calibration (u32 rows, cols,
//! N_tall, f32 dy_multip, µm per pixel in x and y, offsets), the measurement configuration
//! (u32 type, algorithm, method, objective, area type; the scan settings; u8 restore, number of
//! layers, version, hardware configuration, ...)). Then, for a topography (type 3): u32 rows,
//! u32 cols and `rows × cols` f32 heights in µm, row by row; 1000001 marks points that were not
//! measured. The file has no magic number: it starts with a C `ctime` date.

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le, unix_time_iso};
use std::path::Path;

pub(crate) const NAME: &str = "Sensofar PLu";

const DATE_SIZE: usize = 128;
const COMMENT_OFFSET: usize = DATE_SIZE + 4;
const COMMENT_SIZE: usize = 256;
const CALIBRATION: usize = COMMENT_OFFSET + COMMENT_SIZE;
const CONFIGURATION: usize = CALIBRATION + 40;
const HEADER_SIZE: usize = 500;

/// Measurement type of a topography (the others are images, profiles, thickness...).
const TYPE_TOPOGRAPHY: u32 = 3;
/// Height value of points that were not measured.
const NOT_MEASURED: f32 = 1_000_001.0;

/// Whether the file starts with a `ctime` date such as `Fri Mar 10 16:35:59 2023`.
pub(crate) fn sniff(bytes: &[u8]) -> bool {
    const DAYS: [&[u8]; 7] = [b"Mon", b"Tue", b"Wed", b"Thu", b"Fri", b"Sat", b"Sun"];
    const MONTHS: [&[u8]; 12] = [
        b"Jan", b"Feb", b"Mar", b"Apr", b"May", b"Jun", b"Jul", b"Aug", b"Sep", b"Oct", b"Nov",
        b"Dec",
    ];
    bytes.len() >= HEADER_SIZE + 8
        && DAYS.contains(&&bytes[0..3])
        && MONTHS.contains(&&bytes[4..7])
        && bytes[3] == b' '
        && bytes[7] == b' '
        && bytes[13] == b':'
        && bytes[16] == b':'
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    b.slice(0, HEADER_SIZE, "header")?;
    let mppx = f64::from(b.f32::<Le>(CALIBRATION + 16, "µm per pixel in x")?);
    let mppy = f64::from(b.f32::<Le>(CALIBRATION + 20, "µm per pixel in y")?);
    let kind = b.u32::<Le>(CONFIGURATION, "measurement type")?;
    if kind != TYPE_TOPOGRAPHY {
        return Err(b.err(format!(
            "measurement type {kind} is not a topography (type 3): images, profiles and \
             thickness measurements are not read"
        )));
    }
    let layers = b.u8(CONFIGURATION + 61, "number of layers")?;
    if layers == 0 {
        return Err(b.err("the header states 0 layers: the file holds no topography"));
    }
    let ny = b.u32::<Le>(HEADER_SIZE, "number of rows")?;
    let nx = b.u32::<Le>(HEADER_SIZE + 4, "number of columns")?;
    let (nx, ny) = b.grid(i64::from(nx), i64::from(ny))?;
    let dx = b.spacing(mppx * 1e-6, "pixel size in x (m)")?;
    let dy = b.spacing(mppy * 1e-6, "pixel size in y (m)")?;
    let values = b.array(HEADER_SIZE + 8, nx * ny, 4, "height data")?;

    let mut heights = Vec::with_capacity(nx * ny);
    for (k, v) in values.chunks_exact(4).enumerate() {
        let v = f32::from_le_bytes([v[0], v[1], v[2], v[3]]);
        if !v.is_finite() {
            return Err(b.err(format!(
                "height {v} at column {}, row {} (heights must be finite; 1000001 marks \
                 non-measured points)",
                k % nx,
                k / nx
            )));
        }
        heights.push(if v == NOT_MEASURED {
            f64::NAN
        } else {
            f64::from(v) * 1e-6
        });
    }
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;

    let meta = &mut map.meta;
    let date = b.text(0, DATE_SIZE, "date")?;
    let time = b.u32::<Le>(DATE_SIZE, "time")?;
    meta.date = if date.is_empty() {
        unix_time_iso(i64::from(time))
    } else {
        Some(date)
    };
    let hardware = b.u8(CONFIGURATION + 63, "hardware configuration")?;
    meta.instrument = Some(format!("Sensofar (hardware configuration {hardware})"));
    let comment = b.text(COMMENT_OFFSET, COMMENT_SIZE, "comment")?;
    if !comment.is_empty() && comment != "(None)" {
        meta.extra.push(("comment".into(), comment));
    }
    for (key, offset) in [("algorithm", 4), ("method", 8), ("objective_code", 12)] {
        let code = b.u32::<Le>(CONFIGURATION + offset, key)?;
        meta.extra.push((key.into(), code.to_string()));
    }
    meta.extra.push((
        "format_version".into(),
        b.u8(CONFIGURATION + 62, "version")?.to_string(),
    ));
    if layers > 1 {
        meta.warn(format!(
            "the file holds {layers} layers; only the first is read"
        ));
    }
    Ok(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny(values: [f32; 6]) -> Vec<u8> {
        let mut f = vec![0u8; HEADER_SIZE];
        f[..24].copy_from_slice(b"Fri Mar 10 16:35:59 2023");
        f[CALIBRATION + 16..CALIBRATION + 20].copy_from_slice(&1.5f32.to_le_bytes());
        f[CALIBRATION + 20..CALIBRATION + 24].copy_from_slice(&2.5f32.to_le_bytes());
        f[CONFIGURATION..CONFIGURATION + 4].copy_from_slice(&TYPE_TOPOGRAPHY.to_le_bytes());
        f[CONFIGURATION + 61] = 1;
        f.extend(2u32.to_le_bytes());
        f.extend(3u32.to_le_bytes());
        for v in values {
            f.extend(v.to_le_bytes());
        }
        f
    }

    #[test]
    fn reads_rows_in_micrometres_with_the_marker_invalid() {
        let bytes = tiny([1.0, 2.0, 3.0, 4.0, NOT_MEASURED, 6.0]);
        assert!(sniff(&bytes));
        let map = parse(Path::new("t.plu"), &bytes).unwrap();
        assert_eq!((map.nx(), map.ny()), (3, 2));
        assert!((map.dx() - 1.5e-6).abs() < 1e-18 && (map.dy() - 2.5e-6).abs() < 1e-18);
        assert!((map.get(2, 0).unwrap() - 3e-6).abs() < 1e-18);
        assert_eq!(map.get(1, 1), None);
        assert_eq!(map.meta.date.as_deref(), Some("Fri Mar 10 16:35:59 2023"));
    }

    #[test]
    fn infinite_heights_and_bad_spacing_are_errors() {
        let p = Path::new("t.plu");
        let e = parse(p, &tiny([1.0, f32::INFINITY, 3.0, 4.0, 5.0, 6.0])).unwrap_err();
        assert!(e.to_string().contains("t.plu"), "{e}");
        let mut bad = tiny([0.0; 6]);
        bad[CALIBRATION + 16..CALIBRATION + 20].copy_from_slice(&(-1.0f32).to_le_bytes());
        assert!(parse(p, &bad).is_err());
        let full = tiny([0.0; 6]);
        assert!(parse(p, &full[..full.len() - 1]).is_err());
    }
}
