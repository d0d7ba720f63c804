//! An analytic Ward BRDF, tabulated and exported to the Mitsuba 3 / pbrt-v4 tensor format, read
//! back with our evaluator of that format (which follows Mitsuba's `measured` plugin), agrees
//! with the analytic value within 5% at 100 direction pairs wherever the value is above 1% of
//! the largest value among them.
//!
//! Where Mitsuba 3 is installed (`pip install mitsuba numpy`; `.ci/run` installs it), the same
//! files are also loaded by Mitsuba itself through `tests/mitsuba3.py`: its evaluation, its own
//! sampler's albedo and a rendered image are checked, for an RGB table and for the spectral
//! Cornell Cayman table. Without Mitsuba those checks say so and skip, unless
//! `GONIO_REQUIRE_ORACLES=1` (set by `.ci/run`), when a missing Mitsuba fails them.

use glam::{DVec2, DVec3};
use gonio_brdf::Brdf;
use gonio_brdf::formats::mitsuba::{self, MitsubaOptions, TensorBrdf};
use gonio_brdf::formats::scattered::NOISE_FLOOR_PER_SR;
use gonio_brdf::models::{Model, Ward};
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_brdf::validate::{SamplerCheck, check_sampler};
use rand::{RngExt, SeedableRng};
use std::path::Path;

/// The Ward model of these tests, with a Lambertian part so that both the lobe and the wide
/// diffuse reflection must come through the file.
fn ward() -> Model {
    Model::diffuse_specular(
        DVec3::new(0.25, 0.2, 0.1),
        Model::Ward(Ward::isotropic(DVec3::new(0.6, 0.4, 0.2), 0.2)),
    )
}

fn ward_table() -> BrdfTable {
    BrdfTable::from_brdf(
        &ward(),
        Resolution::isotropic(90, 64, 64),
        false,
        Provenance::new("ward alpha 0.2 + lambert", "model"),
    )
    .unwrap()
}

/// 100 (viewer, light) pairs: viewers uniform in solid angle up to 80°, lights drawn from the
/// lobe (the model's own sampler), so that most pairs lie where the BRDF matters.
fn direction_pairs(brdf: &dyn Brdf) -> Vec<(DVec3, DVec3)> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    let mut pairs = vec![];
    while pairs.len() < 100 {
        let z = 1.0 - rng.random::<f64>() * (1.0 - 80f64.to_radians().cos());
        let phi = rng.random::<f64>() * std::f64::consts::TAU;
        let r = (1.0 - z * z).sqrt();
        let wo = DVec3::new(r * phi.cos(), r * phi.sin(), z);
        if let Some(s) = brdf.sample(wo, DVec2::new(rng.random(), rng.random()))
            && s.wi.z > 0.05
        {
            pairs.push((wo, s.wi));
        }
    }
    pairs
}

/// Check `got` against the model at every pair whose value is above 1% of the largest one;
/// returns the number of pairs checked.
fn check_against_model(
    brdf: &dyn Brdf,
    pairs: &[(DVec3, DVec3)],
    got: impl Fn(usize) -> [f64; 3],
    what: &str,
) -> usize {
    let peak = pairs
        .iter()
        .map(|(wo, wi)| brdf.eval(*wo, *wi).x)
        .fold(0.0, f64::max);
    let mut checked = 0;
    let mut worst = 0.0f64;
    for (k, (wo, wi)) in pairs.iter().enumerate() {
        let want = brdf.eval(*wo, *wi);
        if want.x < 0.01 * peak {
            continue;
        }
        checked += 1;
        let got = got(k);
        for c in 0..3 {
            let rel = (got[c] - want[c]).abs() / want[c];
            worst = worst.max(rel);
            assert!(
                rel < 0.05,
                "{what}: wo {wo} wi {wi}: {got:?} vs model {want} ({rel:.3})"
            );
        }
    }
    println!("{what}: {checked} pairs checked, worst relative error {worst:.4}");
    checked
}

