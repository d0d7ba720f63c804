//! The half/difference parameterisation of Rusinkiewicz ("A new change of variables for efficient
//! BRDF representation", EGWR 1998) and the grid of a tabulated BRDF over it.
//!
//! `h = normalize(wi + wo)` has polar angles (theta_h, phi_h); the difference vector `d` is `wi`
//! expressed in the frame of `h`: `d = Ry(-theta_h) Rz(-phi_h) wi`, with polar angles
//! (theta_d, phi_d). Swapping `wi` and `wo` maps `d` to `-d`, i.e. `phi_d` to `phi_d + π` with the
//! other three angles unchanged, which is what makes reciprocity a property of the grid.
//!
//! Nodes (as in the MERL tables of Matusik et al. 2003, "A data-driven reflectance model"):
//! `theta_h[j] = (π/2) (j/N)²` (square-root spacing: node density grows as `1/sqrt(theta_h)`
//! toward the specular direction), `theta_d[j] = (π/2) j/N`, `phi_d[j] = 2π j/N` and
//! `phi_h[j] = 2π j/N` (both periodic). Queries beyond the last theta node take its value.

use crate::trig::{acos, atan2};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

/// The four Rusinkiewicz angles of a pair of directions, in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfDiff {
    /// Polar angle of the half vector, [0, π/2] for directions above the surface.
    pub theta_h: f64,
    /// Azimuth of the half vector, [0, 2π).
    pub phi_h: f64,
    /// Polar angle of `wi` about the half vector, [0, π/2].
    pub theta_d: f64,
    /// Azimuth of `wi` about the half vector, [0, 2π).
    pub phi_d: f64,
}

/// `v` turned about z by the angle of sine `s` and cosine `c`.
fn rot_z_by(v: DVec3, (s, c): (f64, f64)) -> DVec3 {
    DVec3::new(v.x * c - v.y * s, v.x * s + v.y * c, v.z)
}

/// `v` turned about y by the angle of sine `s` and cosine `c`.
fn rot_y_by(v: DVec3, (s, c): (f64, f64)) -> DVec3 {
    DVec3::new(v.x * c + v.z * s, v.y, -v.x * s + v.z * c)
}

/// An azimuth from `atan2`, in [-π, π], brought into [0, 2π) (as `rem_euclid(2π)` would, without
/// its division: for |a| < 2π both give `a`, or `a + 2π` when `a` is negative).
fn wrap_2pi(a: f64) -> f64 {
    let w = if a < 0.0 { a + TAU } else { a };
    if w >= TAU { 0.0 } else { w }
}

impl HalfDiff {
    /// The angles of the pair (`wi` toward the light, `wo` toward the viewer), both unit length.
    /// `None` when `wi + wo` vanishes (opposite directions).
    pub fn from_dirs(wi: DVec3, wo: DVec3) -> Option<HalfDiff> {
        HalfDiff::from_dirs_with(wi, wo, true)
    }

    /// [`HalfDiff::from_dirs`], with `phi_h` left at 0 unless `with_phi_h` (an isotropic table's
    /// stencil does not read it, and its `atan2` is a good part of the conversion's cost).
    ///
    /// `d = Ry(-theta_h) Rz(-phi_h) wi` with the sines and cosines of the two turns read off `h`
    /// instead of found from the angles: `cos theta_h = h.z`, `sin theta_h = r = |(h.x, h.y)|`
    /// and `(cos phi_h, sin phi_h) = (h.x, h.y) / r`. Then `d.z = wi · h`,
    /// `r d.x = (wi.x h.x + wi.y h.y) h.z - wi.z r²` and `r d.y = wi.y h.x - wi.x h.y`; the
    /// common factor `r > 0` leaves `phi_d = atan2(d.y, d.x)` unchanged, so neither a square
    /// root nor a division is needed. When `h` is on the pole (`r = 0`, `phi_h = 0`),
    /// `d = Ry(-theta_h) wi`.
    pub(crate) fn from_dirs_with(wi: DVec3, wo: DVec3, with_phi_h: bool) -> Option<HalfDiff> {
        let h = (wi + wo).try_normalize()?;
        let theta_h = acos(h.z.clamp(-1.0, 1.0));
        let r2 = h.x * h.x + h.y * h.y;
        let (dx, dy) = if r2 > 0.0 {
            let along = wi.x * h.x + wi.y * h.y;
            (along * h.z - wi.z * r2, wi.y * h.x - wi.x * h.y)
        } else {
            (wi.x * h.z, wi.y)
        };
        let theta_d = acos(wi.dot(h).clamp(-1.0, 1.0));
        let phi_d = wrap_2pi(atan2(dy, dx));
        let phi_h = if with_phi_h {
            wrap_2pi(atan2(h.y, h.x))
        } else {
            0.0
        };
        Some(HalfDiff {
            theta_h,
            phi_h,
            theta_d,
            phi_d,
        })
    }

