//! Export to the PAB-Opto goniophotometer data files that Radiance's `pabopto2bsdf` reads to
//! build its BSDF interpolant (G. Ward, Radiance `src/cv/pabopto2bsdf.c`, whose
//! `init_pabopto_inp` parses the header and `add_pabopto_inp` the data; `bsdf2ttree` then
//! writes the tensor-tree XML that Radiance renders). One text file per incidence direction,
//! with a header of `#` lines
//!
//! ```text
//! #sample_name "name"
//! #format: theta phi BSDF
//! #colorimetry: CIE-XYZ          (CIE-Y for a monochrome table)
//! #upphi 90
//! #intheta 30
//! #inphi 0
//! ```
//!
//! then one line per outgoing direction: `theta phi Y` for a monochrome table, `theta phi X Y
//! Z` for a colour table. Angles are in degrees (theta from the normal, phi counter-clockwise
//! from +x), values are BSDFs in 1/sr. The incidence direction points toward the light; both
//! directions lie on the +z side, which `pabopto2bsdf` (without `-t`) stores as the reflection
//! of the side the surface normal faces ("Reflection Back" in the XML). Radiance's renderer
//! takes the files' incidence for the direction toward the viewer (it traces from the eye), so
//! a table that is not reciprocal renders as its transpose (measured with `rtrace`;
//! docs/brdf-tables.md).
//!
//! **Frame.** `pabopto2bsdf` adds `90° - upphi` to every azimuth (it turns the file's "up"
//! azimuth into its +Y); `#upphi 90` leaves the azimuths as they are, so gonio's x and y are
//! the x and y of Radiance's BSDF frame and a material's up vector gives gonio's +y.
//!
//! **Colour.** `#colorimetry: CIE-XYZ` makes `pabopto2bsdf` read three values, X Y Z, and keep
//! the chromaticity of each lobe of its interpolant (`bsdfrbf.c`, `create_lobe`; without the
//! line it reads one value, the photopic Y). Radiance's white is the equal-energy white (its
//! RGB ↔ XYZ matrices in `src/common/color.h` use x = y = 1/3), so colours are written relative
//! to it (a monochrome table says `CIE-Y`, the photopic value, which is also what
//! `pabopto2bsdf` assumes without the line): spectral tables are integrated with the CIE 1931
//! 2° colour-matching functions under an equal-energy illuminant (Y = the ȳ-weighted mean of
//! the spectrum, a flat spectrum gives X = Y = Z); linear sRGB tables go to XYZ with the sRGB
//! matrix (D65 white), then X and Z are divided by those of D65 (von Kries scaling in XYZ),
//! which maps the sRGB white onto the equal-energy white and keeps Y, the luminance
//! `0.2126 R + 0.7152 G + 0.0722 B`: a grey table stays grey, as its monochrome export would,
//! and every table keeps its photometry. XYZ tables are written as they are.
//!
//! **Sampling.** Radiance bins the samples on a 256² grid of the Shirley-Chiu square (equal
//! solid angle per cell), builds a quadtree down to where a quadrant holds no sample, and puts a
//! Gaussian lobe on each leaf whose volume is the mean of its samples times the leaf's solid
//! angle (`bsdfrbf.c`). Crowded samples therefore bias the lobes: the former 2° × 5° grid put 72
//! samples on each 2° ring near the pole and gave a Lambert table back 10–23% too high there.
//! The outgoing directions are now rings every [`SPACING_DEG`] in theta with
//! `round(2π sin θ / spacing)` azimuths each and one sample at the pole: evenly spread in solid
//! angle, the same set for every incidence, each direction once. A table with a narrow
//! specular peak (see [`spacing_deg`]) is sampled every [`PEAKED_SPACING_DEG`] instead, on
//! rings that leave the pole out ([`directions`]). docs/brdf-tables.md gives what Radiance
//! makes of it, and why `pabopto2bsdf -g 6` should read the files: Radiance's interpolant
//! diverges toward the horizon of its outgoing directions (lights near grazing in a render,
//! up to 34% high with `bsdf2ttree`'s defaults), whatever the samples; leaving out those within
//! 6° of the horizon brings it to 13%.

use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use crate::table::coords::dir;
use crate::table::{BrdfTable, Channels};
use glam::DVec3;
use gonio_color::srgb::srgb_white;
use gonio_color::{LinearSrgb, Observer};
use std::f64::consts::TAU;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Incidence angles exported by default (degrees).
pub const DEFAULT_THETA_I_DEG: [f64; 9] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0];

