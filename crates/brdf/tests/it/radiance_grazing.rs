//! Radiance at grazing light: which direction Radiance's renderer takes the files' incidence
//! for, and what it makes of a Lambert table lit near the horizon. A Lambert table exported for
//! `pabopto2bsdf` comes back 20% high (`bsdf2ttree -g 5`; 34% with its default `-g 6`) for
//! lights at 70° and beyond seen along the diagonals of Radiance's Shirley-Chiu square
//! (relative azimuths 45°, 135°). It is Radiance's: the same table written as a
//! goniophotometer's grid without gonio comes back the same, `bsdf2ttree`'s own tabulation of
//! the function is exact, and the fault is in the interpolant's outgoing directions, which more
//! incidence files cannot reach. The figures are pinned here (each within a fifth of its
//! measured value, so that a change of Radiance's or of the export shows), with the
//! workaround docs/brdf-tables.md gives (`pabopto2bsdf -g 6`). Skipped without pyradiance,
//! like `radiance`.

use crate::radiance::{Pair, RadianceReport, lambert_table, run_radiance};
use gonio_brdf::formats::pabopto;
use gonio_brdf::table::{Channels, Resolution, TableBuilder};
use serde_json::json;
use std::f64::consts::PI;

/// The albedo of the Lambert tables.
const RHO: f64 = 0.5;

/// Lights (degrees) at `lights` (azimuth 0), viewers at `views`, at every relative azimuth
/// from 0° to 180° in steps of 15° (an isotropic table is symmetric about the plane of
/// incidence): the diagonals of Radiance's square, 45° and 135°, among them.
fn grid_pairs(lights: &[f64], views: &[f64]) -> Vec<Pair> {
    let mut out = vec![];
    for &light in lights {
        for &view in views {
            for k in 0..=12 {
                out.push([light, 0.0, view, 15.0 * k as f64]);
            }
        }
    }
    out
}

/// Grazing lights, 70° to 85°, seen from 12° to 75°.
fn grazing() -> Vec<Pair> {
    grid_pairs(
        &[70.0, 75.0, 80.0, 85.0],
        &[12.0, 20.0, 30.0, 45.0, 60.0, 75.0],
    )
}

/// Lights up to 60°, seen from 0° to 75°.
fn inner() -> Vec<Pair> {
    grid_pairs(
        &[0.0, 20.0, 40.0, 60.0],
        &[0.0, 12.0, 30.0, 45.0, 60.0, 75.0],
    )
}

/// The relative error of largest magnitude, with its sign, of the values against the Lambert
/// table's `RHO / PI`.
fn worst(values: &[f64]) -> f64 {
    let f = RHO / PI;
    values
        .iter()
        .map(|y| y / f - 1.0)
        .fold(0.0, |w: f64, e| if e.abs() > w.abs() { e } else { w })
}

/// Radiance on the export of the Lambert table of albedo `RHO` at the default incidences plus
/// `more` (degrees), or on the script's own source if `queries` names one (`grid_lambert`,
/// `function`), with the `queries` (see `tests/radiance.py`) and the pairs `grazing` then
/// `inner`; the report and the worst errors of the two sets.
fn lambert_run(more: &[f64], mut queries: serde_json::Value) -> Option<(RadianceReport, f64, f64)> {
    let (grazing, inner) = (grazing(), inner());
    let pairs: Vec<Pair> = grazing.iter().chain(&inner).copied().collect();
    queries["pairs"] = json!(pairs);
    queries["dhr_theta"] = json!([0.0, 60.0]);
    let incidences: Vec<f64> = pabopto::DEFAULT_THETA_I_DEG
        .iter()
        .chain(more)
        .copied()
        .collect();
    let table = lambert_table(RHO);
    let own = queries.get("grid_lambert").is_none() && queries.get("function").is_none();
    let source = own.then_some((&table, incidences.as_slice()));
    let report = run_radiance(source, queries)?;
    let (g, i) = report.y.split_at(grazing.len());
    let (g, i) = (worst(g), worst(i));
    Some((report, g, i))
}

