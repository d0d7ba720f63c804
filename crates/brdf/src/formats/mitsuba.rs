//! Export to, and evaluation of, the measured-BRDF tensor file (`.bsdf`) of Dupuy & Jakob 2018
//! that Mitsuba 3's and pbrt-v4's `measured` material load (container: [`super::tensor`]).
//!
//! Fields, and how Mitsuba's `measured.cpp` uses them (the conditioning direction `v` is the one
//! toward the viewer, its angles are the parameters (phi_i, theta_i); `l` toward the light;
//! `m = normalize(v + l)`; `u(θ) = sqrt(θ / (π/2))`, `u(φ) = (φ + π) / 2π`, with φ of `m`
//! relative to φ of `v` for isotropic files):
//!
//! | field | shape | meaning |
//! |---|---|---|
//! | `description` | `[n] u8` | text |
//! | `jacobian` | `[1] u8` | 1: values are multiplied by `ndf / (4 sigma)` |
//! | `theta_i`, `phi_i` | `[n] f32` | parameter nodes in radians (one phi_i node: isotropic) |
//! | `ndf` | `[ny, nx] f32` | microfacet distribution `D(m)` on the (u(φ), u(θ)) grid |
//! | `sigma` | `[ny, nx] f32` | projected area `σ(v) = ∫ D(m) max(0, m·v) dm` |
//! | `vndf` | `[φi, θi, ny, nx] f32` | visible normals `D(m) (m·v)` × `2π² u sin θ`, a warp |
//! | `luminance` | `[φi, θi, n, n] f32` | luminance of the values over the vndf's sample square, a warp |
//! | `rgb` / `spectra` | `[φi, θi, c, n, n] f32` | values over the vndf's sample square |
//! | `wavelengths` | `[c] f32` | nm (spectral files only) |
//!
//! Evaluation: `s = vndf.invert(u(m))`, then `f(l, v) cos θ_l = values(s) ndf(u(m)) /
//! (4 sigma(u(v)))`. The writer therefore stores, at each node `s` of the value grid, with
//! `u(m) = vndf.sample(s)`: `values = f cos θ_l · 4 sigma / ndf`, using the very interpolants
//! the reader will use, so that the file reproduces the table at every node. The `ndf` is taken
//! from the table's retro-reflection, `D(m) ∝ f(m, m) cos² θ_m` (the microfacet relation
//! `f(m, m) = D F G / (4 cos² θ)` with F G taken as constant), so that the values are smooth.

use super::tensor::{self, Field};
use crate::bxdf::{Brdf, BrdfSample, Rgb};
use crate::error::{BrdfError, Result};
use crate::sampling::Marginal2D;
use crate::table::coords::{dir, theta_of};
use crate::table::{BrdfTable, Channels, rgb_weights};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

fn theta2u(theta: f64) -> f64 {
    (theta / FRAC_PI_2).max(0.0).sqrt()
}
fn phi2u(phi: f64) -> f64 {
    (phi + PI) / (2.0 * PI)
}
fn u2theta(u: f64) -> f64 {
    u * u * FRAC_PI_2
}
fn u2phi(u: f64) -> f64 {
    (2.0 * u - 1.0) * PI
}

/// Resolutions of the exported file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MitsubaOptions {
    /// Nodes of theta_i, from 0 to 88°.
    pub theta_i: usize,
    /// Nodes of phi_i over a full turn (anisotropic tables only).
    pub phi_i: usize,
    /// Nodes per axis of the ndf, sigma and vndf grids.
    pub ndf: usize,
    /// Nodes per axis of the value (and luminance) grid. 128 by default: a sharply peaked
    /// measured paint's rim is then within a few per cent (64 nodes: +38% in the outermost ring
    /// of Cayman's grid, its albedo at 60° +7%; docs/brdf-tables.md).
    pub values: usize,
}

impl Default for MitsubaOptions {
    fn default() -> Self {
        MitsubaOptions {
            theta_i: 24,
            phi_i: 16,
            ndf: 64,
            values: 128,
        }
    }
}

/// Largest theta_i node in radians.
const THETA_I_MAX: f64 = 88.0 * PI / 180.0;

