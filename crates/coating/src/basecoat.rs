//! The pigmented basecoat as a radiative-transfer medium that holds the flakes: a layer of
//! binder (the coat's index, no interface with the clear coat above) of thickness d over the
//! Kubelka-Munk base's diffuse substrate, absorbing and scattering by its pigments, with the
//! effect flakes inside it, in one sheet at a chosen depth or spread through the depth. The
//! transport through it is [`crate::layered`]'s depth-tracking walk (`layered/basecoat.rs`).
//!
//! **Kubelka-Munk to radiative transfer.** The pigments are given by their Kubelka-Munk K and S
//! (the library's, [`crate::pigment_library`], or by hand), mixed by Duncan's rule; the medium
//! needs the absorption and scattering coefficients σa and σs of the radiative-transfer equation
//! and a phase function. For a diffuse field, the relation of D. J. Gate (Appl. Opt. 13, 236,
//! 1974) is `K = 2 σa`, `S = (3/4) σs (1 − g)`: K is twice σa because diffuse light's mean path
//! across a slab is twice its thickness, and S counts what is sent back across the layer's plane.
//! S. N. Thennadil ("Relationship between the Kubelka-Munk scattering and radiative transfer
//! coefficients", JOSA A 25(7), 1480, 2008) derives the same for diffuse incidence and shows,
//! against exact transport, that the form with an absorption term (Star, Marijnissen & van
//! Gemert, Phys. Med. Biol. 33, 437, 1988: `S = (3/4) σs (1 − g) − σa/4`) is the worse one. So
//! `σa = K/2`, `σs = (4/3) S / (1 − g)` ([`transport_coefficients`]), with g = 0. Its error,
//! measured here against the adding-doubling solution of the slab (iadpython, index-matched,
//! diffuse illumination): the opaque reflectance is low by
//! 0.0048 at single-scattering albedo 0.3 (R∞ 0.0696 against 0.0744), 0.0085 at 0.6, 0.0065 at
//! 0.9, 0.0029 at 0.97 and under 0.001 from 0.99; layers of optical thickness 1 by up to 0.018
//! (albedo 0.999); the walk's reflectance of such layers, over substrates 0 and 0.5, is within
//! 0.020 of Kubelka-Munk's (`tests/it/basecoat.rs`). The conversion assumes diffuse light, as
//! Kubelka-Munk does; the walk then carries the collimated light of a real instrument, which
//! Kubelka-Munk cannot.
//!
//! **The phase function** is isotropic (g = 0): a pigment's K and S alone do not fix g, and the
//! transparent toners of a metallic basecoat (phthalocyanines, quinacridones, perylenes milled to
//! tens of nanometres) are Rayleigh scatterers, whose phase function `(3/16π)(1 + cos² θ)` has
//! g = 0 like the isotropic one. Titanium white's particles (about 0.25 µm) scatter forwards
//! (g near 0.5); with g = 0 its σs is its transport coefficient σs(1 − g), which is what a
//! diffuse layer's reflectance depends on (the similarity relation).
//!
//! **The flakes in the layer** ([`FlakeDepth`]). Their optics and tilts are those of
//! [`crate::flakes`]: a flake met from direction w has its normal h distributed as its projected
//! area, `D(h) |w·h| / N(w)`, reflects specularly with R at the local angle and (interference
//! flakes) transmits `1 − R` undeviated; both faces reflect. In a sheet at depth `depth · d` a
//! crossing ray meets a flake with probability `coverage` (the flake layer of
//! [`crate::flakes::FlakeLayer`], now inside the pigment, with Smith's shadowing `cos θ / N(w)`
//! of the light that leaves it). Spread through the depth, the flakes are a sparse medium of
//! platelets, `a_f` of their plane-projected area per unit volume: a ray of direction w meets
//! them at the rate `σf(w) = a_f N(w)` per unit length (`N(w) = cos θ` for flat flakes, so `a_f`
//! per unit depth), and scatters by the kernel `a_f D(h) R / 4`, reciprocal. The coverage keeps
//! its meaning, the fraction of a normal ray's cross-section that the flakes hide across the
//! layer: `1 − exp(−a_f d) = c`, so `a_f = −ln(1 − c)/d` ([`spread_extinction_per_um`]), and a
//! spread coverage must be below 1.

use crate::clear_coat::{Base, Pigment};
use crate::error::{CoatingError, Result};
use crate::flakes::{FlakeLayer, Flakes};
use crate::kubelka_munk::Coefficients;
use crate::layered::{Basecoat, EmbeddedFlakes};
use gonio_color::Spectrum;

/// Where the flakes lie in a Kubelka-Munk basecoat (`[flakes] depth`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FlakeDepth {
    /// One sheet at this fraction of the basecoat's thickness below its top (0: at the top, the
    /// pigment all below the flakes; 1: on the substrate, all above them).
    Sheet(f64),
    /// Spread uniformly through the depth.
    Spread,
}

impl FlakeDepth {
    /// Check the fraction (0 to 1) and, spread, the coverage (below 1).
    pub fn check(&self, coverage: f64) -> Result<()> {
        match *self {
            FlakeDepth::Sheet(f) if !(0.0..=1.0).contains(&f) => {
                Err(CoatingError::Invalid(format!(
                    "flakes.depth {f}: a fraction of the basecoat's thickness from 0 (its top) to \
                     1 (the substrate), or \"spread\""
                )))
            }
            FlakeDepth::Spread if coverage >= 1.0 => Err(CoatingError::Invalid(format!(
                "flakes.coverage {coverage} with depth = \"spread\": must be below 1 (spread \
                 flakes hide 1 − exp(−a d) of a normal ray, never all of it)"
            ))),
            _ => Ok(()),
        }
    }
}

