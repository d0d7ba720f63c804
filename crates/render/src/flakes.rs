//! Discrete flakes: a metallic or pearlescent coating's flakes drawn one by one, so that they
//! sparkle. The flakes are a procedural solid texture (S. Worley, "A cellular texture basis
//! function", SIGGRAPH 1996): flake sites, one per cell of a cubic grid at a place drawn in the
//! cell, and every point of space belonging to its nearest site. A surface cuts these cells
//! into polygons, the flakes; each site is a flake with probability c (the coverage) and a gap
//! otherwise, and a flake's normal is drawn from the coating's tilt distribution (`D(h) cos θh`,
//! in the surface's shading frame). Everything is a function of the site's cell and the
//! field's seed (a hash): no list is stored, the same flake is found on every frame and thread,
//! and any surface (a curved panel, a plane) has flakes without texture coordinates or seams.
//!
//! Size: a plane through a tessellation of cells one site per cube of side s, each site
//! uniform in its cube, meets cells of mean section area `κ s²` with κ = 0.696 (measured on
//! 12 random planes through 40 × 40 cell windows, ±0.002; the Poisson–Voronoi tessellation's
//! value is 0.686, D. Stoyan, W. S. Kendall & J. Mecke, *Stochastic Geometry and its
//! Applications*, 2nd ed., 1995, table 10.4), so flakes of mean area `π d²/4` take
//! `s = d √(π / (4κ))`. The sections' areas spread as such sections do (a test measures the
//! mean); real flakes spread too (a pigment's diameters span a factor of 3 or more between
//! its 10th and 90th percentiles).
//!
//! Light: under the coat, the camera's ray refracts through the coat's mean plane, meets the
//! flake plane at the coat's depth, and the flake there mirrors it ([`Glint::flake`]): a delta
//! lobe the path follows. Averaged over many flakes this is the coating's glint exactly (the
//! weights of [`Glint::flake`]); the rest of the coating's BRDF, a table without the glint
//! ([`gonio_coating::system::Coating::table_without_glint`]), is the material's BRDF as
//! usual. Why explicit flakes rather than counting them statistically (W. Jakob et al.,
//! "Discrete stochastic microfacet models", SIGGRAPH 2014; B. Atanasov & V. Koylazov, "A
//! practical stochastic algorithm for rendering mirror-like flakes", SIGGRAPH 2016 talk;
//! X. Chermain et al., "Procedural physically based BRDF for real-time rendering of glints",
//! 2020; T. Deliot & L. Belcour, "Real-time rendering of glinty appearances using distributed
//! binomial laws on anisotropic grids", 2023): gonio renders close-ups where a pixel covers a
//! few flakes at most (a sparkle camera's pixel of a few µm to tens of µm), there explicit
//! flakes are exact and cost one cell search per sample, while the statistical methods
//! approximate the count of flakes in a footprint so as to render distant views where a pixel
//! holds thousands; see `docs/render.md`.

use crate::error::{RenderError, Result};
use glam::{DVec2, DVec3};
use gonio_brdf::Rgb;
use gonio_brdf::sampling::Frame;
use gonio_coating::glint::Glint;

/// κ: the mean area of a plane section of the cells over s² (see the module's documentation).
pub const SECTION_AREA: f64 = 0.696;

/// The most bands a flake field's glint may have (the path keeps a flake's weights on the
/// stack).
pub const MAX_BANDS: usize = 64;

/// A coating's flakes, drawn one by one.
#[derive(Debug, Clone)]
pub struct FlakeField {
    glint: Glint,
    /// The grid's spacing, m.
    spacing: f64,
    seed: u64,
    /// Per band, the linear sRGB weights of a spectrum at the glint's bands (D65, CIE 1931).
    rgb_weights: Vec<[f64; 3]>,
    /// Whether a path follows the flakes' mirror ([`FlakeField::without_glint`]).
    glints: bool,
}

/// A flake found at a point: its site (for telling flakes apart) and its normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flake {
    /// The cell of its site.
    pub site: [i64; 3],
    /// Its normal in the surface's shading frame (z the normal).
    pub normal: DVec3,
}