/// Spacing in degrees of the outgoing directions of a smooth table: rings every 2° with about
/// one sample per 2° × 2° of solid angle (5069 directions per file).
pub const SPACING_DEG: f64 = 2.0;

/// Spacing in degrees for a table with a narrow specular peak (about 20600 directions per
/// file).
pub const PEAKED_SPACING_DEG: f64 = 1.0;

/// Step in degrees of the incidence azimuths of an anisotropic table: all round the circle.
/// `pabopto2bsdf` infers a symmetry from the quadrants of azimuth its incidences fall in
/// (`bsdfrep.c`, `new_input_direction` and `use_symmetry`): incidences in the first two
/// quadrants only (0°–135°, as gonio wrote before) make it mirror the data about the x axis
/// (y → −y) for the other two, which is wrong for a surface without that symmetry (measured
/// with a Ward lobe turned by 30°: Radiance's value at an incidence azimuth of 160° 3.4 times
/// gonio's; docs/brdf-tables.md). With incidences in all four quadrants it assumes none.
pub const ANISOTROPIC_PHI_STEP_DEG: f64 = 45.0;

/// The incidence azimuths (degrees) exported for `table`: 0° for an isotropic table, every
/// [`ANISOTROPIC_PHI_STEP_DEG`] from 0° to 315° for an anisotropic one.
pub fn incidence_azimuths_deg(table: &BrdfTable) -> Vec<f64> {
    if table.resolution().is_isotropic() {
        vec![0.0]
    } else {
        let n = (360.0 / ANISOTROPIC_PHI_STEP_DEG).round() as usize;
        (0..n)
            .map(|k| k as f64 * ANISOTROPIC_PHI_STEP_DEG)
            .collect()
    }
}

/// A table is sampled every [`PEAKED_SPACING_DEG`] when, at some exported incidence up to 60°,
/// its value at the mirror direction exceeds this many times the mean of its values 4° before
/// and after it in the plane of incidence: a lobe whose 1/e half width in theta_o is below
/// about 8° (a Beckmann lobe of m < 0.075). Radiance's lobes have twice the radius of their
/// quadtree cell (`bsdfrbf.c`, `RSCA`), about the sample spacing, so 2° samples blur such a
/// peak: the directional-hemispherical reflectance of an m = 0.067 Beckmann lobe (the
/// ray-method lobe of a 201 nm epoxy surface) comes back up to 3.6% high at 0–45° from 2°
/// samples, within 1.4% from 1° ones. Smooth tables keep 2°: Radiance's interpolant of a
/// Lambert table ripples by 1.6% with them, by 3.5–7% with 1° ones, both with the help of
/// Radiance's BSDF minimum, which sits 1.5% below a constant table (docs/brdf-tables.md).
pub const PEAK_RATIO: f64 = 1.25;

/// Write one file per incidence angle (phi_i = 0, and for anisotropic tables every
/// [`ANISOTROPIC_PHI_STEP_DEG`] around the circle) into the directory `out_dir` (created if
/// needed), named `<name>_t<theta>_p<phi>.dat`. Returns the paths written.
pub fn write(
    table: &BrdfTable,
    out_dir: &Path,
    name: &str,
    theta_i_deg: &[f64],
) -> Result<Vec<PathBuf>> {
    if let Some(ti) = theta_i_deg.iter().find(|t| !(0.0..90.0).contains(*t)) {
        return Err(BrdfError::Invalid(format!(
            "incidence {ti}° outside [0, 90)°"
        )));
    }
    std::fs::create_dir_all(out_dir).map_err(|e| BrdfError::io(out_dir, e))?;
    let phis = incidence_azimuths_deg(table);
    let phis = phis.as_slice();
    let weights = xyz_weights(table.channels())?;
    let spacing = spacing_deg(table, theta_i_deg, phis);
    let outgoing: Vec<(DVec3, f64, f64)> = directions(spacing)
        .into_iter()
        .map(|wo| {
            let theta = wo.z.clamp(-1.0, 1.0).acos().to_degrees();
            let phi = wo.y.atan2(wo.x).to_degrees().rem_euclid(360.0);
            (wo, theta, phi)
        })
        .collect();
    let mut written = Vec::new();
    let mut buf = vec![0.0; table.channel_count()];
    for &pi in phis {
        for &ti in theta_i_deg {
            let path = out_dir.join(format!("{name}_t{ti}_p{pi}.dat"));
            let wi = dir(ti.to_radians(), pi.to_radians());
            write_atomic(&path, |w| {
                writeln!(w, "#sample_name \"{name}\"")?;
                writeln!(w, "#format: theta phi BSDF")?;
                let colorimetry = if weights.is_some() {
                    "CIE-XYZ"
                } else {
                    "CIE-Y"
                };
                writeln!(w, "#colorimetry: {colorimetry}")?;
                writeln!(w, "#upphi 90")?;
                writeln!(w, "#intheta {ti}")?;
                writeln!(w, "#inphi {pi}")?;
                for &(wo, theta, phi) in &outgoing {
                    table.eval_channels(wo, wi, &mut buf);
                    match &weights {
                        None => writeln!(w, "{theta:.4} {phi:.4} {:.6e}", clean(buf[0]))?,
                        Some(weights) => {
                            let [x, y, z] = to_xyz(weights, &buf).map(clean);
                            writeln!(w, "{theta:.4} {phi:.4} {x:.6e} {y:.6e} {z:.6e}")?
                        }
                    }
                }
                Ok(())
            })?;
            written.push(path);
        }
    }
    Ok(written)
}

