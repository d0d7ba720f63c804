//! The long-wave topography of a coating (orange peel) in the bands wave-scan instruments report:
//! the slope or the curvature of each profile along one direction of a map, band-pass filtered
//! with the Gaussian filter of ISO 16610-21 ([`crate::gaussian_filter`]) between the cutoffs of
//! each band, and its rms in each band.
//!
//! Slope is the forward difference `(z[i+1] − z[i]) / d` (rad), curvature the central second
//! difference `(z[i+1] − 2 z[i] + z[i−1]) / d²` (1/m), each where all its heights are valid. For a
//! sine of wavelength λ and amplitude a these have amplitudes `a k sinc(k d/2)` and
//! `a k² sinc²(k d/2)` (`k = 2π/λ`, `sinc x = sin x / x`): short of the derivatives' `a k` and
//! `a k²` by `(π d/λ)²/6` and `(π d/λ)²/3` to leading order, 0.4% and 0.8% at λ = 20 d.
//!
//! Wave-scan meters (BYK-Gardner's wave-scan; the "orange peel meter" of the literature) run a
//! laser spot, incident at 60°, some 10 cm along a panel and record, point by point, the light
//! reflected at the opposite 60° into a detector: an optical profile of the surface. A fixed
//! aperture catches more or less of the beam as the surface under the spot focuses it (concave)
//! or spreads it (convex), so that signal follows the profile's curvature more than its slope;
//! the manufacturers do not publish the transfer. Rhopoint's Optimap PSD, which measures the
//! slopes of a whole area by deflectometry, reports curvature bands Ka–Ke, Ksw, Klw (the
//! standard deviation of the curvature in each band) and a total K over 0.1–30 mm, mapped by
//! regression onto the wave-scan's scale. The meters report the variance in bands of wavelength
//! (BYK-Gardner's wave-scan: Wa 0.1–0.3 mm, Wb 0.3–1, Wc 1–3, Wd 3–10, We 10–30 mm, and the
//! older short wave 0.3–1.2 mm and long wave 1.2–12 mm) on a 0–100 scale of their own, whose
//! calibration is not public. gonio reports physical quantities, the rms slope in each band
//! (mrad) or the rms curvature (1/m), and beside the slope a 0–100 value of its own, `100 (1 − exp(−σ / 3 mrad))` (σ the band's rms
//! slope): 0 for a flat band, 28 at 1 mrad (a visible orange peel), 63 at 3 mrad, rising without
//! reaching 100. It is monotonic with the slope, as the instruments' values are, and is not
//! their scale. Curvature has no 0–100 value.
//!
//! A band is measured on every run of consecutive valid samples longer than twice its long
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

/// What is band-passed: the profile's slope or its curvature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// dz/dx, rad.
    Slope,
    /// d²z/dx², 1/m.
    Curvature,
}

impl Quantity {
    /// Its name, as the command line and JSON write it.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Slope => "slope",
            Quantity::Curvature => "curvature",
        }
    }

    /// The number of consecutive heights one sample needs.
    fn stencil(self) -> usize {
        match self {
            Quantity::Slope => 2,
            Quantity::Curvature => 3,
        }
    }

    /// The sample from `stencil()` consecutive heights `z` at spacing `d`.
    fn sample(self, z: &[f64], d: f64) -> f64 {
        match self {
            Quantity::Slope => (z[1] - z[0]) / d,
            Quantity::Curvature => (z[2] - 2.0 * z[1] + z[0]) / (d * d),
        }
    }
}

/// One band's reading.
#[derive(Debug, Clone, PartialEq)]
pub struct BandReading {
    pub band: Band,
    /// What was band-passed.
    pub quantity: Quantity,
    /// The rms of the band-passed quantity (rad for slope, 1/m for curvature); `None` when the
    /// band cannot be measured.
    pub rms: Option<f64>,
    /// Filtered samples behind it.
    pub samples: usize,
    /// Why the band has no number.
    pub unresolved: Option<String>,
}

impl BandReading {
    /// A band the data cannot measure, and why.
    fn unresolved(band: Band, quantity: Quantity, why: String) -> BandReading {
        BandReading {
            band,
            quantity,
            rms: None,
            samples: 0,
            unresolved: Some(why),
        }
    }

    /// gonio's 0–100 value ([`value`]) of a slope band; `None` for curvature, which gonio gives
    /// no such scale.
    pub fn value(&self) -> Option<f64> {
        match self.quantity {
            Quantity::Slope => self.rms.map(value),
            Quantity::Curvature => None,
        }
    }
}

/// The runs of consecutive valid samples of `quantity` along `map`'s profiles in `direction`,
/// with the spacing along it: a sample where all the heights of its stencil are valid.
fn sample_runs(map: &HeightMap, direction: Direction, quantity: Quantity) -> (Vec<Vec<f64>>, f64) {
    let (profiles, points, d) = match direction {
        Direction::X => (map.ny(), map.nx(), map.dx()),
        Direction::Y => (map.nx(), map.ny(), map.dy()),
    };
    let at = |p: usize, i: usize| match direction {
        Direction::X => map.get(i, p),
        Direction::Y => map.get(p, i),
    };
    let width = quantity.stencil();
    let mut runs = Vec::new();
    let mut z = vec![0.0; width];
    for p in 0..profiles {
        let mut run = Vec::new();
        for i in 0..(points + 1).saturating_sub(width) {
            // `get` is `None` exactly where a point was not measured.
            let valid = (0..width).all(|j| match at(p, i + j) {
                Some(v) => {
                    z[j] = v;
                    true
                }
                None => false,
            });
            if valid {
                run.push(quantity.sample(&z, d));
            } else if !run.is_empty() {
                runs.push(std::mem::take(&mut run));
            }
        }
        if !run.is_empty() {
            runs.push(run);
        }
    }
    (runs, d)
}

/// The band readings ([`BANDS`]) of `quantity` along `map`'s profiles in `direction` (a line
/// profile runs along x).
pub fn waviness(
    map: &HeightMap,
    direction: Direction,
    quantity: Quantity,
) -> Result<Vec<BandReading>> {
    let direction = if map.is_profile() {
        Direction::X
    } else {
        direction
    };
    let (runs, d) = sample_runs(map, direction, quantity);
    let longest = runs.iter().map(Vec::len).max().unwrap_or(0);
    if longest == 0 {
        return Err(SurfaceError::Invalid(format!(
            "waviness: no {} neighbouring valid points along the profiles for a {}",
            quantity.stencil(),
            quantity.name()
        )));
    }
    let mm = |m: f64| m * 1e3;
    BANDS
        .iter()
        .map(|&band| {
            if band.short_m < 2.0 * d {
                return Ok(BandReading::unresolved(
                    band,
                    quantity,
                    format!(
                        "too coarse: the spacing {:.4} mm resolves waves down to {:.4} mm, the \
                         band starts at {} mm",
                        mm(d),
                        mm(2.0 * d),
                        mm(band.short_m)
                    ),
                ));
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
                return Ok(BandReading::unresolved(
                    band,
                    quantity,
                    format!(
                        "too short: the longest valid run is {:.2} mm, the band needs more than \
                         {} mm (twice its long cutoff)",
                        mm((longest as f64 - 1.0) * d),
                        mm(2.0 * band.long_m)
                    ),
                ));
            }
            Ok(BandReading {
                band,
                quantity,
                rms: Some((sum / n as f64).sqrt()),
                samples: n,
                unresolved: None,
            })
        })
        .collect()
}
