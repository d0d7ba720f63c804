//! The visible-normal warp of a table's sampler: the unit square onto half vectors, by the
//! distribution of visible normals of a GGX fitted to the table (Dupuy & Jakob, "An adaptive
//! parameterization for efficient material acquisition and rendering", ACM TOG 37(6), 2018,
//! §5, who warp by the visible normals of the material's own microfacet distribution; here a
//! fitted GGX, sampled by E. Heitz, "Sampling the GGX distribution of visible normals", JCGT
//! 7(4), 2018).
//!
//! A point of the square maps to the unit disk by Shirley & Chiu's concentric map, and the disk
//! point to a normal `h` visible from `wo` by Heitz's half-disk warp and projection
//! ([`Microfacet::visible_normal_on_disk`]). Both steps map a uniform density to a uniform one
//! and then to the visible normals' `D_vis(h) = G1(wo) (wo·h) D(h) / cos θo` (Heitz 2018,
//! eq. 1), so a density `p` on the square gives `h` the density `p D_vis(h)` per steradian, and
//! `wi = reflect(wo, h)` that over `4 (wo·h)` (Walter et al. 2007, eq. 14), in which `wo·h`
//! cancels. The concentric map rather than Heitz's polar one (`r = √u.x`, `φ = 2π u.y`): a
//! polar map cuts the lobe about its centre into thin wedges, and the renderer's
//! low-discrepancy points then stratify it less well (measured in `docs/brdf-tables.md`).

use super::BrdfTable;
use super::coords::dir;
use crate::microfacet::Microfacet;
use crate::sampling::{concentric_disk, concentric_square};
use glam::{DVec2, DVec3};

/// The warp of the unit square onto visible half vectors of a fitted GGX.
#[derive(Debug, Clone, Copy)]
pub(super) struct VisibleNormalWarp {
    ggx: Microfacet,
}

impl VisibleNormalWarp {
    /// The warp of a GGX of roughness `alpha` fitted to `table` ([`fit_alpha`]).
    pub(super) fn fitted(table: &BrdfTable) -> VisibleNormalWarp {
        VisibleNormalWarp {
            ggx: Microfacet::ggx(fit_alpha(table)),
        }
    }

    /// The fitted roughness.
    pub(super) fn alpha(&self) -> f64 {
        self.ggx.alpha_x
    }

    /// The half vector at the point `pos` of the square, seen from `wo` (`wo.z > 0`).
    pub(super) fn half_vector(&self, wo: DVec3, pos: DVec2) -> DVec3 {
        self.ggx.visible_normal_on_disk(wo, concentric_disk(pos))
    }

    /// The point of the square that maps to `h` seen from `wo`; `None` if `h` is not visible.
    pub(super) fn point(&self, wo: DVec3, h: DVec3) -> Option<DVec2> {
        Some(concentric_square(self.ggx.visible_disk_point(wo, h)?))
    }

    /// The density of `wi = reflect(wo, h)` per steradian for a unit density on the square
    /// (module doc): `G1(wo) D(h) / (4 cos θo)`.
    pub(super) fn wi_density(&self, wo: DVec3, h: DVec3) -> f64 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.ggx.g1(wo) * self.ggx.d(h) / (4.0 * wo.z)
    }
}

/// The GGX roughness of `table`'s lobe, from its back-scatter `f(θ, θ)` (where `h = wo`, so
/// that Fresnel is constant and `f cos² θ ∝ D(θ) G2`, Walter et al. 2007 eq. 20): above its floor
/// (the least back-scatter up to 80°), `f cos² θ` falls to half its value at normal incidence at
/// `θ½`, and GGX's `D(θ)/D(0) = 1 / (cos⁴θ (1 + tan²θ/α²)²) = ½` gives
/// `α² = tan²θ½ / (√2 / cos²θ½ - 1)`. Masking is near one at `θ½` for the narrow lobes this
/// matters for. A table without a peak gets `α = 1`; the result is kept in [0.01, 1].
pub(super) fn fit_alpha(table: &BrdfTable) -> f64 {
    let mut f = vec![0.0; table.channel_count()];
    let steps = 720;
    let back: Vec<(f64, f64)> = (0..=steps)
        .map(|k| {
            let theta = 89.0f64.to_radians() * k as f64 / steps as f64;
            let w = dir(theta, 0.0);
            table.eval_channels(w, w, &mut f);
            (theta, BrdfTable::scalar(&f))
        })
        .collect();
    let floor = back
        .iter()
        .filter(|(t, _)| *t <= 80.0f64.to_radians())
        .map(|&(_, v)| v)
        .fold(f64::INFINITY, f64::min);
    let lobe = |(t, v): (f64, f64)| (v - floor) * t.cos().powi(2);
    let peak = lobe(back[0]);
    if !(peak > 0.0 && peak.is_finite()) {
        return 1.0;
    }
    let half = back.windows(2).find_map(|p| {
        let (l0, l1) = (lobe(p[0]) / peak, lobe(p[1]) / peak);
        (l0 > 0.5 && l1 <= 0.5).then(|| p[0].0 + (p[1].0 - p[0].0) * (l0 - 0.5) / (l0 - l1))
    });
    let Some(theta) = half else {
        return 1.0;
    };
    let (c2, t2) = (theta.cos().powi(2), theta.tan().powi(2));
    let denominator = std::f64::consts::SQRT_2 / c2 - 1.0;
    if denominator <= 0.0 {
        return 1.0;
    }
    (t2 / denominator).sqrt().clamp(0.01, 1.0)
}
