//! The glint of a coating's flakes: the light that one flake mirrors, entering and leaving
//! through the coat's mean plane, with nothing else on the way. It is what a viewer sees flash
//! when single flakes catch the light (sparkle), and the part of the coating's BRDF that the
//! renderer draws flake by flake (`gonio_render::flakes`): the table it renders with leaves
//! this part out ([`crate::system::Coating::table_without_glint`]) and the discrete flakes
//! put it back, so that averaged over many flakes the picture is the coating's BRDF.
//!
//! Through a smooth interface of index n, with the Fresnel transmittances `T` both ways and
//! the coat's absorption `exp(−τ (1/cos θo' + 1/cos θi'))` (primes: inside), a layer of BRDF
//! `f'` seen from inside has the BRDF `T(θo) T(θi) exp(…) f'(wo', wi') / n²` from outside:
//! radiance entering the coat is multiplied by n² and leaving it divided by n², and the
//! solid angles inside and out are related by `n² cos θ' dω' = cos θ dω` (Snell's law; e.g.
//! M. Born & E. Wolf, *Principles of Optics*, §1.5; the same relation makes the exact clear
//! coat of [`crate::clear_coat`]). Here `f'` is the flakes' lobe ([`FlakeLayer::lobe`]).
//!
//! The glint is refracted through the coat's *mean* plane at one index, the coat's at 550 nm,
//! whatever the top's roughness and dispersion: one flake then mirrors one direction, the same
//! for every band. A rough top blurs the glint a little further (its microfacets tilt the
//! refracted ray by about `α (n − 1)/n` rad: 0.6° for the silver metallic's α 0.03) and a
//! dispersive coat splits it by `Δn/n` of the refraction angle; both are left out of the
//! glint. The rest of the table ([`crate::system::Coating::table_without_glint`]) leaves out
//! the glint as the walks see it, through the rough top: a discrete picture's average differs
//! from the full table by the top's blur of the glint, second order in the blur.

use crate::error::Result;
use crate::flakes::FlakeLayer;
use crate::interface::{Interface, Transport};
use crate::system::Coating;
use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;

/// A coating's flakes' glint, per band ([`Glint::new`]).
#[derive(Clone, Debug)]
pub struct Glint {
    /// The coat's index at 550 nm.
    eta: f64,
    /// σ d per band, the coat's optical thickness at normal incidence.
    tau: Vec<f64>,
    /// The flake layer over a black base (only its lobe is used).
    layer: FlakeLayer,
    /// The distribution of the flakes' normals.
    orientation: Microfacet,
    /// The top interface (its own reflection is what the flakes do not shade).
    top: Interface,
    /// The flakes' mean diameter, m.
    diameter: f64,
    /// The coat's thickness above the flakes, m.
    depth: f64,
    /// The bands, nm.
    wavelengths_nm: Vec<f64>,
}

impl Glint {
    /// The glint of `coating`'s flakes at `wavelengths_nm`; `None` without flakes; an error for
    /// flakes inside the basecoat ([`crate::basecoat::glint_not_modelled`]).
    pub fn new(coating: &Coating, wavelengths_nm: &[f64]) -> Result<Option<Glint>> {
        let Some(flakes) = &coating.flakes else {
            return Ok(None);
        };
        if flakes.depth.is_some() {
            return Err(crate::basecoat::glint_not_modelled());
        }
        coating.check(wavelengths_nm)?;
        let eta = coating.coat.index.at(550.0);
        let optics = wavelengths_nm
            .iter()
            .map(|&w| flakes.optics(eta, w))
            .collect::<Result<Vec<_>>>()?;
        let tau = wavelengths_nm
            .iter()
            .map(|&w| coating.coat.absorption_per_um.value_at(w) * coating.coat.thickness_um)
            .collect();
        Ok(Some(Glint {
            eta,
            tau,
            layer: FlakeLayer::new(flakes, optics, vec![0.0; wavelengths_nm.len()]),
            orientation: flakes.orientation(),
            top: Interface::new(eta, coating.roughness),
            diameter: flakes.diameter_um * 1e-6,
            depth: coating.coat.thickness_um * 1e-6,
            wavelengths_nm: wavelengths_nm.to_vec(),
        }))
    }

