//! The screen's model ([`crate::screen`]) for flakes inside the pigmented basecoat
//! (`[flakes] depth`, `gonio_coating::basecoat`): a table of the coating's reflectance factor
//! over the basecoat's optical depths, read once with the coating's own walk, interpolated per
//! band of each combination.
//!
//! **Why a table.** [`crate::screen::StackResponse`] reads the pigments as a Lambertian base
//! under the flakes; inside the basecoat they surround the flakes (absorption σa = K/2 and
//! scattering σs = (4/3) S per µm, the basecoat's conversion,
//! `gonio_coating::basecoat::transport_coefficients`), so the light a flake mirrors crosses
//! pigment and no function of the base's ρ describes it. At one wavelength and geometry the
//! coating's reflectance factor depends on the pigments only through the layer's optical depths
//! τa = σa d and τs = σs d (d the basecoat's thickness; the phase function is isotropic whatever
//! the pigment): the radiative-transfer equation of a slab is scaled by its optical depth (S.
//! Chandrasekhar, *Radiative Transfer*, Oxford, 1950, ch. 1; for the spread flakes their
//! extinction a_f d = −ln(1 − coverage) is fixed by the start). The rest — the flakes' optics,
//! the substrate, the clear coat — varies slowly with wavelength. So the start is read
//! ([`EmbeddedResponse::measure`]) with its pigments replaced by one medium of given (τa, τs)
//! on a grid, at a few anchor wavelengths, with the match's walks and seed 0 (its common random
//! numbers), and a combination's reading ([`EmbeddedResponse::reading`]) takes each band's
//! (τa, τs) from Duncan's mixture, interpolates each anchor's table by Catmull-Rom cubic
//! convolution in both depths (R. G. Keys, IEEE Trans. ASSP 29, 1153, 1981; ghost nodes by
//! linear extrapolation) and the anchors linearly in wavelength.
//!
//! **The grid** ([`Grid::for_bands`]): nodes evenly spaced in `ln(1 + τa/0.25)` (16) and
//! `ln(1 + τs)` (12), from 0 to the reach ([`reach`]: the start's own pigments plus the
//! `max_pigments` strongest candidates at concentration 1, the screen's upper bound; about
//! τa 55, τs 16 for 15 µm and the whole library, N = 3), anchors every 50 nm over the match's
//! bands. The logarithm makes the response smooth: it falls like exp(−m τa) with m from the
//! paths' lengths, steepest near τa = 0, where the scale 0.25 puts a third of the nodes
//! (τa < 0.9).
//!
//! **Measured** (the start of `tests/it/embedded_screen.rs`: aluminium spread through a 15 µm
//! basecoat with white 0.05 over a 0.3 primer under a glossy rough top; six random combinations
//! of 1–3 of the 18 other library pigments at log-uniform concentrations 0.001–1; ΔE00 at
//! E2194's five geometries against full walks of the same coating, 31 bands, seed 0; worst and
//! mean over the 30):
//!
//! | grid (nodes τa × τs, scale of τa) | 1024 walks | 8192 walks |
//! |---|---|---|
//! | 12 × 12, 1 | 2.78, 0.81 | 2.62, 0.79 |
//! | 12 × 24, 1 | 2.68, 0.78 | |
//! | 24 × 12, 1 | 1.26, 0.33 | |
//! | 24 × 24, 1 | 1.21, 0.28 | |
//! | 12 × 8, 0.25 | 0.50, 0.14 | |
//! | 16 × 12, 0.25 (chosen) | 0.41, 0.19 | 0.20, 0.09 |
//! | 24 × 12, 0.25 | 0.40, 0.18 | |
//!
//! The error is the τa direction's (more τs nodes change nothing) and, once the scale 0.25
//! resolves small τa, the walks' noise: the table reads other bands than the full reading, so
//! its noise is another seed's, and the same coating read at seeds 0 and 1 differs by 0.02–0.71
//! ΔE00 at 1024 walks (largest at the flop, 45as75 and 45as110); with 8192 walks the
//! difference halves to 0.20 worst, the interpolation's own error. Anchors: 2 (450 and 650 nm),
//! 7 (every 50 nm) and all 31 bands give 0.41, 0.49 and 0.47 worst: aluminium's optics and a
//! grey primer do not vary enough across the visible to matter; the 50 nm anchors are kept for
//! coloured primers and flakes whose optics vary more (interference flakes' fringes narrower
//! than 100 nm would need more: not measured).
//!
//! **Cost** (the test build, 2 cores shared with other work, load 5–8): the table is 192
//! readings at up to 7 anchors, 10–13 s with 1024 walks (2.1 s for 12 × 12 nodes at 2 anchors
//! on a quieter machine; 68 s with all 31 bands as anchors); a full reading of one combination
//! 0.15–0.5 s; the table's reading 40–70 µs. The selection test's screen (21 combinations, up to
//! 2 of 6 candidates) took 19.5–22.3 s in all, nearly all of it the table.

