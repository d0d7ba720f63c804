//! The screen of a colorant selection ([`crate::selection`]): every combination of library
//! pigments scored by a cheap model, its concentrations fitted, so that the full match runs on
//! the best few only (the formulation programs' search: E. Allen, "Colorant formulation and
//! shading", ch. 7 of F. Grum & C. J. Bartleson (eds.), *Optical Radiation Measurements*,
//! vol. 2, Academic Press, 1980, which solves every combination of the colorant file's
//! candidates and keeps the best; R. S. Berns, *Billmeyer and Saltzman's Principles of Color
//! Technology*, 4th ed., Wiley, 2019, ch. 9).
//!
//! The cheap model is the coating's own, made cheap by its structure ([`StackResponse`]): the
//! pigments change only the base's diffuse reflectance ρ(λ) (Kubelka-Munk of the layer over its
//! substrate, `Base::reflectance`), and everything above the base (the coat, its top, the
//! flakes) answers a Lambertian base of albedo ρ with `R = a + b ρ / (1 − c ρ)` at each geometry
//! and wavelength — the adding method for a Lambertian bottom (H. C. van de Hulst, *Multiple
//! Light Scattering*, vol. 2, Academic Press, 1980, ch. 18: the light the base sends up is
//! Lambertian whatever came down, so its interreflections with the stack above form a geometric
//! series in c ρ, c being the stack's diffuse reflectance seen from below). Saunderson's
//! correction `R = k1 + (1 − k1)(1 − k2) ρ / (1 − k2 ρ)` is its special case for a bare surface
//! (`gonio_coating::kubelka_munk::saunderson`). Three readings of the stack over grey bases
//! (ρ = 0, ½, 1, the match's walks and seed 0) give a, b and c; after them a combination costs
//! Kubelka-Munk and a colour conversion per evaluation, no walk. For a smooth top without flakes
//! the coating has a closed form of exactly this shape, so the screen is exact there; for flakes
//! and a rough top it is exact up to the walks' noise, with the other constituents (coverage,
//! tilt, thicknesses) at their start values — which the full match then fits.
//!
//! When the flakes lie inside the pigmented basecoat (`[flakes] depth`) the pigments surround
//! them and are no base under the stack: the screen then reads the coating from a table over the
//! basecoat's optical depths ([`crate::embedded_screen`], chosen by [`Response::measure`]),
//! within 0.2 ΔE00 of the full model plus the walks' noise.
//!
//! Each combination's concentrations are fitted by the match's own search ([`crate::search`],
//! Nelder–Mead within the bounds) on the screen's model, in log10 of the concentration (tints
//! span decades), on the match's objective (mean ΔE00 or rms ΔR).

use crate::coating_sensitivity::Varied;
use crate::embedded_screen::{self, EmbeddedResponse, Grid};
use crate::error::{FormulationError, Result};
use crate::match_objective::{Objective, reflectance_differences, rms};
use crate::search::{Search, best_run, minimise};
use gonio_coating::clear_coat::{Base, Pigment};
use gonio_coating::pigment_library::LibraryPigment;
use gonio_coating::system::Coating;
use gonio_color::{SpectralToXyz, Spectrum, white};
use gonio_instrument::coating_study;
use gonio_instrument::coating_study::Constituent;
use gonio_instrument::multiangle::{
    Geometry, GeometryReading, MultiangleReading, Settings as ReadSettings,
};
use gonio_instrument::multiangle_target::Target;

/// The screen's bounds of a concentration (the fraction of the pigment's paint in the layer,
/// 1 for the paint as it comes): 0.001 (a trace) to 1 (the masstone), searched in log10.
pub const CONCENTRATION_RANGE: (f64, f64) = (1e-3, 1.0);

/// How the screen fits one combination: Nelder–Mead from the middle of the log range and from
/// two Sobol points, then again from the best (a run converges in a few dozen evaluations of a
/// model that costs microseconds).
const SEARCH: Search = Search {
    starts: 3,
    iterations: 200,
    tolerance: 1e-4,
};

/// The grey bases the stack's response is read over.
const GREYS: [f64; 3] = [0.0, 0.5, 1.0];

/// How everything above the base answers a Lambertian base of albedo ρ: `R = a + b ρ/(1 − c ρ)`
/// at each geometry and wavelength (module docs).
#[derive(Clone, Debug)]
pub struct StackResponse {
    geometries: Vec<Geometry>,
    wavelengths_nm: Vec<f64>,
    /// [geometry][band] (a, b, c).
    abc: Vec<Vec<[f64; 3]>>,
    to_xyz: SpectralToXyz,
    settings: ReadSettings,
}