/// What `tests/mitsuba3.py` reports about a file loaded in Mitsuba 3.
#[derive(serde::Deserialize)]
struct MitsubaReport {
    mitsuba: String,
    eval: Vec<Vec<f64>>,
    albedo: std::collections::BTreeMap<String, [f64; 2]>,
    render: RenderReport,
}

#[derive(serde::Deserialize)]
struct RenderReport {
    values: usize,
    nan: usize,
    inf: usize,
    sphere_min: f64,
    sphere_mean: f64,
    sphere_max: f64,
    background_mean: f64,
    background_max: f64,
}

/// Skip the check with a reason, or fail when `GONIO_REQUIRE_ORACLES=1` demands the oracle.
fn oracle_missing(why: &str) -> Option<MitsubaReport> {
    crate::common::oracle_missing("Mitsuba 3", why);
    None
}

/// Run Mitsuba 3 on `bsdf` with the `variant`, evaluating at `pairs`; `None` (with a note on
/// stderr) where Python or Mitsuba is not installed.
fn mitsuba3(variant: &str, bsdf: &Path, pairs: &[(DVec3, DVec3)]) -> Option<MitsubaReport> {
    let dir = bsdf.parent().unwrap();
    let pairs_path = dir.join("pairs.txt");
    let text: String = pairs
        .iter()
        .map(|(wo, wi)| format!("{} {} {} {} {} {}\n", wo.x, wo.y, wo.z, wi.x, wi.y, wi.z))
        .collect();
    std::fs::write(&pairs_path, text).unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mitsuba3.py");
    let python = std::env::var("GONIO_PYTHON").unwrap_or_else(|_| "python3".into());
    let out = match std::process::Command::new(&python)
        .arg(&script)
        .arg(variant)
        .arg(bsdf)
        .arg(&pairs_path)
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            return oracle_missing(&format!("cannot run {python}: {e}"));
        }
    };
    if out.status.code() == Some(77) {
        return oracle_missing("Mitsuba 3 is not installed (`pip install mitsuba numpy`)");
    }
    assert!(
        out.status.success(),
        "Mitsuba 3 failed on {}: {}",
        bsdf.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let report: MitsubaReport = serde_json::from_slice(&out.stdout).unwrap();
    println!("Mitsuba {} ({variant})", report.mitsuba);
    Some(report)
}

/// `∫ f(wo, wi) cos θi dωi` for the viewer `wo` at `theta_o` in the x-z plane: the albedo that
/// Mitsuba's sampler estimates (it fixes the viewer and draws lights; the table's own albedo
/// fixes the light, which differs for a non-reciprocal measurement such as Cornell's), of
/// channel `band` or of the mean of the channels. Midpoint rule on a 400 × 800 grid uniform in
/// (cos θi, φi).
fn albedo_over_lights(
    eval_channels: impl Fn(DVec3, DVec3, &mut [f64]),
    channels: usize,
    theta_o: f64,
    band: Option<usize>,
) -> f64 {
    let wo = DVec3::new(theta_o.sin(), 0.0, theta_o.cos());
    let (n, mut total) = (400, 0.0);
    let mut buf = vec![0.0; channels];
    for a in 0..n {
        let cos_i = (a as f64 + 0.5) / n as f64;
        let sin_i = (1.0 - cos_i * cos_i).sqrt();
        for b in 0..2 * n {
            let phi = (b as f64 + 0.5) / (2 * n) as f64 * std::f64::consts::TAU;
            let wi = DVec3::new(sin_i * phi.cos(), sin_i * phi.sin(), cos_i);
            eval_channels(wo, wi, &mut buf);
            total += cos_i
                * match band {
                    Some(i) => buf[i],
                    None => buf.iter().sum::<f64>() / buf.len() as f64,
                };
        }
    }
    total * std::f64::consts::TAU / (2 * n * n) as f64
}