use crate::error::{FormulationError, Result};
use crate::screen::modelled_reading;
use gonio_coating::basecoat::{self, transport_coefficients};
use gonio_coating::clear_coat::{Base, Pigment};
use gonio_coating::pigment_library::LibraryPigment;
use gonio_coating::system::Coating;
use gonio_color::{SpectralToXyz, Spectrum};
use gonio_instrument::coating_study;
use gonio_instrument::multiangle::{self, Geometry, MultiangleReading, Settings as ReadSettings};
use rayon::prelude::*;

/// The table's grid: `nodes[0]` × `nodes[1]` nodes evenly spaced in `ln(1 + τa/scale[0])` and
/// `ln(1 + τs/scale[1])` from 0 to the reach, read at `anchors_nm` (the flakes' optics, the
/// substrate and the clear coat taken there and interpolated linearly between them; increasing).
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    pub nodes: [usize; 2],
    pub scale: [f64; 2],
    pub anchors_nm: Vec<f64>,
}

impl Grid {
    /// The screen's grid for a match at `wavelengths_nm` (module docs, "Measured"): 16 × 12
    /// nodes, scales 0.25 and 1, anchors every [`ANCHOR_STEP_NM`] from the first band to the last
    /// (both included; two at least).
    pub fn for_bands(wavelengths_nm: &[f64]) -> Self {
        let first = wavelengths_nm.iter().copied().fold(f64::INFINITY, f64::min);
        let last = wavelengths_nm
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let steps = ((last - first) / ANCHOR_STEP_NM).ceil().max(1.0) as usize;
        Grid {
            nodes: [16, 12],
            scale: [0.25, 1.0],
            anchors_nm: (0..=steps)
                .map(|i| first + (last - first) * i as f64 / steps as f64)
                .collect(),
        }
    }
}

/// The anchors' spacing, nm.
pub const ANCHOR_STEP_NM: f64 = 50.0;

/// How a coating with its flakes in the basecoat answers the basecoat's optical depths: at each
/// geometry and anchor wavelength, the reflectance factor over a grid of `(ln(1 + τa),
/// ln(1 + τs))` (module docs).
#[derive(Clone, Debug)]
pub struct EmbeddedResponse {
    geometries: Vec<Geometry>,
    wavelengths_nm: Vec<f64>,
    grid: Grid,
    thickness_um: f64,
    /// The largest ln(1 + τa), ln(1 + τs) of the grid.
    top: [f64; 2],
    /// [anchor][geometry][ia · nodes + is].
    table: Vec<Vec<Vec<f64>>>,
    to_xyz: SpectralToXyz,
    settings: ReadSettings,
}

/// The optical depths `(τa, τs)` the grid must reach for `start`'s basecoat with up to
/// `max_pigments` of `candidates` added at concentration 1 (the screen's upper bound): the base's
/// own pigments plus the `max_pigments` candidates of the largest σa (and, apart, of the largest
/// σs), each at its largest over `wavelengths_nm`, times the basecoat's thickness.
pub fn reach(
    start: &Coating,
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    wavelengths_nm: &[f64],
) -> Result<(f64, f64)> {
    let (present, thickness_um, _) = basecoat::layer_of(&start.base)?;
    let largest = |pigments: &[Pigment]| -> Result<(f64, f64)> {
        let mut most = (0.0f64, 0.0f64);
        for &w in wavelengths_nm {
            let (a, s) = transport_coefficients(basecoat::mixture_at(pigments, w)?);
            most = (most.0.max(a), most.1.max(s));
        }
        Ok(most)
    };
    let (mut a, mut s) = largest(present)?;
    let mut each = candidates
        .iter()
        .map(|p| largest(&[p.pigment(1.0)?]))
        .collect::<Result<Vec<_>>>()?;
    each.sort_by(|x, y| y.0.total_cmp(&x.0));
    a += each.iter().take(max_pigments).map(|x| x.0).sum::<f64>();
    each.sort_by(|x, y| y.1.total_cmp(&x.1));
    s += each.iter().take(max_pigments).map(|x| x.1).sum::<f64>();
    Ok((a * thickness_um, s * thickness_um))
}

