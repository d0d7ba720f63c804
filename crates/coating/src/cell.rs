//! A table cell's estimate by the random walks: reciprocal, the same on any number of threads,
//! and with walks added where the noise in lightness is above a target.
//!
//! A cell's value is `½ (W(wi → wo) + W(wo → wi))`, both halves drawn from the same streams,
//! seeded by what the pair shares with its swap and its turns about the normal, so that the cell
//! and its reciprocal cell compute the same estimate.
//!
//! Walks where the noise is ([`CellWalks`]): every cell first takes the base walks, and each
//! estimates its standard error from them ([`Evaluator::eval_cell`]); then a cell takes as many
//! walks as its neighbours' standard errors say it needs to bring its own under the target
//! ([`walks_needed`], [`Evaluator::refine_cell`]). Why the neighbours' and not its own:
//!
//! - Heavy tails. On the silver metallic near the specular direction (the cells the readings
//!   at 15as-15 and 15as15 interpolate) the standard error that a cell's 32 walks show is a
//!   median 0.16–0.64 of its true one (the standard deviation of its L* over 100 independent
//!   estimates), and under 0.10–0.35 of it in 5% of the estimates: a few rare walks carry much
//!   of the variance and 32 walks usually miss them. The root mean square over the cell's 124
//!   neighbours ([`NEIGHBOURHOOD`], 3 968 walks) is a median 0.94–1.8 of it and at least 0.65
//!   in 95% of the estimates, over all 34 cells of the E2539 readings (the `--cells` study of
//!   `instrument/examples/table_noise.rs`).
//! - Bias. A cell that stops adding walks when its own walks look quiet keeps the estimates
//!   that missed the rare walks: the rule on the cell's own standard error read those
//!   near-specular cells 0.14–0.22 L* high on average (the same study), the neighbours' rule
//!   within 0.13 of the first walks' mean (that mean's own noise). The neighbours' walks are independent of the
//!   cell's, so its number of walks is too, and its estimate stays unbiased.
//!
//! Both passes are deterministic per cell, so the table stays the same on any number of threads;
//! a cell and its reciprocal have reciprocal neighbourhoods of equal estimates, so they take the
//! same walks and stay equal.
//!
//! Why in lightness: a reading's standard deviation in L* is what the multi-angle colour needs
//! (docs/coatings.md, "Noise"); the walks' noise in reflectance costs L* in proportion to the
//! slope of L* (CIE 15:2004, §8.2.1: (116/3) (Y/Yn)^(1/3) dY/Y above L* 8, linear below;
//! [`gonio_color::lightness_slope`]), so a dark cell needs a smaller relative error than a
//! bright one.

use crate::interface::Transport;
use crate::layered::{Scratch, Walk};
use crate::system::Evaluator;
use glam::DVec3;
use gonio_brdf::table::Resolution;
use gonio_color::{Illuminant, Observer, SpectralToXyz, lightness_slope};
use std::f64::consts::PI;

/// How many walks a table cell gets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellWalks {
    /// Walks per cell (half of them each way) before any are added: `--samples`.
    pub base: usize,
    /// The standard error of a cell's L* that walks are added to reach; `None` for a fixed
    /// number of walks.
    pub target_dl: Option<f64>,
    /// The most walks a cell takes, as a multiple of `base`.
    pub max_factor: usize,
    /// The streams' offset: 0 for the tables gonio writes; any other value gives estimates
    /// independent of them (as a table computed with other random numbers).
    pub stream: u64,
}

impl CellWalks {
    /// The most walks per cell, as a multiple of the base count.
    pub const MAX_FACTOR: usize = 16;

    /// `base` walks in every cell.
    pub fn fixed(base: usize) -> CellWalks {
        CellWalks {
            base,
            target_dl: None,
            max_factor: 1,
            stream: 0,
        }
    }

    /// `base` walks, and more where the cell's standard error in L* would be above `target_dl`,
    /// up to [`CellWalks::MAX_FACTOR`] times `base`. A target of 0, below 0, infinite or NaN
    /// gives `base` walks everywhere.
    pub fn adaptive(base: usize, target_dl: f64) -> CellWalks {
        if !(target_dl > 0.0 && target_dl.is_finite()) {
            return CellWalks::fixed(base);
        }
        CellWalks {
            target_dl: Some(target_dl),
            max_factor: CellWalks::MAX_FACTOR,
            ..CellWalks::fixed(base)
        }
    }