/// The checks every file must pass in Mitsuba: a finite image whose sphere is no brighter than
/// the uniform environment it is lit by (a passive surface on a convex object reflects at most
/// its albedo, at most 1, times the environment's radiance; the environment's own pixels carry
/// the same sampling noise, so their largest value is the bound), and Mitsuba's own sampler
/// giving the file's albedo (its sample weights are f cos / pdf, so their mean over a
/// stratified set is the albedo: this fails if the file's warps cannot reach part of the
/// reflection), which is the table's within `fidelity`.
///
/// `band`: the channel Mitsuba's albedo is of (a spectral variant's evaluation at 550 nm), or
/// the mean of the channels (an RGB variant).
fn check_render_and_albedo(
    report: &MitsubaReport,
    (table, file): (&BrdfTable, &TensorBrdf),
    band: Option<usize>,
    fidelity: f64,
    what: &str,
) {
    let r = &report.render;
    println!(
        "{what}: render: sphere luminance {:.4} .. {:.4} (mean {:.4}), environment {:.4} (max {:.4})",
        r.sphere_min, r.sphere_max, r.sphere_mean, r.background_mean, r.background_max
    );
    assert_eq!(
        (r.nan, r.inf),
        (0, 0),
        "{what}: {} NaN, {} inf",
        r.nan,
        r.inf
    );
    assert!(
        r.values > 0 && r.sphere_min >= 0.0,
        "{what}: sphere luminance {}",
        r.sphere_min
    );
    assert!(
        r.sphere_max <= r.background_max,
        "{what}: a sphere pixel of luminance {} under an environment of at most {}",
        r.sphere_max,
        r.background_max
    );
    for (theta, &[got, std_error]) in &report.albedo {
        let theta_o = theta.parse::<f64>().unwrap().to_radians();
        let nc = table.channel_count();
        let of_table =
            albedo_over_lights(|o, i, b| table.eval_channels(o, i, b), nc, theta_o, band);
        let nc = file.channel_count();
        let of_file = albedo_over_lights(|o, i, b| file.eval_channels(o, i, b), nc, theta_o, band);
        println!(
            "{what}: albedo at {theta}°: Mitsuba's sampler {got:.4} ± {std_error:.4}, file {of_file:.4}, table {of_table:.4}"
        );
        // Mitsuba's estimate within four of its standard errors, plus 0.5% for the 400 × 800
        // quadrature of the file.
        assert!(
            (got - of_file).abs() < 4.0 * std_error + 0.005 * of_file,
            "{what}: albedo at {theta}°: Mitsuba's sampler {got} vs the file's {of_file}"
        );
        assert!(
            (of_file - of_table).abs() < fidelity * of_table,
            "{what}: albedo at {theta}°: file {of_file} vs table {of_table}"
        );
    }
}