    /// The pair of directions `(wi, wo)` with these angles (inverse of [`HalfDiff::from_dirs`]).
    pub fn to_dirs(&self) -> (DVec3, DVec3) {
        self.to_dirs_with([
            self.theta_h.sin_cos(),
            self.phi_h.sin_cos(),
            self.theta_d.sin_cos(),
            self.phi_d.sin_cos(),
        ])
    }

    /// [`HalfDiff::to_dirs`] from the `(sine, cosine)` of `theta_h`, `phi_h`, `theta_d` and
    /// `phi_d`, found once for many pairs (a table's nodes share them along each axis).
    pub fn to_dirs_with(&self, trig: [(f64, f64); 4]) -> (DVec3, DVec3) {
        let [(sh, ch), (sph, cph), (sd, cd), (spd, cpd)] = trig;
        let h = DVec3::new(sh * cph, sh * sph, ch);
        let d = DVec3::new(sd * cpd, sd * spd, cd);
        let wi = rot_z_by(rot_y_by(d, trig[0]), trig[1]);
        let wo = 2.0 * wi.dot(h) * h - wi;
        (wi, wo)
    }
}

/// Number of nodes along each of the four angles. `phi_h == 1` means an isotropic table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Resolution {
    pub theta_h: usize,
    pub theta_d: usize,
    pub phi_d: usize,
    pub phi_h: usize,
}

impl Resolution {
    /// An isotropic table (3 angles).
    pub fn isotropic(theta_h: usize, theta_d: usize, phi_d: usize) -> Resolution {
        Resolution {
            theta_h,
            theta_d,
            phi_d,
            phi_h: 1,
        }
    }

    /// An anisotropic table (4 angles).
    pub fn anisotropic(theta_h: usize, theta_d: usize, phi_d: usize, phi_h: usize) -> Resolution {
        Resolution {
            theta_h,
            theta_d,
            phi_d,
            phi_h,
        }
    }

    /// MERL's resolution (90 × 90 × 180 over half the phi_d circle) on the full phi_d circle:
    /// 90 × 90 × 360 nodes.
    pub fn merl_like() -> Resolution {
        Resolution::isotropic(90, 90, 360)
    }

    /// Whether the table has no phi_h dependence.
    pub fn is_isotropic(&self) -> bool {
        self.phi_h == 1
    }

    /// Total number of nodes.
    pub fn cell_count(&self) -> usize {
        self.theta_h * self.theta_d * self.phi_d * self.phi_h
    }

    /// Check the counts: at least 2 theta nodes, an even number (>= 2) of phi_d nodes so that
    /// every node has its reciprocal, and phi_h either 1 or >= 2.
    pub fn validate(&self) -> Result<(), String> {
        if self.theta_h < 2 || self.theta_d < 2 {
            return Err(format!(
                "resolution {}: theta_h and theta_d need at least 2 nodes",
                self.describe()
            ));
        }
        if self.phi_d < 2 || !self.phi_d.is_multiple_of(2) {
            return Err(format!(
                "resolution {}: phi_d needs an even number of nodes (>= 2), so that each node's \
                 reciprocal phi_d + 180° is a node",
                self.describe()
            ));
        }
        if self.phi_h == 0 {
            return Err(format!(
                "resolution {}: phi_h must be 1 (isotropic) or more",
                self.describe()
            ));
        }
        let nodes =
            self.theta_h as u128 * self.theta_d as u128 * self.phi_d as u128 * self.phi_h as u128;
        if nodes > 1 << 32 {
            return Err(format!(
                "resolution {}: more than 2^32 nodes",
                self.describe()
            ));
        }
        Ok(())
    }

