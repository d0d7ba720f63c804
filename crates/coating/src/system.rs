//! A coating system: the top interface (smooth, or rough with a microfacet distribution), the
//! clear coat, optional effect flakes and the base; its spectral BRDF table.
//!
//! A smooth top over a diffuse base has an exact closed form ([`crate::clear_coat`]), which the
//! table then uses; every other system goes through the random walks of [`crate::layered`].
//! With a smooth top the table holds the body reflection (the mirror reflection `F(θi)`, a delta,
//! is left out and said so in the provenance); with a rough top it holds everything the coating
//! reflects.

use crate::basecoat;
use crate::cell::{self, CellWalks, luminance_weights};
use crate::clear_coat::{self, AtWavelength, Base, ClearCoatOverBase, Coat};
use crate::error::{CoatingError, Result};
use crate::flakes::{FlakeLayer, Flakes};
use crate::interface::{Interface, Transport};
use crate::layered::{Scratch, Walk};
use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_brdf::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use gonio_io::Cancel;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// Random walks per table cell before any are added (`gonio coating compute --samples`, the
/// pictures' tables): half each way ([`crate::cell`]).
pub const TABLE_WALKS: usize = 32;

/// The bands of a coating's tables and readings unless told otherwise: 400, 410, ..., 700 nm
/// (31 bands, the CIE tables' 10 nm step over the visible).
pub fn default_bands() -> Vec<f64> {
    (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
}

/// The standard error of a table cell's L* above which walks are added (in batches of
/// the first walks, up to [`CellWalks::MAX_FACTOR`] times them) unless told otherwise
/// (`gonio coating compute --target-dl`). A reading interpolates up to eight cells with weights
/// `w_k` that sum to 1; their estimates are independent, so the reading's variance is
/// `Σ w_k² σ_k² ≤ max σ_k² Σ w_k² ≤ max σ_k²` (equality on a node): cells within 1/3 L* keep
/// every reading within 1/3 L* (one standard deviation), so that 1 L* is three (docs/coatings.md,
/// "Noise").
pub const TARGET_DL: f64 = 1.0 / 3.0;

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
    /// Random walks, so many per table cell.
    RandomWalk(CellWalks),
}

/// The walks a table's cells took (those computed, above the horizon).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spent {
    /// Cells computed by the walks.
    pub cells: usize,
    /// Walks in all.
    pub walks: u64,
    /// The most walks one cell took.
    pub max: usize,
    /// Cells that stopped at the most walks allowed ([`CellWalks::most`]) with an expected
    /// standard error still above the target.
    pub capped: usize,
}

impl Spent {
    /// Walks per cell on average.
    pub fn mean(&self) -> f64 {
        self.walks as f64 / self.cells.max(1) as f64
    }

