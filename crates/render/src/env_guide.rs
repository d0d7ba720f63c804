//! Sampling an environment map in proportion to its radiance times the cosine a surface's
//! normal makes with the light: the product of the two factors that every reflection's
//! integrand `f L cos θ` shares, tabulated for a set of normal directions.
//!
//! An environment light sampled by luminance alone (pbrt-v4 §12.5.2) spends half its samples
//! below the surface's horizon and weights the rest by `cos θ`, which varies from 0 to 1; for a
//! matte surface under a studio map that is most of the noise of a picture
//! (`docs/performance.md`, "Toward 3× Mitsuba's efficiency"). Here the map is split into coarse
//! cells (at most 64 × 32, each a block of whole pixels), and for each node of a grid of
//! normals (the centres of the cells of the octahedral map of the sphere, 32 × 32; Engelhardt &
//! Dachsbacher, "Octahedron environment maps", VMV 2008) the cells are weighted by their
//! luminance × `sin θ` summed over their pixels times the node's cosine averaged over the cell
//! (its clamped value at the centres of the cell's ninths). A sample takes the node of the
//! octahedral cell holding the surface's normal, a map cell from that node's distribution, then
//! a pixel of the cell in proportion to its luminance × `sin θ`, reusing the uniform numbers'
//! remaining fractions so that the inversions stay monotone and keep the stratification of the
//! renderer's points (pbrt-v4 §A.4.2). (A bilinear mixture of the four nodes around the normal,
//! chosen by a third number, measured the same noise on the benchmark's sphere at more cost.)
//! This is piecewise-constant product sampling in the manner of Clarberg et al.
//! ("Wavelet importance sampling", SIGGRAPH 2005) with one factor, the cosine, tabulated per
//! normal instead of computed per shading point.
//!
//! Each node's cell weight has a floor of 2% of its largest cosine over the two cells (the
//! cosine of the angle between them less both cells' angular radii): a map cell of non-zero
//! luminance then has non-zero probability whenever some direction in it lies above the horizon
//! of some normal near the node, so the density covers the whole integrand and a light sample
//! alone (the last vertex of a path, which takes no BRDF sample) stays unbiased.

use crate::light::map_direction;
use glam::{DVec2, DVec3};
use gonio_brdf::sampling::PiecewiseConstant2D;
use rayon::prelude::*;
use std::f64::consts::FRAC_PI_2;

/// Cells per side of the octahedral grid of normals.
const NORMAL_SIDE: usize = 32;
/// The floor of a map cell's weight, a share of its largest cosine (module doc).
const FLOOR: f64 = 0.02;
/// The most columns and rows of coarse map cells.
const MAX_CELLS: (usize, usize) = (64, 32);

/// The distributions of one map.
#[derive(Debug)]
pub(crate) struct CosineGuide {
    /// The map's pixels (columns, rows).
    size: (usize, usize),
    /// Columns and rows of coarse cells.
    cells: (usize, usize),
    /// Pixels per cell (columns, rows).
    block: (usize, usize),
    /// Per normal cell (row-major over the octahedral grid), the distribution of the map cells.
    normals: Vec<PiecewiseConstant2D>,
    /// Per map cell (row-major), the distribution of its pixels.
    pixels: Vec<PiecewiseConstant2D>,
    /// Sum of the pixel weights.
    total: f64,
}

/// The largest divisor of `n` that is at most `most`.
fn divisor_at_most(n: usize, most: usize) -> usize {
    (1..=most.min(n))
        .rev()
        .find(|d| n.is_multiple_of(*d))
        .unwrap_or(1)
}

/// The unit direction of the point (`x`, `y`) of the octahedral square [-1, 1]² (the lower
/// hemisphere folded onto the corners).
fn octahedral_decode(x: f64, y: f64) -> DVec3 {
    let z = 1.0 - x.abs() - y.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum())
    } else {
        (x, y)
    };
    DVec3::new(x, y, z).normalize()
}