/// Write `table` as a Mitsuba 3 / pbrt-v4 `measured` tensor file (RGB tables and monochrome
/// ones as `rgb`, spectral ones as `spectra` + `wavelengths`).
pub fn write(table: &BrdfTable, path: &Path, opts: MitsubaOptions) -> Result<()> {
    let iso = table.resolution().is_isotropic();
    let n_t = opts.theta_i.max(2);
    let n_p = if iso { 1 } else { opts.phi_i.max(2) };
    // The ndf and sigma of an isotropic table do not depend on phi: two phi nodes hold them.
    // The vndf does, through the visibility m·v (phi_m is relative to phi_v), so its grid keeps
    // the full phi resolution: with two nodes Mitsuba's sampler would miss every direction
    // off the plane of incidence at oblique viewing.
    let (nx, ny) = (opts.ndf.max(4), if iso { 2 } else { opts.ndf.max(4) });
    let n_vndf_phi = opts.ndf.max(4);
    let nv = opts.values.max(4);
    let theta_i: Vec<f64> = (0..n_t)
        .map(|k| THETA_I_MAX * k as f64 / (n_t - 1) as f64)
        .collect();
    let phi_i: Vec<f64> = if iso {
        vec![0.0]
    } else {
        (0..n_p)
            .map(|k| u2phi(k as f64 / (n_p - 1) as f64))
            .collect()
    };
    let nc = table.channel_count();
    let mut buf = vec![0.0; nc];

    // ndf from the retro-reflection, floored so that every ratio stays finite.
    let mut ndf = vec![0.0f32; nx * ny];
    for row in 0..ny {
        for col in 0..nx {
            let m = dir(
                u2theta(col as f64 / (nx - 1) as f64),
                u2phi(row as f64 / (ny - 1) as f64),
            );
            table.eval_channels(m, m, &mut buf);
            ndf[row * nx + col] = (BrdfTable::scalar(&buf) * m.z * m.z) as f32;
        }
    }
    let d_max = ndf.iter().copied().fold(0.0f32, f32::max);
    if d_max.is_nan() || d_max <= 0.0 {
        return Err(BrdfError::Invalid(
            "the table has no retro-reflection to derive an ndf from".into(),
        ));
    }
    ndf.iter_mut().for_each(|d| *d = d.max(1e-4 * d_max));
    let ndf_i = Marginal2D::new(&ndf, nx, ny, vec![], false).map_err(BrdfError::Invalid)?;

    // sigma(v) by midpoint quadrature of the interpolated ndf over the u square.
    let q = 2 * nx;
    let sigma: Vec<f32> = (0..nx * ny)
        .into_par_iter()
        .map(|k| {
            let (row, col) = (k / nx, k % nx);
            let v = dir(
                u2theta(col as f64 / (nx - 1) as f64),
                u2phi(row as f64 / (ny - 1) as f64),
            );
            let mut s = 0.0;
            for i in 0..q {
                let u = (i as f64 + 0.5) / q as f64;
                let theta = u2theta(u);
                for j in 0..q {
                    let w = (j as f64 + 0.5) / q as f64;
                    let m = dir(theta, u2phi(w));
                    let c = m.dot(v);
                    if c > 0.0 {
                        s += ndf_i.eval([u, w], &[]) * c * 2.0 * PI * PI * u * theta.sin();
                    }
                }
            }
            (s / (q * q) as f64) as f32
        })
        .collect();
    let sigma_i = Marginal2D::new(&sigma, nx, ny, vec![], false).map_err(BrdfError::Invalid)?;

    let out_channels = match table.channels() {
        Channels::Spectral { wavelengths_nm } => wavelengths_nm.len(),
        _ => 3,
    };
    let slices: Vec<(Vec<f32>, Vec<f32>, Vec<f32>)> = (0..n_p * n_t)
        .into_par_iter()
        .map(|k| {
            let (p, t) = (k / n_t, k % n_t);
            export_slice(
                table,
                &ndf_i,
                &sigma_i,
                phi_i[p],
                theta_i[t],
                iso,
                (nx, n_vndf_phi, nv),
                out_channels,
            )
        })
        .collect::<Result<_>>()?;
    let mut vndf = Vec::with_capacity(n_p * n_t * nx * n_vndf_phi);
    let mut lum = Vec::with_capacity(n_p * n_t * nv * nv);
    let mut values = Vec::with_capacity(n_p * n_t * out_channels * nv * nv);
    for (v, l, s) in slices {
        vndf.extend(v);
        lum.extend(l);
        values.extend(s);
    }
    let f32s = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    let mut fields = BTreeMap::new();
    let description = table
        .provenance()
        .description
        .clone()
        .or_else(|| table.provenance().source.clone())
        .unwrap_or_else(|| "gonio table".into());
    fields.insert("description".into(), Field::u8(description.as_bytes()));
    fields.insert("jacobian".into(), Field::u8(&[1]));
    fields.insert("theta_i".into(), Field::f32(&[n_t], &f32s(&theta_i)));
    fields.insert("phi_i".into(), Field::f32(&[n_p], &f32s(&phi_i)));
    fields.insert("ndf".into(), Field::f32(&[ny, nx], &ndf));
    fields.insert("sigma".into(), Field::f32(&[ny, nx], &sigma));
    fields.insert(
        "vndf".into(),
        Field::f32(&[n_p, n_t, n_vndf_phi, nx], &vndf),
    );
    fields.insert("luminance".into(), Field::f32(&[n_p, n_t, nv, nv], &lum));
    let shape = [n_p, n_t, out_channels, nv, nv];
    match table.channels() {
        Channels::Spectral { wavelengths_nm } => {
            fields.insert("spectra".into(), Field::f32(&shape, &values));
            fields.insert(
                "wavelengths".into(),
                Field::f32(&[out_channels], &f32s(wavelengths_nm)),
            );
        }
        _ => {
            fields.insert("rgb".into(), Field::f32(&shape, &values));
        }
    }
    tensor::write(path, &fields)
}

