//! Importance sampling of a tabulated BRDF (method and measurements: `docs/brdf-tables.md`,
//! "Importance sampling").
//!
//! For a set of nodes of the conditioning direction `wo` (theta_o, and phi_o for anisotropic
//! tables), the BRDF is split into the largest constant that fits under it, `c = min f` over the
//! node's grid (the "smallest hemisphere inside the data"), sampled by the cosine law, and the
//! remainder `f - c`, sampled in the coordinates of the visible normals of a GGX fitted to the
//! table ([`super::vndf_warp`]): a point of the unit square is drawn from a piecewise-bilinear
//! density through node values of the remainder's density in those coordinates (Mitsuba 3's
//! `Marginal2D`, [`crate::sampling::Marginal2D`]), mapped to the unit disk by the concentric map
//! and to a visible normal `h` of the fitted GGX by Heitz's (2018) half-disk warp, and
//! `wi = reflect(wo, h)`. This is the parameterisation of Mitsuba's `measured` plugin (Dupuy &
//! Jakob 2018), with a fitted GGX in place of the material's own distribution: the warp follows
//! the lobe, off the normal and cut by the horizon at grazing `wo`, so that the tabulated
//! correction is nearly flat (for a GGX table it is `F G2 / G1`, zero where `wi` falls below
//! the horizon), and the bilinear correction makes a continuous warp that keeps the
//! stratification of the renderer's low-discrepancy points.
//!
//! It replaced cells of the half vector polar about the normal (rows in `sqrt(theta_h)`,
//! columns in azimuth), piecewise constant: on the benchmark sphere of
//! `crates/render/benches/versus_mitsuba.py` at equal samples, the squared error of the rings of
//! pixels 1–3 px inside the silhouette (theta_o 77–83°) fell by 49% (GGX alpha 0.2) and 38%
//! (alpha 0.05), of the silhouette pixels by 11% and 29%, of the rings 4–8 px inside by 25%
//! for both, and the interior's changed by −1% and +2% (within the spread of seeds). The
//! render's CPU time grew by about 15%, of which 0.2 s is the build (0.25 s against 0.05 s for
//! a 90 × 90 × 180 table): at equal time the whole image's squared error is about 0.9 of the
//! cells', the rings' 0.6–0.7, the interior's 1.15 (`docs/brdf-tables.md`).
//!
//! A node's density on the square is `g = (f - c) cos θi dωi / d(square)`, with
//! `dωi / d(square) = 1 / wi_density` ([`super::vndf_warp`]). Between nodes of `wo` the density
//! is the mixture of the neighbouring nodes' densities with weights linear in theta_o (and
//! phi_o): the cosine law with probability `Σ w_b p_b`, and otherwise the square's density
//! `Σ w_b g_b / E_b`, which the `Marginal2D` samples by inverting the interpolated cumulative
//! distributions (the mixture's own, monotone in each coordinate and continuous in the weights),
//! not by choosing a node with part of `u.x`, which cuts the range of `u.x` into pieces whose
//! ends move with `wo`, so that the points of one pixel (whose `wo` varies across it) land in
//! two unrelated warps. The two parts of a node are chosen in proportion to their energies,
//! `c π` and `E_b = ∫ (f - c) cos θi dωi`, the first weighted by `κ = 1` unless the caller asks
//! for less (below). [`TableSampler::pdf`] returns the density of the whole mixture for any pair
//! of directions.
//!
//! Compensation. With `κ = 1` the samples follow `f cos θi`. A renderer that also samples its
//! lights and weights the two by multiple importance sampling may want fewer BRDF samples in the
//! constant part: there the integrand is `c L cos θi`, which a light sampled in proportion to
//! `L cos θi` samples exactly, while the lobe's part, which only the BRDF sample finds where the
//! lobe is narrower than the light's features, is sampled no more often than its share of the
//! energy (a glossy coat of α 0.05 over a diffuse base: about 1 BRDF sample in 8 in the lobe).
//! [`TableSampler::sample_direction_compensated`] chooses the cosine law with probability
//! `κ p / (κ p + 1 - p)` instead of `p`, `0 < κ ≤ 1`: the MIS compensation of Karlík, Šik,
//! Vévoda, Skřivan and Křivánek ("MIS compensation: optimizing sampling techniques in multiple
//! importance sampling", SIGGRAPH Asia 2019) on the BRDF's side. The density stays positive
//! wherever `wi` is above the horizon, at least `κ` times the uncompensated one, so estimates
//! stay unbiased. When to use it is the renderer's choice (`gonio_render`'s
//! `path::constant_weight`, with its measurements).