impl StackResponse {
    /// Read `start` with its base replaced by greys of ρ = 0, ½ and 1 at `geometries` and
    /// `wavelengths_nm`, `walks` per geometry, seed 0 (the match's common random numbers).
    pub fn measure(
        start: &Coating,
        geometries: &[Geometry],
        wavelengths_nm: &[f64],
        walks: usize,
    ) -> Result<Self> {
        let readings = GREYS
            .iter()
            .map(|&rho| {
                let mut c = start.clone();
                c.base = Base::Diffuse {
                    reflectance: Spectrum::new(
                        wavelengths_nm.to_vec(),
                        vec![rho; wavelengths_nm.len()],
                    )
                    .map_err(|e| FormulationError::Invalid(e.to_string()))?,
                };
                let evaluator = c.evaluator(wavelengths_nm)?;
                Ok(coating_study::multiangle_reading(
                    &evaluator,
                    wavelengths_nm,
                    geometries,
                    walks,
                    0,
                )?)
            })
            .collect::<Result<Vec<MultiangleReading>>>()?;
        let (r1, r2) = (GREYS[1], GREYS[2]);
        let abc = (0..geometries.len())
            .map(|g| {
                (0..wavelengths_nm.len())
                    .map(|k| {
                        let at = |i: usize| readings[i].geometries[g].reflectance_factor[k];
                        let a = at(0);
                        let (y1, y2) = (at(1) - a, at(2) - a);
                        // y = b ρ/(1 − c ρ) at ρ1 and ρ2: y1/ρ1 − c y1 = y2/ρ2 − c y2.
                        let c = if (y1 - y2).abs() > 1e-12 {
                            ((y1 / r1 - y2 / r2) / (y1 - y2)).clamp(0.0, 0.99)
                        } else {
                            0.0
                        };
                        let b = y1 * (1.0 - c * r1) / r1;
                        [a, b, c]
                    })
                    .collect()
            })
            .collect();
        let settings = ReadSettings::default();
        let to_xyz = SpectralToXyz::new(wavelengths_nm, settings.illuminant, settings.observer)
            .map_err(|e| FormulationError::Invalid(e.to_string()))?;
        Ok(StackResponse {
            geometries: geometries.to_vec(),
            wavelengths_nm: wavelengths_nm.to_vec(),
            abc,
            to_xyz,
            settings,
        })
    }

    /// The multi-angle reading of the coating whose base reflects `rho` (one value per band).
    pub fn reading(&self, rho: &[f64]) -> Result<MultiangleReading> {
        modelled_reading(
            &self.geometries,
            &self.wavelengths_nm,
            self.settings,
            &self.to_xyz,
            |g| {
                self.abc[g]
                    .iter()
                    .zip(rho)
                    .map(|([a, b, c], r)| a + b * r / (1.0 - c * r))
                    .collect()
            },
        )
    }
}

