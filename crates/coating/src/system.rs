//! A coating system: the top interface (smooth, or rough with a microfacet distribution), the
//! clear coat, optional effect flakes and the base; its spectral BRDF table.
//!
//! A smooth top over a diffuse base has an exact closed form ([`crate::clear_coat`]), which the
//! table then uses; every other system goes through the random walks of [`crate::layered`].
//! With a smooth top the table holds the body reflection (the mirror reflection `F(θi)`, a delta,
//! is left out and said so in the provenance); with a rough top it holds everything the coating
//! reflects.

use crate::clear_coat::{self, AtWavelength, Base, ClearCoatOverBase, Coat};
use crate::error::{CoatingError, Result};
use crate::flakes::{FlakeLayer, Flakes};
use crate::interface::{Interface, Transport};
use crate::layered::{Scratch, Walk};
use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_brdf::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Random walks per table cell unless told otherwise (`gonio coating compute --samples`, the
/// pictures' tables). With the walks' bidirectional estimator a table of the silver metallic
/// read at the ASTM E2194/E2539 geometries is within 0.3–0.7 L* (one standard deviation) of
/// the direct reading (docs/coatings.md, "Noise").
pub const TABLE_WALKS: usize = 32;

/// The bands of a coating's tables and readings unless told otherwise: 400, 410, ..., 700 nm
/// (31 bands, the CIE tables' 10 nm step over the visible).
pub fn default_bands() -> Vec<f64> {
    (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
}

/// A coating system.
#[derive(Clone, Debug, PartialEq)]
pub struct Coating {
    /// The top interface's microfacet distribution; `None` for a smooth (mirror) interface.
    pub roughness: Option<Microfacet>,
    pub coat: Coat,
    /// Effect flakes at the bottom of the coat, over the base.
    pub flakes: Option<Flakes>,
    pub base: Base,
}

/// How the table is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// The exact series of a smooth coat over a diffuse base.
    ClosedForm,
    /// Random walks, this many per table cell.
    RandomWalk { samples: usize },
}

impl Coating {
    /// A smooth coat over a diffuse base, as [`Coating`].
    pub fn from_clear_coat(stack: ClearCoatOverBase) -> Self {
        Coating {
            roughness: None,
            coat: stack.coat,
            flakes: None,
            base: stack.base,
        }
    }

    /// The closed-form model when the system has one (a smooth top, no flakes).
    pub fn clear_coat(&self) -> Option<ClearCoatOverBase> {
        (self.roughness.is_none() && self.flakes.is_none()).then(|| ClearCoatOverBase {
            coat: self.coat.clone(),
            base: self.base.clone(),
        })
    }

    /// Check the description at `wavelengths_nm`.
    pub fn check(&self, wavelengths_nm: &[f64]) -> Result<()> {
        ClearCoatOverBase {
            coat: self.coat.clone(),
            base: self.base.clone(),
        }
        .check(wavelengths_nm)?;
        if let Some(m) = self.roughness
            && !(m.alpha_x > 0.0 && m.alpha_x <= 1.0 && m.alpha_y > 0.0 && m.alpha_y <= 1.0)
        {
            return Err(CoatingError::Invalid(format!(
                "top roughness α {}: must be above 0 and at most 1 (a glossy coat has 0.01–0.1; \
                 leave the roughness out for a smooth coat)",
                m.alpha_x
            )));
        }
        if let Some(f) = &self.flakes {
            f.check()?;
        }
        Ok(())
    }

    /// How [`Coating::table`] computes with `samples` walks per cell.
    pub fn method(&self, samples: usize) -> Method {
        match self.clear_coat() {
            Some(_) => Method::ClosedForm,
            None => Method::RandomWalk { samples },
        }
    }

    /// The random-walk estimators for `wavelengths_nm`: the bands grouped by the coat's index
    /// (one group when it does not depend on wavelength), each group with its walk.
    pub fn walks(&self, wavelengths_nm: &[f64]) -> Result<Vec<(Vec<usize>, Walk)>> {
        let mut groups: Vec<(f64, Vec<usize>)> = Vec::new();
        for (i, &w) in wavelengths_nm.iter().enumerate() {
            let n = self.coat.index.at(w);
            match groups.iter_mut().find(|(m, _)| *m == n) {
                Some((_, bands)) => bands.push(i),
                None => groups.push((n, vec![i])),
            }
        }
        groups
            .into_iter()
            .map(|(n, bands)| {
                let wl: Vec<f64> = bands.iter().map(|&b| wavelengths_nm[b]).collect();
                let tau = wl
                    .iter()
                    .map(|&w| self.coat.absorption_per_um.value_at(w) * self.coat.thickness_um)
                    .collect();
                let rho = wl
                    .iter()
                    .map(|&w| self.base.reflectance(w))
                    .collect::<Result<Vec<_>>>()?;
                let bottom = match &self.flakes {
                    None => FlakeLayer::bare(rho),
                    Some(f) => {
                        let optics = wl
                            .iter()
                            .map(|&w| f.optics(n, w))
                            .collect::<Result<Vec<_>>>()?;
                        FlakeLayer::new(f, optics, rho)
                    }
                };
                let walk = Walk {
                    top: Interface::new(n, self.roughness),
                    tau,
                    bottom,
                };
                Ok((bands, walk))
            })
            .collect()
    }

    /// The provenance of a table made from the description at `source`.
    pub fn provenance(&self, source: impl Into<String>, method: Method) -> Provenance {
        if method == Method::ClosedForm {
            return clear_coat::body_provenance(source);
        }
        let mut provenance = Provenance::new(source, "coating:layered-random-walk");
        let mirror = if self.roughness.is_none() {
            "; the smooth top's mirror reflection F(θi) is not in the table"
        } else {
            ""
        };
        let samples = match method {
            Method::RandomWalk { samples } => samples,
            Method::ClosedForm => 0,
        };
        provenance.description = Some(format!(
            "coating system by position-free Monte Carlo layered transport (Guo et al. 2018), \
             {samples} walks per cell{mirror}"
        ));
        provenance
    }

    /// What evaluates the coating's BRDF at `wavelengths_nm`: the exact series where it applies,
    /// otherwise the random walks.
    pub fn evaluator(&self, wavelengths_nm: &[f64]) -> Result<Evaluator> {
        self.check(wavelengths_nm)?;
        Ok(match self.clear_coat() {
            Some(exact) => Evaluator::Exact(
                wavelengths_nm
                    .iter()
                    .map(|&w| exact.at(w))
                    .collect::<Result<Vec<_>>>()?,
            ),
            None => Evaluator::Walks(self.walks(wavelengths_nm)?),
        })
    }

    /// The coating's BRDF tabulated at `resolution`, one channel per wavelength of
    /// `wavelengths_nm`, by the exact series where it applies and otherwise by `samples` random
    /// walks per cell ([`Evaluator::eval_reciprocal`]: the table is reciprocal to its
    /// interpolation and does not depend on the number of threads).
    pub fn table(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        samples: usize,
        provenance: Provenance,
    ) -> Result<BrdfTable> {
        self.table_cells(resolution, wavelengths_nm, samples, provenance, |_| true)
    }

    /// [`Coating::table`] with the walks run only in the cells whose index `keep` accepts (the
    /// others hold 0): what a reading at a few geometries interpolates, each cell as in the
    /// whole table, without the whole table's cost. The exact series fills every cell.
    pub fn table_cells(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        samples: usize,
        provenance: Provenance,
        keep: impl Fn(usize) -> bool + Sync,
    ) -> Result<BrdfTable> {
        if let Some(exact) = self.clear_coat() {
            self.check(wavelengths_nm)?;
            return exact.body_table(resolution, wavelengths_nm, provenance);
        }
        if samples == 0 {
            return Err(CoatingError::Invalid(
                "samples: at least one random walk per cell is needed".into(),
            ));
        }
        let evaluator = self.evaluator(wavelengths_nm)?;
        let channels = Channels::Spectral {
            wavelengths_nm: wavelengths_nm.to_vec(),
        };
        let table_error = |e: gonio_brdf::BrdfError| CoatingError::Invalid(e.to_string());
        let mut builder = TableBuilder::new(resolution, channels)
            .map_err(table_error)?
            .with_provenance(provenance);
        builder.fill(|cell, out| {
            if keep(cell.index) {
                let mut scratch = Scratch::default();
                evaluator.eval_reciprocal(cell.wo, cell.wi, samples, &mut scratch, out);
            }
        });
        builder.build().map_err(table_error)
    }
}

/// The coating's BRDF, ready to evaluate (see [`Coating::evaluator`]).
#[derive(Clone, Debug)]
pub enum Evaluator {
    /// The exact series of a smooth coat over a diffuse base, per band.
    Exact(Vec<AtWavelength>),
    /// Random walks, per group of bands sharing the coat's index.
    Walks(Vec<(Vec<usize>, Walk)>),
}

impl Evaluator {
    /// The BRDF for light from `wi` to `wo` (both above), one value per band into `out`: exact,
    /// or estimated with `samples` walks drawn from the stream `seed` (for a smooth top without
    /// its mirror reflection, a delta).
    pub fn eval(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        self.eval_body(wo, wi, samples, seed, scratch, out);
        if let Evaluator::Walks(walks) = self {
            for (bands, walk) in walks {
                let reflection = walk.top.f(wo, wi, Transport::Radiance);
                for &b in bands {
                    out[b] += reflection;
                }
            }
        }
    }

    /// The BRDF estimated so that swapping `wi` and `wo` gives the same value: half of
    /// `samples` (rounded up) walks each way, `f̂(a, b) = ½ (W(a → b) + W(b → a))`, both drawn
    /// from a stream seeded by what the pair has in common with its swap and with its turns
    /// about the normal (the two cosines, sorted, and the angle between the directions). Each
    /// half is an unbiased estimate of the same reciprocal BRDF, so their mean is too; its
    /// noise no longer differs between `(wi, wo)` and `(wo, wi)`.
    pub fn eval_reciprocal(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        if let Evaluator::Exact(_) = self {
            return self.eval(wo, wi, samples, 0, scratch, out);
        }
        let half = samples.div_ceil(2);
        let seed = pair_seed(wo, wi);
        self.eval(wo, wi, half, seed, scratch, out);
        let mut back = vec![0.0; out.len()];
        self.eval(wi, wo, half, seed, scratch, &mut back);
        for (o, b) in out.iter_mut().zip(&back) {
            *o = 0.5 * (*o + b);
        }
    }

    /// [`Evaluator::eval`] without the top interface's own reflection (for a smooth top, the
    /// same: its mirror reflection is never in `eval`).
    pub fn eval_body(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        match self {
            Evaluator::Exact(optics) => {
                for (o, at) in out.iter_mut().zip(optics) {
                    *o = at.brdf(wi.z, wo.z);
                }
            }
            Evaluator::Walks(walks) => {
                let groups = walks.len() as u64;
                let mut values = Vec::new();
                for (g, (bands, walk)) in walks.iter().enumerate() {
                    values.resize(bands.len(), 0.0);
                    let seed = seed.wrapping_mul(groups).wrapping_add(g as u64);
                    walk.eval_body(wo, wi, samples, seed, scratch, &mut values);
                    for (&b, v) in bands.iter().zip(&values) {
                        out[b] = *v;
                    }
                }
            }
        }
    }

    /// The top interface of the first group of bands (all groups share its roughness; their
    /// indices differ only with a dispersive coat).
    pub fn top(&self) -> Option<&Interface> {
        match self {
            Evaluator::Exact(_) => None,
            Evaluator::Walks(walks) => walks.first().map(|(_, w)| &w.top),
        }
    }

    /// The mirror reflectance of a smooth top at incidence `cos_i`, per band (0 for a rough
    /// top, whose reflection is in [`Evaluator::eval`]).
    pub fn mirror(&self, cos_i: f64) -> Vec<f64> {
        match self {
            Evaluator::Exact(optics) => optics.iter().map(|o| o.specular(cos_i)).collect(),
            Evaluator::Walks(walks) => {
                let bands = walks.iter().map(|(b, _)| b.len()).sum();
                let mut out = vec![0.0; bands];
                for (bands, walk) in walks {
                    let r = if walk.top.is_smooth() {
                        dielectric(cos_i, walk.top.eta)
                    } else {
                        0.0
                    };
                    for &b in bands {
                        out[b] = r;
                    }
                }
                out
            }
        }
    }

    /// The directional-hemispherical reflectance for light arriving at `cos_i`, per band, the
    /// mirror reflection included: exact, or by `samples` outgoing directions drawn with
    /// density cos θo/π, one walk each (standard error about 0.5/√samples of the value).
    pub fn albedo(&self, cos_i: f64, samples: usize) -> Vec<f64> {
        let mut total = self.mirror(cos_i);
        if let Evaluator::Exact(optics) = self {
            for (t, o) in total.iter_mut().zip(optics) {
                *t += o.body_albedo(cos_i);
            }
            return total;
        }
        let wi = DVec3::new((1.0 - cos_i * cos_i).max(0.0).sqrt(), 0.0, cos_i);
        let mut scratch = Scratch::default();
        let mut out = vec![0.0; total.len()];
        let mut sum = vec![0.0; total.len()];
        let mut rng = Pcg64Mcg::seed_from_u64(samples as u64);
        for k in 0..samples {
            let (u1, u2): (f64, f64) = (rng.random(), rng.random());
            let r = u1.sqrt();
            let phi = 2.0 * std::f64::consts::PI * u2;
            let wo = DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(1e-9).sqrt());
            self.eval(wo, wi, 1, k as u64, &mut scratch, &mut out);
            for (s, o) in sum.iter_mut().zip(&out) {
                *s += o;
            }
        }
        for (t, s) in total.iter_mut().zip(&sum) {
            *t += s * std::f64::consts::PI / samples as f64;
        }
        total
    }
}

/// A seed shared by a pair of directions, its swap and its turns about the normal: the two
/// cosines (sorted) and the cosine between them, each rounded to 1e-9 (so that the table's
/// cells, which compute their directions separately, agree), mixed by SplitMix64.
fn pair_seed(a: DVec3, b: DVec3) -> u64 {
    let q = |x: f64| (x * 1e9).round() as i64 as u64;
    let (lo, hi) = if a.z <= b.z { (a.z, b.z) } else { (b.z, a.z) };
    let mix = |mut z: u64| {
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    mix(mix(mix(q(lo)) ^ q(hi)) ^ q(a.dot(b)))
}
