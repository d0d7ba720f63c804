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
        })
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
    /// `None` for a gap.
    pub fn flake_at(&self, p: DVec3) -> Option<Flake> {
        let q = p / self.spacing;
        let base = q.floor();
        let mut best = (f64::INFINITY, [0i64; 3]);
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let cell = [base.x as i64 + dx, base.y as i64 + dy, base.z as i64 + dz];
                    let site = DVec3::new(cell[0] as f64, cell[1] as f64, cell[2] as f64)
                        + self.uniform3(cell, 0);
                    let d2 = site.distance_squared(q);
                    if d2 < best.0 {
                        best = (d2, cell);
                    }
                }
            }
        }
        let site = best.1;
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

/// SplitMix64's finaliser (S. Vigna), a 64-bit mix.
fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}
