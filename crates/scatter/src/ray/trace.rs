//! What one facet does with the incident light: specular reflection, refraction into the
//! material, the power it intercepts, Fresnel reflectance at its local angle, shadowing and
//! masking by the height field and an optional second bounce.
//!
//! Formulas of `docs/ray-method.md`, "Method" and "Transmission" (geometric optics of a faceted
//! surface, as in the facet model of K. E. Torrance & E. M. Sparrow, "Theory for off-specular
//! reflection from roughened surfaces", JOSA 57, 1105 (1967)): a facet of unit normal `n` lit
//! from `wi` intercepts the share `(wi·n) / (n_z N cos ti)` of the power incident on the map's
//! `N` facets (its true area `dx dy / n_z` times `wi·n`, out of the `N dx dy cos ti` the map
//! receives). It reflects `wr = 2(wi·n)n - wi` with the fraction `R(wi·n)` of that share, and
//! refracts the rest, `1 - R(wi·n)`, into a dielectric of relative index `n_rel` along Snell's
//! law in vector form (B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet models for
//! refraction through rough surfaces", EGSR 2007, eq. 40, with `η = 1/n_rel` and `c = wi·n`):
//! `wt = (η c - √(1 - η²(1 - c²))) n - η wi`.

use super::index::BinMask;
use super::march::{Fate, HeightField};
use super::reflected::Ray;
use glam::DVec3;
use gonio_brdf::Ior;
use ndarray::Array2;

/// One facet: a grid point with a valid normal.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Facet {
    /// Position in metres (`x = ix dx`, `y = iy dy`, height).
    pub pos: DVec3,
    /// Unit normal, `n_z > 0`.
    pub n: DVec3,
    /// Row-major index of its grid point, `iy · nx + ix`.
    pub index: usize,
}

/// Everything a facet needs to trace light for one incidence.
pub(crate) struct Tracer<'a> {
    pub field: &'a HeightField,
    /// Normals of every grid point, shape `(ny, nx)`, for the second bounce.
    pub normals: &'a Array2<DVec3>,
    pub ior: Ior,
    pub polarised: bool,
    pub shadowing: bool,
    pub second_bounce: bool,
    /// Source direction in the map's frame.
    pub wi: DVec3,
    /// When the source lies along a grid axis: the horizon map toward it and the slope
    /// `wi_z / |wi_xy|` of the rays toward it (shadowing is then one comparison per facet).
    pub source_horizon: Option<(&'a [f64], f64)>,
    /// Rotation about z that takes map-frame directions into the detectors' frame, as
    /// `(cos, sin)` of the angle.
    pub to_detector: (f64, f64),
    /// `1 / (N cos ti)`.
    pub scale: f64,
    /// When set (and without a second bounce), rays whose direction falls outside these bins
    /// reach no detector and are dropped before the costly shadowing and masking tests.
    pub wanted: Option<&'a BinMask>,
}