/// vndf, luminance and values of one (phi_i, theta_i) slice.
#[allow(clippy::too_many_arguments)]
fn export_slice(
    table: &BrdfTable,
    ndf: &Marginal2D,
    sigma: &Marginal2D,
    phi_v: f64,
    theta_v: f64,
    iso: bool,
    (nx, ny, nv): (usize, usize, usize),
    out_channels: usize,
) -> Result<(Vec<f32>, Vec<f32>, Vec<f32>)> {
    let v = dir(theta_v, phi_v);
    let m_of = |u: f64, w: f64| dir(u2theta(u), u2phi(w) + if iso { phi_v } else { 0.0 });
    let mut vndf = vec![0.0f32; nx * ny];
    for row in 0..ny {
        for col in 0..nx {
            let (u, w) = (col as f64 / (nx - 1) as f64, row as f64 / (ny - 1) as f64);
            let m = m_of(u, w);
            let visible = m.dot(v).max(0.0);
            vndf[row * nx + col] =
                (ndf.eval([u, w], &[]) * visible * 2.0 * PI * PI * u * u2theta(u).sin()) as f32;
        }
    }
    let warp = Marginal2D::new(&vndf, nx, ny, vec![], true).map_err(BrdfError::Invalid)?;
    let sigma_v = sigma.eval([theta2u(theta_v), phi2u(phi_v)], &[]);
    let nc = table.channel_count();
    let mut buf = vec![0.0; nc];
    let mut values = vec![0.0f32; out_channels * nv * nv];
    let mut lum = vec![0.0f32; nv * nv];
    for row in 0..nv {
        for col in 0..nv {
            let s = [col as f64 / (nv - 1) as f64, row as f64 / (nv - 1) as f64];
            let (um, _) = warp.sample(s, &[]);
            let m = m_of(um[0], um[1]);
            let l = 2.0 * v.dot(m) * m - v;
            if l.z <= 0.0 || v.dot(m) <= 0.0 {
                continue;
            }
            table.eval_channels(v, l, &mut buf);
            let scale = l.z * 4.0 * sigma_v / ndf.eval(um, &[]);
            let out: Vec<f64> = match table.channels() {
                Channels::Spectral { .. } => buf.iter().map(|f| f * scale).collect(),
                _ => (table.to_rgb(&buf) * scale).to_array().to_vec(),
            };
            for (c, o) in out.iter().enumerate() {
                values[(c * nv + row) * nv + col] = o.max(0.0) as f32;
            }
            lum[row * nv + col] = match table.channels() {
                Channels::Spectral { .. } => out.iter().sum::<f64>() / out.len() as f64,
                _ => 0.2126 * out[0] + 0.7152 * out[1] + 0.0722 * out[2],
            }
            .max(0.0) as f32;
        }
    }
    // A luminance floor keeps every direction reachable by Mitsuba's sampler and every slice
    // normalisable.
    let l_max = lum.iter().copied().fold(0.0f32, f32::max);
    let floor = if l_max > 0.0 { 1e-3 * l_max } else { 1.0 };
    lum.iter_mut().for_each(|l| *l = l.max(floor));
    Ok((vndf, lum, values))
}