    /// The same walks with streams offset by `stream`.
    pub fn with_stream(self, stream: u64) -> CellWalks {
        CellWalks { stream, ..self }
    }

    /// The walks of a cell before any are added (an even number: half each way).
    pub fn first(&self) -> usize {
        2 * self.base.div_ceil(2)
    }

    /// The most walks one cell takes.
    pub fn most(&self) -> usize {
        self.first() * self.max_factor.max(1)
    }
}

/// The largest angle from the normal, degrees, of a direction that the multi-angle readings take
/// from a table: ASTM E2194 and E2539 view at most 65° off the normal (45as110 and 15as80), and
/// a reading at 65° interpolates cells within about 1.6° more (the theta_h spacing there on the
/// default 90-node grid; theta_d's is 1°). Cells with both directions within this angle are held
/// to the target; cells beyond it, which no standard geometry reads, to
/// [`GRAZING_TARGET_FACTOR`] times it ([`CellWalks::target_at`]).
pub const READ_LIMIT_DEG: f64 = 70.0;

/// How much looser the target is in a cell with a direction beyond [`READ_LIMIT_DEG`]: three
/// times, 1 L* for the default 1/3. There the walks' noise is largest (a dark flank, where the
/// slope of L* is steep, and heavy tails): on the silver metallic at 1/3 L* everywhere, the
/// cells with a direction beyond 63° took 71% of the table's walks and half of them stopped at
/// the cap still above the target, while no multi-angle reading needs them. The readings at
/// E2194/E2539 interpolate only cells within [`READ_LIMIT_DEG`], which keep their walks.
pub const GRAZING_TARGET_FACTOR: f64 = 3.0;

impl CellWalks {
    /// The target in L* of the table cell of the pair `(wo, wi)`: the target within
    /// [`READ_LIMIT_DEG`] of the normal, [`GRAZING_TARGET_FACTOR`] times it beyond; `None`
    /// for a fixed number of walks.
    pub fn target_at(&self, wo: DVec3, wi: DVec3) -> Option<f64> {
        let limit = READ_LIMIT_DEG.to_radians().cos();
        self.target_dl.map(|t| {
            if wo.z.min(wi.z) >= limit {
                t
            } else {
                t * GRAZING_TARGET_FACTOR
            }
        })
    }
}

/// `base` walks in every cell ([`CellWalks::fixed`]): what a number of walks meant before they
/// were added where the noise is (the pictures' tables still take them so).
impl From<usize> for CellWalks {
    fn from(base: usize) -> CellWalks {
        CellWalks::fixed(base)
    }
}

/// The walks a cell takes when its first walks' standard error in L* is expected to be `se_dl`
/// and its target is `target` ([`CellWalks::target_at`]): the error falls as 1/√n, so
/// `first · (se_dl / target)²`, rounded up to a multiple of the first walks and kept within
/// [`CellWalks::first`] and [`CellWalks::most`]. Without a target, the first walks.
pub fn walks_needed(walks: &CellWalks, target: Option<f64>, se_dl: f64) -> usize {
    let first = walks.first();
    let Some(target) = target else {
        return first;
    };
    // A NaN error casts to 0 batches, an infinite one to usize::MAX: both kept within bounds.
    let batches = (se_dl / target).powi(2).ceil() as usize;
    first * batches.clamp(1, walks.max_factor.max(1))
}

/// How far a cell's neighbourhood reaches, in nodes along each angle: two nodes either way, 124
/// neighbours in an isotropic table away from the grid's ends. With it the 34 cells of the
/// silver metallic's E2539 readings end at 0.15–0.34 L* (one standard deviation over 100
/// tables) for a target of 1/3 (module documentation).
pub const NEIGHBOURHOOD: usize = 2;