    /// The bands, nm.
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The coat's index the glint is refracted with.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// The distribution of the flakes' normals (Beckmann, about the coating's normal).
    pub fn orientation(&self) -> Microfacet {
        self.orientation
    }

    /// The fraction of the base's area the flakes cover.
    pub fn coverage(&self) -> f64 {
        self.layer.coverage()
    }

    /// The flakes' mean diameter, m.
    pub fn diameter(&self) -> f64 {
        self.diameter
    }

    /// How deep the flakes lie under the coat's surface, m (the coat's thickness).
    pub fn depth(&self) -> f64 {
        self.depth
    }

    /// The direction inside the coat (pointing up, away from the flakes) of `w` outside.
    pub fn inside(&self, w: DVec3) -> DVec3 {
        let (x, y) = (w.x / self.eta, w.y / self.eta);
        DVec3::new(x, y, (1.0 - x * x - y * y).max(0.0).sqrt())
    }

    /// The direction outside of `w` inside (pointing up), `None` beyond the critical angle.
    fn outside(&self, w: DVec3) -> Option<DVec3> {
        let (x, y) = (w.x * self.eta, w.y * self.eta);
        let z2 = 1.0 - x * x - y * y;
        (z2 > 0.0).then(|| DVec3::new(x, y, z2.sqrt()))
    }

    /// Multiply `out` (per band) by `T(θo) T(θi) exp(−τ (1/cos θo' + 1/cos θi')) / n²·scale`:
    /// the transmissions both ways and the absorption, for the directions outside (`wo`, `wi`)
    /// and inside (`wo_in`, `wi_in`), and `scale`.
    fn through_coat(&self, [wo, wi, wo_in, wi_in]: [DVec3; 4], scale: f64, out: &mut [f64]) {
        let t = (1.0 - dielectric(wo.z, self.eta)) * (1.0 - dielectric(wi.z, self.eta)) * scale;
        let path = 1.0 / wo_in.z + 1.0 / wi_in.z;
        for (o, tau) in out.iter_mut().zip(&self.tau) {
            *o *= t * (-tau * path).exp();
        }
    }

    /// The glint's BRDF for light from `wi` to `wo` (both outside, above the coating), per band
    /// into `out`, 1/sr: the mean of the discrete flakes' [`Glint::flake`].
    pub fn eval(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return;
        }
        let (wo_in, wi_in) = (self.inside(wo), self.inside(wi));
        self.layer.lobe(wo_in, wi_in, out);
        self.through_coat([wo, wi, wo_in, wi_in], 1.0 / (self.eta * self.eta), out);
    }

    /// The top interface's own reflection for light from `wi` to `wo` (outside), 1/sr: 0 for a
    /// smooth top, whose mirror is a delta kept apart.
    pub fn top_reflection(&self, wo: DVec3, wi: DVec3) -> f64 {
        if self.top.is_smooth() {
            0.0
        } else {
            self.top.f(wo, wi, Transport::Radiance)
        }
    }

    /// What a point of the flake layer lets through towards the viewer at `wo` (outside) of
    /// the light that has been inside the coat, relative to the layer's mean, per band into
    /// `out`: between flakes (`normal` `None`) `1 / a(wo')`, on a flake of normal h
    /// `T_flake(wo'·h) / a(wo')` (0 for metal), with `a(wo') = 1 − c + c T̃(wo')` the mean
    /// ([`FlakeLayer::through`], primes: inside). Its mean over the layer's points is 1, so a
    /// renderer that scales the coating's light from inside by it (a pixel then sees the base
    /// between the flakes, and not through a metal flake) keeps the coating's BRDF on average;
    /// what it scales exactly is the light that leaves through the flake layer from below
    /// (the base's), and the rest (light the flakes send up after bouncing in the coat) is
    /// scaled alike, an approximation of its pattern, not of its mean.
    pub fn body_scale(&self, wo: DVec3, normal: Option<DVec3>, out: &mut [f64]) {
        let w = self.inside(wo);
        for (b, o) in out.iter_mut().enumerate() {
            let a = self.layer.through(b, w);
            let local = match normal {
                None => 1.0,
                Some(h) => self.layer.flake_transmittance(b, w.dot(h).max(0.0)),
            };
            *o = if a > 0.0 { local / a } else { 0.0 };
        }
    }

    /// One flake of normal `h` (the coating's frame, `h.z > 0`) seen from `wo` outside: the
    /// direction outside from which the light it mirrors comes, and per band into `out` the
    /// factor on that light's radiance (transmission both ways, absorption, the flake's
    /// reflectance and its projected-area weight, [`FlakeLayer::mirror`]); `None` (and `out` 0)
    /// when the flake faces away, mirrors the light below its plane or beyond the critical
    /// angle (light that the top reflects back down: not a glint). Averaged over the points
    /// of the layer (a fraction c on flakes, their normals distributed as `D(h) cos θh`), the
    /// reflected radiance is that of [`Glint::eval`]: the radiance crossing the coat scales
    /// by n² and back, and the solid angles inside and out by `n² cos θ' dω' = cos θ dω`.
    pub fn flake(&self, wo: DVec3, h: DVec3, out: &mut [f64]) -> Option<DVec3> {
        if wo.z <= 0.0 {
            out.fill(0.0);
            return None;
        }
        let wo_in = self.inside(wo);
        let exit = self
            .layer
            .mirror(wo_in, h, out)
            .and_then(|wi_in| self.outside(wi_in).map(|wi| (wi, wi_in)));
        let Some((wi, wi_in)) = exit else {
            out.fill(0.0);
            return None;
        };
        self.through_coat([wo, wi, wo_in, wi_in], 1.0, out);
        Some(wi)
    }
}