impl FlakeField {
    /// The flakes of `glint`'s coating (their size, coverage, tilts and optics), placed by
    /// `seed`.
    pub fn new(glint: Glint, seed: u64) -> Result<FlakeField> {
        use gonio_color::{Illuminant, Observer, SpectralToXyz};
        if glint.wavelengths_nm().len() > MAX_BANDS {
            return Err(RenderError::Invalid(format!(
                "flakes: at most {MAX_BANDS} bands, got {}",
                glint.wavelengths_nm().len()
            )));
        }
        let rgb_weights = SpectralToXyz::new(
            glint.wavelengths_nm(),
            Illuminant::D65,
            Observer::Cie1931TwoDegree,
        )
        .map_err(|e| RenderError::Invalid(format!("flakes: {e}")))?
        .rgb_weights()
        .to_vec();
        let spacing = glint.diameter() * (std::f64::consts::PI / (4.0 * SECTION_AREA)).sqrt();
        Ok(FlakeField {
            glint,
            spacing,
            seed,
            rgb_weights,
            glints: true,
        })
    }

    /// The same flakes shading the light from inside as before (the base between them, not
    /// through a metal flake) but not mirroring: a path does not follow their glint, which the
    /// caller adds itself (the texture camera integrates it over each pixel exactly,
    /// [`crate::texture_glint`]).
    pub fn without_glint(self) -> FlakeField {
        FlakeField {
            glints: false,
            ..self
        }
    }

    /// Whether a path follows the flakes' mirror (see [`FlakeField::without_glint`]).
    pub fn glints(&self) -> bool {
        self.glints
    }

    /// The coating's glint: the flakes' optics and the coat they lie under.
    pub fn glint(&self) -> &Glint {
        &self.glint
    }

    /// The linear sRGB of a spectrum given at the glint's bands.
    pub fn to_rgb(&self, values: &[f64]) -> Rgb {
        self.rgb_weights
            .iter()
            .zip(values)
            .map(|(w, v)| Rgb::from_array(*w) * *v)
            .sum()
    }

    /// The site nearest to `p` (m, any frame fixed to the surface) and whether it is a flake:
    /// `None` for a gap. The site is sought in the 27 cells around `p`'s own.
    pub fn flake_at(&self, p: DVec3) -> Option<Flake> {
        let q = p / self.spacing;
        let base = q.floor();
        let mut best = (f64::INFINITY, [0i64; 3]);
        for cell in neighbours([base.x as i64, base.y as i64, base.z as i64]) {
            let d2 = self.site(cell).distance_squared(q);
            if d2 < best.0 {
                best = (d2, cell);
            }
        }
        self.flake_of(best.1)
    }

    /// The flakes' cells cut by the horizontal plane at height `z` (m, in the frame the field
    /// is placed in) within the rectangle from `lo` to `hi` (x, y, m): `visit` is told each
    /// piece of a cell in the rectangle whose site's flake (`None` for a gap) is `wanted`, the
    /// flake and the piece's area, m² (a cell may come in several pieces; the areas of all add
    /// up to the rectangle's; the pieces not wanted are not clipped). The cells are
    /// [`FlakeField::flake_at`]'s exactly: within one cube of the grid a point's candidates are
    /// the same 27 sites, and the points of the plane nearer to site a than to site b form a
    /// half-plane, `2 q·(b − a) ≤ |b|² − |a|²` (q in the plane: the section of a Voronoi
    /// tessellation by a plane is a power diagram, F. Aurenhammer, "Power diagrams:
    /// properties, algorithms and applications", SIAM J. Comput. 16(1), 78, 1987), so each
    /// piece is the cube's square in the rectangle clipped by 26 half-planes (I. E. Sutherland
    /// & G. W. Hodgman, "Reentrant polygon clipping", CACM 17(1), 32, 1974) and its area the
    /// shoelace formula's.
    pub fn sections(
        &self,
        z: f64,
        lo: DVec2,
        hi: DVec2,
        wanted: impl Fn(Option<&Flake>) -> bool,
        mut visit: impl FnMut(Option<Flake>, f64),
    ) {
        let s = self.spacing;
        let (a, b, qz) = (lo / s, hi / s, z / s);
        let cz = qz.floor() as i64;
        let (mut poly, mut next) = (Vec::with_capacity(32), Vec::with_capacity(32));
        for cy in a.y.floor() as i64..b.y.ceil() as i64 {
            for cx in a.x.floor() as i64..b.x.ceil() as i64 {
                let (x0, x1) = (a.x.max(cx as f64), b.x.min(cx as f64 + 1.0));
                let (y0, y1) = (a.y.max(cy as f64), b.y.min(cy as f64 + 1.0));
                if x1 <= x0 || y1 <= y0 {
                    continue;
                }
                let cells = neighbours([cx, cy, cz]);
                let sites = cells.map(|c| self.site(c));
                for (i, &site) in sites.iter().enumerate() {
                    let flake = self.flake_of(cells[i]);
                    if !wanted(flake.as_ref()) {
                        continue;
                    }
                    poly.clear();
                    poly.extend([
                        DVec2::new(x0, y0),
                        DVec2::new(x1, y0),
                        DVec2::new(x1, y1),
                        DVec2::new(x0, y1),
                    ]);
                    for (j, &other) in sites.iter().enumerate() {
                        if j == i || poly.is_empty() {
                            continue;
                        }
                        // Nearer to `site` than to `other`: n·q ≤ k.
                        let d = other - site;
                        let n = 2.0 * DVec2::new(d.x, d.y);
                        let k = other.length_squared() - site.length_squared() - 2.0 * qz * d.z;
                        clip(&poly, n, k, &mut next);
                        std::mem::swap(&mut poly, &mut next);
                    }
                    let area = shoelace(&poly) * s * s;
                    if area > 0.0 {
                        visit(flake, area);
                    }
                }
            }
        }
    }