/// The cells within `radius` nodes of `index` in `res` along each angle (phi_h only in an
/// anisotropic table; phi_d and phi_h wrap around, theta_h and theta_d stop at the grid's
/// ends), `index` itself left out: (2 radius + 1)³ − 1 in an isotropic table away from the
/// ends.
pub fn neighbours(res: &Resolution, index: usize, radius: usize) -> Vec<usize> {
    let [ph, th, td, pd] = res.cell_indices(index);
    let r = radius as i64;
    let side = 2 * r + 1;
    let ph_side = if res.is_isotropic() { 1 } else { side };
    let wrap = |i: usize, d: i64, n: usize| (i as i64 + d).rem_euclid(n as i64) as usize;
    let clamp = |i: usize, d: i64, n: usize| {
        let j = i as i64 + d;
        (0..n as i64).contains(&j).then_some(j as usize)
    };
    let mut cells = Vec::new();
    for k in 0..ph_side * side * side * side {
        let offset = |place: i64| (k / place) % side - r;
        let dph = if res.is_isotropic() {
            0
        } else {
            offset(side * side * side)
        };
        let (dth, dtd, dpd) = (offset(side * side), offset(side), offset(1));
        let (Some(th), Some(td)) = (clamp(th, dth, res.theta_h), clamp(td, dtd, res.theta_d))
        else {
            continue;
        };
        let cell = res.cell_index(wrap(ph, dph, res.phi_h), th, td, wrap(pd, dpd, res.phi_d));
        cells.push(cell);
    }
    // A φ circle of fewer than 2 radius + 1 nodes meets the same cells twice.
    cells.sort_unstable();
    cells.dedup();
    cells.retain(|&c| c != index);
    cells
}

/// The standard error in L* that a cell's first walks are expected to have, from its
/// neighbours' (`se` gives a cell's, `None` where it has none): the root mean square over the
/// neighbours, the variances pooled. `None` when no neighbour has one.
pub fn neighbourhood_se(
    res: &Resolution,
    index: usize,
    se: impl Fn(usize) -> Option<f64>,
) -> Option<f64> {
    let (mut sum, mut count) = (0.0, 0usize);
    for cell in neighbours(res, index, NEIGHBOURHOOD) {
        if let Some(s) = se(cell) {
            sum += s * s;
            count += 1;
        }
    }
    (count > 0).then(|| (sum / count as f64).sqrt())
}

/// The weight of each band in the luminance Y/Yn of a reflectance factor: the CIE 1964 10°
/// observer under D65, as the multi-angle readings take it (`gonio multiangle`), by the
/// weighting factors of ASTM E308 ([`SpectralToXyz`]; the spectrum is linear between bands and
/// held beyond the first and last, so the weights sum to 1 for any bands).
pub fn luminance_weights(wavelengths_nm: &[f64]) -> crate::Result<Vec<f64>> {
    if let [_] = wavelengths_nm {
        return Ok(vec![1.0]);
    }
    let reduce = SpectralToXyz::new(wavelengths_nm, Illuminant::D65, Observer::Cie1964TenDegree)
        .map_err(|e| crate::CoatingError::Invalid(format!("bands: {e}")))?;
    Ok(reduce.xyz_weights().iter().map(|w| w[1] / 100.0).collect())
}

