//! The isotropy check: the in-plane curves of a height map and of the same map turned about its
//! normal, and their differences. An isotropic surface scatters the same whatever its azimuth, so
//! the curves differ only by the map's finite statistics; an anisotropic one (brushed, stretched,
//! a grating) changes its lobe with the direction of the plane of incidence, whose width follows
//! the rms slope along that plane (facet model: by the law of reflection, a facet tilted by `a`
//! in the plane of incidence turns the reflected ray by `2a`).
//!
//! Quarter turns are exact: the grid is transposed and flipped, spacings swapped, no height is
//! interpolated. Other angles use [`gonio_surface::ops::rotate`] (bicubic spline, corners whose
//! source lies off the map invalid), and both maps are then cropped to the largest centred square
//! that lies inside the turned map, so that the original and the turned map are read over the
//! same area: the turned crop is the original's crop turned about the same centre.

use crate::compare::{Comparison, compare};
use crate::error::{InstrumentError, Result};
use gonio_brdf::Ior;
use gonio_io::Progress;
use gonio_scatter::InplaneCurve;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::HeightMap;
use gonio_surface::ops::{crop, rotate};
use gonio_surface::stats::statistics;
use ndarray::Array2;

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
    /// Incidence angles, degrees.
    pub incidences_deg: Vec<f64>,
    /// Signed scatter angles, degrees (specular at +incidence).
    pub scatter_deg: Vec<f64>,
    /// Detector half-angle, radians.
    pub half_angle: f64,
    pub method: Method,
}