/// The point of the octahedral square [0, 1)² of the unit direction `n`.
fn octahedral_encode(n: DVec3) -> DVec2 {
    let s = n.x.abs() + n.y.abs() + n.z.abs();
    let (mut x, mut y) = (n.x / s, n.y / s);
    if n.z < 0.0 {
        (x, y) = ((1.0 - y.abs()) * x.signum(), (1.0 - x.abs()) * y.signum());
    }
    DVec2::new(x + 1.0, y + 1.0) * 0.5
}

/// The node (row-major index of its cell) of the octahedral cell holding the unit direction `n`.
fn octahedral_node(n: DVec3) -> usize {
    let p = (octahedral_encode(n) * NORMAL_SIDE as f64).as_uvec2();
    let cell = |c: u32| (c as usize).min(NORMAL_SIDE - 1);
    cell(p.y) * NORMAL_SIDE + cell(p.x)
}

/// The centre direction of a cell and the largest angle (radians) from it to a point of the
/// cell's boundary, from a 5 × 5 grid of the cell's points, which the cell's small curvature
/// lets exceed the true largest angle by a few per cent at most; 5% is added to be safe.
fn cell_extent(point: impl Fn(f64, f64) -> DVec3) -> (DVec3, f64) {
    let centre = point(0.5, 0.5);
    let mut radius: f64 = 0.0;
    for a in 0..5 {
        for b in 0..5 {
            let p = point(a as f64 / 4.0, b as f64 / 4.0);
            radius = radius.max(centre.dot(p).clamp(-1.0, 1.0).acos());
        }
    }
    (centre, radius * 1.05)
}

impl CosineGuide {
    /// The guide of a map of `width × height` pixels with `weights` (row-major, the luminance
    /// of each pixel times `sin θ` at its row), whose column `u` lies at azimuth
    /// `φ = 2π u + rotation` (the map's convention, [`crate::light::EnvMap`]).
    pub(crate) fn new(weights: &[f64], width: usize, height: usize, rotation: f64) -> CosineGuide {
        let cells = (
            divisor_at_most(width, MAX_CELLS.0),
            divisor_at_most(height, MAX_CELLS.1),
        );
        let block = (width / cells.0, height / cells.1);
        let pixels: Vec<PiecewiseConstant2D> = (0..cells.0 * cells.1)
            .map(|c| {
                let (ci, cj) = (c % cells.0, c / cells.0);
                let block_weights: Vec<f64> = (0..block.1)
                    .flat_map(|b| {
                        let row = (cj * block.1 + b) * width + ci * block.0;
                        weights[row..row + block.0].iter().copied()
                    })
                    .collect();
                PiecewiseConstant2D::new(&block_weights, block.0)
            })
            .collect();
        // Per map cell: its centre, its angular radius, its weight and 3 × 3 directions
        // spread over it (centres of its ninths in (u, v)).
        let map_cells: Vec<(DVec3, f64, f64, [DVec3; 9])> = (0..cells.0 * cells.1)
            .map(|c| {
                let (ci, cj) = (c % cells.0, c / cells.0);
                let at = |a: f64, b: f64| {
                    map_direction(
                        (ci as f64 + a) / cells.0 as f64,
                        (cj as f64 + b) / cells.1 as f64,
                        rotation,
                    )
                };
                let (centre, radius) = cell_extent(at);
                let ninths = std::array::from_fn(|k| {
                    at(
                        (k % 3) as f64 / 3.0 + 1.0 / 6.0,
                        (k / 3) as f64 / 3.0 + 1.0 / 6.0,
                    )
                });
                (centre, radius, pixels[c].total(), ninths)
            })
            .collect();
        let side = NORMAL_SIDE as f64;
        let normals = (0..NORMAL_SIDE * NORMAL_SIDE)
            .into_par_iter()
            .map(|k| {
                let (kx, ky) = ((k % NORMAL_SIDE) as f64, (k / NORMAL_SIDE) as f64);
                let (normal, spread) = cell_extent(|a, b| {
                    octahedral_decode((kx + a) / side * 2.0 - 1.0, (ky + b) / side * 2.0 - 1.0)
                });
                let w: Vec<f64> = map_cells
                    .iter()
                    .map(|(centre, radius, weight, ninths)| {
                        let cos = normal.dot(*centre).clamp(-1.0, 1.0);
                        let nearest = (cos.acos() - spread - radius).max(0.0);
                        if *weight > 0.0 && nearest < FRAC_PI_2 {
                            let mean =
                                ninths.iter().map(|d| normal.dot(*d).max(0.0)).sum::<f64>() / 9.0;
                            weight * mean.max(FLOOR * nearest.cos())
                        } else {
                            0.0
                        }
                    })
                    .collect();
                PiecewiseConstant2D::new(&w, cells.0)
            })
            .collect();
        let total = pixels.iter().map(PiecewiseConstant2D::total).sum();
        CosineGuide {
            size: (width, height),
            cells,
            block,
            normals,
            pixels,
            total,
        }
    }

