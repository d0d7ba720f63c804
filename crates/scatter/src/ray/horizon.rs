//! Exact shadowing and masking tests for rays that run along a grid axis, through horizon maps.
//!
//! A ray leaving grid point `p` in the direction of a grid axis stays over the row (or column)
//! of `p`, where the bilinear surface is the piecewise-linear profile through that line's
//! heights. The height of the ray minus the profile is then linear on every segment between
//! two grid points, so the ray passes below the surface somewhere iff it passes below a grid
//! point: a rising ray of slope `s = d_z / |d_xy|` from `p` is blocked iff
//! `s < H(p) = max_q (h_q - h_p) / |q - p|` over the measured points `q` ahead of `p` on its
//! line (at least one grid spacing away: the facet's neighbours are part of the facet, as in
//! the march). `H` is the horizon of `p` in that direction; for every point of a line it is the
//! slope of the tangent from `p` to the upper convex hull of the points ahead, found for the
//! whole line in O(n) by one sweep that keeps that hull on a stack (the standard
//! linear-time horizon algorithm for terrain profiles: a hull vertex under the segment from
//! `p` to its tangent point is never the tangent of a point further back).
//!
//! Sources in tables of isotropic surfaces lie in the x-z plane, so the shadowing test of every
//! facet for every incidence is one comparison against the horizon toward +x, instead of a
//! march; the result is the march's without its sampling (a march samples every half spacing
//! and can step over a grazing crossing after a block skip; the horizon cannot). Points that
//! were not measured (NaN) never block, as in the march, and leaving the footprint while rising
//! is escaping.

use std::sync::OnceLock;

/// The four grid-axis directions of travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Axis {
    PlusX,
    MinusX,
    PlusY,
    MinusY,
}

impl Axis {
    /// The axis a horizontal direction `(dx, dy)` runs along, if it runs along one (to within
    /// 1e-12 of its length sideways: over 10⁶ grid spacings a drift of 10⁻⁶ of a spacing).
    pub(crate) fn of(dx: f64, dy: f64) -> Option<Axis> {
        const SIDEWAYS: f64 = 1e-12;
        if dy.abs() <= SIDEWAYS * dx.abs() {
            Some(if dx > 0.0 { Axis::PlusX } else { Axis::MinusX })
        } else if dx.abs() <= SIDEWAYS * dy.abs() {
            Some(if dy > 0.0 { Axis::PlusY } else { Axis::MinusY })
        } else {
            None
        }
    }

    fn slot(self) -> usize {
        self as usize
    }
}

/// Horizon maps of a height field toward each grid axis, computed when first asked for.
#[derive(Debug, Default)]
pub(crate) struct Horizons {
    maps: [OnceLock<Vec<f64>>; 4],
}

impl Horizons {
    /// The horizon toward `axis` of every grid point of the row-major `heights` (`nx × ny`,
    /// spacings `dx`, `dy` in metres): the largest slope `(h_q - h_p) / |q - p|` to a measured
    /// point `q` ahead of `p` along the axis, `-inf` where there is none (and for points not
    /// measured).
    pub(crate) fn get(
        &self,
        axis: Axis,
        heights: &[f64],
        (nx, ny): (usize, usize),
        (dx, dy): (f64, f64),
    ) -> &[f64] {
        self.maps[axis.slot()].get_or_init(|| {
            let mut out = vec![f64::NEG_INFINITY; nx * ny];
            let mut hull = Vec::new();
            // Each line as (first index, stride, length, spacing), walked against the
            // direction of travel: the farthest point ahead first.
            let lines: Vec<(usize, isize, usize, f64)> = match axis {
                Axis::PlusX => (0..ny).map(|iy| (iy * nx + nx - 1, -1, nx, dx)).collect(),
                Axis::MinusX => (0..ny).map(|iy| (iy * nx, 1, nx, dx)).collect(),
                Axis::PlusY => (0..nx)
                    .map(|ix| ((ny - 1) * nx + ix, -(nx as isize), ny, dy))
                    .collect(),
                Axis::MinusY => (0..nx).map(|ix| (ix, nx as isize, ny, dy)).collect(),
            };
            for (first, stride, len, spacing) in lines {
                hull.clear();
                for s in 0..len {
                    let i = first.wrapping_add_signed(stride * s as isize);
                    let h = heights[i];
                    if h.is_nan() {
                        continue;
                    }
                    // Distance ahead of a hull point (s_q < s, walked first) is s - s_q steps.
                    let slope = |(sq, hq): (usize, f64)| (hq - h) / (s - sq) as f64;
                    while let [.., second, top] = hull[..] {
                        if slope(top) <= slope(second) {
                            hull.pop();
                        } else {
                            break;
                        }
                    }
                    if let Some(&top) = hull.last() {
                        out[i] = slope(top) / spacing;
                    }
                    hull.push((s, h));
                }
            }
            out
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The horizon found by the hull sweep is the plain maximum over the points ahead, in all
    /// four directions, on a rough field with holes.
    #[test]
    fn sweep_is_the_plain_maximum() {
        let (nx, ny) = (37, 23);
        let (dx, dy) = (0.5, 0.8);
        let heights: Vec<f64> = (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as f64, (i / nx) as f64);
                if i % 17 == 5 {
                    f64::NAN
                } else {
                    (0.7 * x).sin() + (1.3 * y + 0.2 * x * x).cos() * 0.8
                }
            })
            .collect();
        let horizons = Horizons::default();
        for axis in [Axis::PlusX, Axis::MinusX, Axis::PlusY, Axis::MinusY] {
            let got = horizons.get(axis, &heights, (nx, ny), (dx, dy));
            for iy in 0..ny {
                for ix in 0..nx {
                    let h = heights[iy * nx + ix];
                    let mut want = f64::NEG_INFINITY;
                    for m in 1.. {
                        let (qx, qy, spacing) = match axis {
                            Axis::PlusX => (ix as isize + m, iy as isize, dx),
                            Axis::MinusX => (ix as isize - m, iy as isize, dx),
                            Axis::PlusY => (ix as isize, iy as isize + m, dy),
                            Axis::MinusY => (ix as isize, iy as isize - m, dy),
                        };
                        if qx < 0 || qy < 0 || qx >= nx as isize || qy >= ny as isize {
                            break;
                        }
                        let hq = heights[qy as usize * nx + qx as usize];
                        if !h.is_nan() && !hq.is_nan() {
                            want = want.max((hq - h) / (m as f64 * spacing));
                        }
                    }
                    let g = got[iy * nx + ix];
                    assert!(
                        g == want || (g - want).abs() < 1e-12,
                        "{axis:?} ({ix}, {iy}): {g} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn axis_of_a_direction() {
        assert_eq!(Axis::of(0.3, 0.0), Some(Axis::PlusX));
        assert_eq!(Axis::of(-0.3, 1e-17), Some(Axis::MinusX));
        assert_eq!(Axis::of(1e-17, 0.5), Some(Axis::PlusY));
        assert_eq!(Axis::of(0.0, -0.5), Some(Axis::MinusY));
        assert_eq!(Axis::of(0.3, 1e-6), None);
    }
}
