//! The visible-normal warp of a table's sampler: the unit square onto half vectors, by the
//! distribution of visible normals of a GGX fitted to the table (Dupuy & Jakob, "An adaptive
//! parameterization for efficient material acquisition and rendering", ACM TOG 37(6), 2018,
//! §5, who warp by the visible normals of the material's own microfacet distribution; here a
//! fitted GGX, sampled by E. Heitz, "Sampling the GGX distribution of visible normals", JCGT
//! 7(4), 2018).
//!
//! A point `(a, y)` of the square maps to Heitz's uniforms `u = (1 - (1 - y)², a - ¼)` (the
//! azimuth taken modulo 1) and so to a normal `h` visible from `wo`. The radial coordinate
//! `y = 1 - √(1 - u.x)` spreads the rim of the disk of visible normals, where the half vectors
//! far from the lobe (those of a diffuse remainder) are crowded: `1 - u.x ≈ α² / tan² θ_h` away
//! from the peak, so `1 - y ≈ α / tan θ_h`. The quarter turn puts the seam of the azimuth on the
//! side of the disk facing away from `wo`, where at grazing `wo` the reflected direction lies
//! below the horizon and the density is zero.
//!
//! The density of `h` per steradian for a density `p(a, y)` on the square is
//! `p · D_vis(h) / (2 (1 - y))` (`D_vis = G1(wo) (wo·h) D(h) / cos θo`, Heitz 2018 eq. 1,
//! the density of Heitz's map of uniform `u`, and `du.x/dy = 2 (1 - y)`); of `wi = reflect(wo, h)`
//! it is that over `4 (wo·h)` (Walter et al. 2007, eq. 14), in which `wo·h` cancels.

use super::BrdfTable;
use super::coords::dir;
use crate::microfacet::Microfacet;
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

    /// The half vector at the point `pos = (a, y)` of the square, seen from `wo` (`wo.z > 0`).
    pub(super) fn half_vector(&self, wo: DVec3, pos: DVec2) -> DVec3 {
        let r = 1.0 - pos.y;
        let u = DVec2::new(1.0 - r * r, (pos.x + 0.75).fract());
        self.ggx.sample_visible(wo, u)
    }

    /// The point of the square that maps to `h` seen from `wo`; `None` if `h` is not visible.
    pub(super) fn point(&self, wo: DVec3, h: DVec3) -> Option<DVec2> {
        let u = self.ggx.invert_visible(wo, h)?;
        let a = (u.y + 0.25).fract();
        Some(DVec2::new(a, 1.0 - (1.0 - u.x).max(0.0).sqrt()))
    }

    /// The density of `wi = reflect(wo, h)` per steradian for a unit density on the square at
    /// `pos` (module doc): `G1(wo) D(h) / (8 (1 - y) cos θo)`; zero on the rim `y = 1`.
    pub(super) fn wi_density(&self, wo: DVec3, h: DVec3, pos: DVec2) -> f64 {
        let rim = 1.0 - pos.y;
        if rim <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        self.ggx.g1(wo) * self.ggx.d(h) / (8.0 * rim * wo.z)
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