#[test]
fn mitsuba3_loads_evaluates_samples_and_renders_an_rgb_file() {
    let ward = ward();
    let table = ward_table();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ward.bsdf");
    mitsuba::write(&table, &path, MitsubaOptions::default()).unwrap();
    let pairs = direction_pairs(&ward);
    let Some(report) = mitsuba3("scalar_rgb", &path, &pairs) else {
        return;
    };
    assert_eq!(report.eval.len(), pairs.len());
    let checked = check_against_model(
        &ward,
        &pairs,
        |k| [report.eval[k][0], report.eval[k][1], report.eval[k][2]],
        "Mitsuba 3",
    );
    assert!(checked >= 60, "only {checked} pairs above 1% of the peak");
    let file = TensorBrdf::read(&path).unwrap();
    // An analytic model tabulated finely: the file holds its albedo to 1%.
    check_render_and_albedo(&report, (&table, &file), None, 0.01, "ward (rgb)");
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn mitsuba3_loads_and_renders_the_spectral_cayman_file() {
        let (file, table) = crate::common::cayman_table();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cayman.bsdf");
        // The default 128² value grids: 64² holds this peaked paint's albedo at 60° to 7%, 128² to
        // 3%, 256² to 2% (docs/brdf-tables.md).
        mitsuba::write(table, &path, MitsubaOptions::default()).unwrap();
        let pairs = direction_pairs(table);
        let tensor = TensorBrdf::read(&path).unwrap();
        let Some(report) = mitsuba3("scalar_spectral", &path, &pairs) else {
            return;
        };
        // The script evaluates at 550 nm; the table interpolates between its bands.
        let i = file
            .wavelengths_nm
            .iter()
            .position(|&w| (w - 550.0).abs() < 1e-9)
            .expect("the Cornell files have a 550 nm band");
        let mut buf = vec![0.0; table.channel_count()];
        let at_550 = |wo: DVec3, wi: DVec3, buf: &mut Vec<f64>| {
            table.eval_channels(wo, wi, buf);
            buf[i]
        };
        let peak = pairs
            .iter()
            .map(|&(wo, wi)| at_550(wo, wi, &mut buf))
            .fold(0.0, f64::max);
        let (mut checked, mut errors, mut file) = (0, vec![], buf.clone());
        for (k, &(wo, wi)) in pairs.iter().enumerate() {
            let want = at_550(wo, wi, &mut buf);
            // Below the instrument's noise floor (1e-3 1/sr) the table's faint tail is not data.
            if want < (1e-3 * peak).max(NOISE_FLOOR_PER_SR) {
                continue;
            }
            checked += 1;
            let got = report.eval[k][0];
            tensor.eval_channels(wo, wi, &mut file);
            // Mitsuba and our reader implement the same plugin on the same f32 data.
            assert!(
                (got - file[i]).abs() < 1e-3 * file[i],
                "cayman 550 nm: wo {wo} wi {wi}: Mitsuba {got} vs our reader {}",
                file[i]
            );
            errors.push((got - want).abs() / want);
        }
        assert!(
            checked >= 40,
            "only {checked} pairs above 0.1% of the peak and the noise floor"
        );
        // How well the file holds the table: a 64² value grid per incidence node reproduces the
        // measured-paint lobe to about 1% typically, and loses a few percent at the very peak
        // and in the faint tail (measured 0.5% median, 11% worst when this test was written).
        errors.sort_by(f64::total_cmp);
        let (median, worst) = (errors[errors.len() / 2], errors[errors.len() - 1]);
        println!("cayman 550 nm, file vs table: median {median:.4}, worst {worst:.4}");
        assert!(
            median < 0.02 && worst < 0.15,
            "median {median}, worst {worst}"
        );
        // A measured metallic paint: the file's 128² value grids hold its albedo to 1.1% at 60°
        // (measured; 64² grids: 7% on the earlier import, whose peak was a thin in-plane streak).
        // 5%: the bound required on a measured paint's rim, which the albedo integrates.
        check_render_and_albedo(
            &report,
            (table, &tensor),
            Some(i),
            0.05,
            "cayman (spectral)",
        );
    }

    #[test]
    fn ward_table_through_the_tensor_file_matches_the_model() {
        let ward = ward();
        let table = ward_table();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ward.bsdf");
        mitsuba::write(&table, &path, MitsubaOptions::default()).unwrap();
        let tensor = TensorBrdf::read(&path).unwrap();
        assert_eq!(tensor.channel_count(), 3);

        let pairs = direction_pairs(&ward);
        let checked = check_against_model(
            &ward,
            &pairs,
            |k| tensor.eval(pairs[k].0, pairs[k].1).to_array(),
            "our reader",
        );
        assert!(checked >= 60, "only {checked} pairs above 1% of the peak");

        // Mitsuba's sampling routine, as reproduced by the reader, samples what its pdf says.
        for theta in [10.0f64, 50.0] {
            let wo = DVec3::new(theta.to_radians().sin(), 0.0, theta.to_radians().cos());
            let report = check_sampler(&tensor, wo, &SamplerCheck::default());
            assert!(report.passed(), "theta_o {theta}: {report:?}");
        }
    }
}