impl IsotropyConfig {
    /// A quarter turn at the NIST STARR geometry (incidence 20/45/60/70°, scatter -75..75° in 1°
    /// steps, 1.4° detectors), index 1.55.
    pub fn starr(method: Method) -> Self {
        IsotropyConfig {
            angles_deg: vec![90.0],
            ior: 1.55,
            incidences_deg: vec![20.0, 45.0, 60.0, 70.0],
            scatter_deg: (-75..=75).map(f64::from).collect(),
            half_angle: 1.4f64.to_radians(),
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

/// The map turned by `turns` quarter turns counter-clockwise (from +x toward +y) about its
/// centre, exactly: the point at `(x, y)` of the result is the point at `(y, -x)` of `map`
/// (about the centre), as [`rotate`] by 90° would give, but without interpolation; the grid and
/// spacings are swapped for odd turns.
pub fn quarter_turns(map: &HeightMap, turns: i64) -> Result<HeightMap> {
    let mut out = map.clone();
    for _ in 0..turns.rem_euclid(4) {
        let h = out.heights();
        let ny = h.nrows();
        let turned = Array2::from_shape_fn((h.ncols(), ny), |(iy, ix)| h[[ny - 1 - ix, iy]]);
        let meta = out.meta.clone();
        out = HeightMap::with_invalid(turned, out.dy(), out.dx())?;
        out.meta = meta;
    }
    Ok(out)
}

/// The number of quarter turns `angle_deg` is, when it is a whole number of them.
fn as_quarter_turns(angle_deg: f64) -> Option<i64> {
    let q = angle_deg / 90.0;
    ((q - q.round()).abs() < 1e-9).then(|| q.round() as i64)
}

/// The original map and the map turned by `angle_deg`, over the same area: for a quarter turn
/// the whole map and its exact turn; otherwise both cropped to the largest centred square that
/// lies inside the turned map. Returns `(original, turned, exact)`.
pub fn turned_pair(map: &HeightMap, angle_deg: f64) -> Result<(HeightMap, HeightMap, bool)> {
    if !angle_deg.is_finite() {
        return Err(InstrumentError::Invalid(format!(
            "rotation angle {angle_deg}° is not finite"
        )));
    }
    if let Some(turns) = as_quarter_turns(angle_deg) {
        return Ok((map.clone(), quarter_turns(map, turns)?, true));
    }
    // A centred square of half-side h turned by theta stays inside the half-extents (a, b) when
    // h (|cos| + |sin|) <= min(a, b); one point of margin keeps its corners off the edge.
    let theta = angle_deg.to_radians();
    let a = 0.5 * (map.nx() - 1) as f64 * map.dx();
    let b = 0.5 * (map.ny() - 1) as f64 * map.dy();
    let half = a.min(b) / (theta.cos().abs() + theta.sin().abs());
    // Points along an axis of `n` with spacing `d`: the same parity as `n`, so the crop is
    // centred exactly, and within 2·half less one point of margin.
    let side = |n: usize, d: f64| -> usize {
        let fit = ((2.0 * half / d).floor() as usize).saturating_sub(1);
        let mut m = fit.min(n);
        if (n - m) % 2 == 1 {
            m = m.saturating_sub(1);
        }
        m
    };
    let (cx, cy) = (side(map.nx(), map.dx()), side(map.ny(), map.dy()));
    if cx < 8 || cy < 8 {
        return Err(InstrumentError::Invalid(format!(
            "the {} × {} map leaves only {cx} × {cy} points inside its turn by {angle_deg}°; \
             use a larger map",
            map.nx(),
            map.ny()
        )));
    }
    let (x0, y0) = ((map.nx() - cx) / 2, (map.ny() - cy) / 2);
    let turned = rotate(map, theta)?;
    Ok((
        crop(map, x0, y0, cx, cy)?,
        crop(&turned, x0, y0, cx, cy)?,
        false,
    ))
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
    let curves = match config.method {
        Method::Ray => config
            .incidences_deg
            .iter()
            .map(|&ti| engine.inplane(ti, &config.scatter_deg, config.half_angle))
            .collect::<Result<Vec<_>, _>>()?,
        Method::Kirchhoff { wavelength } => {
            let radians = |v: &[f64]| v.iter().map(|t| t.to_radians()).collect::<Vec<_>>();
            Kirchhoff::new(map, KirchhoffOptions::new(ior))?.inplane(
                &[wavelength],
                &radians(&config.incidences_deg),
                &radians(&config.scatter_deg),
                config.half_angle,
                &gonio_io::Progress::silent(),
            )?
        }
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
        || config.incidences_deg.is_empty()
        || config.scatter_deg.is_empty()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-square map with unequal spacings and a non-measured point.
    fn odd_map() -> HeightMap {
        let h = Array2::from_shape_fn((5, 7), |(iy, ix)| {
            if (ix, iy) == (1, 3) {
                f64::NAN
            } else {
                1e-7 * (ix as f64 * 1.3 + (iy * iy) as f64 * 0.7).sin()
            }
        });
        HeightMap::with_invalid(h, 1e-6, 2e-6).unwrap()
    }

    /// Four quarter turns give the map back bit for bit; one turn swaps the grid and spacings and
    /// moves the non-measured point where the rotation takes it.
    #[test]
    fn four_quarter_turns_are_the_identity() {
        let map = odd_map();
        let one = quarter_turns(&map, 1).unwrap();
        assert_eq!((one.nx(), one.ny(), one.dx(), one.dy()), (5, 7, 2e-6, 1e-6));
        // Content at (x, y) came from (y, -x) about the centre: point (ix, iy) from (iy, 4 - ix).
        assert!(!one.is_valid(4 - 3, 1));
        assert_eq!(one.valid_count(), map.valid_count());
        let back = quarter_turns(
            &quarter_turns(&quarter_turns(&one, 1).unwrap(), 1).unwrap(),
            1,
        );
        let back = back.unwrap();
        assert_eq!(
            (back.nx(), back.ny(), back.dx(), back.dy()),
            (7, 5, 1e-6, 2e-6)
        );
        for (a, b) in back.heights().iter().zip(map.heights()) {
            assert!(a.to_bits() == b.to_bits(), "{a} != {b}");
        }
        let minus = quarter_turns(&map, -1).unwrap();
        let three = quarter_turns(&map, 3).unwrap();
        assert_eq!(minus.heights().shape(), three.heights().shape());
        assert!(
            minus
                .heights()
                .iter()
                .zip(three.heights())
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }

    /// The exact quarter turn is the interpolating rotation by 90° on a square grid.
    #[test]
    fn quarter_turn_agrees_with_rotate() {
        let n = 9;
        let h = Array2::from_shape_fn((n, n), |(iy, ix)| 1e-7 * ((ix * 3 + iy * 7) % 5) as f64);
        let map = HeightMap::new(h, 1e-6, 1e-6).unwrap();
        let exact = quarter_turns(&map, 1).unwrap();
        let spline = rotate(&map, std::f64::consts::FRAC_PI_2).unwrap();
        for (a, b) in exact.heights().iter().zip(spline.heights()) {
            assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        }
    }

    /// A turn by 45° crops both maps to the largest centred square inside the turned map: for a
    /// 101 × 101 map, half-side 50/√2 = 35.4 points, so 70 points less one of margin, made odd to
    /// stay centred: 69. Every point of the crop is measured; 90° is exact and uncropped.
    #[test]
    fn turned_pair_crops_to_the_inscribed_square() {
        let n = 101;
        let h = Array2::from_shape_fn((n, n), |(iy, ix)| {
            1e-8 * (ix as f64 * 0.3).sin() * iy as f64
        });
        let map = HeightMap::new(h, 1e-6, 1e-6).unwrap();
        let (orig, turned, exact) = turned_pair(&map, 45.0).unwrap();
        assert!(!exact);
        assert_eq!(
            (orig.nx(), orig.ny(), turned.nx(), turned.ny()),
            (69, 69, 69, 69)
        );
        assert_eq!(turned.valid_count(), 69 * 69);
        assert_eq!(orig.get(0, 0), map.get(16, 16));
        let (orig, turned, exact) = turned_pair(&map, -270.0).unwrap();
        assert!(exact && orig.nx() == n && turned.nx() == n);
        // A wide map: the square is set by its short side, and centred on both axes.
        let wide = crop(&map, 0, 20, 101, 40).unwrap();
        let (o, t, _) = turned_pair(&wide, 30.0).unwrap();
        assert_eq!((o.nx(), o.ny()), (27, 26));
        assert_eq!(t.valid_count(), 27 * 26);
        assert!(turned_pair(&map, f64::NAN).is_err());
        let tiny = crop(&map, 0, 0, 9, 9).unwrap();
        assert!(
            turned_pair(&tiny, 45.0)
                .unwrap_err()
                .to_string()
                .contains("larger map")
        );
    }
}