/// The multi-angle reading at `geometries` of a screen's model, whose reflectance factors at the
/// `g`-th geometry (one per band of `wavelengths_nm`) are `factors(g)`: CIE XYZ and CIELAB under
/// `settings`' illuminant and observer, as an instrument's reading gives them.
pub(crate) fn modelled_reading(
    geometries: &[Geometry],
    wavelengths_nm: &[f64],
    settings: ReadSettings,
    to_xyz: &SpectralToXyz,
    factors: impl Fn(usize) -> Vec<f64>,
) -> Result<MultiangleReading> {
    let w = white(settings.illuminant, settings.observer);
    let geometries = geometries
        .iter()
        .enumerate()
        .map(|(g, &geometry)| {
            let reflectance_factor = factors(g);
            let xyz = to_xyz
                .xyz(&reflectance_factor)
                .map_err(|e| FormulationError::Invalid(e.to_string()))?;
            Ok(GeometryReading {
                geometry,
                reflectance_factor,
                xyz,
                lab: xyz.to_lab(w),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(MultiangleReading {
        wavelengths_nm: wavelengths_nm.to_vec(),
        settings,
        geometries,
    })
}

/// The screen's model of the start: [`StackResponse`] when the pigments act through a base under
/// everything else, [`EmbeddedResponse`] when the flakes lie inside the pigmented basecoat
/// (`[flakes] depth`), where the light the flakes reflect crosses the pigments.
#[derive(Clone, Debug)]
pub enum Response {
    Stack(StackResponse),
    Embedded(EmbeddedResponse),
}

impl Response {
    /// The model of `start` ([`Response`]) at `geometries` and `wavelengths_nm`, read with
    /// `walks` per geometry and seed 0; the embedded table reaches the optical depths of up to
    /// `max_pigments` of `candidates` at concentration 1 ([`embedded_screen::reach`]).
    pub fn measure(
        start: &Coating,
        geometries: &[Geometry],
        wavelengths_nm: &[f64],
        walks: usize,
        candidates: &[&LibraryPigment],
        max_pigments: usize,
    ) -> Result<Self> {
        if start.flakes.as_ref().is_some_and(|f| f.depth.is_some()) {
            let reach = embedded_screen::reach(start, candidates, max_pigments, wavelengths_nm)?;
            Ok(Response::Embedded(EmbeddedResponse::measure(
                start,
                geometries,
                wavelengths_nm,
                walks,
                reach,
                &Grid::for_bands(wavelengths_nm),
            )?))
        } else {
            Ok(Response::Stack(StackResponse::measure(
                start,
                geometries,
                wavelengths_nm,
                walks,
            )?))
        }
    }

    /// The multi-angle reading of `coating` (the start with pigments added) by the model.
    pub fn reading(&self, coating: &Coating) -> Result<MultiangleReading> {
        match self {
            Response::Stack(r) => {
                let rho = r
                    .wavelengths_nm
                    .iter()
                    .map(|&w| Ok(coating.base.reflectance(w)?))
                    .collect::<Result<Vec<f64>>>()?;
                r.reading(&rho)
            }
            Response::Embedded(r) => r.reading(coating),
        }
    }

    /// Readings of the real coating the model took.
    pub fn readings(&self) -> usize {
        match self {
            Response::Stack(_) => GREYS.len(),
            Response::Embedded(r) => r.readings(),
        }
    }
}

/// One combination as the screen scored it.
#[derive(Clone, Debug, PartialEq)]
pub struct Screened {
    /// The library pigments added to the start's base, in the library's order.
    pub pigments: Vec<String>,
    /// Their fitted concentrations.
    pub concentrations: Vec<f64>,
    /// The screen's objective at them (the match's: mean ΔE00 or rms ΔR).
    pub score: f64,
}

/// `start`'s base with `pigments` added at `concentrations` (library pigments, named as the
/// library names them, as a description's `library = "NAME"` gives them).
pub fn with_pigments(
    start: &Coating,
    pigments: &[&LibraryPigment],
    concentrations: &[f64],
) -> Result<Coating> {
    let mut c = start.clone();
    let Base::KubelkaMunk {
        pigments: present, ..
    } = &mut c.base
    else {
        return Err(FormulationError::Invalid(
            "selecting pigments needs a base of kind = \"kubelka-munk\" (a layer of pigments); \
             the start's base is kind = \"diffuse\""
                .into(),
        ));
    };
    for (p, &x) in pigments.iter().zip(concentrations) {
        present.push(p.pigment(x)?);
    }
    Ok(c)
}

/// The screen's objective of `start` with `pigments` at `concentrations`, against `target`.
pub fn score(
    response: &Response,
    start: &Coating,
    target: &Target,
    objective: Objective,
    pigments: &[&LibraryPigment],
    concentrations: &[f64],
) -> Result<f64> {
    let coating = with_pigments(start, pigments, concentrations)?;
    let reading = response.reading(&coating)?;
    Ok(match objective {
        Objective::De00 => {
            let de = target.de00(&reading)?;
            de.iter().sum::<f64>() / de.len() as f64
        }
        Objective::Spectral => rms(&reflectance_differences(target, &reading)?),
    })
}

/// Fit the concentrations of `pigments` added to `start` on the screen's model (module docs).
pub fn fit(
    response: &Response,
    start: &Coating,
    target: &Target,
    objective: Objective,
    pigments: &[&LibraryPigment],
) -> Result<Screened> {
    let (lo, hi) = CONCENTRATION_RANGE;
    let varied: Vec<Varied> = pigments
        .iter()
        .map(|p| Varied {
            name: format!("log10 concentration:{}", p.name),
            constituent: Constituent::Concentration(p.name.clone()),
            lo: lo.log10(),
            hi: hi.log10(),
        })
        .collect();
    let of = |u: &[f64]| -> Vec<f64> { u.iter().map(|l| 10f64.powf(*l)).collect() };
    let x0 = vec![0.5 * (lo.log10() + hi.log10()); pigments.len()];
    let search = Search {
        tolerance: SEARCH.tolerance * objective.per_de00(),
        ..SEARCH
    };
    let runs = minimise(
        &varied,
        &x0,
        &search,
        &|u| score(response, start, target, objective, pigments, &of(u)),
        &|_| String::new(),
        &mut |_| {},
    )?;
    let best = best_run(&runs);
    Ok(Screened {
        pigments: pigments.iter().map(|p| p.name.clone()).collect(),
        concentrations: of(&best.to),
        score: best.objective,
    })
}

/// A pigment of `start`'s base, to tell a library pigment already in it.
pub fn base_pigments(start: &Coating) -> &[Pigment] {
    match &start.base {
        Base::KubelkaMunk { pigments, .. } => pigments,
        Base::Diffuse { .. } => &[],
    }
}