    /// `theta_h x theta_d x phi_d [x phi_h]`.
    pub fn describe(&self) -> String {
        if self.is_isotropic() {
            format!("{} x {} x {}", self.theta_h, self.theta_d, self.phi_d)
        } else {
            format!(
                "{} x {} x {} x {}",
                self.theta_h, self.theta_d, self.phi_d, self.phi_h
            )
        }
    }

    /// Linear node index of (phi_h, theta_h, theta_d, phi_d) indices.
    #[inline]
    pub fn cell_index(&self, ph: usize, th: usize, td: usize, pd: usize) -> usize {
        ((ph * self.theta_h + th) * self.theta_d + td) * self.phi_d + pd
    }

    /// The (phi_h, theta_h, theta_d, phi_d) indices of a linear node index.
    #[inline]
    pub fn cell_indices(&self, node: usize) -> [usize; 4] {
        let pd = node % self.phi_d;
        let rest = node / self.phi_d;
        let td = rest % self.theta_d;
        let rest = rest / self.theta_d;
        let th = rest % self.theta_h;
        [rest / self.theta_h, th, td, pd]
    }

    /// The angles of a node.
    pub fn cell_angles(&self, node: usize) -> HalfDiff {
        let [ph, th, td, pd] = self.cell_indices(node);
        let u = th as f64 / self.theta_h as f64;
        HalfDiff {
            theta_h: FRAC_PI_2 * u * u,
            phi_h: TAU * ph as f64 / self.phi_h as f64,
            theta_d: FRAC_PI_2 * td as f64 / self.theta_d as f64,
            phi_d: TAU * pd as f64 / self.phi_d as f64,
        }
    }

    /// The node whose `phi_d` is half a turn from `node`'s: the same pair with `wi` and `wo`
    /// swapped.
    #[inline]
    pub fn reciprocal_cell(&self, node: usize) -> usize {
        let pd = node % self.phi_d;
        node - pd + (pd + self.phi_d / 2) % self.phi_d
    }

    /// The node whose `phi_d` is `node`'s reflected through 0 (`2π − phi_d`): in an isotropic
    /// table, the pair mirrored through the plane of incidence (`phi_h` is 0, so `h` lies in the
    /// x–z plane, and the mirror y → −y turns `d`'s azimuth to its negative).
    #[inline]
    pub fn mirror_cell(&self, node: usize) -> usize {
        let pd = node % self.phi_d;
        node - pd + (self.phi_d - pd) % self.phi_d
    }

    /// The node whose values stand for `node` in a table of a reciprocal BRDF: the lower of
    /// `node` and its [`Resolution::reciprocal_cell`] and, in an isotropic table when `mirror`
    /// (a BRDF also symmetric about the plane of incidence: any isotropic surface without a
    /// handedness), of their [`Resolution::mirror_cell`]s. `phi_d` nodes
    /// `k, k + N/2, N − k, N/2 − k` make one class, so a table computed on its representatives
    /// alone costs half the cells (reciprocity), or about a quarter with the mirror.
    #[inline]
    pub fn representative_cell(&self, node: usize, mirror: bool) -> usize {
        let r = self.reciprocal_cell(node);
        let lowest = node.min(r);
        if mirror && self.is_isotropic() {
            lowest.min(self.mirror_cell(node)).min(self.mirror_cell(r))
        } else {
            lowest
        }
    }

    /// Interpolation stencil of a point: for each of (phi_h, theta_h, theta_d, phi_d) the two
    /// bracketing node indices and the weight of the second.
    #[inline]
    pub fn stencil(&self, a: &HalfDiff) -> [(usize, usize, f64); 4] {
        let th = clamped(
            (a.theta_h.max(0.0) / FRAC_PI_2).sqrt() * self.theta_h as f64,
            self.theta_h,
        );
        let td = clamped(
            a.theta_d.max(0.0) / FRAC_PI_2 * self.theta_d as f64,
            self.theta_d,
        );
        let pd = periodic(a.phi_d / TAU * self.phi_d as f64, self.phi_d);
        let ph = if self.phi_h == 1 {
            (0, 0, 0.0)
        } else {
            periodic(a.phi_h / TAU * self.phi_h as f64, self.phi_h)
        };
        [ph, th, td, pd]
    }