/// The error of the flakes' glint drawn flake by flake ([`crate::glint`], the renderer's
/// discrete flakes and the texture camera) for flakes inside the basecoat, which it does not
/// model (the glint would cross no pigment).
pub fn glint_not_modelled() -> CoatingError {
    CoatingError::Invalid(
        "the flakes' glint drawn flake by flake (discrete flakes, texture) is not modelled for \
         flakes inside the basecoat (flakes.depth): render them smooth"
            .into(),
    )
}

/// The radiative-transfer coefficients `(σa, σs)` (1/µm, isotropic scattering) of a medium of
/// Kubelka-Munk coefficients `km`: `σa = K/2`, `σs = 4S/3` (Gate 1974; Thennadil 2008; module
/// documentation).
pub fn transport_coefficients(km: Coefficients) -> (f64, f64) {
    (0.5 * km.k, 4.0 / 3.0 * km.s)
}

/// The Kubelka-Munk coefficients of a medium of radiative-transfer coefficients `σa`, `σs`
/// (isotropic), the inverse of [`transport_coefficients`].
pub fn kubelka_munk_coefficients(sigma_a: f64, sigma_s: f64) -> Coefficients {
    Coefficients {
        k: 2.0 * sigma_a,
        s: 0.75 * sigma_s,
    }
}

/// The flakes' projected area per unit volume, 1/µm, when `coverage` of a normal ray's
/// cross-section is hidden by flakes spread through `thickness_um`: `−ln(1 − c)/d` (0 for a
/// layer of no thickness or no flakes).
pub fn spread_extinction_per_um(coverage: f64, thickness_um: f64) -> f64 {
    if coverage <= 0.0 || thickness_um <= 0.0 {
        return 0.0;
    }
    -(1.0 - coverage).ln() / thickness_um
}

/// The walk's basecoat ([`crate::layered::Basecoat`]) for `flakes` placed in the Kubelka-Munk
/// `base` at `flakes.depth`, in a binder of index `binder`, at `wavelengths_nm`: the pigments'
/// mixture (Duncan) converted by [`transport_coefficients`], the substrate's reflectance, the
/// flakes' optics. An error when the base is not a Kubelka-Munk layer or has no thickness
/// ([`layer_of`]).
pub fn embedded(
    flakes: &Flakes,
    depth: FlakeDepth,
    base: &Base,
    binder: f64,
    wavelengths_nm: &[f64],
) -> Result<Basecoat> {
    let (pigments, thickness_um, substrate) = layer_of(base)?;
    let (mut absorption, mut scattering, mut rho) = (Vec::new(), Vec::new(), Vec::new());
    for &w in wavelengths_nm {
        let (sa, ss) = transport_coefficients(mixture_at(pigments, w)?);
        absorption.push(sa);
        scattering.push(ss);
        rho.push(substrate.value_at(w));
    }
    let optics = wavelengths_nm
        .iter()
        .map(|&w| flakes.optics(binder, w))
        .collect::<Result<Vec<_>>>()?;
    Ok(Basecoat {
        thickness_um,
        absorption,
        scattering,
        flakes: Some(EmbeddedFlakes {
            depth,
            coverage: flakes.coverage,
            orientation: flakes.orientation(),
            optics: FlakeLayer::new(flakes, optics, rho.clone()),
        }),
        substrate: rho,
    })
}

/// The pigments, thickness (µm) and substrate of the Kubelka-Munk `base` that holds flakes
/// (`flakes.depth`); an error when the base is not a Kubelka-Munk layer or has no thickness.
pub fn layer_of(base: &Base) -> Result<(&[Pigment], f64, &Spectrum)> {
    let Base::KubelkaMunk {
        pigments,
        thickness_um,
        substrate,
    } = base
    else {
        return Err(CoatingError::Invalid(
            "flakes.depth places the flakes inside a pigmented basecoat: it needs [base] kind = \
             \"kubelka-munk\" (leave depth out for flakes over a diffuse base)"
                .into(),
        ));
    };
    if !(*thickness_um > 0.0 && thickness_um.is_finite()) {
        return Err(CoatingError::Invalid(format!(
            "base.thickness_um {thickness_um}: flakes inside the basecoat (flakes.depth) need a \
             basecoat of some thickness"
        )));
    }
    Ok((pigments, *thickness_um, substrate))
}

/// The Kubelka-Munk coefficients of `pigments` mixed by Duncan's rule at `wavelength_nm`.
pub fn mixture_at(pigments: &[Pigment], wavelength_nm: f64) -> Result<Coefficients> {
    let parts = pigments
        .iter()
        .map(|p| {
            Coefficients::new(
                p.k_per_um.value_at(wavelength_nm),
                p.s_per_um.value_at(wavelength_nm),
            )
            .map(|c| (p.concentration, c))
            .map_err(|e| CoatingError::Invalid(format!("pigment {}: {e}", p.name)))
        })
        .collect::<Result<Vec<_>>>()?;
    Coefficients::mixture(&parts)
}
