//! Ray marching over a height field: does a ray leaving a point of the surface escape, or does it
//! strike the surface again (and where)? Used for shadowing (the ray toward the source), masking
//! (the reflected ray) and the second bounce of the ray method.
//!
//! The surface between grid points is the bilinear interpolant of the heights. A ray is followed
//! in horizontal steps of half the smaller grid spacing, starting one grid spacing away from its
//! origin: the facet's own normal comes from its 3 × 3 neighbourhood, so the neighbours are part
//! of the facet and cannot shadow it. A rising ray above the highest point of its block of
//! 8 × 8 cells jumps to the edge of the block (a two-level maximum map). A ray that rises above the highest point of the map, or
//! leaves the map's footprint while rising, escapes; a ray that leaves the footprint while
//! descending is lost (it would meet the continuation of the surface). Points the instrument did
//! not measure (NaN heights) never block a ray. A rising ray from a grid point along a grid
//! axis is not marched: its line's horizon map decides exactly (see `horizon`).
//!
//! Rays inside the material (refracted at a facet, descending under the surface `h`) are
//! followed by the same march over the mirrored field ([`HeightField::mirrored`]): mirroring
//! `z -> -z` turns the material under `h` into the air over `-h` and the descending ray into a
//! rising one, so "escapes" there means the ray goes down into the bulk without leaving the
//! material, and "hits" that it meets the surface from below.

use super::horizon::{Axis, Horizons};
use glam::DVec3;
use rayon::prelude::*;

/// What happens to a ray followed over the height field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Fate {
    /// The ray leaves the surface unobstructed.
    Escapes,
    /// The ray strikes the surface at this point (metres).
    Hits(DVec3),
    /// The ray goes down and out of the map, or straight down: it cannot reach a detector.
    Lost,
}

/// Heights on a regular grid, with what marching needs precomputed.
#[derive(Debug)]
pub(crate) struct HeightField {
    /// Row-major heights, `h[iy * nx + ix]`, metres; NaN where not measured.
    heights: Vec<f64>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    /// Highest valid height, metres.
    h_max: f64,
    /// Highest valid height of each block of `BLOCK × BLOCK` cells (grid points
    /// `[b·BLOCK, (b+1)·BLOCK]` along each axis, both ends included), row-major.
    block_max: Vec<f64>,
    /// Blocks along x and y.
    bx: usize,
    by: usize,
    /// Horizontal step of the march, metres.
    step: f64,
    /// `1/dx`, `1/dy`, and the largest grid coordinates inside the footprint.
    inv_dx: f64,
    inv_dy: f64,
    fx_max: f64,
    fy_max: f64,
    /// Per grid point, the highest valid height within `2^k + 1` grid points along each axis
    /// (`k = 1 ..= WINDOW_LEVELS`), rounded up to f32.
    windows: Vec<[f32; WINDOW_LEVELS]>,
    /// Horizon maps toward the grid axes, made when a ray along that axis first needs one.
    horizons: Horizons,
}

/// Bisection steps used to locate a hit between two march samples.
const REFINE_STEPS: usize = 12;

/// Cells per side of a block of the coarse maximum map. A rising ray above the highest point
/// of its block cannot meet the surface before it leaves the block, so it jumps to the block's
/// edge.
const BLOCK: usize = 8;

impl HeightField {
    /// A field of `nx × ny` row-major `heights` (at least 2 × 2) on spacings `dx`, `dy`.
    pub(crate) fn new(heights: Vec<f64>, nx: usize, ny: usize, dx: f64, dy: f64) -> Self {
        debug_assert_eq!(heights.len(), nx * ny);
        debug_assert!(nx >= 2 && ny >= 2);
        let valid_max = |a: f64, b: f64| if b.is_nan() { a } else { a.max(b) };
        let h_max = heights.iter().copied().fold(f64::NEG_INFINITY, valid_max);
        let (bx, by) = ((nx - 1).div_ceil(BLOCK), (ny - 1).div_ceil(BLOCK));
        let mut block_max = vec![f64::NEG_INFINITY; bx * by];
        for j in 0..by {
            for i in 0..bx {
                let mut m = f64::NEG_INFINITY;
                for iy in j * BLOCK..=((j + 1) * BLOCK).min(ny - 1) {
                    let row = &heights[iy * nx..(iy + 1) * nx];
                    for &h in &row[i * BLOCK..=((i + 1) * BLOCK).min(nx - 1)] {
                        m = valid_max(m, h);
                    }
                }
                block_max[j * bx + i] = m;
            }
        }
        let windows = window_maxima(&heights, nx, ny);
        HeightField {
            windows,
            heights,
            nx,
            ny,
            dx,
            dy,
            h_max,
            block_max,
            bx,
            by,
            step: 0.5 * dx.min(dy),
            inv_dx: 1.0 / dx,
            inv_dy: 1.0 / dy,
            fx_max: (nx - 1) as f64,
            fy_max: (ny - 1) as f64,
            horizons: Horizons::default(),
        }
    }

