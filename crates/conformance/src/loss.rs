//! What each renderer's version of a scene loses against the scene itself, in words, and how:
//! a bounded approximation, whose size is added to the tolerance, or a thing the export cannot
//! hold at all, for which a failure is expected and reported as that loss (its tolerance is not
//! loosened).

use crate::Renderer;
use crate::compare;
use crate::error::Result;
use crate::export::{self, Format};
use crate::optics::{coat_radiance, diffuse_reflectance, fresnel, mitsuba_diffuse_reflectance};
use crate::reference::Reference;
use crate::scene::{COAT, Material, Scene, SceneId};
use crate::suite::Route;
use serde::Serialize;
use std::path::Path;

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

/// The loss of `renderer`'s version of `scene` (whose analytic picture is `reference`) by
/// `route` (its exported files in `dir`), if any.
pub fn loss(
    renderer: Renderer,
    route: Route,
    scene: &Scene,
    reference: &Reference,
    dir: &Path,
) -> Result<Option<Loss>> {
    match route {
        Route::Own => own_loss(scene, reference),
        Route::Export => export_loss(renderer, scene, dir),
        Route::Native => Ok(native_loss(renderer, scene.id)),
    }
}

/// What gonio's own version of `scene` loses: the coat's body is a table ([`export::table`], the
/// closed form at the nodes the renderer computes on loading, `gonio_render::panel::resolution`)
/// and its mirror a delta added by its index (exact). The loss is the table's: the reference
/// picture made again with the coat's reflection under the sky from the table, evaluated by its
/// interpolation ([`export::under_sky`]) plus the mirror's F(θv), and each region's mean compared
/// with the closed form's; the largest relative difference is added to the tolerance. That
/// reflection is computed every 0.5° of view angle and interpolated linearly between, whose
/// error is h²/8 |a''| with h = 0.0087 rad: in the region (view within 60° of the normal) the
/// second differences of a at 5° steps give |a''| < 0.5 per rad², so the error is below 5e-6,
/// 1.3e-5 of a (a ≈ 0.38–0.40). Every other scene's material is exact in gonio (a Lambertian
/// model, a black base under a delta, a constant spectral table).
fn own_loss(scene: &Scene, reference: &Reference) -> Result<Option<Loss>> {
    let Some(coat) = scene.objects.iter().find_map(|o| match &o.material {
        Material::Coat(c) => Some(*c),
        _ => None,
    }) else {
        return Ok(None);
    };
    let table = export::table(&Material::Coat(coat))?;
    let step = 0.5f64.to_radians();
    let under_sky: Vec<f64> = (0..=180)
        .map(|k| {
            let theta_v = k as f64 * step;
            let body = export::under_sky(theta_v, |v, l| {
                let mut out = [0.0];
                table.eval_channels(v, l, &mut out);
                out[0]
            });
            body + fresnel(theta_v.cos(), coat.index)
        })
        .collect();
    let of_cos = |cos: f64| {
        let x = cos.clamp(0.0, 1.0).acos() / step;
        let k = (x as usize).min(179);
        let f = x - k as f64;
        under_sky[k] * (1.0 - f) + under_sky[k + 1] * f
    };
    let tabulated = scene.reference_with_coat(&of_cos)?;
    let error = compare::regions(scene, reference, &tabulated.rgb)
        .iter()
        .map(|r| ((r.value - r.reference) / r.reference).abs())
        .fold(0.0, f64::max);
    Ok(approx(
        format!(
            "the coat's body is the table gonio computes on loading ({} × {} × {} nodes of the \
             closed form): interpolated between them, its reflection under the sky moves the \
             region's mean by {:.3}%; the mirror is exact",
            table.resolution().theta_h,
            table.resolution().theta_d,
            table.resolution().phi_d,
            100.0 * error
        ),
        error,
    ))
}

/// The coat's mirror reflection as a fraction of the coat's radiance under the sky, at normal
/// view and at 60° (the region's edge).
fn coat_mirror_share() -> [f64; 2] {
    let rb = COAT.base_reflectance();
    [0.0f64, 60.0].map(|deg| {
        let c = deg.to_radians().cos();
        fresnel(c, COAT.index) / coat_radiance(c, COAT.index, rb, 1.0)
    })
}

/// The file of an object's export: `(dir, scene, object)` to its path.
type FileOf = fn(&Path, &str, &str) -> std::path::PathBuf;

/// What gonio's export of `scene` to `renderer` loses: the tables' error under the sky
/// ([`export::table_error`], the largest of the scene's objects'), added to the tolerance; and
/// the delta reflections no table holds, as known losses.
fn export_loss(renderer: Renderer, scene: &Scene, dir: &Path) -> Result<Option<Loss>> {
    let (format, file): (Format, FileOf) = match renderer {
        Renderer::Mitsuba => (Format::Mitsuba, export::mitsuba_file),
        Renderer::Radiance => (Format::Radiance, export::radiance_file),
        Renderer::Gonio => return Ok(None),
    };
    let mut error: Option<f64> = None;
    for o in &scene.objects {
        let path = file(dir, scene.id.name(), &o.name);
        if let Some(e) = export::table_error(&o.material, format, &path)? {
            error = Some(error.map_or(e, |w| w.max(e)));
        }
    }
    let what = match format {
        Format::Mitsuba => "the tensor .bsdf",
        Format::Radiance => "the XML BSDF (tensor tree)",
    };
    let table = match error {
        Some(e) => format!(
            "{what}, evaluated as the renderer does and integrated under the sky, is within \
             {:.3}% of the model at view angles 0–70°",
            100.0 * e
        ),
        None => format!("{what} holds each patch's colour as XYZ"),
    };
    Ok(match scene.id {
        SceneId::Coat => {
            let [normal, edge] = coat_mirror_share();
            cannot(format!(
                "{table}, but it holds the coat's body only: no table holds a delta, so the \
                 coat's mirror reflection F(θv)·L is lost, {:.1}% of the reference at normal \
                 view to {:.1}% at 60°",
                100.0 * normal,
                100.0 * edge
            ))
        }
        SceneId::Mirror => cannot(
            "the mirror is a delta reflection over a black base: its table is black, so the \
             whole reflection is lost",
        ),
        SceneId::MetamerA if renderer == Renderer::Radiance => cannot(format!(
            "{table}; Radiance is RGB, so the two metamers, equal under D65, stay equal under \
             illuminant A: the pair collapses"
        )),
        SceneId::Plate | SceneId::MetamerD65 if renderer == Renderer::Radiance => cannot(format!(
            "{table}; the XML holds colour as XYZ relative to the equal-energy white, which \
                 Radiance renders in its own RGB (primaries 0.640/0.330, 0.290/0.600, \
                 0.150/0.060, white E) while the lights and the suite's reading of the pixels \
                 are linear sRGB: colours shift (grey is kept: the furnaces pass)"
        )),
        _ => approx(table, error.unwrap_or(0.0)),
    })
}

/// What `renderer`'s native version of scene `id` loses, if anything.
fn native_loss(renderer: Renderer, id: SceneId) -> Option<Loss> {
    match (renderer, id) {
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
                    "the native plastic plugin takes the internal diffuse reflectance from a fit \
                     ({fit:.4} against the integral's {exact:.4} at n = {}), which changes the \
                     body reflection by {:.2}%",
                    COAT.index,
                    100.0 * rel
                ),
                rel,
            )
        }
        (Renderer::Mitsuba, SceneId::Mirror) => approx(
            "the native plastic plugin with a black base is a smooth dielectric: exact",
            0.0,
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
