//! NanoFocus µsurf `.nms` reader: the single-image files (version `OM_MS_2.0`) of NanoFocus
//! confocal microscopes.
//!
//! Layout, as read by D. Mendroch's `musurf_reader` (written for NanoFocus's description of
//! `OM_MS_2.0`) and SurfaceTopography's `NMS.py`: a 3468-byte little-endian header, then
//! columns × rows u16 counts row by row, then (when the header says so) an 8-bit intensity
//! image of the same grid. Header fields read: data type (u32 at 0, 2 = unsigned 16-bit),
//! dimension type (u32 at 4, 1 = area), the counts of the lowest and highest height (u32 at 8
//! and 12) and those heights in µm (f64 at 16 and 24), the version string at 32, columns and
//! rows (u32 at 1368, 1372), the x and y steps in nm (f64 at 1376, 1384) and the intensity flag
//! (u32 at 1416). `height = low + (count − n_low) · (high − low) / (n_high − n_low)`; where the
//! intensity image is present, intensity 0 marks a point that was not measured.
//!
//! SurfaceTopography 1.27 takes the steps as millimetres, which makes a 512-point field 160 m
//! wide; `musurf_reader` divides them by 1000 to get µm, i.e. they are nanometres, and the
//! field is 160 µm (test `nms_lateral_size_is_160_um_not_160_m`).

use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le};
use std::path::Path;

pub(crate) const NAME: &str = "NanoFocus NMS";

const VERSION: &[u8] = b"OM_MS_2.0";
const VERSION_OFFSET: usize = 32;
const HEADER_SIZE: usize = 3468;
const DATA_TYPE_U16: u32 = 2;
const DIMENSION_AREA: u32 = 1;
/// Units of the steps (nm) and of the heights (µm), in metres.
const NM: f64 = 1e-9;
const UM: f64 = 1e-6;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.get(VERSION_OFFSET..VERSION_OFFSET + VERSION.len()) == Some(VERSION)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if b.slice(VERSION_OFFSET, VERSION.len(), "version")? != VERSION {
        return Err(b.err("version 'OM_MS_2.0' missing at offset 32: not a µsurf .nms file"));
    }
    b.slice(0, HEADER_SIZE, "header")?;
    let data_type = b.u32::<Le>(0, "data type")?;
    if data_type != DATA_TYPE_U16 {
        return Err(b.err(format!(
            "data type {data_type} is not 2 (unsigned 16-bit heights)"
        )));
    }
    let dimension = b.u32::<Le>(4, "dimension type")?;
    if dimension != DIMENSION_AREA {
        return Err(b.err(format!(
            "dimension type {dimension} is not 1 (an area): profiles are not read"
        )));
    }
    let n_low = f64::from(b.u32::<Le>(8, "lowest count")?);
    let n_high = f64::from(b.u32::<Le>(12, "highest count")?);
    let z_low = b.f64::<Le>(16, "lowest height")?;
    let z_high = b.f64::<Le>(24, "highest height")?;
    let z_step = (z_high - z_low) / (n_high - n_low) * UM;
    if !(z_step.is_finite() && z_low.is_finite() && n_high != n_low) {
        return Err(b.err(format!(
            "height range {z_low} to {z_high} µm over counts {n_low} to {n_high} does not \
             give a finite height step"
        )));
    }
    let nx = b.u32::<Le>(1368, "number of columns")?;
    let ny = b.u32::<Le>(1372, "number of rows")?;
    let (nx, ny) = b.grid(i64::from(nx), i64::from(ny))?;
    let dx = b.spacing(b.f64::<Le>(1376, "x step")? * NM, "x step (m)")?;
    let dy = b.spacing(b.f64::<Le>(1384, "y step")? * NM, "y step (m)")?;
    let has_intensity = b.u32::<Le>(1416, "intensity flag")? != 0;
    let counts = b.array(HEADER_SIZE, nx * ny, 2, "heights")?;
    let intensity = if has_intensity {
        Some(b.array(HEADER_SIZE + 2 * nx * ny, nx * ny, 1, "intensity image")?)
    } else {
        None
    };
    let heights = counts
        .chunks_exact(2)
        .enumerate()
        .map(|(i, c)| {
            if intensity.is_some_and(|im| im[i] == 0) {
                f64::NAN
            } else {
                z_low * UM + (f64::from(u16::from_le_bytes([c[0], c[1]])) - n_low) * z_step
            }
        })
        .collect();
    let mut map = b.height_map(heights, (nx, ny), (dx, dy))?;
    map.meta.instrument = Some("NanoFocus µsurf".into());
    let date = b.text(1076, 20, "date")?;
    if !date.is_empty() {
        map.meta.date = Some(date);
    }
    let title = b.text(52, 64, "image title")?;
    if !title.is_empty() {
        map.meta.extra.push(("title".into(), title));
    }
    if has_intensity {
        map.meta.extra.push(("channel".into(), "Intensity".into()));
    }
    Ok(map)
}