    /// `M on average, N at most`, and the share of the cells left above the target at the cap.
    pub fn describe(&self) -> String {
        let mut text = format!("{:.1} on average, {} at most", self.mean(), self.max);
        if self.capped > 0 {
            text.push_str(&format!(
                " ({} cells, {:.2}%, at the most and still above the target)",
                self.capped,
                100.0 * self.capped as f64 / self.cells.max(1) as f64
            ));
        }
        text
    }
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
            if f.depth.is_some() {
                basecoat::layer_of(&self.base)?;
            }
        }
        Ok(())
    }

    /// How [`Coating::table`] computes with `walks` per cell.
    pub fn method(&self, walks: impl Into<CellWalks>) -> Method {
        match self.clear_coat() {
            Some(_) => Method::ClosedForm,
            None => Method::RandomWalk(walks.into()),
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
                    // Inside the basecoat the flakes are the basecoat walk's.
                    Some(f) if f.depth.is_some() => FlakeLayer::bare(rho),
                    Some(f) => {
                        let optics = wl
                            .iter()
                            .map(|&w| f.optics(n, w))
                            .collect::<Result<Vec<_>>>()?;
                        FlakeLayer::new(f, optics, rho)
                    }
                };
                let basecoat = match &self.flakes {
                    Some(f) => f
                        .depth
                        .map(|depth| basecoat::embedded(f, depth, &self.base, n, &wl))
                        .transpose()?,
                    None => None,
                };
                let walk = Walk {
                    top: Interface::new(n, self.roughness),
                    tau,
                    bottom,
                    basecoat,
                };
                Ok((bands, walk))
            })
            .collect()
    }

    /// The provenance of a table made from the description at `source` ([`Coating::table`]
    /// adds the walks it spent).
    pub fn provenance(&self, source: impl Into<String>, method: Method) -> Provenance {
        let Method::RandomWalk(walks) = method else {
            return clear_coat::body_provenance(source);
        };
        let mut provenance = Provenance::new(source, "coating:layered-random-walk");
        let mirror = if self.roughness.is_none() {
            "; the smooth top's mirror reflection F(θi) is not in the table"
        } else {
            ""
        };
        let count = match walks.target_dl {
            None => format!("{} walks per cell", walks.base),
            Some(target) => format!(
                "{} walks per cell and more (up to {}) where the walks of the cell's \
                 neighbourhood put its standard error above {target:.3} L* ({:.3} L* where a \
                 direction is more than {}° from the normal)",
                walks.base,
                walks.most(),
                target * cell::GRAZING_TARGET_FACTOR,
                cell::READ_LIMIT_DEG
            ),
        };
        provenance.description = Some(format!(
            "coating system by position-free Monte Carlo layered transport (Guo et al. 2018), \
             {count}{mirror}"
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
    /// `wavelengths_nm`, by the exact series where it applies and otherwise by random walks,
    /// `walks` per cell (a number: that many in every cell;
    /// [`Evaluator::eval_cell`]: the table is reciprocal to its interpolation and does not depend
    /// on the number of threads). What the walks spent is in the table's provenance
    /// (`walks_per_cell`).
    pub fn table(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        walks: impl Into<CellWalks>,
        provenance: Provenance,
    ) -> Result<BrdfTable> {
        self.table_until(
            resolution,
            wavelengths_nm,
            walks,
            provenance,
            &Cancel::default(),
        )
    }

    /// [`Coating::table`] that stops when `cancel` is raised: each cell looks at the flag before
    /// its walks (a cell's walks take milliseconds at most), and the whole returns
    /// [`CoatingError::Cancelled`] instead of a table. Not cancelled, the table is the same bit
    /// for bit.
    pub fn table_until(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        walks: impl Into<CellWalks>,
        provenance: Provenance,
        cancel: &Cancel,
    ) -> Result<BrdfTable> {
        self.cells(
            resolution,
            wavelengths_nm,
            walks.into(),
            provenance,
            |_| true,
            cancel,
            false,
        )
        .map(|(table, _)| table)
    }

    /// [`Coating::table_until`] without the flakes' glint ([`crate::glint::Glint`]): the
    /// table a renderer that draws the flakes one by one ([`crate::glint::Glint::flake`]) adds
    /// them to. The walks leave out the light that meets the flake layer once and is mirrored
    /// by a flake (the layer's BRDF at such a single visit taken without the flakes' lobe,
    /// [`FlakeLayer::without_glint`]), so that the rest carries none of the glint's noise; under
    /// a smooth top the table and this one differ by the glint exactly (each walk's single
    /// visit is exact there). The provenance says what was left out (`glint`).
    pub fn table_without_glint(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        walks: impl Into<CellWalks>,
        provenance: Provenance,
        cancel: &Cancel,
    ) -> Result<BrdfTable> {
        self.cells(
            resolution,
            wavelengths_nm,
            walks.into(),
            provenance,
            |_| true,
            cancel,
            true,
        )
        .map(|(table, _)| table)
    }

    /// [`Coating::table`] with the walks run only in the cells whose index `keep` accepts (the
    /// others hold 0): what a reading at a few geometries interpolates, each cell as in the
    /// whole table, without the whole table's cost. The exact series fills every cell. With
    /// the walks the cells took.
    pub fn table_cells(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        walks: impl Into<CellWalks>,
        provenance: Provenance,
        keep: impl Fn(usize) -> bool + Sync,
    ) -> Result<(BrdfTable, Spent)> {
        let cancel = Cancel::default();
        self.cells(
            resolution,
            wavelengths_nm,
            walks.into(),
            provenance,
            keep,
            &cancel,
            false,
        )
    }

    /// [`Coating::table_cells`], stopped by `cancel` ([`Coating::table_until`]), without the
    /// flakes' glint when `glint_left_out` ([`Coating::table_without_glint`]).
    #[allow(clippy::too_many_arguments)]
    fn cells(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        walks: CellWalks,
        mut provenance: Provenance,
        keep: impl Fn(usize) -> bool + Sync,
        cancel: &Cancel,
        glint_left_out: bool,
    ) -> Result<(BrdfTable, Spent)> {
        let stopped = || {
            if cancel.is_cancelled() {
                Err(CoatingError::Cancelled)
            } else {
                Ok(())
            }
        };
        if let Some(exact) = self.clear_coat() {
            self.check(wavelengths_nm)?;
            let table = exact.body_table(resolution, wavelengths_nm, provenance)?;
            stopped()?;
            return Ok((table, Spent::default()));
        }
        if walks.base == 0 {
            return Err(CoatingError::Invalid(
                "samples: at least one random walk per cell is needed".into(),
            ));
        }
        let embedded = self.flakes.as_ref().is_some_and(|f| f.depth.is_some());
        if glint_left_out && embedded {
            return Err(basecoat::glint_not_modelled());
        }
        let mut evaluator = self.evaluator(wavelengths_nm)?;
        if glint_left_out && let Evaluator::Walks(groups) = &mut evaluator {
            for (_, walk) in groups.iter_mut() {
                walk.bottom = walk.bottom.clone().without_glint();
            }
        }
        let luminance = luminance_weights(wavelengths_nm)?;
        let channels = Channels::Spectral {
            wavelengths_nm: wavelengths_nm.to_vec(),
        };
        let table_error = |e: gonio_brdf::BrdfError| CoatingError::Invalid(e.to_string());
        let mut builder = TableBuilder::new(resolution, channels).map_err(table_error)?;
        // First pass: the first walks in every cell kept and, when walks are to be added, in
        // its neighbourhood, each with the standard error it shows (crate::cell).
        let adaptive = walks.target_dl.is_some();
        let first_se: Vec<AtomicU64> = (0..resolution.cell_count())
            .map(|_| AtomicU64::new(f64::NAN.to_bits()))
            .collect();
        // The coating is reciprocal (each cell's estimate is, [`Evaluator::eval_cell`]) and,
        // isotropic, symmetric about the plane of incidence: the walks run in one cell of each
        // class of cells these relate ([`Resolution::representative_cell`]), which stands for
        // the class and whose values the others take. A class is kept (wanted) when any of its
        // cells is.
        let representative = |i: usize| resolution.representative_cell(i, true);
        let mut kept = vec![false; resolution.cell_count()];
        for i in (0..resolution.cell_count()).filter(|&i| keep(i)) {
            kept[representative(i)] = true;
        }
        let mut wanted = kept.clone();
        if adaptive && wanted.contains(&false) {
            for i in (0..resolution.cell_count()).filter(|&i| kept[representative(i)]) {
                for n in cell::neighbours(&resolution, i, cell::NEIGHBOURHOOD) {
                    wanted[representative(n)] = true;
                }
            }
        }
        builder.fill_symmetric(true, |c, out| {
            if wanted[c.index] && !cancel.is_cancelled() {
                let se = evaluator.eval_cell(
                    c.wo,
                    c.wi,
                    &walks,
                    &luminance,
                    &mut Scratch::default(),
                    out,
                );
                first_se[c.index].store(se.to_bits(), Ordering::Relaxed);
            }
        });
        stopped()?;
        // Second pass: the cells kept take the walks their neighbourhood asks for.
        let se_of = |i: usize| {
            let i = representative(i);
            Some(f64::from_bits(first_se[i].load(Ordering::Relaxed))).filter(|s| !s.is_nan())
        };
        let [cells, max, capped] = [0; 3].map(AtomicUsize::new);
        let total = AtomicU64::new(0);
        builder.refine_symmetric(true, |c, out| {
            if !kept[c.index] || cancel.is_cancelled() {
                out.fill(0.0);
                return;
            }
            let target = walks.target_at(c.wo, c.wi);
            let (count, short) = match target {
                None => (walks.first(), false),
                Some(target) => {
                    let se = cell::neighbourhood_se(&resolution, c.index, se_of)
                        .or_else(|| se_of(c.index))
                        .unwrap_or(0.0);
                    let count = cell::walks_needed(&walks, Some(target), se);
                    (
                        count,
                        se * (walks.first() as f64 / count as f64).sqrt() > target,
                    )
                }
            };
            evaluator.refine_cell(c.wo, c.wi, &walks, count, &mut Scratch::default(), out);
            cells.fetch_add(1, Ordering::Relaxed);
            total.fetch_add(count as u64, Ordering::Relaxed);
            max.fetch_max(count, Ordering::Relaxed);
            capped.fetch_add(usize::from(short), Ordering::Relaxed);
        });
        stopped()?;
        let spent = Spent {
            cells: cells.into_inner(),
            walks: total.into_inner(),
            max: max.into_inner(),
            capped: capped.into_inner(),
        };
        spent.record(&mut provenance, &walks);
        if glint_left_out {
            provenance.extra.insert(
                "glint".into(),
                serde_json::json!({
                    "left_out": "the flakes' glint, drawn flake by flake by the renderer",
                }),
            );
        }
        builder
            .with_provenance(provenance)
            .build()
            .map_err(table_error)
            .map(|t| (t, spent))
    }
}

impl Spent {
    /// Add what was spent to a table's provenance: `walks_per_cell` (base, target in L*,
    /// mean, max) and the description's last words.
    fn record(&self, provenance: &mut Provenance, walks: &CellWalks) {
        provenance.extra.insert(
            "walks_per_cell".into(),
            serde_json::json!({
                "base": walks.base,
                "target_dl": walks.target_dl,
                "mean": self.mean(),
                "max": self.max,
                "cells_at_cap_above_target": self.capped,
            }),
        );
        if let Some(d) = provenance.description.as_mut() {
            d.push_str(&format!("; walks per cell: {}", self.describe()));
        }
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
            Evaluator::Walks(_) => {
                out.fill(0.0);
                if samples == 0 {
                    return;
                }
                self.add_walks(wo, wi, 0..samples, seed, scratch, out, None);
                for o in out.iter_mut() {
                    *o /= samples as f64;
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
    /// mirror reflection included: exact, or the top's own reflection by 64 × 64 stratified
    /// samples of its lobes ([`Interface::reflection_samples`]) plus the light from inside the
    /// coat by `samples` outgoing directions drawn with density cos θo/π, one walk each
    /// ([`Evaluator::eval_body`]). The top's lobe is sampled, not found by the cosine-weighted
    /// directions: a glossy lobe that those rarely hit left the silver metallic's albedo at 75°
    /// at 0.41 ± 0.15 (mean ± standard deviation over 16 estimates of 2048 directions; 0.51 at
    /// 65 536), docs/instruments.md, "The lab's readings".
    pub fn albedo(&self, cos_i: f64, samples: usize) -> Vec<f64> {
        let mut total = self.mirror(cos_i);
        if let Evaluator::Exact(optics) = self {
            for (t, o) in total.iter_mut().zip(optics) {
                *t += o.body_albedo(cos_i);
            }
            return total;
        }
        let wi = DVec3::new((1.0 - cos_i * cos_i).max(0.0).sqrt(), 0.0, cos_i);
        if let Evaluator::Walks(groups) = self {
            const STRATA: usize = 64;
            for (bands, walk) in groups {
                if walk.top.is_smooth() {
                    continue;
                }
                let reflected = walk
                    .top
                    .reflection_samples(wi, STRATA)
                    .filter(|s| s.wi.z > 0.0)
                    .map(|s| s.weight())
                    .sum::<f64>()
                    / (STRATA * STRATA) as f64;
                for &b in bands {
                    total[b] += reflected;
                }
            }
        }
        let mut scratch = Scratch::default();
        let mut out = vec![0.0; total.len()];
        let mut sum = vec![0.0; total.len()];
        let mut rng = Pcg64Mcg::seed_from_u64(samples as u64);
        for k in 0..samples {
            let (u1, u2): (f64, f64) = (rng.random(), rng.random());
            let r = u1.sqrt();
            let phi = 2.0 * std::f64::consts::PI * u2;
            let wo = DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(1e-9).sqrt());
            self.eval_body(wo, wi, 1, k as u64, &mut scratch, &mut out);
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