/// The parameters (phi_v, theta_v), u(v), u(m) and m of a (viewer, light) pair.
struct Frame {
    params: [f64; 2],
    uv: [f64; 2],
    um: [f64; 2],
    m: DVec3,
}

/// A tensor file read back and evaluated the way Mitsuba 3's `measured` plugin does.
pub struct TensorBrdf {
    ndf: Marginal2D,
    sigma: Marginal2D,
    vndf: Marginal2D,
    luminance: Marginal2D,
    values: Marginal2D,
    channels: usize,
    isotropic: bool,
    jacobian: bool,
    rgb_weights: Vec<[f64; 3]>,
    /// The `description` field.
    pub description: String,
}

impl TensorBrdf {
    /// Read and check a tensor file.
    pub fn read(path: &Path) -> Result<TensorBrdf> {
        let fields = tensor::read(path)?;
        let bad = |p: String| BrdfError::format(path, p);
        let get = |name: &str| {
            fields
                .get(name)
                .ok_or_else(|| bad(format!("no '{name}' field")))
        };
        let f32s = |name: &str, rank: usize| -> Result<(Vec<f32>, Vec<usize>)> {
            let f = get(name)?;
            let v = f
                .as_f32()
                .ok_or_else(|| bad(format!("field '{name}' is not f32")))?;
            if f.shape.len() != rank {
                return Err(bad(format!(
                    "field '{name}' has rank {}, expected {rank}",
                    f.shape.len()
                )));
            }
            Ok((v, f.shape.iter().map(|&s| s as usize).collect()))
        };
        let to64 = |v: Vec<f32>| v.into_iter().map(f64::from).collect::<Vec<f64>>();
        let (theta_i, _) = f32s("theta_i", 1)?;
        let (phi_i, _) = f32s("phi_i", 1)?;
        let (ndf, ns) = f32s("ndf", 2)?;
        let (sigma, ss) = f32s("sigma", 2)?;
        let (vndf, vs) = f32s("vndf", 4)?;
        let (lum, ls) = f32s("luminance", 4)?;
        let spectral = fields.contains_key("wavelengths");
        let (values, cs) = f32s(if spectral { "spectra" } else { "rgb" }, 5)?;
        let wavelengths: Vec<f64> = if spectral {
            to64(f32s("wavelengths", 1)?.0)
        } else {
            vec![0.0, 1.0, 2.0]
        };
        let (nt, np) = (theta_i.len(), phi_i.len());
        if vs[..2] != [np, nt]
            || ls[..2] != [np, nt]
            || cs[..2] != [np, nt]
            || cs[2] != wavelengths.len()
        {
            return Err(bad(
                "vndf, luminance and values do not match theta_i, phi_i, wavelengths".into(),
            ));
        }
        if ls[2..] != cs[3..] {
            return Err(bad("luminance and values grids differ".into()));
        }
        let isotropic = np <= 2;
        if !isotropic {
            let span = f64::from(phi_i[np - 1] - phi_i[0]);
            if (2.0 * PI / span).round() as i64 != 1 {
                return Err(bad(
                    "anisotropic files with symmetry reduction are not supported".into(),
                ));
            }
        }
        let jacobian = get("jacobian")?.data.first().copied().unwrap_or(0) != 0;
        let description = String::from_utf8_lossy(&get("description")?.data).into_owned();
        let params = vec![to64(phi_i), to64(theta_i)];
        let mk = |d: &[f32], nx: usize, ny: usize, p: Vec<Vec<f64>>, warp: bool| {
            Marginal2D::new(d, nx, ny, p, warp).map_err(&bad)
        };
        let channels = if spectral {
            Channels::Spectral {
                wavelengths_nm: wavelengths.clone(),
            }
        } else {
            Channels::Rgb
        };
        let rgb_weights = rgb_weights(&channels).map_err(|e| bad(e.to_string()))?;
        Ok(TensorBrdf {
            ndf: mk(&ndf, ns[1], ns[0], vec![], false)?,
            sigma: mk(&sigma, ss[1], ss[0], vec![], false)?,
            vndf: mk(&vndf, vs[3], vs[2], params.clone(), true)?,
            luminance: mk(&lum, ls[3], ls[2], params.clone(), true)?,
            values: mk(
                &values,
                cs[4],
                cs[3],
                vec![params[0].clone(), params[1].clone(), wavelengths],
                false,
            )?,
            channels: cs[2],
            isotropic,
            jacobian,
            rgb_weights,
            description,
        })
    }

