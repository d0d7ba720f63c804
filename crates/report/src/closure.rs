//! The booth's closure against the multi-angle instrument (`docs/standard.md`, closure (b)),
//! for any front end: at each geometry, what a picture of a flat panel of the material reads
//! (its pixels' mean as CIELAB, with the noise bound: `gonio_render::booth::closure`) beside
//! what `gonio multiangle` reads of the same table (`gonio_instrument::multiangle`, point
//! apertures), and their CIEDE2000 difference (CIE 142:2001).
//!
//! It lives here rather than in `gonio-render` because it needs both the renderer and the
//! instrument, which sit side by side (`coating < instrument, render`): the report crate is the
//! lowest that depends on both, and it is where the comparison is shown.

use crate::Result;
use gonio_brdf::table::BrdfTable;
use gonio_color::{Lab, ciede2000};
use gonio_instrument::multiangle::{self, Geometry, Settings};
use gonio_render::booth::Run;
use gonio_render::booth::closure::{ClosurePicture, read_flat_panel};
use gonio_render::material::Material;

/// One geometry's picture against its instrument.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosureRow {
    pub geometry: Geometry,
    /// `gonio multiangle`'s reading of the table (D65, 10°).
    pub instrument: Lab,
    /// The picture's: its specimen pixels' mean against the perfect diffuser (D65, 10°).
    pub picture: Lab,
    /// CIEDE2000 between the two.
    pub delta_e00: f64,
    /// The picture's noise bound: the largest ΔE00 from moving its mean by three standard
    /// errors in X, Y or Z.
    pub noise_bound: f64,
    /// The pixels averaged.
    pub pixels: usize,
}

/// The closure of `table` (under a smooth top of refractive index `coat`, whose mirror the
/// picture adds and which no non-specular geometry sees) at each of `geometries`, the pictures
/// as `picture` says.
pub fn closure(
    table: &BrdfTable,
    coat: Option<f64>,
    geometries: &[Geometry],
    picture: &ClosurePicture,
    run: &Run,
) -> Result<Vec<ClosureRow>> {
    let reading = multiangle::read_table(table, geometries, &Settings::default())?;
    let mut material = Material::from_table("specimen", table.clone());
    if let Some(n) = coat {
        material = material.with_coat(n);
    }
    reading
        .geometries
        .iter()
        .map(|g| {
            let read = read_flat_panel(
                &material,
                g.geometry.illumination_deg,
                g.geometry.aspecular_deg,
                picture,
                run,
            )?;
            Ok(ClosureRow {
                geometry: g.geometry,
                instrument: g.lab,
                picture: read.lab,
                delta_e00: ciede2000(read.lab, g.lab),
                noise_bound: read.noise_bound,
                pixels: read.mean.pixels,
            })
        })
        .collect()
}
