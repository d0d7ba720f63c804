//! The reflectance a detector cone collects, `rho = ∫_cone f cos t dω`, from the field on the
//! lattice of wave vectors that the spot resolves.
//!
//! With `dvx dvy = k² cos t dω`, the Kirchhoff BRDF of the parent module (Beckmann & Spizzichino
//! 1963, ch. 3 and 5; `docs/kirchhoff.md`) gives
//! `rho = R cos ti / (4π² ∫∫W²) ∫_cone |F E(v)|² / cos t dvx dvy`. `|E|²` is the Fourier
//! transform of the autocorrelation of `W e^(i vz h)`, which vanishes beyond the spot's diameter
//! D, so sampling `E` at spacing `2π/L` (`L ≥ D`, the width of the facet grid) resolves every
//! speckle grain and the sum over the lattice is the integral (exactly, by Parseval, over the whole
//! plane). The lattice points near the detector's central wave vector `v0` come from a zoomed
//! transform: each row of facets (phase taken at `v0`) is Fourier transformed and only the
//! `2P + 1` frequencies within the cone's reach are kept, then those columns are transformed. The
//! phase `vz h` and the facets' sinc factors are taken at `v0` for the whole cone: across a cone of
//! half-angle alpha, `vz` changes by about `k alpha sin ts`, which reshuffles the speckle but
//! changes the mean BRDF only at second order in alpha.

use super::facets::FacetGrid;
use super::kernel::fill_row;
use crate::error::{Result, ScatterError};
use crate::geometry::Detector;
use glam::DVec3;
use gonio_brdf::Ior;
use num_complex::Complex64;
use std::f64::consts::{PI, TAU};

/// Reflectance collected by `detector` for light of wave number `k` arriving from `wi`, each
/// lattice direction `wo` weighted by `visible(wo)` (the shadowing and masking factor).
pub(crate) fn cone_reflectance(
    grid: &FacetGrid,
    ior: Ior,
    k: f64,
    wi: DVec3,
    detector: &Detector,
    visible: impl Fn(DVec3) -> f64,
) -> Result<f64> {
    let axis = detector.direction.normalize();
    let v0 = -k * (wi + axis);
    let (dvx, dvy) = lattice_spacing(grid);
    let reach = reach(k, detector.half_angle);
    let pmax = (reach / dvx).ceil() as usize + 1;
    let qmax = (reach / dvy).ceil() as usize + 1;
    if 2 * pmax + 1 > grid.nx || 2 * qmax + 1 > grid.ny {
        return Err(ScatterError::Invalid(format!(
            "a detector of half-angle {:.3}° reaches beyond the wave vectors that cells of \
             {:.3} × {:.3} µm resolve at this wavelength; use a smaller aperture or a finer map",
            detector.half_angle.to_degrees(),
            grid.ax * 1e6,
            grid.ay * 1e6
        )));
    }
    let np = 2 * pmax + 1;
    let v = [v0.x, v0.y, v0.z];
    let mut columns = vec![Complex64::default(); np * grid.ny];
    let mut row = vec![Complex64::default(); grid.nx];
    let mut scratch = vec![
        Complex64::default();
        grid.row_fft
            .get_inplace_scratch_len()
            .max(grid.col_fft.get_inplace_scratch_len())
    ];
    for m in 0..grid.ny {
        fill_row(&grid.row(m), &grid.row_params(v, v, m), &mut row);
        grid.row_fft.process_with_scratch(&mut row, &mut scratch);
        for (ip, p) in (-(pmax as isize)..=pmax as isize).enumerate() {
            columns[ip * grid.ny + m] = row[p.rem_euclid(grid.nx as isize) as usize];
        }
    }
    let cos_alpha = detector.half_angle.cos();
    let mut sum = 0.0;
    for (ip, column) in columns.chunks_exact_mut(grid.ny).enumerate() {
        grid.col_fft.process_with_scratch(column, &mut scratch);
        let vx = v0.x + (ip as f64 - pmax as f64) * dvx;
        for q in -(qmax as isize)..=qmax as isize {
            let vy = v0.y + q as f64 * dvy;
            let Some(wo) = outgoing(k, wi, vx, vy) else {
                continue;
            };
            if wo.dot(axis) < cos_alpha {
                continue;
            }
            let e = column[q.rem_euclid(grid.ny as isize) as usize];
            sum += visible(wo) * brdf_factor(ior, wi, wo) * e.norm_sqr() / wo.z;
        }
    }
    Ok(sum * dvx * dvy * wi.z / (4.0 * PI * PI * grid.w2_area))
}

/// How far the wave vectors of a cone of half-angle `alpha` reach from its axis's, in x and y:
/// directions within alpha of the axis differ from it by at most `2 sin(alpha/2)`.
pub(crate) fn reach(k: f64, alpha: f64) -> f64 {
    2.0 * k * (0.5 * alpha).sin()
}

/// Spacing of the wave-vector lattice a grid resolves, `2π/(n a)` along x and y.
pub(crate) fn lattice_spacing(grid: &FacetGrid) -> (f64, f64) {
    (
        TAU / (grid.nx as f64 * grid.ax),
        TAU / (grid.ny as f64 * grid.ay),
    )
}

/// The outgoing direction whose wave vector `-k (wi + wo)` has these x and y components, if it
/// lies above the surface.
pub(crate) fn outgoing(k: f64, wi: DVec3, vx: f64, vy: f64) -> Option<DVec3> {
    let (x, y) = (-vx / k - wi.x, -vy / k - wi.y);
    let z2 = 1.0 - x * x - y * y;
    (z2 > 0.0).then(|| DVec3::new(x, y, z2.sqrt()))
}

/// `R(iota) F²` with Beckmann's `F = (1 + wi·wo)/(cos ti (cos ti + cos to))` and the Fresnel
/// reflectance at the local angle `cos iota = sqrt((1 + wi·wo)/2)`, that of the facet that
/// mirrors `wi` into `wo` (`docs/kirchhoff.md`, "The integral").
pub(crate) fn brdf_factor(ior: Ior, wi: DVec3, wo: DVec3) -> f64 {
    let c = wi.dot(wo);
    let f = (1.0 + c) / (wi.z * (wi.z + wo.z));
    ior.reflectance(((1.0 + c) / 2.0).max(0.0).sqrt()) * f * f
}