impl Tracer<'_> {
    /// Fresnel reflectance at local incidence `cos_i`: unpolarised, s, p.
    fn fresnel(&self, cos_i: f64) -> (f64, f64, f64) {
        if self.polarised {
            let p = self.ior.polarised(cos_i);
            (p.unpolarised(), p.s, p.p)
        } else {
            (self.ior.reflectance(cos_i), 0.0, 0.0)
        }
    }

    /// The share of the incident power that `facet` intercepts, `(wi·n) / (n_z N cos ti)`, and
    /// `wi·n`; `None` when it faces away from the source.
    pub(crate) fn intercepted(&self, facet: &Facet) -> Option<(f64, f64)> {
        let c = self.wi.dot(facet.n);
        (c > 0.0).then(|| (c / facet.n.z * self.scale, c))
    }

    /// Whether the source sees `facet` (always, without shadowing).
    pub(crate) fn lit(&self, facet: &Facet) -> bool {
        !self.shadowing
            || match self.source_horizon {
                Some((horizon, slope)) => slope >= horizon[facet.index],
                None => self.field.escapes(facet.index, facet.pos, self.wi),
            }
    }

    /// The ray a facet sends toward the detectors, or `None` when it faces away from the source,
    /// is shadowed, or its reflected light does not leave the surface.
    pub(crate) fn trace(&self, facet: &Facet) -> Option<Ray> {
        let (power, c) = self.intercepted(facet)?;
        let wr = 2.0 * c * facet.n - self.wi;
        let unwanted = |d: DVec3| {
            self.wanted
                .is_some_and(|m| !m.contains(self.to_detector_frame(d)))
        };
        if !self.second_bounce && (wr.z <= 0.0 || unwanted(wr)) {
            return None;
        }
        if !self.lit(facet) {
            return None;
        }
        let (r, rs, rp) = self.fresnel(c);
        let mut ray = Ray {
            d: wr,
            w: r * power,
            ws: rs * power,
            wp: rp * power,
        };
        if self.second_bounce {
            match self.field.march(facet.pos, wr) {
                Fate::Escapes => {}
                Fate::Hits(p) => ray = self.bounce(ray, p)?,
                Fate::Lost => return None,
            }
        } else if self.shadowing && !self.field.escapes(facet.index, facet.pos, wr) {
            return None;
        }
        ray.d = self.to_detector_frame(ray.d);
        Some(ray)
    }

    /// The ray a facet refracts into a dielectric of relative index `n_rel`, or `None` when it
    /// faces away from the source, is shadowed, no light enters (total reflection, possible only
    /// for `n_rel < 1`), or the refracted ray meets the surface again from below. `below` is the
    /// height field seen from inside the material ([`HeightField::mirrored`]): the refracted
    /// ray, descending under the surface `h`, is followed as the rising ray mirrored in `z`
    /// over the surface `-h`. A refracted ray that does not descend (`wt_z >= 0`, a facet
    /// steeper than the refraction angle) runs up into the surface above it and is dropped,
    /// as a reflected ray below the horizon is. Its share is `(1 - R(wi·n))` times the
    /// intercepted share (and `1 - R_s`, `1 - R_p` for s and p: a dielectric absorbs nothing).
    pub(crate) fn transmit(&self, facet: &Facet, below: &HeightField, n_rel: f64) -> Option<Ray> {
        let (power, c) = self.intercepted(facet)?;
        let wt = refract(self.wi, facet.n, c, 1.0 / n_rel)?;
        if wt.z >= 0.0 || !self.lit(facet) {
            return None;
        }
        if self.shadowing && !below.escapes(facet.index, mirror(facet.pos), mirror(wt)) {
            return None;
        }
        let (r, rs, rp) = self.fresnel(c);
        Some(Ray {
            d: self.to_detector_frame(wt),
            w: (1.0 - r) * power,
            ws: if self.polarised {
                (1.0 - rs) * power
            } else {
                0.0
            },
            wp: if self.polarised {
                (1.0 - rp) * power
            } else {
                0.0
            },
        })
    }

    fn to_detector_frame(&self, d: DVec3) -> DVec3 {
        let (cos, sin) = self.to_detector;
        DVec3::new(cos * d.x - sin * d.y, sin * d.x + cos * d.y, d.z)
    }

    /// Reflect `ray` a second time at the surface point `p`, using the normal of the nearest
    /// facet, and follow it again; `None` if it meets the back of that facet or the surface a
    /// third time.
    fn bounce(&self, ray: Ray, p: DVec3) -> Option<Ray> {
        let (ix, iy) = self.field.nearest(p.x, p.y);
        let n = self.normals[[iy, ix]];
        let c = -ray.d.dot(n);
        if c.is_nan() || c <= 0.0 {
            return None;
        }
        let d = ray.d + 2.0 * c * n;
        if self.field.march(p, d) != Fate::Escapes {
            return None;
        }
        let (r, rs, rp) = self.fresnel(c);
        Some(Ray {
            d,
            w: ray.w * r,
            ws: ray.ws * rs,
            wp: ray.wp * rp,
        })
    }
}

/// The direction refracted at a facet of unit normal `n` from the unit direction `wi` toward the
/// source, with `c = wi·n > 0` and `eta` the index of incidence over that of transmission
/// (Walter et al. 2007, eq. 40); `None` on total internal reflection.
pub(crate) fn refract(wi: DVec3, n: DVec3, c: f64, eta: f64) -> Option<DVec3> {
    let k = 1.0 - eta * eta * (1.0 - c * c);
    (k > 0.0).then(|| (eta * c - k.sqrt()) * n - eta * wi)
}

/// `v` mirrored in the mean plane (`z -> -z`): a point or direction under the surface `h` as
/// seen over the surface `-h`.
pub(crate) fn mirror(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.y, -v.z)
}