impl EmbeddedResponse {
    /// Read `start` with its basecoat's pigments replaced by a medium of optical depths on
    /// `grid`'s nodes up to `reach` `(τa, τs)`, at its anchors and `geometries`, `walks` per
    /// geometry, seed 0 (the match's common random numbers); a combination is then read at
    /// `wavelengths_nm`. An error when the start's flakes are not in a Kubelka-Munk basecoat of
    /// some thickness, or the grid has fewer than 2 nodes per depth.
    pub fn measure(
        start: &Coating,
        geometries: &[Geometry],
        wavelengths_nm: &[f64],
        walks: usize,
        reach: (f64, f64),
        grid: &Grid,
    ) -> Result<Self> {
        let (nodes, scale, anchors_nm) = (grid.nodes, grid.scale, &grid.anchors_nm[..]);
        let (_, thickness_um, _) = basecoat::layer_of(&start.base)?;
        if nodes.iter().any(|&n| n < 2) {
            return Err(FormulationError::Invalid(format!(
                "an embedded screen's grid needs at least 2 nodes per depth ({nodes:?} given)"
            )));
        }
        let top = [
            (reach.0.max(0.0) / scale[0]).ln_1p(),
            (reach.1.max(0.0) / scale[1]).ln_1p(),
        ];
        let settings = ReadSettings::default();
        let at =
            |i: usize, k: usize| scale[k] * (top[k] * i as f64 / (nodes[k] - 1) as f64).exp_m1();
        let cells = (0..nodes[0] * nodes[1])
            .into_par_iter()
            .map(|n| {
                let (tau_a, tau_s) = (at(n / nodes[1], 0), at(n % nodes[1], 1));
                let coating = with_depths(start, tau_a, tau_s, thickness_um, anchors_nm)?;
                let evaluator = coating.evaluator(anchors_nm)?;
                let brdf = coating_study::walked_brdf(&evaluator, walks, 0);
                Ok(multiangle::read(&brdf, anchors_nm, geometries, &settings)?)
            })
            .collect::<Result<Vec<MultiangleReading>>>()?;
        let table = (0..anchors_nm.len())
            .map(|k| {
                (0..geometries.len())
                    .map(|g| {
                        cells
                            .iter()
                            .map(|c| c.geometries[g].reflectance_factor[k])
                            .collect()
                    })
                    .collect()
            })
            .collect();
        let to_xyz = SpectralToXyz::new(wavelengths_nm, settings.illuminant, settings.observer)
            .map_err(|e| FormulationError::Invalid(e.to_string()))?;
        Ok(EmbeddedResponse {
            geometries: geometries.to_vec(),
            wavelengths_nm: wavelengths_nm.to_vec(),
            grid: grid.clone(),
            thickness_um,
            top,
            table,
            to_xyz,
            settings,
        })
    }

    /// The multi-angle reading of `coating` (the start with pigments added: the same flakes,
    /// coat and basecoat thickness) from the table.
    pub fn reading(&self, coating: &Coating) -> Result<MultiangleReading> {
        let (pigments, _, _) = basecoat::layer_of(&coating.base)?;
        // Per band: the grid's weights at its optical depths and the anchors' weights.
        let weights = self
            .wavelengths_nm
            .iter()
            .map(|&w| {
                let (a, s) = transport_coefficients(basecoat::mixture_at(pigments, w)?);
                let g = &self.grid;
                let ua = cubic(
                    (a * self.thickness_um / g.scale[0]).ln_1p() / self.top[0],
                    g.nodes[0],
                );
                let us = cubic(
                    (s * self.thickness_um / g.scale[1]).ln_1p() / self.top[1],
                    g.nodes[1],
                );
                Ok((ua, us, linear(w, &g.anchors_nm)))
            })
            .collect::<Result<Vec<_>>>()?;
        modelled_reading(
            &self.geometries,
            &self.wavelengths_nm,
            self.settings,
            &self.to_xyz,
            |g| {
                weights
                    .iter()
                    .map(|(ua, us, anchors)| {
                        anchors
                            .iter()
                            .map(|&(k, wk)| {
                                let t = &self.table[k][g];
                                wk * ua
                                    .iter()
                                    .map(|&(i, wi)| {
                                        wi * us
                                            .iter()
                                            .map(|&(j, wj)| wj * t[i * self.grid.nodes[1] + j])
                                            .sum::<f64>()
                                    })
                                    .sum::<f64>()
                            })
                            .sum()
                    })
                    .collect()
            },
        )
    }

