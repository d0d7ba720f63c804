//! The mesoscale height map of a material (orange peel): a height map at millimetre scale whose
//! local slope tilts the shading normal, over the material's microscale BRDF (a table, a model,
//! a height map's table, a coating's table under its smooth coat), so that the reflection of a
//! straight edge waves as it does in a real clear coat.
//!
//! - **Slope.** The gradient of the map at its grid points by central differences on the repeated
//!   map, interpolated bilinearly between them: a normal field continuous everywhere, across the
//!   tile boundaries too. Second-order accurate: a sine of wavelength Λ sampled at spacing Δ keeps
//!   `sin(kΔ)/(kΔ)` of its slope at the nodes (k = 2π/Λ; 0.9984 at 64 points per wavelength).
//! - **Bump mapping.** The height `H(p) = h(p·a, p·b)` of a world point `p` through the planar
//!   projection (map axes `a`, `b`) has the world gradient `g = h_x a + h_y b`; the perturbed
//!   normal is `normalize(n − (g − (g·n) n))`, the normal minus the surface gradient (Blinn,
//!   "Simulation of wrinkled surfaces", SIGGRAPH 1978; Mikkelsen, "Surface gradient-based bump
//!   mapping framework", JCGT 9(3), 2020): on a flat rectangle in the projection plane exactly the
//!   normal of the surface `z = h(x, y)`.
//! - **Shading normals.** A tilted normal can put the viewer below its horizon, or mirror the
//!   view below the geometric surface (Veach, "Non-symmetric scattering in light transport
//!   algorithms", EGWR 1996; pbrt-v4 §10.1.1). Where the mirror direction of the view about the
//!   tilted normal would fall lower than `τ = min(0.9 cos θ_g, 0.01)` above the geometric horizon,
//!   the normal is bent to the half vector between the view and that direction raised to `τ`
//!   (the remedy of Keller et al., "The Iray light transport simulation and rendering system",
//!   arXiv:1705.01263, 2017, §A.3, as Blender's Cycles applies it): the viewer then always sees
//!   the front of the shading frame, and the coat's mirror stays above the surface. The geometric
//!   normal still decides which light samples and continued paths are allowed.
//! - **Repetition.** Beyond its extent the map repeats. A periodic map (a synthetic map from the
//!   FFT filter of `gonio_surface::synth`) wraps: period `n Δ`, seamless. A measured map is not
//!   periodic: it is levelled (least-squares plane) and mirror-repeated (period `2 (n − 1) Δ`),
//!   which keeps heights continuous; the slope across a mirror line passes through zero within one
//!   spacing (a crease rounded over one grid cell), and the pattern shows mirror symmetry about
//!   it. `repeat = "auto"` (the default) tells them apart: a map is periodic when the differences
//!   across its wrap-around edges are no larger, in rms, than three times those between
//!   neighbours inside (a stationary random map gives a ratio about 1; a measured map's edges
//!   differ by about √2 Sq, far more than neighbours a small spacing apart).

use crate::error::{RenderError, Result};
use crate::geometry::Hit;
use crate::material::Material;
use crate::path::facing_frame;
use crate::scene::Scene;
use glam::{DVec2, DVec3};
use gonio_brdf::sampling::Frame;
use gonio_surface::HeightMap;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// `mesoscale = { ... }` in a material: a height-map file or a synthetic Gaussian map, its scale
/// factor, its repetition and its projection axis.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MesoscaleDesc {
    /// A height-map file (any format `gonio surface` reads).
    #[serde(default)]
    pub file: Option<PathBuf>,
    /// The file's channel, a name or a 0-based index (multi-channel AFM files).
    #[serde(default)]
    pub channel: Option<String>,
    /// Or a synthetic periodic Gaussian map (`gonio_surface::synth`) of this rms height, µm...
    #[serde(default)]
    pub sq_um: Option<f64>,
    /// ...correlation length, mm...
    #[serde(default)]
    pub corr_mm: Option<f64>,
    /// ...points per side (default 256)...
    #[serde(default)]
    pub points: Option<usize>,
    /// ...spacing, mm (default a sixteenth of the correlation length)...
    #[serde(default)]
    pub spacing_mm: Option<f64>,
    /// ...and seed (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Factor on the heights, so on the slopes (default 1): exaggerates or shrinks the map.
    #[serde(default)]
    pub scale: Option<f64>,
    /// `auto` (default), `wrap` or `mirror`.
    #[serde(default)]
    pub repeat: Option<RepeatChoice>,
    /// The object axis the map is projected along: `x`, `y` or `z` (default: the axis along
    /// which the shape is thinnest, a rectangle's or disk's normal z).
    #[serde(default)]
    pub axis: Option<Axis>,
}