    /// The field of the surface seen from inside the material: the same grid with every height
    /// negated (points not measured stay so), its maxima made afresh.
    pub(crate) fn mirrored(&self) -> HeightField {
        let heights = self.heights.iter().map(|&h| -h).collect();
        HeightField::new(heights, self.nx, self.ny, self.dx, self.dy)
    }

    /// The horizon map for rays in direction `d`, if `d` rises along a grid axis (made now if
    /// it was not yet: call this before a parallel loop that will need it).
    pub(crate) fn horizon(&self, d: DVec3) -> Option<&[f64]> {
        if d.z <= 0.0 {
            return None;
        }
        let axis = Axis::of(d.x, d.y)?;
        Some(
            self.horizons
                .get(axis, &self.heights, (self.nx, self.ny), (self.dx, self.dy)),
        )
    }

    /// Whether a ray in direction `d` from the grid point of row-major index `index` (at
    /// `origin`) leaves the surface: exactly from the horizon map when `d` rises along a grid
    /// axis; else, for a rising ray, at once if it clears the window maxima around its origin;
    /// else by marching.
    pub(crate) fn escapes(&self, index: usize, origin: DVec3, d: DVec3) -> bool {
        let slope = d.z / (d.x * d.x + d.y * d.y).sqrt();
        match self.horizon(d) {
            Some(horizon) => slope >= horizon[index],
            None => {
                (d.z > 0.0 && self.clears_windows(index, origin.z, slope))
                    || self.march(origin, d) == Fate::Escapes
            }
        }
    }

    /// Whether a ray rising at `slope` (height per horizontal distance) from height `z0` at
    /// grid point `index` stays above the surface, judged from the window maxima: a point of
    /// the ray at most `2^(k+2) - 1` grid spacings from its origin lies over a cell whose
    /// corners are within window `k` (half-width `2^(k+2)` points), and from where the march
    /// starts (one spacing `m`, the smaller one) to there the ray is at least
    /// `z0 + slope (2^(k+1) - 1) m` high; if that clears window `k`'s maximum for every `k`, and
    /// the map's maximum beyond the last window, the ray cannot meet the surface. A sufficient
    /// test: `false` means "march to find out".
    fn clears_windows(&self, index: usize, z0: f64, slope: f64) -> bool {
        let m = 2.0 * self.step;
        let mut from = 1.0;
        for &w in &self.windows[index] {
            if z0 + slope * from * m < f64::from(w) {
                return false;
            }
            from = 2.0 * from + 1.0;
        }
        z0 + slope * from * m >= self.h_max
    }

    /// Position in metres of grid point `(ix, iy)`, with its height.
    pub(crate) fn point(&self, ix: usize, iy: usize) -> DVec3 {
        DVec3::new(
            ix as f64 * self.dx,
            iy as f64 * self.dy,
            self.heights[iy * self.nx + ix],
        )
    }

    /// The grid point nearest to horizontal position `(x, y)` metres (clamped to the map).
    pub(crate) fn nearest(&self, x: f64, y: f64) -> (usize, usize) {
        let ix = (x / self.dx).round().clamp(0.0, (self.nx - 1) as f64) as usize;
        let iy = (y / self.dy).round().clamp(0.0, (self.ny - 1) as f64) as usize;
        (ix, iy)
    }

    /// Whether grid coordinates `(fx, fy)` lie inside the footprint.
    fn inside(&self, fx: f64, fy: f64) -> bool {
        fx >= 0.0 && fy >= 0.0 && fx <= self.fx_max && fy <= self.fy_max
    }