    /// Readings of the coating the table took (its nodes).
    pub fn readings(&self) -> usize {
        self.grid.nodes[0] * self.grid.nodes[1]
    }
}

/// `start` with its basecoat's pigments replaced by one medium of optical depths `tau_a`,
/// `tau_s` over `thickness_um` at `anchors_nm` (K = 2σa, S = ¾σs: the inverse of the basecoat's
/// conversion, `basecoat::kubelka_munk_coefficients`).
fn with_depths(
    start: &Coating,
    tau_a: f64,
    tau_s: f64,
    thickness_um: f64,
    anchors_nm: &[f64],
) -> Result<Coating> {
    let km = basecoat::kubelka_munk_coefficients(tau_a / thickness_um, tau_s / thickness_um);
    // A spectrum needs two samples: constant over the anchors' span widened by a nanometre.
    let span = vec![
        anchors_nm.iter().copied().fold(f64::INFINITY, f64::min) - 1.0,
        anchors_nm.iter().copied().fold(f64::NEG_INFINITY, f64::max) + 1.0,
    ];
    let flat = |v: f64| {
        Spectrum::constant(span.clone(), v).map_err(|e| FormulationError::Invalid(e.to_string()))
    };
    let mut c = start.clone();
    if let Base::KubelkaMunk { pigments, .. } = &mut c.base {
        *pigments = vec![Pigment {
            name: "screen".into(),
            concentration: 1.0,
            k_per_um: flat(km.k)?,
            s_per_um: flat(km.s)?,
        }];
    }
    Ok(c)
}

/// Catmull-Rom weights (cubic convolution, Keys 1981, a = −½) of the nodes `0..n` at `x` in
/// [0, 1] (clamped), the ghost nodes beyond the ends extrapolated linearly.
fn cubic(x: f64, n: usize) -> Vec<(usize, f64)> {
    let last = n - 1;
    let p = x.clamp(0.0, 1.0) * last as f64;
    let i = (p.floor() as usize).min(last.saturating_sub(1));
    let t = p - i as f64;
    let w = [
        0.5 * (-t + 2.0 * t * t - t * t * t),
        0.5 * (2.0 - 5.0 * t * t + 3.0 * t * t * t),
        0.5 * (t + 4.0 * t * t - 3.0 * t * t * t),
        0.5 * (-t * t + t * t * t),
    ];
    let mut out: Vec<(usize, f64)> = Vec::with_capacity(4);
    let mut add = |node: usize, weight: f64| match out.iter_mut().find(|(m, _)| *m == node) {
        Some((_, v)) => *v += weight,
        None => out.push((node, weight)),
    };
    for (k, &wk) in w.iter().enumerate() {
        let j = i as i64 + k as i64 - 1;
        if j < 0 {
            // p(−1) = 2 p(0) − p(1).
            add(0, 2.0 * wk);
            add(1.min(last), -wk);
        } else if j as usize > last {
            // p(n) = 2 p(n − 1) − p(n − 2).
            add(last, 2.0 * wk);
            add(last.saturating_sub(1), -wk);
        } else {
            add(j as usize, wk);
        }
    }
    out
}

/// Linear weights of the anchors `at` (increasing) at `w`, constant beyond the ends.
fn linear(w: f64, at: &[f64]) -> Vec<(usize, f64)> {
    if at.len() == 1 || w <= at[0] {
        return vec![(0, 1.0)];
    }
    match at.windows(2).position(|p| w <= p[1]) {
        Some(i) => {
            let t = (w - at[i]) / (at[i + 1] - at[i]);
            vec![(i, 1.0 - t), (i + 1, t)]
        }
        None => vec![(at.len() - 1, 1.0)],
    }
}