/// How the map repeats beyond its extent, as asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RepeatChoice {
    /// Wrap a periodic map, mirror any other ([`is_periodic`]).
    Auto,
    /// Wrap around: period `n Δ` (a periodic map).
    Wrap,
    /// Mirror at the edges: period `2 (n − 1) Δ` (any map).
    Mirror,
}

/// How the map repeats: [`RepeatChoice`] once `auto` is decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Repeat {
    /// Wrap around.
    Wrap,
    /// Mirror at the edges.
    Mirror,
}

/// An object axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    /// The two object axes spanning the projection plane, as the map's x and y: along z (x, y),
    /// along y (x, z), along x (y, z).
    pub fn plane(self) -> [DVec3; 2] {
        match self {
            Axis::X => [DVec3::Y, DVec3::Z],
            Axis::Y => [DVec3::X, DVec3::Z],
            Axis::Z => [DVec3::X, DVec3::Y],
        }
    }

    /// The axis along which points spanning `lo..hi` (object coordinates) are thinnest; z on a
    /// tie.
    pub fn thinnest(lo: DVec3, hi: DVec3) -> Axis {
        let e = hi - lo;
        if e.z <= e.x && e.z <= e.y {
            Axis::Z
        } else if e.y <= e.x {
            Axis::Y
        } else {
            Axis::X
        }
    }
}

/// A mesoscale map ready to shade with: its heights (times the scale factor, levelled when it
/// is mirrored), spacing, repetition and projection axis.
#[derive(Debug, Clone)]
pub struct Mesoscale {
    heights: Vec<f64>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    repeat: Repeat,
    axis: Option<Axis>,
}