impl Evaluator {
    /// A table cell's BRDF for the pair `(wo, wi)` from its first walks
    /// ([`CellWalks::first`], half each way), one value per band into `out`, estimated so that
    /// swapping `wi` and `wo` gives the same value; and the standard error of the cell's L*
    /// that the walks show (0 for the exact series). `luminance` weights the bands
    /// ([`luminance_weights`]).
    ///
    /// The standard error: walk k of the two halves, `a_k` and `b_k` (luminance-weighted,
    /// drawn from the same stream and so correlated), make one sample `c_k = ½ (a_k + b_k)` of
    /// the cell's estimate `c̄`, whose variance is estimated by `s²(c) / n` as for independent
    /// walks. In L*: `π s(c)/√n` times [`lightness_slope`] at the cell's luminance factor. The
    /// Sobol stratification between walks makes the true error smaller than this, more so as
    /// the walks grow: an estimate on the safe side (the readings' measured noise is in
    /// docs/coatings.md, "Noise").
    pub fn eval_cell(
        &self,
        wo: DVec3,
        wi: DVec3,
        walks: &CellWalks,
        luminance: &[f64],
        scratch: &mut Scratch,
        out: &mut [f64],
    ) -> f64 {
        if let Evaluator::Exact(_) = self {
            self.eval(wo, wi, 0, 0, scratch, out);
            return 0.0;
        }
        let nb = out.len();
        let n = walks.first() / 2;
        let seed = cell_seed(wo, wi, walks);
        let top = [self.reflection(wo, wi), self.reflection(wi, wo)];
        let mut per_walk = [vec![0.0; n], vec![0.0; n]];
        let mut back = vec![0.0; nb];
        for (side, (a, b), values) in [(0, (wo, wi), &mut *out), (1, (wi, wo), &mut back)] {
            values.fill(0.0);
            let tally = Some((luminance, per_walk[side].as_mut_slice()));
            self.add_walks(a, b, 0..n, seed, scratch, values, tally);
            for (v, r) in values.iter_mut().zip(&top[side]) {
                *v /= n as f64;
                *v += r;
            }
        }
        for (o, b) in out.iter_mut().zip(&back) {
            *o = 0.5 * (*o + b);
        }
        let samples: Vec<f64> = per_walk[0]
            .iter()
            .zip(&per_walk[1])
            .map(|(a, b)| 0.5 * (a + b))
            .collect();
        let weighted = |f: &[f64]| f.iter().zip(luminance).map(|(a, w)| a * w).sum::<f64>();
        lightness_error(&samples, PI * weighted(out))
    }

    /// A cell whose `out` holds its first walks' estimate ([`Evaluator::eval_cell`]) taken on
    /// to `total` walks (half each way) of the same streams: walks `first/2 .. total/2` of each
    /// half added to the sums the first ones left.
    pub fn refine_cell(
        &self,
        wo: DVec3,
        wi: DVec3,
        walks: &CellWalks,
        total: usize,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        let (first, total) = (walks.first() / 2, total / 2);
        if total <= first || matches!(self, Evaluator::Exact(_)) {
            return;
        }
        let seed = cell_seed(wo, wi, walks);
        let top = [self.reflection(wo, wi), self.reflection(wi, wo)];
        let mut sums = vec![0.0; out.len()];
        self.add_walks(wo, wi, first..total, seed, scratch, &mut sums, None);
        self.add_walks(wi, wo, first..total, seed, scratch, &mut sums, None);
        // The first estimate is (S_a + S_b) / (2 first) + r̄ with r̄ the top's reflection
        // averaged both ways; the whole one (S_a + S_b + the new sums) / (2 total) + r̄.
        for ((o, s), (ra, rb)) in out.iter_mut().zip(&sums).zip(top[0].iter().zip(&top[1])) {
            let r = 0.5 * (ra + rb);
            let before = 2.0 * first as f64 * (*o - r);
            *o = (before + s) / (2.0 * total as f64) + r;
        }
    }

    /// The top interface's own reflection from `wi` to `wo`, per band (0 for the exact series,
    /// whose mirror is not in its values).
    fn reflection(&self, wo: DVec3, wi: DVec3) -> Vec<f64> {
        let Evaluator::Walks(groups) = self else {
            return Vec::new();
        };
        let mut r = vec![0.0; groups.iter().map(|(b, _)| b.len()).sum()];
        for (bands, walk) in groups {
            let f = walk.top.f(wo, wi, Transport::Radiance);
            bands.iter().for_each(|&k| r[k] = f);
        }
        r
    }

