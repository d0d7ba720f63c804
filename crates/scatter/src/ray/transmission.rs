//! Transmission: the light each facet refracts into the material under the surface, and where
//! the incident power goes (reflected, transmitted, shadowed, masked).
//!
//! Every facet the source sees refracts the incident ray into a dielectric of relative index
//! `n` (the real part of [`RayOptions::ior`](super::RayOptions)) by Snell's law and carries the
//! fraction `1 - R(wi·n)` of the facet's intercepted share `(wi·n)/(n_z N cos ti)`, the
//! complement of its reflected share (`docs/ray-method.md`, "Transmission"; formulas in
//! [`super::trace`]). With shadowing on, a refracted ray that meets the surface again from
//! below (it would leave the material) is masked: it is followed over the mirrored height field
//! by the same march as the reflected rays. A metal absorbs what it does not reflect, so
//! transmission needs a dielectric and a metal is refused.

use super::hemisphere::TransmissionTable;
use super::march::HeightField;
use super::reflected::Ray;
use super::trace::mirror;
use super::{HemisphereGrid, RayEngine, check_incidence};
use crate::error::{Result, ScatterError};
use glam::DVec3;
use gonio_brdf::Ior;

/// Where the power incident on the map goes, as fractions of the power incident on its mean
/// plane, for one source direction (averaged over the azimuths of incidence). Each facet's
/// intercepted share is split without remainder:
/// `intercepted = shadowed + reflected + reflected_lost + transmitted + transmitted_lost`
/// (to rounding).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyBudget {
    /// Intercepted by the facets facing the source, `Σ (wi·n)/(n_z N cos ti)` over them: 1 for a
    /// facetted surface that tiles its mean plane, within the mean slope times `tan ti` of it.
    pub intercepted: f64,
    /// Intercepted by facets the source does not see (zero without shadowing).
    pub shadowed: f64,
    /// Reflected and leaving the surface: the total of [`RayEngine::detect_hemisphere`].
    pub reflected: f64,
    /// Reflected by lit facets but not leaving: masked, or below the horizon without
    /// shadowing; with a second bounce, less what the second reflection sends out.
    pub reflected_lost: f64,
    /// Refracted and going down into the material: the total of
    /// [`RayEngine::transmit_hemisphere`].
    pub transmitted: f64,
    /// Refracted by lit facets but meeting the surface again from below (masked), or not
    /// descending.
    pub transmitted_lost: f64,
}

impl EnergyBudget {
    fn add(&mut self, other: &EnergyBudget) {
        self.intercepted += other.intercepted;
        self.shadowed += other.shadowed;
        self.reflected += other.reflected;
        self.reflected_lost += other.reflected_lost;
        self.transmitted += other.transmitted;
        self.transmitted_lost += other.transmitted_lost;
    }

    fn scaled(&self, k: f64) -> EnergyBudget {
        EnergyBudget {
            intercepted: self.intercepted * k,
            shadowed: self.shadowed * k,
            reflected: self.reflected * k,
            reflected_lost: self.reflected_lost * k,
            transmitted: self.transmitted * k,
            transmitted_lost: self.transmitted_lost * k,
        }
    }
}

/// Facets per chunk of a budget run (each chunk's partial budget is six numbers).
const BUDGET_CHUNK: usize = 1 << 14;

impl RayEngine {
    /// The relative index of the dielectric under the surface, or an error for a metal or an
    /// index that is not a positive finite number.
    fn dielectric_index(&self) -> Result<f64> {
        match self.options.ior {
            Ior::Dielectric(n) if n.is_finite() && n > 0.0 => Ok(n),
            Ior::Dielectric(n) => Err(ScatterError::Invalid(format!(
                "refractive index {n}: transmission needs a positive finite index"
            ))),
            Ior::Conductor(n) => Err(ScatterError::Invalid(format!(
                "refractive index {n}: transmission needs a dielectric (a real index); a metal \
                 absorbs the light it does not reflect"
            ))),
        }
    }

    /// The height field seen from inside the material (made on first use).
    fn below(&self) -> &HeightField {
        self.below.get_or_init(|| self.field.mirrored())
    }

    /// Sum the light refracted into the material for a source in direction `wi` (unit,
    /// `z > 0`) into the cells of a hemisphere grid mirrored below the surface (see
    /// [`TransmissionTable`]: power-based, Walter's `f_t` per cell). Every transmitted ray lands
    /// in exactly one cell, so the table's total is the transmittance. Needs a dielectric
    /// [`RayOptions::ior`](super::RayOptions); the second bounce does not apply (a refracted ray
    /// that meets the surface again is dropped). As [`RayEngine::detect_hemisphere`], the
    /// result does not depend on the number of threads.
    pub fn transmit_hemisphere(
        &self,
        wi: DVec3,
        grid: &HemisphereGrid,
    ) -> Result<TransmissionTable> {
        let wi = check_incidence(wi)?;
        let n = self.dielectric_index()?;
        let below = self.below();
        let table = self.hemisphere_table(wi, grid, |tracer, f| {
            tracer.transmit(f, below, n).map(|ray| Ray {
                d: mirror(ray.d),
                ..ray
            })
        });
        Ok(TransmissionTable::from_mirrored(table))
    }

    /// Where the power from a source in direction `wi` (unit, `z > 0`) goes: reflected,
    /// transmitted, shadowed or masked ([`EnergyBudget`]), summed per fixed chunk of facets in
    /// chunk order (the same on any number of threads). Needs a dielectric, as
    /// [`RayEngine::transmit_hemisphere`].
    pub fn energy_budget(&self, wi: DVec3) -> Result<EnergyBudget> {
        let wi = check_incidence(wi)?;
        let n = self.dielectric_index()?;
        let below = self.below();
        let partials = self.fold_chunks(
            wi,
            BUDGET_CHUNK,
            EnergyBudget::default,
            |tracer, _, f| {
                let (share, c) = tracer.intercepted(f)?;
                if !tracer.lit(f) {
                    return Some(EnergyBudget {
                        intercepted: share,
                        shadowed: share,
                        ..EnergyBudget::default()
                    });
                }
                let r = self.options.ior.reflectance(c);
                let reflected = tracer.trace(f).map_or(0.0, |ray| ray.w);
                let transmitted = tracer.transmit(f, below, n).map_or(0.0, |ray| ray.w);
                Some(EnergyBudget {
                    intercepted: share,
                    shadowed: 0.0,
                    reflected,
                    reflected_lost: r * share - reflected,
                    transmitted,
                    transmitted_lost: (1.0 - r) * share - transmitted,
                })
            },
            |part, facets| {
                for b in facets {
                    part.add(b);
                }
            },
        );
        let mut total = EnergyBudget::default();
        for p in &partials {
            total.add(p);
        }
        Ok(total.scaled(1.0 / self.options.azimuths as f64))
    }
}