impl Mesoscale {
    /// The map `map` with its heights times `scale`, repeated as `repeat` says, projected along
    /// `axis` (`None`: each shape's thinnest). Fails, saying why, on a profile, a map with
    /// invalid points, fewer than 3 points along a side, or a bad scale.
    pub fn new(
        map: &HeightMap,
        scale: f64,
        repeat: RepeatChoice,
        axis: Option<Axis>,
    ) -> std::result::Result<Mesoscale, String> {
        if map.is_profile() || map.nx() < 3 || map.ny() < 3 {
            return Err(format!(
                "a mesoscale map needs at least 3 × 3 points (an areal map), got {} × {}",
                map.nx(),
                map.ny()
            ));
        }
        if map.valid_count() < map.nx() * map.ny() {
            return Err(format!(
                "the map has {} invalid points; a mesoscale map must be complete (fill or crop \
                 them away, e.g. `gonio surface crop`)",
                map.nx() * map.ny() - map.valid_count()
            ));
        }
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(format!("`scale` must be a finite number >= 0, got {scale}"));
        }
        let repeat = match repeat {
            RepeatChoice::Wrap => Repeat::Wrap,
            RepeatChoice::Mirror => Repeat::Mirror,
            RepeatChoice::Auto if is_periodic(map) => Repeat::Wrap,
            RepeatChoice::Auto => Repeat::Mirror,
        };
        // A measured map's tilt would become a triangle wave of slopes when mirrored; a periodic
        // map is kept as it is (levelling would break its periodicity).
        let levelled;
        let map = match repeat {
            Repeat::Wrap => map,
            Repeat::Mirror => {
                levelled = gonio_surface::ops::level(map).map_err(|e| e.to_string())?;
                &levelled
            }
        };
        let heights = map.heights().iter().map(|h| h * scale).collect();
        Ok(Mesoscale {
            heights,
            nx: map.nx(),
            ny: map.ny(),
            dx: map.dx(),
            dy: map.dy(),
            repeat,
            axis,
        })
    }

    /// The object axis the map is projected along (`None`: each shape's thinnest).
    pub fn axis(&self) -> Option<Axis> {
        self.axis
    }

    /// How the map repeats.
    pub fn repeat(&self) -> Repeat {
        self.repeat
    }

    /// The period of the repeated map along x and y, metres: `n Δ` wrapped, `2 (n − 1) Δ`
    /// mirrored.
    pub fn period(&self) -> DVec2 {
        let p = |n: usize, d: f64| match self.repeat {
            Repeat::Wrap => n as f64 * d,
            Repeat::Mirror => 2.0 * (n - 1) as f64 * d,
        };
        DVec2::new(p(self.nx, self.dx), p(self.ny, self.dy))
    }

    /// The map's extent, metres: `(n − 1) Δ` along each axis. The projection puts its centre at
    /// the object's origin.
    pub fn extent(&self) -> DVec2 {
        DVec2::new(
            (self.nx - 1) as f64 * self.dx,
            (self.ny - 1) as f64 * self.dy,
        )
    }

    /// The height of the repeated map at grid index `(i, j)` (any integers).
    fn node(&self, i: i64, j: i64) -> f64 {
        let fold = |k: i64, n: usize| -> usize {
            let n = n as i64;
            match self.repeat {
                Repeat::Wrap => k.rem_euclid(n) as usize,
                Repeat::Mirror => {
                    let m = k.rem_euclid(2 * (n - 1));
                    (if m < n { m } else { 2 * (n - 1) - m }) as usize
                }
            }
        };
        self.heights[fold(j, self.ny) * self.nx + fold(i, self.nx)]
    }

    /// The gradient of the repeated map at grid index `(i, j)`: central differences.
    fn node_slope(&self, i: i64, j: i64) -> DVec2 {
        DVec2::new(
            (self.node(i + 1, j) - self.node(i - 1, j)) / (2.0 * self.dx),
            (self.node(i, j + 1) - self.node(i, j - 1)) / (2.0 * self.dy),
        )
    }

    /// The cell of map point `(x, y)` metres (from grid point (0, 0)) and the position in it.
    fn cell(&self, x: f64, y: f64) -> (i64, i64, f64, f64) {
        let (u, v) = (x / self.dx, y / self.dy);
        let (i, j) = (u.floor(), v.floor());
        (i as i64, j as i64, u - i, v - j)
    }

    /// The height at map point `(x, y)` metres from grid point (0, 0), bilinear between the
    /// nodes of the repeated map.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let (i, j, fx, fy) = self.cell(x, y);
        let row = |j| self.node(i, j) * (1.0 - fx) + self.node(i + 1, j) * fx;
        row(j) * (1.0 - fy) + row(j + 1) * fy
    }

    /// The slope `(∂h/∂x, ∂h/∂y)` (metres per metre) at map point `(x, y)` metres from grid
    /// point (0, 0): the nodes' central differences, bilinear between them.
    pub fn slope(&self, x: f64, y: f64) -> DVec2 {
        let (i, j, fx, fy) = self.cell(x, y);
        let row = |j| self.node_slope(i, j) * (1.0 - fx) + self.node_slope(i + 1, j) * fx;
        row(j) * (1.0 - fy) + row(j + 1) * fy
    }
}

/// Whether `map` is periodic: the rms of the differences across its wrap-around edges (last
/// column to first, last row to first) at most three times the rms of the differences between
/// neighbours inside it.
pub fn is_periodic(map: &HeightMap) -> bool {
    let h = map.heights();
    let (ny, nx) = h.dim();
    let rms = |pairs: &mut dyn Iterator<Item = (f64, f64)>| {
        let (s, n) = pairs.fold((0.0, 0usize), |(s, n), (a, b)| (s + (a - b).powi(2), n + 1));
        (s / n.max(1) as f64).sqrt()
    };
    let inside_x = rms(&mut (0..ny).flat_map(|j| (1..nx).map(move |i| (h[[j, i]], h[[j, i - 1]]))));
    let inside_y = rms(&mut (1..ny).flat_map(|j| (0..nx).map(move |i| (h[[j, i]], h[[j - 1, i]]))));
    let edge_x = rms(&mut (0..ny).map(|j| (h[[j, 0]], h[[j, nx - 1]])));
    let edge_y = rms(&mut (0..nx).map(|i| (h[[0, i]], h[[ny - 1, i]])));
    edge_x <= 3.0 * inside_x && edge_y <= 3.0 * inside_y
}