    /// Number of channels (3 for RGB files).
    pub fn channel_count(&self) -> usize {
        self.channels
    }

    /// Common set-up of a (viewer, light) pair.
    fn frame(&self, v: DVec3, l: DVec3) -> Option<Frame> {
        if v.z <= 0.0 || l.z <= 0.0 {
            return None;
        }
        let m = (v + l).try_normalize()?;
        let (theta_v, phi_v) = (theta_of(v), v.y.atan2(v.x));
        let phi_m = m.y.atan2(m.x);
        let mut um = [
            theta2u(theta_of(m)),
            phi2u(if self.isotropic { phi_m - phi_v } else { phi_m }),
        ];
        um[1] -= um[1].floor();
        Some(Frame {
            params: [phi_v, theta_v],
            uv: [theta2u(theta_v), phi2u(phi_v)],
            um,
            m,
        })
    }

    /// `f` in 1/sr per channel for light from `wi` seen from `wo`, as Mitsuba evaluates it.
    pub fn eval_channels(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        let Some(Frame { params, uv, um, .. }) = self.frame(wo, wi) else {
            return;
        };
        let (s, _) = self.vndf.invert(um, &params);
        let scale = if self.jacobian {
            self.ndf.eval(um, &params) / (4.0 * self.sigma.eval(uv, &params))
        } else {
            1.0
        };
        let out = &mut out[..self.channels];
        self.values.eval_at_last_nodes(s, &params, out);
        for o in out {
            *o = (*o * scale).max(0.0) / wi.z;
        }
    }
}

impl Brdf for TensorBrdf {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        let mut buf = vec![0.0; self.channels];
        self.eval_channels(wo, wi, &mut buf);
        self.rgb_weights
            .iter()
            .zip(&buf)
            .fold(Rgb::ZERO, |a, (w, v)| a + Rgb::from_array(*w) * *v)
    }

    /// Mitsuba's sampling: luminance warp, then the visible-normal warp, then reflection. The
    /// returned pdf is that of [`Brdf::pdf`] at the sampled direction: the density the warps
    /// give along the way differs from it by the warps' near-linear shortcut (relative 1e-4
    /// where neighbouring nodes differ by less than that), and a sampler must be exactly
    /// consistent with its pdf for multiple importance sampling.
    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let params = [wo.y.atan2(wo.x), theta_of(wo)];
        let (s, lum_pdf) = self.luminance.sample([u.y, u.x], &params);
        let (um, ndf_pdf) = self.vndf.sample(s, &params);
        let phi_m = u2phi(um[1]) + if self.isotropic { params[0] } else { 0.0 };
        let theta_m = u2theta(um[0]);
        let m = dir(theta_m, phi_m);
        let jac = (2.0 * PI * PI * um[0] * theta_m.sin()).max(1e-6) * 4.0 * wo.dot(m);
        let wi = 2.0 * wo.dot(m) * m - wo;
        let path_pdf = ndf_pdf * lum_pdf / jac;
        if !(wi.z > 0.0 && path_pdf > 0.0 && path_pdf.is_finite()) {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BrdfSample {
            wi,
            f: self.eval(wo, wi),
            pdf,
        })
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        let Some(Frame { params, um, m, .. }) = self.frame(wo, wi) else {
            return 0.0;
        };
        let (s, vndf_pdf) = self.vndf.invert(um, &params);
        let lum = self.luminance.eval(s, &params);
        let sin_m = (m.x * m.x + m.y * m.y).sqrt();
        let jac = (2.0 * PI * PI * um[0] * sin_m).max(1e-6) * 4.0 * wo.dot(m);
        vndf_pdf * lum / jac
    }
}