/// A value as written: negative values (an out-of-gamut colour's X or Z) become 0, and so do
/// the cells without data (NaN).
fn clean(v: f64) -> f64 {
    if v.is_finite() { v.max(0.0) } else { 0.0 }
}

/// `Σ_c weights[c] · values[c]`: the XYZ of a table value.
fn to_xyz(weights: &[[f64; 3]], values: &[f64]) -> [f64; 3] {
    let mut xyz = [0.0; 3];
    for (w, v) in weights.iter().zip(values) {
        for k in 0..3 {
            xyz[k] += w[k] * v;
        }
    }
    xyz
}

/// Per-channel weights giving the CIE XYZ that the files hold (Y in the table's units, 1/sr),
/// relative to Radiance's equal-energy white: `None` for a monochrome table, whose single
/// value is written as the photopic Y. See the module documentation for the conversions.
pub fn xyz_weights(channels: &Channels) -> Result<Option<Vec<[f64; 3]>>> {
    Ok(match channels {
        Channels::Mono => None,
        Channels::Xyz => Some(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
        Channels::Rgb => {
            // sRGB → XYZ (D65), then X and Z scaled by the equal-energy white over D65's
            // (von Kries in XYZ), which maps the one white onto the other and keeps Y.
            let d65 = srgb_white().to_array().map(|v| v / 100.0);
            Some(
                (0..3)
                    .map(|c| {
                        let mut rgb = [0.0; 3];
                        rgb[c] = 1.0;
                        let xyz = LinearSrgb {
                            r: rgb[0],
                            g: rgb[1],
                            b: rgb[2],
                        }
                        .to_xyz()
                        .to_array();
                        std::array::from_fn(|k| xyz[k] / 100.0 / d65[k])
                    })
                    .collect(),
            )
        }
        Channels::Spectral { wavelengths_nm } => Some(equal_energy_weights(wavelengths_nm)?),
    })
}

/// Band weights for spectra sampled at `wavelengths_nm` under an equal-energy illuminant, CIE
/// 1931 2° observer: the spectrum is linear between bands and held beyond the first and last
/// (as gonio-color's `SpectralToXyz` does under D65), and the sums over the 1 nm table of the
/// colour-matching functions are divided by that of ȳ, so that a flat spectrum of value v
/// gives Y = v (and X, Z within 0.01% of v: the three functions have almost equal areas).
fn equal_energy_weights(wavelengths_nm: &[f64]) -> Result<Vec<[f64; 3]>> {
    if wavelengths_nm.is_empty() || wavelengths_nm.windows(2).any(|w| w[1] <= w[0]) {
        return Err(BrdfError::Invalid(
            "spectral table: wavelengths must increase".into(),
        ));
    }
    let cmfs = Observer::Cie1931TwoDegree.cmfs();
    let (x, y, z) = (cmfs.xbar.values(), cmfs.ybar.values(), cmfs.zbar.values());
    let last = wavelengths_nm.len() - 1;
    let mut weights = vec![[0.0; 3]; wavelengths_nm.len()];
    for (k, &l) in cmfs.wavelengths_nm().iter().enumerate() {
        let cmf = [x[k], y[k], z[k]];
        let mut add = |band: usize, t: f64| {
            for c in 0..3 {
                weights[band][c] += t * cmf[c];
            }
        };
        if l <= wavelengths_nm[0] {
            add(0, 1.0);
        } else if l >= wavelengths_nm[last] {
            add(last, 1.0);
        } else {
            let i = wavelengths_nm.partition_point(|&w| w <= l) - 1;
            let t = (l - wavelengths_nm[i]) / (wavelengths_nm[i + 1] - wavelengths_nm[i]);
            add(i, 1.0 - t);
            add(i + 1, t);
        }
    }
    let norm: f64 = y.iter().sum();
    Ok(weights.into_iter().map(|w| w.map(|v| v / norm)).collect())
}

/// The spacing (degrees) of the outgoing directions for `table`: [`PEAKED_SPACING_DEG`] if
/// its luminance at the mirror direction of some incidence up to 60° (of `theta_i_deg`, at the
/// azimuths `phi_i_deg`) exceeds [`PEAK_RATIO`] times the mean of its values 4° before and
/// after the mirror direction in the plane of incidence, else [`SPACING_DEG`].
pub fn spacing_deg(table: &BrdfTable, theta_i_deg: &[f64], phi_i_deg: &[f64]) -> f64 {
    let weights = xyz_weights(table.channels()).ok().flatten();
    let mut buf = vec![0.0; table.channel_count()];
    let mut luminance = |wo: DVec3, wi: DVec3| {
        table.eval_channels(wo, wi, &mut buf);
        let y = match &weights {
            None => buf[0],
            Some(w) => to_xyz(w, &buf)[1],
        };
        clean(y)
    };
    for &pi in phi_i_deg {
        for &ti in theta_i_deg.iter().filter(|&&t| t <= 60.0) {
            let wi = dir(ti.to_radians(), pi.to_radians());
            // Theta_o along the mirror azimuth; a negative angle is the other side of the pole.
            let at = |t: f64| dir(t.to_radians(), (pi + 180.0).to_radians());
            let peak = luminance(at(ti), wi);
            let sides = 0.5 * (luminance(at(ti - 4.0), wi) + luminance(at(ti + 4.0), wi));
            if peak > PEAK_RATIO * sides {
                return PEAKED_SPACING_DEG;
            }
        }
    }
    SPACING_DEG
}

/// The outgoing directions for a spacing of `spacing_deg`: rings with
/// `max(1, round(2π sin θ / spacing))` azimuths, about one sample per spacing² of solid angle.
/// For [`SPACING_DEG`]: the pole, then rings at theta = k · spacing below 90°, odd rings turned
/// by half an azimuth step. For [`PEAKED_SPACING_DEG`] (any spacing below 2°): no sample at the
/// pole, rings at theta = (k - ½) · spacing, every ring turned by a quarter step and odd ones
/// by a further half. Both layouts were chosen by measuring what Radiance makes of them
/// (docs/brdf-tables.md): with the first, a Lambert table comes back within 1.6%; the second
/// keeps the reflectance of a lobe at normal incidence, which the pole sample of the first
/// makes 3.7% low at 1°.
pub fn directions(spacing_deg: f64) -> Vec<DVec3> {
    let step = spacing_deg.to_radians();
    let around_pole = spacing_deg >= SPACING_DEG;
    let mut out = if around_pole { vec![DVec3::Z] } else { vec![] };
    for k in 1.. {
        let ring = if around_pole {
            k as f64
        } else {
            k as f64 - 0.5
        };
        let theta = ring * spacing_deg;
        if theta >= 90.0 {
            break;
        }
        let theta = theta.to_radians();
        let n = ((TAU * theta.sin() / step).round() as usize).max(1);
        let stagger = if k % 2 == 1 { 0.5 } else { 0.0 };
        let offset = if around_pole { stagger } else { stagger + 0.25 };
        out.extend((0..n).map(|j| dir(theta, (j as f64 + offset) * TAU / n as f64)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Brdf;
    use crate::fresnel::Ior;
    use crate::microfacet::Microfacet;
    use crate::models::{CookTorrance, Model, Ward};
    use crate::table::{Provenance, Resolution, TableBuilder};
    use glam::DVec3 as V;

    fn lines(path: &Path) -> Vec<String> {
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .map(str::to_owned)
            .collect()
    }

    fn numbers(line: &str) -> Vec<f64> {
        line.split(' ').map(|x| x.parse().unwrap()).collect()
    }

    /// The quadrant of an incidence azimuth as `pabopto2bsdf` classifies it (`bsdfrep.c`,
    /// `new_input_direction`: strictly inside 1°–89°, 91°–179°, ...; on an axis, none).
    fn radiance_quadrant(phi: f64) -> Option<usize> {
        (0..4).find(|&q| {
            let lo = 90.0 * q as f64;
            lo + 1.0 < phi && phi < lo + 89.0
        })
    }

    #[test]
    fn an_anisotropic_table_is_written_in_all_four_quadrants_of_incidence_azimuth() {
        let iso = TableBuilder::new(Resolution::isotropic(8, 8, 8), Channels::Mono)
            .unwrap()
            .build()
            .unwrap();
        assert_eq!(incidence_azimuths_deg(&iso), [0.0]);
        let mut b = TableBuilder::new(Resolution::anisotropic(8, 8, 8, 8), Channels::Mono).unwrap();
        b.fill(|_, out| out[0] = 0.1);
        let t = b.build().unwrap();
        let dir_out = tempfile::tempdir().unwrap();
        let files = write(&t, dir_out.path(), "a", &[30.0]).unwrap();
        let mut quadrants = [false; 4];
        for f in &files {
            let inphi = lines(f)
                .iter()
                .find_map(|l| l.strip_prefix("#inphi ").map(|v| v.parse::<f64>().unwrap()))
                .unwrap();
            if let Some(q) = radiance_quadrant(inphi) {
                quadrants[q] = true;
            }
        }
        // Every quadrant holds an incidence, so Radiance assumes no symmetry.
        assert_eq!(quadrants, [true; 4], "{files:?}");
        assert_eq!(files.len(), 8);
    }

    #[test]
    fn a_monochrome_file_has_the_header_pabopto2bsdf_reads_and_the_table_values() {
        let mut b = TableBuilder::new(Resolution::isotropic(16, 16, 16), Channels::Mono).unwrap();
        b.fill(|c, out| out[0] = 0.2 + c.wo.z);
        let t = b.build().unwrap();
        let dir_out = tempfile::tempdir().unwrap();
        let files = write(&t, dir_out.path(), "grey", &[0.0, 40.0]).unwrap();
        assert_eq!(files.len(), 2);
        let text = lines(&files[1]);
        let header = [
            "#sample_name \"grey\"",
            "#format: theta phi BSDF",
            "#colorimetry: CIE-Y",
            "#upphi 90",
            "#intheta 40",
            "#inphi 0",
        ];
        assert_eq!(&text[..6], &header);
        assert_eq!(text.len() - 6, directions(SPACING_DEG).len());
        for line in &text[6..] {
            let v = numbers(line);
            assert_eq!(v.len(), 3, "{line}");
            let want = 0.2 + v[0].to_radians().cos();
            // The table interpolates a function linear in cos theta_o on 16 nodes per angle:
            // within 1% up to 60° (1.04% at 76°, where cos theta_o changes fastest).
            if v[0] <= 60.0 {
                assert!((v[2] - want).abs() < 0.01 * want, "{line}: want {want}");
            }
        }
    }

    /// Every outgoing direction once, spread evenly in solid angle: a ring stands for the band
    /// of half a spacing either side, so the share of the directions nearer the pole than a
    /// band edge is the share of the sampled solid angle there (up to 89° for the 2° layout,
    /// whose last ring is at 88°; 90° for the 1° one), to the rounding of the azimuth counts
    /// (half a sample per ring, below 1% of the count from 30° on).
    #[test]
    fn directions_are_unique_and_evenly_spread_in_solid_angle() {
        let cap = |t: f64| 1.0 - t.to_radians().cos();
        for (spacing, edges, top) in [
            (SPACING_DEG, [31.0f64, 45.0, 61.0, 81.0], 89.0),
            (PEAKED_SPACING_DEG, [30.0, 45.0, 60.0, 80.0], 90.0),
        ] {
            let d = directions(spacing);
            for (i, a) in d.iter().enumerate() {
                assert!(
                    d[i + 1..].iter().all(|b| a.dot(*b) < 1.0 - 1e-9),
                    "{a} twice"
                );
            }
            for theta in edges {
                let c = theta.to_radians().cos();
                let share = d.iter().filter(|w| w.z > c).count() as f64 / d.len() as f64;
                let want = cap(theta) / cap(top);
                assert!(
                    (share / want - 1.0).abs() < 0.01,
                    "{spacing}°, within {theta}°: {share} of the directions, {want} of the solid angle"
                );
            }
        }
    }

    #[test]
    fn colour_tables_write_xyz_relative_to_the_equal_energy_white() {
        // A grey RGB table: X = Y = Z = the grey (the scaling maps the sRGB white onto E).
        let mut b = TableBuilder::new(Resolution::isotropic(8, 8, 8), Channels::Rgb).unwrap();
        b.fill(|_, out| out.copy_from_slice(&[0.3, 0.3, 0.3]));
        let t = b.build().unwrap();
        let out = tempfile::tempdir().unwrap();
        let files = write(&t, out.path(), "rgb", &[20.0]).unwrap();
        let text = lines(&files[0]);
        assert_eq!(text[2], "#colorimetry: CIE-XYZ");
        for line in text[6..].iter().step_by(97) {
            let v = numbers(line);
            assert_eq!(v.len(), 5, "{line}");
            assert!(v[2..].iter().all(|x| (x - 0.3).abs() < 1e-4), "{line}");
        }
        // The luminance of every colour is that of sRGB (IEC 61966-2-1 rounds it to 4 digits).
        let w = xyz_weights(&Channels::Rgb).unwrap().unwrap();
        for (c, y) in [0.2126, 0.7152, 0.0722].into_iter().enumerate() {
            assert!((w[c][1] - y).abs() < 1e-4, "{:?}", w[c]);
        }
        // A flat spectrum: X = Y = Z (the CIE 1931 functions have equal areas to 0.01%).
        let bands: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let w = xyz_weights(&Channels::Spectral {
            wavelengths_nm: bands.clone(),
        })
        .unwrap()
        .unwrap();
        let xyz = to_xyz(&w, &vec![0.5; bands.len()]);
        for v in xyz {
            assert!((v - 0.5).abs() < 5e-4, "{xyz:?}");
        }
        // A spectrum that is 1 only at 600 nm and falls linearly to 0 at 590 and 610 nm is
        // orange-red: the spectrum locus runs from x = 0.61 at 590 nm to 0.66 at 610 nm.
        let mut spike = vec![0.0; bands.len()];
        spike[20] = 1.0;
        let [x, y, z] = to_xyz(&w, &spike);
        let cx = x / (x + y + z);
        assert!((0.61..0.66).contains(&cx), "x = {cx}");
        assert!(xyz_weights(&Channels::Mono).unwrap().is_none());
    }

    #[test]
    fn narrow_peaks_get_the_finer_spacing() {
        let res = Resolution::isotropic(32, 90, 180);
        let table = |m: &Model| BrdfTable::from_brdf(m, res, true, Provenance::default()).unwrap();
        let beckmann = |m| {
            Model::CookTorrance(CookTorrance {
                microfacet: Microfacet::beckmann(m),
                ior: Ior::Dielectric(1.55),
                tint: crate::Rgb::ONE,
            })
        };
        let lambert = Model::Lambert(crate::models::Lambert {
            albedo: crate::Rgb::splat(0.5),
        });
        let ward = Model::diffuse_specular(
            V::new(0.25, 0.2, 0.1),
            Model::Ward(Ward::isotropic(V::new(0.6, 0.4, 0.2), 0.2)),
        );
        let th = &DEFAULT_THETA_I_DEG;
        assert_eq!(spacing_deg(&table(&lambert), th, &[0.0]), SPACING_DEG);
        assert_eq!(spacing_deg(&table(&ward), th, &[0.0]), SPACING_DEG);
        assert_eq!(
            spacing_deg(&table(&beckmann(0.067)), th, &[0.0]),
            PEAKED_SPACING_DEG
        );
        // The criterion reads the table: the model itself agrees on the ratio.
        let m = beckmann(0.067);
        let wi = dir(30f64.to_radians(), 0.0);
        let at = |t: f64| m.eval(dir(t.to_radians(), std::f64::consts::PI), wi).x;
        assert!(at(30.0) > PEAK_RATIO * 0.5 * (at(26.0) + at(34.0)));
    }
}