/// The map a description names, read or synthesised; `dir` is the scene's directory, `scene`
/// names it in errors.
pub fn load(desc: &MesoscaleDesc, dir: &Path, scene: &Path, name: &str) -> Result<Mesoscale> {
    let bad = |p: String| RenderError::scene(scene, format!("material `{name}`: mesoscale: {p}"));
    let synthetic = [desc.sq_um, desc.corr_mm, desc.spacing_mm]
        .iter()
        .any(Option::is_some)
        || desc.points.is_some()
        || desc.seed.is_some();
    let map = match (&desc.file, synthetic) {
        (Some(file), false) => {
            let path = if file.is_absolute() {
                file.clone()
            } else {
                dir.join(file)
            };
            let channel = desc
                .channel
                .as_deref()
                .map(str::parse::<gonio_surface::ChannelSelector>)
                .transpose()
                .map_err(|e| bad(format!("`channel`: {e}")))?;
            let options = gonio_surface::io::ReadOptions { channel };
            gonio_surface::io::read_with(&path, &options).map_err(|e| {
                RenderError::scene(&path, format!("cannot read the mesoscale map: {e}"))
            })?
        }
        (None, true) if desc.channel.is_none() => {
            let (Some(sq_um), Some(corr_mm)) = (desc.sq_um, desc.corr_mm) else {
                return Err(bad("a synthetic map needs `sq_um` and `corr_mm`".into()));
            };
            let points = desc.points.unwrap_or(256);
            if !(8..=4096).contains(&points) {
                return Err(bad(format!("`points` must be 8 to 4096, got {points}")));
            }
            let spacing = desc.spacing_mm.unwrap_or(corr_mm / 16.0) * 1e-3;
            gonio_surface::synth::GaussianSurface::square(
                sq_um * 1e-6,
                corr_mm * 1e-3,
                points,
                spacing,
                desc.seed.unwrap_or(1),
            )
            .generate()
            .map_err(|e| bad(format!("cannot synthesise the map: {e}")))?
        }
        _ => {
            return Err(bad(
                "give either `file` (with `channel` if needed) or a synthetic map (`sq_um`, \
                 `corr_mm`, optionally `points`, `spacing_mm`, `seed`)"
                    .into(),
            ));
        }
    };
    let source = desc.file.as_ref().map_or_else(
        || "the synthetic map".to_string(),
        |f| f.display().to_string(),
    );
    Mesoscale::new(
        &map,
        desc.scale.unwrap_or(1.0),
        desc.repeat.unwrap_or(RepeatChoice::Auto),
        desc.axis,
    )
    .map_err(|e| bad(format!("{source}: {e}")))
}

/// Where a shape's points lie on a mesoscale map: the world position of its object origin and
/// the unit world directions of the object axes spanning the projection plane (the map's x and
/// y). Lengths along them are world metres, so the map keeps its physical size whatever the
/// shape's scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    pub origin: DVec3,
    pub axes: [DVec3; 2],
}

impl Projection {
    /// The projection along `axis` of a shape placed by `transform`.
    pub fn new(transform: &glam::DAffine3, axis: Axis) -> Projection {
        let [a, b] = axis.plane();
        Projection {
            origin: transform.translation,
            axes: [
                transform.transform_vector3(a).normalize_or_zero(),
                transform.transform_vector3(b).normalize_or_zero(),
            ],
        }
    }
}

/// Each primitive's projection (`None` for emitters and shapes whose material has no map).
#[derive(Debug, Clone, Default)]
pub struct Projections {
    per_prim: Vec<u32>,
    frames: Vec<Projection>,
}

impl Projections {
    /// Add a shape's projection, returning its index for [`Projections::push_prim`].
    pub fn add(&mut self, p: Projection) -> u32 {
        self.frames.push(p);
        (self.frames.len() - 1) as u32
    }

    /// Record the projection (an index from [`Projections::add`], or `None`) of the next
    /// primitive.
    pub fn push_prim(&mut self, frame: Option<u32>) {
        self.per_prim.push(frame.unwrap_or(u32::MAX));
    }

    /// The projection of primitive `prim`.
    pub fn get(&self, prim: usize) -> Option<&Projection> {
        self.frames.get(*self.per_prim.get(prim)? as usize)
    }
}

/// The shading frame at `hit` for a ray in direction `dir` ([`facing_frame`]), its normal tilted
/// by `material`'s mesoscale map where it has one (the module's documentation says how), with
/// the geometric normal on the side the ray arrives from.
pub(crate) fn shading_frame(
    scene: &Scene,
    material: &Material,
    hit: &Hit,
    dir: DVec3,
) -> (DVec3, Frame) {
    let (ng, frame) = facing_frame(hit, dir);
    let (Some(meso), Some(proj)) = (&material.mesoscale, scene.projections.get(hit.prim)) else {
        return (ng, frame);
    };
    let rel = hit.p - proj.origin;
    let centre = 0.5 * meso.extent();
    let s = meso.slope(
        rel.dot(proj.axes[0]) + centre.x,
        rel.dot(proj.axes[1]) + centre.y,
    );
    let g = s.x * proj.axes[0] + s.y * proj.axes[1];
    // The height is measured along the front normal; seen from the back it is negated.
    let side = if frame.n.dot(hit.ns) < 0.0 { -1.0 } else { 1.0 };
    let n = frame.n;
    let tilted = (n - side * (g - g.dot(n) * n)).normalize_or_zero();
    if tilted == DVec3::ZERO {
        return (ng, frame);
    }
    let n = keep_reflection_above(ng, -dir, tilted);
    let t = frame.s - frame.s.dot(n) * n;
    let t = if t.length_squared() > 1e-20 {
        t.normalize()
    } else {
        Frame::from_z(n).s
    };
    (
        ng,
        Frame {
            s: t,
            t: n.cross(t),
            n,
        },
    )
}