/// `value` within a fifth of `measured`: what pins a figure of Radiance's. Each figure came out
/// the same to every digit in repeated runs (a deterministic result of Radiance's algorithms,
/// not a statistic); a fifth leaves room for a Radiance build that rounds otherwise and flags
/// any change of the interpolant or of the export's samples that moves it more.
fn pinned(what: &str, value: f64, measured: f64) {
    println!("{what}: {value:+.4} (measured {measured:+.4} on pyradiance 1.3.1)");
    assert!(
        (value / measured - 1.0).abs() < 0.2,
        "{what}: {value:+.4}, pinned at {measured:+.4} (within a fifth)"
    );
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// Radiance's renderer takes the files' incidence for the viewing direction, and
    /// `tests/radiance.py` evaluates its pairs the same way: checked against `rtrace` on a
    /// table whose value depends on the incidence alone, `0.3 cos theta_i`. Lit from 10° and
    /// seen from 60° it renders as `0.3 cos 60°` would, and the pair swapped as `0.3 cos 10°`:
    /// their ratio is `cos 60° / cos 10° = 0.508` (were the incidence the light, 1.97).
    /// Radiance's interpolant is up to 11% off at such lights (`radiance_overestimates_grazing_
    /// lights_on_the_diagonals`) and its tree evaluates 60° at the centre of its cell, 57.5° at
    /// the default `-g 6` (the cosine 7% higher), so the ratio is within 30% of 0.508 (measured
    /// 0.610); 1.97 is four times further. With the Lambert table lit at 75° and seen from 30°
    /// on a diagonal, `rtrace` renders the 20% excess that the grazing figures below pin: the
    /// fault is the light's. Before `tests/radiance.py` took the pairs in this order it gave
    /// the swapped values (0.263 1/sr where `rtrace` renders 0.161, and 0.1567 for the Lambert
    /// pair where `rtrace` renders 0.1908).
    #[test]
    fn radiance_renders_the_files_incidence_as_the_view() {
        let mut b = TableBuilder::new(Resolution::isotropic(16, 16, 16), Channels::Mono).unwrap();
        b.fill(|c, out| out[0] = 0.3 * c.wi.z);
        let table = b.build().unwrap();
        let swapped: [Pair; 2] = [[10.0, 0.0, 60.0, 180.0], [60.0, 0.0, 10.0, 180.0]];
        let queries = json!({"pairs": swapped, "render": swapped, "dhr_theta": []});
        let source = Some((&table, &pabopto::DEFAULT_THETA_I_DEG[..]));
        let Some(report) = run_radiance(source, queries) else {
            return;
        };
        let lambert: [Pair; 2] = [[75.0, 0.0, 30.0, 45.0], [30.0, 0.0, 75.0, 45.0]];
        let queries = json!({"pairs": lambert, "render": lambert, "dhr_theta": [],
                             "bsdf2ttree": ["-g", "5"]});
        let table = lambert_table(RHO);
        let source = Some((&table, &pabopto::DEFAULT_THETA_I_DEG[..]));
        let lambert_report = run_radiance(source, queries).unwrap();
        // The evaluation through the BSDF library and the rendering read the same tree cell:
        // equal to the float rounding (measured 1e-7); rtrace's source is 0.5° across, inside
        // the cell, so 0.1% bounds it.
        for (report, pairs) in [(&report, &swapped), (&lambert_report, &lambert)] {
            for ((pair, y), r) in pairs.iter().zip(&report.y).zip(&report.rendered) {
                println!("{pair:?}: harness {y:.5}, rtrace {r:.5}");
                assert!(
                    (y / r - 1.0).abs() < 1e-3,
                    "{pair:?}: harness {y}, rtrace {r}"
                );
            }
        }
        let ratio = report.rendered[0] / report.rendered[1];
        let view = 60f64.to_radians().cos() / 10f64.to_radians().cos();
        println!(
            "ratio {ratio:.4}: the incidence as the view {view:.4}, as the light {:.4}",
            1.0 / view
        );
        assert!(
            (ratio / view - 1.0).abs() < 0.3,
            "ratio {ratio}, want about {view}"
        );
        // The Lambert table: lit at 75°, 20% high; lit at 30° and seen at 75°, right (within the
        // 3% of `radiance_gives_a_lambert_table_back`).
        let f = RHO / PI;
        let [high, right] = [0, 1].map(|k| lambert_report.rendered[k] / f - 1.0);
        println!("Lambert, -g 5: lit at 75° {high:+.4}, seen at 75° {right:+.4}");
        assert!(high > 0.1, "lit at 75°: {high:+.4}");
        assert!(right.abs() < 0.03, "seen at 75°: {right:+.4}");
    }

    /// The figures of grazing light, each pinned (`pinned`), and what shows them Radiance's:
    ///
    /// | variant | lights 70°-85° (`-g 5` / default `-g 6`) | lights up to 60° |
    /// |---|---|---|
    /// | gonio's export | +19.9% / +34.1% | +1.7% (the BSDF minimum helps, below) |
    /// | PAB-Opto grid every 2.5° to 87.5°, written by `tests/radiance.py` | — / +36.1% | |
    /// | `bsdf2ttree`'s own tabulation of `0.5/PI` | — / 0 | 0 |
    /// | gonio's export and an 88° incidence | — / +34.1% (the same tree) | |
    /// | gonio's export, `pabopto2bsdf -g 6` | +4.3% / +13.3% | |
    /// | without the BSDF minimum's help | | −10.8%; with `-g 6` −6.1% |
    ///
    /// The tree's last ring of outgoing cells (sin theta from 1 − 2^(1−g) to 1: 69.6° to 90°
    /// at `-g 5`) is evaluated at its centre, 75.6° at `-g 5` and 79.9° at `-g 6`
    /// (`bsdf2ttree.c`, `eval_isotropic`); there the interpolant (a sum of
    /// Gaussian lobes holding f cos theta, divided by cos theta) diverges, since the lobes do
    /// not vanish at the horizon as cos theta does; most along the square's diagonals. The
    /// files' incidence is the tree's other axis: an 88° file changes nothing (with
    /// `pabopto2bsdf -g A` it lowers the grazing cut from 10° to 2° and the figure rises to
    /// that of no cut). `-g 6` drops the samples within 6° of the horizon: the best of the cuts
    /// measured (2°: no change; 4°: +26.7% / +43.8%; 8°: +9.6% / +18.4%; 10°: +15.5% /
    /// +24.5%), and it halves the interpolant's low values too. The BSDF minimum (the first percentile of all samples) sits
    /// 1.5% below a constant table and hides the interpolant's low values there; a dark 89°
    /// file moves it to 0.01 and shows them.
    #[test]
    fn radiance_overestimates_grazing_lights_on_the_diagonals() {
        let Some((issue, g5, i5)) = lambert_run(&[], json!({"bsdf2ttree": ["-g", "5"]})) else {
            return;
        };
        pinned("gonio's export, -g 5, lights 70-85°", g5, 0.1994);
        assert!(i5.abs() < 0.03, "lights up to 60°, -g 5: {i5:+.4}");
        let (_, g6, i6) = lambert_run(&[], json!({})).unwrap();
        pinned("gonio's export, default tree, lights 70-85°", g6, 0.3406);
        assert!(i6.abs() < 0.03, "lights up to 60°: {i6:+.4}");
        println!(
            "lights up to 60°: {i5:+.4} (-g 5), {i6:+.4}; DHR at 0°, 60°: {:?} (-g 5)",
            issue.dhr
        );
        // The same Lambertian written as a goniophotometer's grid, without gonio.
        let grid = json!({"grid_lambert": {
            "albedo": RHO, "step_deg": 2.5, "max_theta_deg": 87.5,
            "incidences_deg": pabopto::DEFAULT_THETA_I_DEG}});
        let (_, g, _) = lambert_run(&[], grid).unwrap();
        pinned("grid every 2.5°, default tree, lights 70-85°", g, 0.3608);
        // bsdf2ttree tabulating the Lambertian itself: the tree holds it to float rounding.
        let (report, g, i) = lambert_run(&[], json!({"function": "0.5/PI"})).unwrap();
        println!("bsdf2ttree's own Lambertian: {g:+.2e}, {i:+.2e}");
        assert!(g.abs() < 1e-6 && i.abs() < 1e-6, "{g}, {i}");
        assert!(report.bsdf_min.is_none());
        // One more incidence file, at 88°: the tree does not change.
        let (more, ..) = lambert_run(&[88.0], json!({})).unwrap();
        let (default, ..) = lambert_run(&[], json!({})).unwrap();
        assert_eq!(more.y, default.y, "an 88° incidence changed the tree");
        // The workaround.
        let cut = json!({"pabopto2bsdf": ["-g", "6"], "bsdf2ttree": ["-g", "5"]});
        let (_, g, i) = lambert_run(&[], cut).unwrap();
        pinned("pabopto2bsdf -g 6, -g 5, lights 70-85°", g, 0.0435);
        assert!(i.abs() < 0.03, "pabopto2bsdf -g 6, -g 5: {i:+.4}");
        let (_, g, i) = lambert_run(&[], json!({"pabopto2bsdf": ["-g", "6"]})).unwrap();
        pinned("pabopto2bsdf -g 6, default tree, lights 70-85°", g, 0.1333);
        assert!(i.abs() < 0.03, "pabopto2bsdf -g 6: {i:+.4}");
        // Without the BSDF minimum's help: a dark file at 89° (views up to 75° read the
        // incidences 0-80° only).
        let floor = json!({"floor_file": {"theta_deg": 89.0, "value": 0.01}});
        let (report, _, i) = lambert_run(&[], floor).unwrap();
        println!("BSDF minimum {:?}", report.bsdf_min);
        pinned(
            "without the floor, default tree, lights up to 60°",
            i,
            -0.1077,
        );
        let floor = json!({"floor_file": {"theta_deg": 89.0, "value": 0.01},
                           "pabopto2bsdf": ["-g", "6"]});
        let (_, _, i) = lambert_run(&[], floor).unwrap();
        pinned(
            "without the floor, pabopto2bsdf -g 6, lights up to 60°",
            i,
            -0.0609,
        );
    }
}