use super::BrdfTable;
use super::coords::dir;
use super::vndf_warp::VisibleNormalWarp;
use crate::bxdf::{Brdf, BrdfSample, Rgb, SpectralBrdf};
use crate::sampling::{Marginal2D, cosine_hemisphere, cosine_hemisphere_pdf};
use crate::trig::acos;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Resolution of the sampler's nodes of `wo` and of its grid on the square.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SamplerOptions {
    /// Nodes of theta_o, from 0 to 90° (at `90° k / n`).
    pub theta_bins: usize,
    /// Nodes of phi_o (anisotropic tables only; isotropic ones use 1).
    pub phi_bins: usize,
    /// Nodes of the grid on the square along y (drawn first, from the cumulative distribution
    /// of the rows).
    pub nodes_y: usize,
    /// Nodes of the grid along x (drawn within the row).
    pub nodes_x: usize,
}

impl SamplerOptions {
    /// Defaults for a table: 64 theta_o nodes and a grid of 129 × 129 nodes; 16 × 8 (theta_o,
    /// phi_o) nodes and a grid of 65 × 65 when anisotropic. Memory: two f64 per grid node and
    /// node of `wo`, 17 MB isotropic, 10 MB anisotropic. (65 × 65 isotropic was a little faster
    /// at equal error on the benchmark's broad lobe but resolves a narrow one worse:
    /// docs/brdf-tables.md.)
    pub fn for_table(table: &BrdfTable) -> SamplerOptions {
        let res = table.resolution();
        SamplerOptions {
            theta_bins: if res.is_isotropic() { 64 } else { 16 },
            phi_bins: if res.is_isotropic() { 1 } else { 8 },
            nodes_y: if res.is_isotropic() { 129 } else { 65 },
            nodes_x: if res.is_isotropic() { 129 } else { 65 },
        }
    }
}

/// One node of `wo`: the probability of the cosine law, and the remainder's density at the
/// grid's nodes (`y × x`, x fastest; all ones when the remainder has no energy).
struct Node {
    p_const: f64,
    density: Vec<f32>,
}

/// Importance sampler of a table; build once, then sample many times.
pub struct TableSampler {
    opts: SamplerOptions,
    warp: VisibleNormalWarp,
    /// Probability of the cosine law at each node of `wo` (`phi × theta`, theta fastest).
    p_const: Vec<f64>,
    /// The remainder's densities on the square, interpolated in (phi_o, theta_o); `None` when
    /// no node has a remainder.
    spec: Option<Marginal2D>,
}

