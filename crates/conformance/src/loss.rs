//! What each renderer's version of a scene loses against the scene itself, in words, and how:
//! a bounded approximation, whose size is added to the tolerance, or a thing the export cannot
//! hold at all, for which a failure is expected and reported as that loss (its tolerance is not
//! loosened).

use crate::Renderer;
use crate::optics::{diffuse_reflectance, mitsuba_diffuse_reflectance};
use crate::scene::{COAT, SceneId};
use serde::Serialize;

/// A loss.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Loss {
    /// What is lost, in words.
    pub text: String,
    /// A bounded approximation: its relative size, added to the tolerance of the region's mean.
    pub tolerance: f64,
    /// The export cannot represent what the scene tests: a failure is expected.
    pub cannot: bool,
}

fn approx(text: impl Into<String>, tolerance: f64) -> Option<Loss> {
    Some(Loss {
        text: text.into(),
        tolerance,
        cannot: false,
    })
}

fn cannot(text: impl Into<String>) -> Option<Loss> {
    Some(Loss {
        text: text.into(),
        tolerance: 0.0,
        cannot: true,
    })
}

/// The loss of `renderer`'s version of scene `id`, if any.
pub fn loss(renderer: Renderer, id: SceneId) -> Option<Loss> {
    match (renderer, id) {
        (Renderer::Gonio, SceneId::MetamerA) => approx(
            "gonio's lights are RGB relative to D65, so illuminant A is folded into the \
             patches' spectra (ρ·A/D65): exact for the patches of this one-bounce scene, but \
             the sky seen directly behind them stays D65's white (FLIP counts it; the regions \
             do not)",
            0.0,
        ),
        (Renderer::Mitsuba, SceneId::Coat) => {
            // Mitsuba's plastic divides the base's light by 1 − R_b r_fit instead of
            // 1 − R_b r_i: the diffuse part changes by (1 − R_b r_i)/(1 − R_b r_fit) − 1,
            // and it is at most the whole radiance.
            let rb = COAT.base_reflectance();
            let exact = diffuse_reflectance(1.0 / COAT.index);
            let fit = mitsuba_diffuse_reflectance(1.0 / COAT.index);
            let rel = ((1.0 - rb * exact) / (1.0 - rb * fit) - 1.0).abs();
            approx(
                format!(
                    "the native plastic plugin stands for the export (a tensor table cannot hold \
                     the coat's delta); it takes the internal diffuse reflectance from a fit \
                     ({fit:.4} against the integral's {exact:.4} at n = {}), which changes the \
                     body reflection by {:.2}%",
                    COAT.index,
                    100.0 * rel
                ),
                rel,
            )
        }
        (Renderer::Mitsuba, SceneId::Mirror) => approx(
            "the native plastic plugin with a black base stands for a smooth dielectric: exact",
            0.0,
        ),
        (Renderer::Radiance, SceneId::Coat) => cannot(
            "the XML BSDF (tensor tree) gonio exports holds the coat's body reflection but no \
             delta component: the coat's mirror reflection F(θv)·L is lost",
        ),
        (Renderer::Radiance, SceneId::Mirror) => cannot(
            "Radiance's mirror has one constant reflectance (set to F at 45°); the Fresnel \
             reflectance's change with angle across the reflection is lost",
        ),
        (Renderer::Radiance, SceneId::MetamerA) => cannot(
            "Radiance is RGB: each patch is reduced to its RGB under D65, so the two metamers \
             have the same RGB and stay equal under illuminant A: the pair collapses",
        ),
        (Renderer::Radiance, SceneId::MetamerD65) => approx(
            "Radiance is RGB: each patch is its RGB under D65, which is exact under D65",
            0.0,
        ),
        _ => None,
    }
}