    /// Bilinear height at grid coordinates inside the footprint: NaN next to a non-measured
    /// point.
    fn height_at(&self, fx: f64, fy: f64) -> f64 {
        let ix = (fx as usize).min(self.nx - 2);
        let iy = (fy as usize).min(self.ny - 2);
        let tx = fx - ix as f64;
        let ty = fy - iy as f64;
        let row = iy * self.nx + ix;
        let (h00, h10) = (self.heights[row], self.heights[row + 1]);
        let (h01, h11) = (self.heights[row + self.nx], self.heights[row + self.nx + 1]);
        let lower = h00 + tx * (h10 - h00);
        let upper = h01 + tx * (h11 - h01);
        lower + ty * (upper - lower)
    }

    /// Distance along the ray from the point at grid coordinates `(fx, fy)` and height `z` to
    /// the edge of the block holding it, if it lies above that block's highest point; `(gx, gy)`
    /// are the ray's grid coordinates per unit distance.
    fn clear_of_block(&self, z: f64, fx: f64, fy: f64, (gx, gy): (f64, f64)) -> Option<f64> {
        let (i, j) = ((fx as usize) / BLOCK, (fy as usize) / BLOCK);
        let (i, j) = (i.min(self.bx - 1), j.min(self.by - 1));
        if z <= self.block_max[j * self.bx + i] {
            return None;
        }
        let exit = |f: f64, g: f64, b: usize| {
            let lo = (b * BLOCK) as f64;
            if g > 0.0 {
                (lo + BLOCK as f64 - f) / g
            } else if g < 0.0 {
                (lo - f) / g
            } else {
                f64::INFINITY
            }
        };
        Some(exit(fx, gx, i).min(exit(fy, gy, j)))
    }

    /// Follow the unit direction `d` from the surface point `origin`.
    pub(crate) fn march(&self, origin: DVec3, d: DVec3) -> Fate {
        let horizontal = (d.x * d.x + d.y * d.y).sqrt();
        if horizontal < 1e-12 {
            return if d.z > 0.0 { Fate::Escapes } else { Fate::Lost };
        }
        let rising = d.z > 0.0;
        let ray = GridRay::new(self, origin, d);
        // Distance along the ray per horizontal step.
        let dt = self.step / horizontal;
        // Rising rays escape once above the highest point: no need to march past it.
        let t_clear = if rising {
            (self.h_max - origin.z) / d.z
        } else {
            f64::INFINITY
        };
        let mut t_above = dt;
        let mut t = 2.0 * dt;
        loop {
            if t > t_clear {
                return Fate::Escapes;
            }
            let (fx, fy, z) = ray.at(t);
            if !self.inside(fx, fy) {
                return if rising { Fate::Escapes } else { Fate::Lost };
            }
            if rising && let Some(skip) = self.clear_of_block(z, fx, fy, ray.g) {
                // At least one ordinary step, so that a ray grazing a block's edge (exit
                // distance 0) still advances.
                t_above = t;
                t += (skip + 1e-3 * dt).max(dt);
                continue;
            }
            if z < self.height_at(fx, fy) {
                return Fate::Hits(self.refine(&ray, origin, d, t_above, t));
            }
            t_above = t;
            t += dt;
        }
    }

    /// Bisect between `t_above` (ray above the surface) and `t_below` for the crossing point.
    fn refine(
        &self,
        ray: &GridRay,
        origin: DVec3,
        d: DVec3,
        mut t_above: f64,
        mut t_below: f64,
    ) -> DVec3 {
        for _ in 0..REFINE_STEPS {
            let t = 0.5 * (t_above + t_below);
            let (fx, fy, z) = ray.at(t);
            if self.inside(fx, fy) && z < self.height_at(fx, fy) {
                t_below = t;
            } else {
                t_above = t;
            }
        }
        origin + t_below * d
    }
}

/// Levels of window maxima per grid point (half-widths 4, 8, ..., 128 points).
const WINDOW_LEVELS: usize = 6;