impl TableSampler {
    /// Build the nodes of `table`.
    pub fn new(table: &BrdfTable, opts: SamplerOptions) -> TableSampler {
        let mut opts = opts;
        opts.theta_bins = opts.theta_bins.max(2);
        opts.nodes_y = opts.nodes_y.max(2);
        opts.nodes_x = opts.nodes_x.max(2);
        opts.phi_bins = if table.resolution().is_isotropic() {
            1
        } else {
            opts.phi_bins.max(1)
        };
        let warp = VisibleNormalWarp::fitted(table);
        let n_nodes = opts.theta_bins * opts.phi_bins;
        let nodes: Vec<Node> = (0..n_nodes)
            .into_par_iter()
            .map(|b| {
                let (kt, kp) = (b % opts.theta_bins, b / opts.theta_bins);
                let theta_o = FRAC_PI_2 * kt as f64 / opts.theta_bins as f64;
                let phi_o = TAU * kp as f64 / opts.phi_bins as f64;
                build_node(table, &opts, &warp, dir(theta_o, phi_o))
            })
            .collect();
        let p_const: Vec<f64> = nodes.iter().map(|n| n.p_const).collect();
        let spec = p_const.iter().any(|&p| p < 1.0).then(|| {
            let thetas: Vec<f64> = (0..opts.theta_bins)
                .map(|k| FRAC_PI_2 * k as f64 / opts.theta_bins as f64)
                .collect();
            let mut data: Vec<f32> = nodes.iter().flat_map(|n| n.density.clone()).collect();
            let params = if opts.phi_bins == 1 {
                vec![thetas]
            } else {
                // phi_o wraps: the node at 2π repeats the one at 0.
                data.extend_from_within(..opts.theta_bins * nodes[0].density.len());
                let phis = (0..=opts.phi_bins)
                    .map(|k| TAU * k as f64 / opts.phi_bins as f64)
                    .collect();
                vec![phis, thetas]
            };
            Marginal2D::new(&data, opts.nodes_x, opts.nodes_y, params, true)
                .expect("every node's density is positive somewhere and finite")
        });
        TableSampler {
            opts,
            warp,
            p_const,
            spec,
        }
    }

    /// The options it was built with.
    pub fn options(&self) -> SamplerOptions {
        self.opts
    }

    /// The roughness of the GGX whose visible normals the sampler warps.
    pub fn fitted_alpha(&self) -> f64 {
        self.warp.alpha()
    }

    /// The interpolation parameters of `wo` for the `Marginal2D` (theta_o, after phi_o when
    /// anisotropic; their count) and the probability of the cosine law there: the nodes'
    /// probabilities with the weights, linear in theta_o (and phi_o), with which the
    /// `Marginal2D` interpolates its slices.
    fn params(&self, wo: DVec3, constant_weight: f64) -> ([f64; 2], usize, f64) {
        let o = &self.opts;
        let theta = acos(wo.z.clamp(-1.0, 1.0));
        let x = (theta / FRAC_PI_2 * o.theta_bins as f64).clamp(0.0, (o.theta_bins - 1) as f64);
        let t0 = (x.floor() as usize).min(o.theta_bins - 2);
        let tt = x - t0 as f64;
        let (param, n, p0, p1, tp) = if o.phi_bins == 1 {
            ([theta, 0.0], 1, 0, 0, 0.0)
        } else {
            let phi = wo.y.atan2(wo.x).rem_euclid(TAU);
            let y = (phi / TAU * o.phi_bins as f64).rem_euclid(o.phi_bins as f64);
            let p0 = (y.floor() as usize).min(o.phi_bins - 1);
            ([phi, theta], 2, p0, (p0 + 1) % o.phi_bins, y - p0 as f64)
        };
        let at = |t: usize, p: usize| self.p_const[p * o.theta_bins + t];
        let p_const = (1.0 - tp) * ((1.0 - tt) * at(t0, p0) + tt * at(t0 + 1, p0))
            + tp * ((1.0 - tt) * at(t0, p1) + tt * at(t0 + 1, p1));
        (param, n, compensated(p_const, constant_weight))
    }

    /// Sample `wi` for `wo` from two uniform numbers, with its density ([`TableSampler::pdf`]);
    /// `None` below the horizon.
    ///
    /// `u.x` chooses between the cosine law and the remainder (by the mixture's probability of
    /// the cosine law), then the point's y on the square by the mixture's marginal distribution;
    /// `u.y` its x by the conditional distribution. Both invert cumulative distributions of a
    /// piecewise-bilinear density, so the warp is continuous and monotone in each coordinate.
    /// The remainder's density comes with its sample, so that only the cosine law's samples
    /// map `wi` back to the square for the density.
    pub fn sample_direction(&self, wo: DVec3, u: DVec2) -> Option<(DVec3, f64)> {
        self.sample_direction_compensated(wo, u, 1.0)
    }

