//! The long-wave topography of a coating (orange peel) in the bands wave-scan instruments report:
//! the slope of each profile along one direction of a map, band-pass filtered with the Gaussian
//! filter of ISO 16610-21 ([`crate::gaussian_filter`]) between the cutoffs of each band, and its
//! rms in each band.
//!
//! Wave-scan meters scan a laser across some 10 cm of a panel and record the light it reflects,
//! which follows the surface's slope; they report the slope's variance in bands of wavelength
//! (BYK-Gardner's wave-scan: Wa 0.1–0.3 mm, Wb 0.3–1, Wc 1–3, Wd 3–10, We 10–30 mm, and the
//! older short wave 0.3–1.2 mm and long wave 1.2–12 mm) on a 0–100 scale of their own, whose
//! calibration is not public. gonio reports the physical quantity, the rms slope in each band
//! (mrad), and beside it a 0–100 value of its own, `100 (1 − exp(−σ / 3 mrad))` (σ the band's rms
//! slope): 0 for a flat band, 28 at 1 mrad (a visible orange peel), 63 at 3 mrad, rising without
//! reaching 100. It is monotonic with the slope, as the instruments' values are, and is not
//! their scale.
//!
//! A band is measured on every run of consecutive valid slope samples longer than twice its long
//! cutoff (the filter needs a cutoff on either side of each point); a band whose short cutoff is
//! below two spacings is too fine for the sampling, and one that no run is long enough for is
//! too long for the profile: either says so instead of giving a number.

use crate::error::{Result, SurfaceError};
use crate::gaussian_filter;
use crate::heightmap::HeightMap;

/// A band of wavelengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// The instruments' name for it.
    pub name: &'static str,
    /// Its short and long cutoffs, m.
    pub short_m: f64,
    pub long_m: f64,
}

/// The wave-scan bands: Wa–We, then short wave and long wave.
pub const BANDS: [Band; 7] = [
    Band {
        name: "Wa",
        short_m: 0.1e-3,
        long_m: 0.3e-3,
    },
    Band {
        name: "Wb",
        short_m: 0.3e-3,
        long_m: 1e-3,
    },
    Band {
        name: "Wc",
        short_m: 1e-3,
        long_m: 3e-3,
    },
    Band {
        name: "Wd",
        short_m: 3e-3,
        long_m: 10e-3,
    },
    Band {
        name: "We",
        short_m: 10e-3,
        long_m: 30e-3,
    },
    Band {
        name: "SW",
        short_m: 0.3e-3,
        long_m: 1.2e-3,
    },
    Band {
        name: "LW",
        short_m: 1.2e-3,
        long_m: 12e-3,
    },
];

/// The rms slope at which gonio's 0–100 value is 63 (1 − 1/e of the way), rad.
pub const VALUE_SCALE_RAD: f64 = 3e-3;

/// gonio's 0–100 value of a band's rms slope `sigma` (rad): `100 (1 − exp(−σ / 3 mrad))`.
pub fn value(sigma: f64) -> f64 {
    100.0 * (1.0 - (-sigma / VALUE_SCALE_RAD).exp())
}

/// Along which axis of a map the profiles run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Along x: each row is a profile.
    X,
    /// Along y: each column is a profile.
    Y,
}

/// One band's reading.
#[derive(Debug, Clone, PartialEq)]
pub struct BandReading {
    pub band: Band,
    /// The rms of the band-passed slope, rad; `None` when the band cannot be measured.
    pub rms_slope: Option<f64>,
    /// Filtered slope samples behind it.
    pub samples: usize,
    /// Why the band has no number.
    pub unresolved: Option<String>,
}

impl BandReading {
    /// gonio's 0–100 value ([`value`]).
    pub fn value(&self) -> Option<f64> {
        self.rms_slope.map(value)
    }
}

/// The runs of consecutive valid slope samples of `map`'s profiles along `direction`, with the
/// spacing along it: slope `(z[i+1] − z[i]) / d` where both heights are valid.
fn slope_runs(map: &HeightMap, direction: Direction) -> (Vec<Vec<f64>>, f64) {
    let (profiles, points, d) = match direction {
        Direction::X => (map.ny(), map.nx(), map.dx()),
        Direction::Y => (map.nx(), map.ny(), map.dy()),
    };
    let at = |p: usize, i: usize| match direction {
        Direction::X => (i, p),
        Direction::Y => (p, i),
    };
    let mut runs = Vec::new();
    for p in 0..profiles {
        let mut run = Vec::new();
        for i in 0..points.saturating_sub(1) {
            let (a, b) = (at(p, i), at(p, i + 1));
            // `get` is `None` exactly where a point was not measured.
            match (map.get(a.0, a.1), map.get(b.0, b.1)) {
                (Some(z0), Some(z1)) => run.push((z1 - z0) / d),
                _ => {
                    if !run.is_empty() {
                        runs.push(std::mem::take(&mut run));
                    }
                }
            }
        }
        if !run.is_empty() {
            runs.push(run);
        }
    }
    (runs, d)
}

/// The band readings ([`BANDS`]) of `map`'s profiles along `direction` (a line profile runs
/// along x).
pub fn waviness(map: &HeightMap, direction: Direction) -> Result<Vec<BandReading>> {
    let direction = if map.is_profile() {
        Direction::X
    } else {
        direction
    };
    let (runs, d) = slope_runs(map, direction);
    let longest = runs.iter().map(Vec::len).max().unwrap_or(0);
    if longest == 0 {
        return Err(SurfaceError::Invalid(
            "waviness: no two neighbouring valid points along the profiles".into(),
        ));
    }
    let mm = |m: f64| m * 1e3;
    BANDS
        .iter()
        .map(|&band| {
            if band.short_m < 2.0 * d {
                return Ok(BandReading {
                    band,
                    rms_slope: None,
                    samples: 0,
                    unresolved: Some(format!(
                        "too coarse: the spacing {:.4} mm resolves waves down to {:.4} mm, the \
                         band starts at {} mm",
                        mm(d),
                        mm(2.0 * d),
                        mm(band.short_m)
                    )),
                });
            }
            let (mut sum, mut n) = (0.0, 0usize);
            for run in runs
                .iter()
                .filter(|r| (r.len() as f64 - 1.0) * d > 2.0 * band.long_m)
            {
                let b = gaussian_filter::band(run, d, band.short_m, band.long_m)?;
                sum += b.values.iter().map(|v| v * v).sum::<f64>();
                n += b.values.len();
            }
            if n == 0 {
                return Ok(BandReading {
                    band,
                    rms_slope: None,
                    samples: 0,
                    unresolved: Some(format!(
                        "too short: the longest valid run is {:.2} mm, the band needs more than \
                         {} mm (twice its long cutoff)",
                        mm((longest as f64 - 1.0) * d),
                        mm(2.0 * band.long_m)
                    )),
                });
            }
            Ok(BandReading {
                band,
                rms_slope: Some((sum / n as f64).sqrt()),
                samples: n,
                unresolved: None,
            })
        })
        .collect()
}