    /// The 16 corners of a point's interpolation stencil: each node's linear index and its
    /// weight in the multilinear interpolation, the product of its four one-dimensional
    /// weights (`1 − t` for the lower node, `t` for the upper). The weights sum to 1; an
    /// isotropic table's phi_h corners, and any axis on a node, give corners of weight 0.
    pub fn corners(&self, a: &HalfDiff) -> [(usize, f64); 16] {
        self.corners_of(&self.stencil(a))
    }

    /// The first `N` of the 16 corners of [`Resolution::corners`] for a stencil: `N = 8` gives
    /// those at the lower phi_h node, all that carry weight in an isotropic table (its phi_h
    /// weight is 0). Corner `k` takes the upper node on axis `j` (phi_h, theta_h, theta_d, phi_d)
    /// when bit `3 − j` of `k` is set; its weight is the product of the axes' weights in that
    /// order.
    #[inline]
    pub(crate) fn corners_of<const N: usize>(
        &self,
        s: &[(usize, usize, f64); 4],
    ) -> [(usize, f64); N] {
        let strides = [
            self.theta_h * self.theta_d * self.phi_d,
            self.theta_d * self.phi_d,
            self.phi_d,
            1,
        ];
        let axis = |k: usize| {
            let (i0, i1, t) = s[k];
            ([i0 * strides[k], i1 * strides[k]], [1.0 - t, t])
        };
        let (ph, th, td, pd) = (axis(0), axis(1), axis(2), axis(3));
        std::array::from_fn(|c| {
            let (bh, bt, bd, bp) = ((c >> 3) & 1, (c >> 2) & 1, (c >> 1) & 1, c & 1);
            (
                ph.0[bh] + th.0[bt] + td.0[bd] + pd.0[bp],
                ph.1[bh] * th.1[bt] * td.1[bd] * pd.1[bp],
            )
        })
    }
}

/// Bracketing nodes of a coordinate `x` (in node units) on a grid of `n` nodes, clamped at the
/// last node.
#[inline]
fn clamped(x: f64, n: usize) -> (usize, usize, f64) {
    let last = (n - 1) as f64;
    if x.is_nan() || x >= last {
        return (n - 1, n - 1, 0.0);
    }
    // x >= 0 (the callers clamp the angles at 0): truncation is floor, without its libm call.
    let i = x as usize;
    (i, i + 1, x - i as f64)
}

/// Bracketing nodes of `x` on a periodic grid of `n` nodes.
#[inline]
fn periodic(x: f64, n: usize) -> (usize, usize, f64) {
    // rem_euclid only off the common path: it is the identity on [0, n).
    let x = if (0.0..n as f64).contains(&x) {
        x
    } else {
        x.rem_euclid(n as f64)
    };
    // x >= 0 here (NaN casts to 0 either way): truncation is floor.
    let i = (x as usize).min(n - 1);
    (i, (i + 1) % n, x - i as f64)
}

/// Polar angle of a unit direction, stable near the pole (`2 asin(|d - z| / 2)`).
pub fn theta_of(d: DVec3) -> f64 {
    let dist = (d.x * d.x + d.y * d.y + (d.z - 1.0) * (d.z - 1.0)).sqrt();
    2.0 * (0.5 * dist).min(1.0).asin()
}

/// Unit direction from polar angle and azimuth.
pub fn dir(theta: f64, phi: f64) -> DVec3 {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    DVec3::new(st * cp, st * sp, ct)
}

/// `v` turned about the normal (z) by `angle` (radians, counter-clockwise seen from above).
pub fn turn_about_z(v: DVec3, angle: f64) -> DVec3 {
    TurnAboutZ::new(angle).apply(v)
}

/// A turn about the normal (z) by a fixed angle, its sine and cosine found once, for turning
/// many vectors: [`TurnAboutZ::apply`] is [`turn_about_z`] to the bit.
#[derive(Debug, Clone, Copy)]
pub struct TurnAboutZ {
    sin: f64,
    cos: f64,
}

impl TurnAboutZ {
    /// The turn by `angle` (radians, counter-clockwise seen from above).
    pub fn new(angle: f64) -> TurnAboutZ {
        let (sin, cos) = angle.sin_cos();
        TurnAboutZ { sin, cos }
    }

    /// `v` turned.
    #[inline]
    pub fn apply(&self, v: DVec3) -> DVec3 {
        let (s, c) = (self.sin, self.cos);
        DVec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
    }
}