    /// Walks `walks` of the estimate seeded `seed`, for every group of bands, their
    /// contributions added into `sums` (per band, not divided by the number of walks) and, with
    /// `tally`, each walk's contributions weighted by `tally.0` (per band) into `tally.1`
    /// ([`Walk::add_walks`]). Walk `k` draws the same numbers whatever range it is run in, so
    /// the walks `0..n` of [`Evaluator::eval_body`] can be run in groups (the gloss meter's
    /// jackknife over groups of walks, `instrument::coating_study`); nothing for the exact
    /// series.
    #[allow(clippy::too_many_arguments)]
    pub fn add_walks(
        &self,
        wo: DVec3,
        wi: DVec3,
        walks: std::ops::Range<usize>,
        seed: u64,
        scratch: &mut Scratch,
        sums: &mut [f64],
        mut tally: Option<(&[f64], &mut [f64])>,
    ) {
        let Evaluator::Walks(groups) = self else {
            return;
        };
        let count = groups.len() as u64;
        let (mut group_sums, mut group_weights) = (Vec::new(), Vec::new());
        for (g, (bands, walk)) in groups.iter().enumerate() {
            let seed = seed.wrapping_mul(count).wrapping_add(g as u64);
            group_sums.clear();
            group_sums.extend(bands.iter().map(|&b| sums[b]));
            let group_tally = match tally.as_mut() {
                Some((weights, values)) => {
                    group_weights.clear();
                    group_weights.extend(bands.iter().map(|&b| weights[b]));
                    Some((group_weights.as_slice(), &mut **values))
                }
                None => None,
            };
            walk.add_walks(
                wo,
                wi,
                walks.clone(),
                seed,
                Walk::MAX_DEPTH,
                scratch,
                &mut group_sums,
                group_tally,
            );
            for (&b, s) in bands.iter().zip(&group_sums) {
                sums[b] = *s;
            }
        }
    }
}

/// The standard error in L* of a cell whose walks gave the luminance-weighted samples
/// `samples` (1/sr) and whose luminance factor is `y`: `π s/√n` in the luminance factor, times
/// the slope of L* at `y`. With fewer than two walks, 0.
fn lightness_error(samples: &[f64], y: f64) -> f64 {
    let n = samples.len() as f64;
    if samples.len() < 2 {
        return 0.0;
    }
    let mean = samples.iter().sum::<f64>() / n;
    let var = samples.iter().map(|c| (c - mean).powi(2)).sum::<f64>() / (n - 1.0);
    PI * (var / n).sqrt() * lightness_slope(y)
}