    /// [`TableSampler::sample_direction`] with the cosine law's share weighted by
    /// `constant_weight` in (0, 1] (module doc, "Compensation"), with its density
    /// ([`TableSampler::pdf_compensated`]).
    pub fn sample_direction_compensated(
        &self,
        wo: DVec3,
        u: DVec2,
        constant_weight: f64,
    ) -> Option<(DVec3, f64)> {
        if wo.z <= 0.0 {
            return None;
        }
        let (param, n, p_const) = self.params(wo, constant_weight);
        let sampled = if u.x < p_const {
            let ux = (u.x / p_const).min(1.0 - f64::EPSILON);
            let wi = cosine_hemisphere(DVec2::new(ux, u.y));
            (wi, self.spec_density(wo, wi, &param[..n]))
        } else {
            let spec = self.spec.as_ref()?;
            let ux = ((u.x - p_const) / (1.0 - p_const)).clamp(0.0, 1.0);
            let (pos, density) = spec.sample([u.y, ux], &param[..n]);
            let h = self.warp.half_vector(wo, DVec2::new(pos[0], pos[1]));
            let c = wo.dot(h);
            let wi = 2.0 * c * h - wo;
            if c <= 0.0 || wi.z <= 0.0 {
                return None;
            }
            (wi, density * self.warp.wi_density(wo, h))
        };
        let (wi, spec) = sampled;
        let pdf = p_const * cosine_hemisphere_pdf(wi.z) + (1.0 - p_const) * spec;
        (pdf > 0.0).then_some((wi, pdf))
    }

    /// Density per steradian with which [`TableSampler::sample_direction`] returns `wi`.
    pub fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        self.pdf_compensated(wo, wi, 1.0)
    }

    /// Density per steradian with which [`TableSampler::sample_direction_compensated`] returns
    /// `wi` for the same `constant_weight`.
    pub fn pdf_compensated(&self, wo: DVec3, wi: DVec3, constant_weight: f64) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let (param, n, p_const) = self.params(wo, constant_weight);
        p_const * cosine_hemisphere_pdf(wi.z)
            + (1.0 - p_const) * self.spec_density(wo, wi, &param[..n])
    }

    /// The remainder's density of `wi` per steradian: `wi` mapped back to the square.
    fn spec_density(&self, wo: DVec3, wi: DVec3, param: &[f64]) -> f64 {
        let Some(spec) = self.spec.as_ref() else {
            return 0.0;
        };
        (wi + wo)
            .try_normalize()
            .and_then(|h| {
                let pos = self.warp.point(wo, h)?;
                Some(spec.eval([pos.x, pos.y], param) * self.warp.wi_density(wo, h))
            })
            .unwrap_or(0.0)
    }
}

/// The probability of the cosine law `p` with the constant part's energy weighted by `kappa`
/// (module doc, "Compensation"): `κ p / (κ p + 1 - p)`, `p` itself for `κ = 1`. `kappa` is
/// taken in [1e-3, 1] (anything else as 1), so that the density stays at least 1e-3 of the
/// uncompensated one.
fn compensated(p: f64, kappa: f64) -> f64 {
    if !(kappa > 0.0 && kappa < 1.0) || p >= 1.0 {
        return p;
    }
    let kp = kappa.max(1e-3) * p;
    kp / (kp + 1.0 - p)
}