/// The shading normal `n`, bent (if needed) so that the mirror direction of `wo` (toward the
/// viewer) about it lies at least `τ = min(0.9 wo·ng, 0.01)` above the geometric horizon: the
/// half vector of `wo` and the mirror direction raised to `τ` (Keller et al. 2017, §A.3).
pub(crate) fn keep_reflection_above(ng: DVec3, wo: DVec3, n: DVec3) -> DVec3 {
    let tau = (0.9 * wo.dot(ng)).min(0.01);
    let r = 2.0 * wo.dot(n) * n - wo;
    if r.dot(ng) >= tau {
        return n;
    }
    let along = (r - r.dot(ng) * ng).normalize_or_zero();
    if along == DVec3::ZERO {
        return ng;
    }
    let raised = along * (1.0 - tau * tau).sqrt() + ng * tau;
    (wo + raised).normalize_or(ng)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    /// A map of `n × m` points at spacing `d` with heights `f(x, y)`.
    fn map(n: usize, m: usize, d: f64, f: impl Fn(f64, f64) -> f64) -> HeightMap {
        let h = Array2::from_shape_fn((m, n), |(j, i)| f(i as f64 * d, j as f64 * d));
        HeightMap::new(h, d, d).unwrap()
    }

    /// A periodic sine wraps: the slope anywhere, the tile boundaries included, is the sine's
    /// within the interpolation's error; heights and slopes agree on both sides of a boundary to
    /// within what their largest rate of change over the distance allows.
    #[test]
    fn periodic_sine_wraps_without_a_seam() {
        // 64 points per wavelength along x, 32 along y; amplitude 1 µm.
        let (n, m, d) = (64, 32, 0.5e-3);
        let (lx, ly) = (n as f64 * d, m as f64 * d);
        let (kx, ky) = (std::f64::consts::TAU / lx, std::f64::consts::TAU / ly);
        let a = 1e-6;
        let sine = map(n, m, d, |x, y| a * (kx * x + ky * y).sin());
        assert!(is_periodic(&sine));
        let meso = Mesoscale::new(&sine, 1.0, RepeatChoice::Auto, None).unwrap();
        assert_eq!(meso.repeat(), Repeat::Wrap);
        assert_eq!(meso.period(), DVec2::new(lx, ly));
        // Interpolation error: the central difference keeps sinc(kΔ) of the slope (1 − (kΔ)²/6
        // at most off), bilinear interpolation of a sinusoid adds at most (kΔ)²/8 of its
        // amplitude; with kΔ ≤ 2π/32 both together stay below 1.2% of the slope amplitude.
        let amp = a * kx.hypot(ky);
        let tol = 0.012 * amp;
        for k in 0..500 {
            let x = (k as f64 * 0.618_034).fract() * 3.0 * lx - lx;
            let y = (k as f64 * 0.414_214).fract() * 3.0 * ly - ly;
            let want = DVec2::new(kx, ky) * a * (kx * x + ky * y).cos();
            assert!((meso.slope(x, y) - want).length() < tol, "at ({x}, {y})");
        }
        // Across the boundaries x = lx and y = ly, ε = 1e-3 Δ either side: the slope changes by
        // at most its largest rate (a k² ≤ a (kx² + ky²)) times 2ε, plus rounding.
        let eps = 1e-3 * d;
        let rate = a * (kx * kx + ky * ky);
        for k in 0..50 {
            let t = k as f64 / 50.0;
            for (p, q) in [
                (DVec2::new(lx - eps, t * ly), DVec2::new(lx + eps, t * ly)),
                (DVec2::new(t * lx, ly - eps), DVec2::new(t * lx, ly + eps)),
            ] {
                let jump = (meso.slope(p.x, p.y) - meso.slope(q.x, q.y)).length();
                assert!(jump <= 2.0 * eps * rate * 1.1 + 1e-12, "slope jump {jump}");
                let dh = (meso.height(p.x, p.y) - meso.height(q.x, q.y)).abs();
                assert!(dh <= 2.0 * eps * amp * 1.1, "height jump {dh}");
            }
        }
    }

    /// A map that is not periodic (a tilted plane plus a sine) is levelled and mirrored: heights
    /// continuous across each mirror line, the slope across it through zero there and continuous.
    #[test]
    fn measured_map_is_levelled_and_mirrored() {
        let (n, d) = (40, 0.25e-3);
        let tilted = map(n, n, d, |x, y| {
            3e-3 * x + 1e-3 * y + 1e-6 * (700.0 * x).sin()
        });
        assert!(!is_periodic(&tilted));
        let meso = Mesoscale::new(&tilted, 2.0, RepeatChoice::Auto, None).unwrap();
        assert_eq!(meso.repeat(), Repeat::Mirror);
        let e = meso.extent();
        assert_eq!(meso.period(), 2.0 * e);
        // The plane (6.3e-3 after the scale) is gone: what is left of the mean slope is the
        // sine's, at most 2 A · scale / extent = 2 · 1 µm · 2 / 9.75 mm = 4.1e-4.
        let mean = (0..n * n)
            .map(|k| meso.slope((k % n) as f64 * d, (k / n) as f64 * d))
            .sum::<DVec2>()
            / (n * n) as f64;
        assert!(mean.length() < 4.2e-4, "mean slope {mean}");
        let eps = 1e-4 * d;
        for k in 0..=20 {
            let y = k as f64 / 20.0 * e.y;
            for x in [0.0, e.x] {
                let (a, b) = (meso.slope(x - eps, y), meso.slope(x + eps, y));
                assert!((meso.height(x - eps, y) - meso.height(x + eps, y)).abs() < 1e-9);
                // The slope across the line is odd about it and continuous: within the rate of
                // change over one cell (the largest node slope / Δ) times 2ε.
                let bound = 2.0 * eps * 4e-3 * 2.0 / d;
                assert!(
                    (a - b).length() < bound,
                    "jump {} at ({x}, {y})",
                    (a - b).length()
                );
                assert!(meso.slope(x, y).x.abs() < 1e-9);
            }
        }
    }

    /// The scale multiplies the slopes; bad maps and scales are refused with the reason.
    #[test]
    fn scale_and_refusals() {
        let sine = map(32, 32, 1e-3, |x, _| {
            1e-6 * (std::f64::consts::TAU * x / 32e-3).sin()
        });
        let one = Mesoscale::new(&sine, 1.0, RepeatChoice::Wrap, None).unwrap();
        let three = Mesoscale::new(&sine, 3.0, RepeatChoice::Wrap, None).unwrap();
        assert!((three.slope(3e-3, 1e-3) - 3.0 * one.slope(3e-3, 1e-3)).length() < 1e-15);
        let err = Mesoscale::new(&sine, -1.0, RepeatChoice::Wrap, None).unwrap_err();
        assert!(err.contains("scale"), "{err}");
        let mut h = sine.heights().clone();
        h[[3, 4]] = f64::NAN;
        let holes = HeightMap::with_invalid(h, 1e-3, 1e-3).unwrap();
        let err = Mesoscale::new(&holes, 1.0, RepeatChoice::Auto, None).unwrap_err();
        assert!(err.contains("1 invalid points"), "{err}");
    }

    /// A normal tilted so far that the view's mirror falls below the surface is bent until the
    /// mirror is τ above it; the viewer then sees the front of the frame. An untilted normal is
    /// left alone.
    #[test]
    fn shading_normal_keeps_the_reflection_above_the_surface() {
        let ng = DVec3::Z;
        let wo = DVec3::new(0.999, 0.0, 0.0447).normalize();
        let n = DVec3::new(-0.2, 0.0, 1.0).normalize();
        assert!((2.0 * wo.dot(n) * n - wo).z < 0.0);
        let bent = keep_reflection_above(ng, wo, n);
        let r = 2.0 * wo.dot(bent) * bent - wo;
        let tau = (0.9 * wo.z).min(0.01);
        assert!((r.z - tau).abs() < 1e-12 && wo.dot(bent) > 0.0, "{r}");
        assert_eq!(keep_reflection_above(ng, wo, ng), ng);
    }
}