/// The streams' seed of a cell: [`pair_seed`], offset by the walks' stream.
fn cell_seed(wo: DVec3, wi: DVec3, walks: &CellWalks) -> u64 {
    pair_seed(wo, wi).wrapping_add(walks.stream.wrapping_mul(0x9e37_79b9_7f4a_7c15))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description;
    use std::path::Path;

    fn silver(wl: &[f64]) -> Evaluator {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/coatings/silver_metallic.toml");
        description::read(&path, wl).unwrap().evaluator(wl).unwrap()
    }

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// With a fixed number of walks a cell is the reciprocal estimate `½ (W(wo → wi) +
    /// W(wi → wo))` of half the walks each way from the pair's stream, bit for bit (the tables
    /// gonio wrote before the walks were added where the noise is); and a cell taken on to
    /// more walks is that estimate with all of them, to rounding (the sums are split in two).
    #[test]
    fn a_cell_is_the_reciprocal_estimate_of_its_walks() {
        let wl = [450.0, 550.0, 650.0];
        let evaluator = silver(&wl);
        let luminance = luminance_weights(&wl).unwrap();
        let (wo, wi) = (dir(30.0, 180.0), dir(45.0, 0.0));
        let seed = pair_seed(wo, wi);
        let reciprocal = |n: usize| {
            let (mut a, mut b) = (vec![0.0; 3], vec![0.0; 3]);
            evaluator.eval(wo, wi, n, seed, &mut Scratch::default(), &mut a);
            evaluator.eval(wi, wo, n, seed, &mut Scratch::default(), &mut b);
            a.iter()
                .zip(&b)
                .map(|(x, y)| 0.5 * (x + y))
                .collect::<Vec<_>>()
        };
        let mut cell = vec![0.0; 3];
        let walks = CellWalks::fixed(16);
        evaluator.eval_cell(
            wo,
            wi,
            &walks,
            &luminance,
            &mut Scratch::default(),
            &mut cell,
        );
        assert_eq!(cell, reciprocal(8));
        evaluator.refine_cell(wo, wi, &walks, 64, &mut Scratch::default(), &mut cell);
        for (c, r) in cell.iter().zip(reciprocal(32)) {
            assert!((c / r - 1.0).abs() < 1e-12, "{c} against {r}");
        }
    }

    /// The walks a cell takes: the first walks when its expected error is within the target,
    /// `first (se/target)²` rounded up to whole batches of the first walks otherwise, at most
    /// `MAX_FACTOR` times the first walks; without a target, the first walks.
    #[test]
    fn walks_follow_the_expected_error() {
        let walks = CellWalks::adaptive(32, 0.5);
        assert_eq!(walks.most(), 512);
        assert_eq!(walks_needed(&walks, walks.target_dl, 0.2), 32);
        assert_eq!(walks_needed(&walks, walks.target_dl, 0.5), 32);
        assert_eq!(walks_needed(&walks, walks.target_dl, 1.0), 128);
        assert_eq!(walks_needed(&walks, walks.target_dl, 0.55), 64);
        assert_eq!(walks_needed(&walks, walks.target_dl, 50.0), 512);
        assert_eq!(walks_needed(&walks, walks.target_dl, f64::NAN), 32);
        assert_eq!(walks_needed(&CellWalks::fixed(32), None, 50.0), 32);
        // The target loosens beyond the readings' angles: a cell with a direction at 75°.
        let (near, far) = (
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(75f64.to_radians().sin(), 0.0, 75f64.to_radians().cos()),
        );
        let inside = DVec3::new(65f64.to_radians().sin(), 0.0, 65f64.to_radians().cos());
        assert_eq!(walks.target_at(near, inside), Some(0.5));
        assert_eq!(
            walks.target_at(far, near),
            Some(0.5 * GRAZING_TARGET_FACTOR)
        );
        assert_eq!(
            walks.target_at(near, far),
            Some(0.5 * GRAZING_TARGET_FACTOR)
        );
        assert_eq!(walks_needed(&walks, walks.target_at(near, far), 1.0), 32);
        assert_eq!(CellWalks::fixed(32).target_at(near, far), None);
        assert_eq!(CellWalks::adaptive(32, 0.0), CellWalks::fixed(32));
        assert_eq!(CellWalks::adaptive(32, f64::INFINITY), CellWalks::fixed(32));
        assert_eq!(CellWalks::fixed(5).first(), 6);
    }

    /// A neighbourhood of radius 2 holds 124 cells away from the grid's ends, fewer at θh = 0,
    /// wraps around φd, and is mutual (j is i's neighbour exactly when i is j's), so that the
    /// first pass's cells are the neighbourhoods of the cells kept.
    #[test]
    fn neighbourhoods_are_mutual() {
        let res = Resolution::isotropic(8, 7, 6);
        let middle = res.cell_index(0, 4, 3, 0);
        let around = neighbours(&res, middle, 2);
        assert_eq!(around.len(), 124);
        assert!(around.contains(&res.cell_index(0, 4, 3, 5)), "φd wraps");
        assert_eq!(neighbours(&res, res.cell_index(0, 0, 3, 2), 2).len(), 74);
        for i in 0..res.cell_count() {
            for j in neighbours(&res, i, 2) {
                assert!(neighbours(&res, j, 2).contains(&i), "{i} and {j}");
            }
        }
        let anisotropic = Resolution::anisotropic(5, 5, 6, 4);
        let middle = anisotropic.cell_index(2, 2, 2, 3);
        assert_eq!(neighbours(&anisotropic, middle, 1).len(), 80);
    }

    /// The luminance weights are those of Y for D65 and the 10° observer, summing to 1 for the
    /// visible bands and for bands beyond them (the spectrum is held beyond the last band).
    #[test]
    fn luminance_weights_sum_to_one() {
        let bands: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let w = luminance_weights(&bands).unwrap();
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        let peak = w.iter().cloned().fold(0.0, f64::max);
        assert_eq!(
            w.iter().position(|&x| x == peak),
            Some(15),
            "the peak at 550 nm"
        );
        let infrared = luminance_weights(&[800.0, 900.0]).unwrap();
        // The observer's tables end at 830 nm: 900 nm takes the little between 800 and 830.
        assert!(
            (infrared.iter().sum::<f64>() - 1.0).abs() < 1e-9 && infrared[1] < 1e-6,
            "{infrared:?}"
        );
        assert_eq!(luminance_weights(&[550.0]).unwrap(), vec![1.0]);
    }
}