/// The split and the remainder's density on the square for one conditioning direction `wo`.
fn build_node(table: &BrdfTable, o: &SamplerOptions, warp: &VisibleNormalWarp, wo: DVec3) -> Node {
    let (na, nr) = (o.nodes_x, o.nodes_y);
    let mut f = vec![0.0; table.channel_count()];
    // Per grid node: the BRDF and `cos θi dωi / d(a, y)`; NaN where `wi` is below the horizon.
    let mut value = vec![f64::NAN; na * nr];
    let mut measure = vec![0.0; na * nr];
    let mut c_min = f64::INFINITY;
    for row in 0..nr {
        for col in 0..na {
            let pos = DVec2::new(col as f64 / (na - 1) as f64, row as f64 / (nr - 1) as f64);
            let h = warp.half_vector(wo, pos);
            let c = wo.dot(h);
            let wi = 2.0 * c * h - wo;
            let jacobian = warp.wi_density(wo, h);
            if c <= 0.0 || wi.z <= 0.0 || !(jacobian > 0.0 && jacobian.is_finite()) {
                continue;
            }
            table.eval_channels(wo, wi.normalize(), &mut f);
            let v = BrdfTable::scalar(&f).max(0.0);
            let k = row * na + col;
            value[k] = v;
            measure[k] = wi.z / jacobian;
            c_min = c_min.min(v);
        }
    }
    let c = if c_min.is_finite() { c_min } else { 0.0 };
    let density: Vec<f64> = value
        .iter()
        .zip(&measure)
        .map(|(v, m)| if v.is_nan() { 0.0 } else { (v - c) * m })
        .collect();
    // The integral of the bilinear interpolant: the trapezoid rule on the grid.
    let trapezoid = |k: usize| {
        let (row, col) = (k / na, k % na);
        let wr = if row == 0 || row == nr - 1 { 0.5 } else { 1.0 };
        let wc = if col == 0 || col == na - 1 { 0.5 } else { 1.0 };
        wr * wc
    };
    let e_spec = density
        .iter()
        .enumerate()
        .map(|(k, g)| g * trapezoid(k))
        .sum::<f64>()
        / ((na - 1) * (nr - 1)) as f64;
    let e_const = c * PI;
    if !(e_spec > 0.0 && e_spec.is_finite()) {
        return Node {
            p_const: 1.0,
            density: vec![1.0; na * nr],
        };
    }
    Node {
        p_const: e_const / (e_const + e_spec),
        density: density.iter().map(|&g| g as f32).collect(),
    }
}

/// A table with its importance sampler: a [`Brdf`] that importance-samples the table's lobes.
pub struct SampledTable {
    table: BrdfTable,
    sampler: TableSampler,
}

impl SampledTable {
    /// Build the sampler of `table` with the default options.
    pub fn new(table: BrdfTable) -> SampledTable {
        let opts = SamplerOptions::for_table(&table);
        SampledTable::with_options(table, opts)
    }

    /// Build the sampler of `table` with these options.
    pub fn with_options(table: BrdfTable, opts: SamplerOptions) -> SampledTable {
        let sampler = TableSampler::new(&table, opts);
        SampledTable { table, sampler }
    }

    /// The table.
    pub fn table(&self) -> &BrdfTable {
        &self.table
    }

    /// The sampler.
    pub fn sampler(&self) -> &TableSampler {
        &self.sampler
    }
}

impl Brdf for SampledTable {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        self.table.eval(wo, wi)
    }

    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        self.sample_compensated(wo, u, 1.0)
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        self.sampler.pdf(wo, wi)
    }

    fn sample_compensated(&self, wo: DVec3, u: DVec2, constant_weight: f64) -> Option<BrdfSample> {
        let (wi, pdf) = self
            .sampler
            .sample_direction_compensated(wo, u, constant_weight)?;
        Some(BrdfSample {
            wi,
            f: self.table.eval(wo, wi),
            pdf,
        })
    }

    fn pdf_compensated(&self, wo: DVec3, wi: DVec3, constant_weight: f64) -> f64 {
        self.sampler.pdf_compensated(wo, wi, constant_weight)
    }

    fn spectral(&self) -> Option<&dyn SpectralBrdf> {
        self.spectral_view()
    }
}