/// For every grid point of the row-major `heights` (`nx × ny`), the highest valid height in
/// the square of half-width `2^(k+2)` points about it (clipped to the map), for
/// `k = 0 .. WINDOW_LEVELS`, rounded up to f32. Starting from the 3 × 3 maximum (half-width 1),
/// each doubling takes the maximum of the previous level at the four points `(±a, ±a)` away,
/// `a` = the previous half-width, which covers the square of twice that half-width.
fn window_maxima(heights: &[f64], nx: usize, ny: usize) -> Vec<[f32; WINDOW_LEVELS]> {
    let valid_max = |a: f64, b: f64| if b.is_nan() { a } else { a.max(b) };
    // One level from the previous: the maximum over the points `(±a, ±a)` away (clipped).
    let double = |previous: &[f64], a: usize| {
        let mut next = vec![f64::NEG_INFINITY; nx * ny];
        next.par_chunks_mut(nx).enumerate().for_each(|(iy, row)| {
            let (y0, y1) = (iy.saturating_sub(a), (iy + a).min(ny - 1));
            let (r0, r1) = (&previous[y0 * nx..][..nx], &previous[y1 * nx..][..nx]);
            for (ix, out) in row.iter_mut().enumerate() {
                let (x0, x1) = (ix.saturating_sub(a), (ix + a).min(nx - 1));
                *out = valid_max(valid_max(valid_max(r0[x0], r0[x1]), r1[x0]), r1[x1]);
            }
        });
        next
    };
    // The 3 × 3 maximum (half-width 1), from which the doublings start.
    let mut level = vec![f64::NEG_INFINITY; nx * ny];
    level.par_chunks_mut(nx).enumerate().for_each(|(iy, row)| {
        for (ix, out) in row.iter_mut().enumerate() {
            for y in iy.saturating_sub(1)..=(iy + 1).min(ny - 1) {
                for x in ix.saturating_sub(1)..=(ix + 1).min(nx - 1) {
                    *out = valid_max(*out, heights[y * nx + x]);
                }
            }
        }
    });
    let mut out = vec![[f32::NEG_INFINITY; WINDOW_LEVELS]; nx * ny];
    // Half-widths 2, 4, 8, ...: the first doubling is not kept.
    for doubling in 0..=WINDOW_LEVELS {
        level = double(&level, 1 << doubling);
        if doubling > 0 {
            out.par_iter_mut().zip(&level).for_each(|(o, &m)| {
                let f = m as f32;
                o[doubling - 1] = if f64::from(f) < m { f.next_up() } else { f };
            });
        }
    }
    out
}

/// A ray in grid coordinates: `(x/dx, y/dy)` and height at distance `t` along it, without a
/// division per step.
struct GridRay {
    /// Grid coordinates of the origin.
    o: (f64, f64),
    /// Grid coordinates per unit distance.
    g: (f64, f64),
    z0: f64,
    dz: f64,
}

impl GridRay {
    fn new(field: &HeightField, origin: DVec3, d: DVec3) -> GridRay {
        GridRay {
            o: (origin.x * field.inv_dx, origin.y * field.inv_dy),
            g: (d.x * field.inv_dx, d.y * field.inv_dy),
            z0: origin.z,
            dz: d.z,
        }
    }