    /// The site of `cell`, in units of the grid's spacing.
    fn site(&self, cell: [i64; 3]) -> DVec3 {
        DVec3::new(cell[0] as f64, cell[1] as f64, cell[2] as f64) + self.uniform3(cell, 0)
    }

    /// The flake of the site in `cell`, `None` for a gap.
    fn flake_of(&self, site: [i64; 3]) -> Option<Flake> {
        let u = self.uniform3(site, 1);
        (u.x < self.glint.coverage()).then(|| Flake {
            site,
            normal: self.glint.orientation().sample_d(DVec2::new(u.y, u.z)),
        })
    }

    /// Three uniform numbers in [0, 1) of `cell` for purpose `k`.
    fn uniform3(&self, cell: [i64; 3], k: u64) -> DVec3 {
        let mut h = self.seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        for c in cell {
            h = splitmix64(h ^ c as u64);
        }
        let a = splitmix64(h);
        let b = splitmix64(a);
        let to_unit = |x: u64| (x >> 11) as f64 / (1u64 << 53) as f64;
        DVec3::new(to_unit(h), to_unit(a), to_unit(b))
    }

    /// Where the viewer's ray, arriving at `p` on the surface from `wo` (in the shading
    /// `frame`), meets the flakes: refracted through the coat's mean plane down to the coat's
    /// depth.
    pub fn under(&self, p: DVec3, frame: &Frame, wo: DVec3) -> DVec3 {
        let w = self.glint.inside(wo);
        p - frame.to_world(w) * (self.glint.depth() / w.z.max(1e-6))
    }
}

/// The 27 cells around `cell` (itself included).
fn neighbours(cell: [i64; 3]) -> [[i64; 3]; 27] {
    std::array::from_fn(|k| {
        let k = k as i64;
        [
            cell[0] + k % 3 - 1,
            cell[1] + (k / 3) % 3 - 1,
            cell[2] + k / 9 - 1,
        ]
    })
}

/// The convex polygon `poly` clipped to the half-plane `n·q ≤ k`, into `out` (one step of
/// Sutherland–Hodgman).
fn clip(poly: &[DVec2], n: DVec2, k: f64, out: &mut Vec<DVec2>) {
    out.clear();
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (fp, fq) = (n.dot(p) - k, n.dot(q) - k);
        if fp <= 0.0 {
            out.push(p);
        }
        if (fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0) {
            out.push(p + (q - p) * (fp / (fp - fq)));
        }
    }
}

/// The area of the polygon `poly` (the shoelace formula; positive counter-clockwise).
fn shoelace(poly: &[DVec2]) -> f64 {
    let mut twice = 0.0;
    for (i, &p) in poly.iter().enumerate() {
        twice += p.perp_dot(poly[(i + 1) % poly.len()]);
    }
    0.5 * twice
}

/// SplitMix64's finaliser (S. Vigna), a 64-bit mix.
fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}