    /// Sum of the pixel weights (zero: a black map, nothing to sample).
    pub(crate) fn total(&self) -> f64 {
        self.total
    }

    /// A pixel (column, row), the position in [0, 1)² of the map and the density there per unit
    /// area of [0, 1)², for a surface of unit normal `n`, from two uniform numbers; `None` when
    /// no light reaches the surface's side.
    pub(crate) fn sample(&self, n: DVec3, u: DVec2) -> Option<((usize, usize), DVec2, f64)> {
        let normal = &self.normals[octahedral_node(n)];
        if normal.total() <= 0.0 {
            return None;
        }
        let ((ci, cj), p) = normal.sample(u);
        let c = cj * self.cells.0 + ci;
        // The position's fraction within the cell, uniform again: x selects the column, y the row.
        let local = DVec2::new(
            p.x * self.cells.0 as f64 - ci as f64,
            p.y * self.cells.1 as f64 - cj as f64,
        )
        .clamp(DVec2::ZERO, DVec2::splat(1.0 - 1e-12));
        let ((bi, bj), q) = self.pixels[c].sample(DVec2::new(local.y, local.x));
        let pixel = (ci * self.block.0 + bi, cj * self.block.1 + bj);
        let position = DVec2::new(
            (ci as f64 + q.x) / self.cells.0 as f64,
            (cj as f64 + q.y) / self.cells.1 as f64,
        );
        let density = normal.density(ci, cj) * self.pixels[c].density(bi, bj);
        (density > 0.0).then_some((pixel, position, density))
    }

    /// The density per unit area of [0, 1)² with which [`CosineGuide::sample`] returns a point
    /// of pixel (`i`, `j`) for a surface of unit normal `n`.
    pub(crate) fn density(&self, n: DVec3, i: usize, j: usize) -> f64 {
        let normal = &self.normals[octahedral_node(n)];
        if normal.total() <= 0.0 {
            return 0.0;
        }
        let (i, j) = (i.min(self.size.0 - 1), j.min(self.size.1 - 1));
        let (ci, cj) = (i / self.block.0, j / self.block.1);
        let c = cj * self.cells.0 + ci;
        normal.density(ci, cj) * self.pixels[c].density(i % self.block.0, j % self.block.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octahedral_cells_hold_their_directions() {
        // Every direction lies in its node's cell (within the cell's angular radius of the
        // node, the reach the weights' floor assumes), and encoding inverts decoding.
        let side = NORMAL_SIDE as f64;
        for k in 0..2000 {
            let z = 1.0 - 2.0 * ((k as f64 + 0.5) / 2000.0);
            let phi = k as f64 * 2.399_963;
            let r = (1.0 - z * z).sqrt();
            let n = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let p = octahedral_encode(n);
            let back = octahedral_decode(p.x * 2.0 - 1.0, p.y * 2.0 - 1.0);
            assert!((back - n).length() < 1e-12, "{n} {back}");
            let node = octahedral_node(n);
            let (kx, ky) = ((node % NORMAL_SIDE) as f64, (node / NORMAL_SIDE) as f64);
            let (centre, spread) = cell_extent(|a, b| {
                octahedral_decode((kx + a) / side * 2.0 - 1.0, (ky + b) / side * 2.0 - 1.0)
            });
            let angle = centre.dot(n).clamp(-1.0, 1.0).acos();
            assert!(angle <= spread, "{n}: {angle} > {spread}");
        }
    }
}
