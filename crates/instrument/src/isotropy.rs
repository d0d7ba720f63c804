//! The isotropy check: the in-plane curves of a height map and of the same map turned about its
//! normal, and their differences. An isotropic surface scatters the same whatever its azimuth, so
//! the curves differ only by the map's finite statistics; an anisotropic one (brushed, stretched,
//! a grating) changes its lobe with the direction of the plane of incidence, whose width follows
//! the rms slope along that plane (facet model: by the law of reflection, a facet tilted by `a`
//! in the plane of incidence turns the reflected ray by `2a`).
//!
//! The maps come from [`gonio_surface::ops::turned_pair`]: quarter turns are exact (the grid is
//! transposed and flipped, spacings swapped, no height is interpolated); other angles use
//! [`gonio_surface::ops::rotate`] (bicubic spline, corners whose source lies off the map
//! invalid), and both maps are then cropped to the largest centred square that lies inside the
//! turned map, so that the original and the turned map are read over the same area.

use crate::compare::{Comparison, compare};
use crate::error::{InstrumentError, Result};
use gonio_brdf::Ior;
use gonio_io::Progress;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneCurve, InplaneMethod};
use gonio_surface::HeightMap;
use gonio_surface::ops::turned_pair;
use gonio_surface::stats::statistics;

/// How the in-plane curves are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Geometric optics on the map's facets (shadowing and masking on, plane-fit normals).
    Ray,
    /// The scalar Kirchhoff integral at one wavelength (metres) over the largest spot.
    Kirchhoff { wavelength: f64 },
}

/// What to compute.
#[derive(Debug, Clone, PartialEq)]
pub struct IsotropyConfig {
    /// Angles to turn the map by, degrees, counter-clockwise (from +x toward +y).
    pub angles_deg: Vec<f64>,
    /// Refractive index of the coating.
    pub ior: f64,
    /// The in-plane goniometer the curves are read at.
    pub goniometer: Goniometer,
    pub method: Method,
}

impl IsotropyConfig {
    /// A quarter turn at the NIST STARR geometry (incidence 20/45/60/70°, scatter -75..75° in 1°
    /// steps, 1.4° detectors), index 1.55.
    pub fn starr(method: Method) -> Self {
        IsotropyConfig {
            angles_deg: vec![90.0],
            ior: 1.55,
            goniometer: Goniometer::starr(),
            method,
        }
    }
}

/// One orientation of the map, as read.
#[derive(Debug, Clone)]
pub struct Orientation {
    /// Points of the map read (after any crop).
    pub nx: usize,
    pub ny: usize,
    /// rms slope of the facets along x, in the plane of incidence, and along y, across it
    /// (the normals the ray method uses, about their means).
    pub rms_slope_x: f64,
    pub rms_slope_y: f64,
    /// ISO 25178 texture aspect ratio Str in (0, 1] (1: isotropic), when the autocorrelation
    /// decays within the map.
    pub str: Option<f64>,
    /// One curve per incidence.
    pub curves: Vec<InplaneCurve>,
}

/// The check at one angle: the original and the turned map over the same area, and the
/// comparison of the turned map's curves (b) against the original's (a) per incidence.
#[derive(Debug, Clone)]
pub struct RotationCheck {
    pub angle_deg: f64,
    /// Whether the turn was an exact quarter turn (no interpolation, no crop).
    pub exact: bool,
    pub original: Orientation,
    pub rotated: Orientation,
    pub comparisons: Vec<Comparison>,
}

/// Read one orientation: statistics and in-plane curves by the configured method.
fn read(map: &HeightMap, config: &IsotropyConfig) -> Result<Orientation> {
    let ior = Ior::Dielectric(config.ior);
    let engine = RayEngine::new(
        map,
        RayOptions {
            ior,
            ..RayOptions::default()
        },
    )?;
    let (rms_slope_x, rms_slope_y) = engine.rms_slopes();
    let silent = Progress::silent();
    let curves = match config.method {
        Method::Ray => engine.inplane_curves(&config.goniometer, &[], &silent)?,
        Method::Kirchhoff { wavelength } => Kirchhoff::new(map, KirchhoffOptions::new(ior))?
            .inplane_curves(&config.goniometer, &[wavelength * 1e9], &silent)?,
    };
    Ok(Orientation {
        nx: map.nx(),
        ny: map.ny(),
        rms_slope_x,
        rms_slope_y,
        str: statistics(map)?.str,
        curves,
    })
}

/// Run the check for every angle of `config`; `progress` is told what each step is about to do
/// and how many angles are done.
pub fn check(
    map: &HeightMap,
    config: &IsotropyConfig,
    progress: &Progress,
) -> Result<Vec<RotationCheck>> {
    if config.angles_deg.is_empty()
        || config.goniometer.incidences.is_empty()
        || config.goniometer.scatter.is_empty()
    {
        return Err(InstrumentError::Invalid(
            "the isotropy check needs rotation, incidence and scatter angles".into(),
        ));
    }
    // The whole map serves every quarter turn as the original: read it once.
    let mut whole: Option<Orientation> = None;
    let mut checks = Vec::new();
    let total = config.angles_deg.len() as u64;
    for (done, &angle) in config.angles_deg.iter().enumerate() {
        let step = |what: &str| progress.report(what, done as u64, total);
        step(&format!("turning the map by {angle}°"));
        let (original_map, turned_map, exact) = turned_pair(map, angle)?;
        let original = match (&whole, exact) {
            (Some(o), true) => o.clone(),
            _ => {
                step(&format!("{angle}°: curves of the original map"));
                let o = read(&original_map, config)?;
                if exact {
                    whole = Some(o.clone());
                }
                o
            }
        };
        step(&format!("{angle}°: curves of the turned map"));
        let rotated = read(&turned_map, config)?;
        let comparisons = original
            .curves
            .iter()
            .zip(&rotated.curves)
            .map(|(a, b)| {
                compare(a, b).ok_or_else(|| {
                    InstrumentError::Invalid(format!(
                        "incidence {}°: a curve has no positive reflectance",
                        a.incidence_deg
                    ))
                })
            })
            .collect::<Result<Vec<_>>>()?;
        checks.push(RotationCheck {
            angle_deg: angle,
            exact,
            original,
            rotated,
            comparisons,
        });
    }
    Ok(checks)
}
