//! A spatial index over reflected directions, so that cone detectors cost O(N + D·k) instead of
//! O(N·D): the rays are sorted (counting sort, O(N)) into a `g × g` grid of bins over the (x, y)
//! components of their unit direction, and a detector visits only the bins that overlap the
//! bounding box of its cone. The cone test itself (`wo·d > cos alpha`) is exact, so the index
//! finds exactly the hits of a plain loop over all rays.
//!
//! Bounding box: a unit vector within angle alpha of `d` makes an angle within alpha of the
//! angle `acos(d_x)` that `d` makes with the x axis (triangle inequality on the sphere), so its
//! x component lies in `[cos(min(acos d_x + alpha, π)), cos(max(acos d_x - alpha, 0))]`; the
//! same holds for y.

use super::reflected::Ray;
use crate::geometry::Detector;

/// What a detector collected: sums of the rays' reflectance shares and the number of rays.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Sums {
    pub w: f64,
    pub ws: f64,
    pub wp: f64,
    pub hits: u64,
}

impl Sums {
    pub(crate) fn add_ray(&mut self, ray: &Ray) {
        self.w += ray.w;
        self.ws += ray.ws;
        self.wp += ray.wp;
        self.hits += 1;
    }

    pub(crate) fn add(&mut self, other: &Sums) {
        self.w += other.w;
        self.ws += other.ws;
        self.wp += other.wp;
        self.hits += other.hits;
    }
}

/// The bins of a `g × g` direction grid that some detector's cone can reach: rays outside them
/// cannot reach any detector and need not be traced further.
pub(crate) struct BinMask {
    g: usize,
    bins: Vec<bool>,
}

impl BinMask {
    /// Mark the bins overlapping the bounding box of any of `detectors`.
    pub(crate) fn new(detectors: &[Detector], g: usize) -> Self {
        let mut bins = vec![false; g * g];
        for det in detectors {
            let (x0, x1) = bin_range(det.direction.x, det.half_angle, g);
            let (y0, y1) = bin_range(det.direction.y, det.half_angle, g);
            for by in y0..=y1 {
                bins[by * g + x0..=by * g + x1].fill(true);
            }
        }
        BinMask { g, bins }
    }

    /// Whether a unit direction falls in a marked bin.
    pub(crate) fn contains(&self, d: glam::DVec3) -> bool {
        self.bins[bin_of(d, self.g)]
    }
}

/// Bin of a direction component in [-1, 1] on a grid of `g` bins.
fn cell(v: f64, g: usize) -> usize {
    (((v + 1.0) * 0.5 * g as f64) as usize).min(g - 1)
}

/// Bin `by * g + bx` of a unit direction.
fn bin_of(d: glam::DVec3, g: usize) -> usize {
    cell(d.y, g) * g + cell(d.x, g)
}

/// Bins `lo..=hi` that one component of the directions within `alpha` of a detector, whose
/// direction has that component `c`, can reach.
fn bin_range(c: f64, alpha: f64, g: usize) -> (usize, usize) {
    let theta = c.clamp(-1.0, 1.0).acos();
    let lo = (theta + alpha).min(std::f64::consts::PI).cos() - BOX_SLACK;
    let hi = (theta - alpha).max(0.0).cos() + BOX_SLACK;
    (cell(lo.max(-1.0), g), cell(hi.min(1.0), g))
}

/// Rays sorted into bins over the (x, y) of their direction.
pub(crate) struct DirectionIndex {
    g: usize,
    /// `start[b]..start[b + 1]` are the rays of bin `b = by * g + bx`.
    start: Vec<usize>,
    rays: Vec<Ray>,
}

/// Slack on the bounding box, far above the rounding of `acos` and `cos`.
const BOX_SLACK: f64 = 1e-9;

impl DirectionIndex {
    /// Bin `rays` on a `g × g` grid (g >= 1). Rays keep their order within a bin.
    pub(crate) fn new(rays: &[Ray], g: usize) -> Self {
        let bin = |r: &Ray| bin_of(r.d, g);
        let mut start = vec![0usize; g * g + 1];
        for r in rays {
            start[bin(r) + 1] += 1;
        }
        for b in 0..g * g {
            start[b + 1] += start[b];
        }
        let mut next = start.clone();
        let mut sorted = vec![
            Ray {
                d: glam::DVec3::ZERO,
                w: 0.0,
                ws: 0.0,
                wp: 0.0
            };
            rays.len()
        ];
        for r in rays {
            let b = bin(r);
            sorted[next[b]] = *r;
            next[b] += 1;
        }
        DirectionIndex {
            g,
            start,
            rays: sorted,
        }
    }

    /// Sum the rays inside the detector's cone.
    pub(crate) fn collect(&self, det: &Detector) -> Sums {
        let cos_a = det.half_angle.cos();
        let (x0, x1) = bin_range(det.direction.x, det.half_angle, self.g);
        let (y0, y1) = bin_range(det.direction.y, det.half_angle, self.g);
        let mut sums = Sums::default();
        for by in y0..=y1 {
            let row = by * self.g;
            let rays = &self.rays[self.start[row + x0]..self.start[row + x1 + 1]];
            for r in rays {
                if r.d.dot(det.direction) > cos_a {
                    sums.add_ray(r);
                }
            }
        }
        sums
    }
}

/// The plain O(N·D) loop the index must agree with: every ray tested against the cone.
#[cfg(test)]
pub(crate) fn collect_exhaustive(rays: &[Ray], det: &Detector) -> Sums {
    let cos_a = det.half_angle.cos();
    let mut sums = Sums::default();
    for r in rays {
        if r.d.dot(det.direction) > cos_a {
            sums.add_ray(r);
        }
    }
    sums
}