    fn at(&self, t: f64) -> (f64, f64, f64) {
        (
            self.o.0 + t * self.g.0,
            self.o.1 + t * self.g.1,
            self.z0 + t * self.dz,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(f: impl Fn(f64, f64) -> f64, n: usize, d: f64) -> HeightField {
        let mut h = Vec::with_capacity(n * n);
        for iy in 0..n {
            for ix in 0..n {
                h.push(f(ix as f64 * d, iy as f64 * d));
            }
        }
        HeightField::new(h, n, n, d, d)
    }

    fn rough(n: usize) -> HeightField {
        field(
            |x, y| (0.9 * x).sin() * (0.4 * y).cos() + 0.3 * (2.1 * x + 1.7 * y).sin(),
            n,
            0.5,
        )
    }

    /// The window maxima hold the plain maximum over each square (rounded up to f32).
    #[test]
    fn window_maxima_are_the_plain_maxima() {
        let (n, f) = (70, rough(70));
        for (iy, ix) in [(0usize, 0usize), (3, 5), (35, 35), (69, 12), (50, 69)] {
            for k in 0..WINDOW_LEVELS {
                let hw = 4usize << k;
                let mut want = f64::NEG_INFINITY;
                for y in iy.saturating_sub(hw)..=(iy + hw).min(n - 1) {
                    for x in ix.saturating_sub(hw)..=(ix + hw).min(n - 1) {
                        want = want.max(f.heights[y * n + x]);
                    }
                }
                let got = f64::from(f.windows[iy * n + ix][k]);
                assert!(
                    got >= want && got - want < 1e-6,
                    "({ix}, {iy}) {k}: {got} {want}"
                );
            }
        }
    }

    /// A ray that clears the windows escapes the march too, and many do.
    #[test]
    fn clearing_the_windows_is_escaping() {
        let f = rough(96);
        let mut cleared = 0;
        for iy in (2..94).step_by(7) {
            for ix in (2..94).step_by(5) {
                let o = f.point(ix, iy);
                for a in 0..24 {
                    for e in [0.05f64, 0.2, 0.5, 1.0, 1.4] {
                        let phi = a as f64 * 0.2618 + 0.1;
                        let d = DVec3::new(e.cos() * phi.cos(), e.cos() * phi.sin(), e.sin());
                        let slope = d.z / d.x.hypot(d.y);
                        if f.clears_windows(iy * 96 + ix, o.z, slope) {
                            cleared += 1;
                            assert_eq!(f.march(o, d), Fate::Escapes, "({ix}, {iy}) {d}");
                        }
                    }
                }
            }
        }
        assert!(cleared > 5000, "{cleared}");
    }

    /// A flat plane never blocks a rising ray, and every descending ray meets it (lost at the
    /// edge of a plane it cannot meet inside the footprint).
    #[test]
    fn flat_plane() {
        let f = field(|_, _| 0.0, 32, 1.0);
        let o = f.point(16, 16);
        let up = DVec3::new(1.0, 0.3, 0.01).normalize();
        assert_eq!(f.march(o, up), Fate::Escapes);
        assert_eq!(f.march(o, DVec3::Z), Fate::Escapes);
        let raised = o + DVec3::new(0.0, 0.0, 1.0);
        match f.march(raised, DVec3::new(1.0, 0.0, -1.0).normalize()) {
            Fate::Hits(p) => assert!((p - DVec3::new(17.0, 16.0, 0.0)).length() < 1e-3, "{p}"),
            other => panic!("{other:?}"),
        }
    }

    /// A wall of height 2 at x = 20 (a ridge in the bilinear surface from x = 19 to 21) stops a ray
    /// of slope 0.15 from x = 10 where `0.15 (x - 10) = 2 (x - 19)`, and lets a ray of slope 0.25
    /// pass over it.
    #[test]
    fn wall_blocks_low_rays() {
        let f = field(
            |x, _| if (19.5..=20.5).contains(&x) { 2.0 } else { 0.0 },
            40,
            1.0,
        );
        let o = f.point(10, 20);
        let low = DVec3::new(1.0, 0.0, 0.15).normalize();
        let high = DVec3::new(1.0, 0.0, 0.25).normalize();
        assert!(matches!(f.march(o, low), Fate::Hits(p) if (p.x - 36.5 / 1.85).abs() < 1e-2));
        assert_eq!(f.march(o, high), Fate::Escapes);
    }

    /// Under a trench of depth 2 at x = 20 (the wall above, upside down), a ray descending at
    /// slope 0.15 inside the material from x = 10 meets the trench's floor from below where
    /// `-0.15 (x - 10) = -2 (x - 19)`, and one descending at 0.25 passes under it: followed
    /// over the mirrored field, as the ray mirrored in z.
    #[test]
    fn mirrored_field_follows_rays_below() {
        let f = field(
            |x, _| {
                if (19.5..=20.5).contains(&x) {
                    -2.0
                } else {
                    0.0
                }
            },
            40,
            1.0,
        );
        let below = f.mirrored();
        let mirror = |v: DVec3| DVec3::new(v.x, v.y, -v.z);
        let o = f.point(10, 20);
        let low = DVec3::new(1.0, 0.0, -0.15).normalize();
        let high = DVec3::new(1.0, 0.0, -0.25).normalize();
        match below.march(mirror(o), mirror(low)) {
            Fate::Hits(p) => {
                let p = mirror(p);
                assert!((p.x - 36.5 / 1.85).abs() < 1e-2 && p.z < 0.0, "{p}");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(below.march(mirror(o), mirror(high)), Fate::Escapes);
        assert!(!below.escapes(20 * 40 + 10, mirror(o), mirror(low)));
        assert!(below.escapes(20 * 40 + 10, mirror(o), mirror(high)));
    }
}
