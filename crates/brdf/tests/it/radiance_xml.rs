//! The XML BSDF that gonio writes itself (`formats::radiance_xml`, a tensor tree), read by
//! Radiance's own BSDF library and renderer (PyPI's pyradiance, through `tests/radiance.py`):
//! a Lambert table comes back at every view for light at 70° and 80°, where the PAB-Opto route
//! through `pabopto2bsdf` misreads it by 20-34% (`radiance_grazing`); Radiance returns what the
//! tree holds at every pair; `rtrace` renders the viewer and the light the right way round and
//! an anisotropic table in the material's frame; colour tables keep their colour. Pairs are
//! (light, view) as Radiance renders them. Skipped without pyradiance, like `radiance`.

use crate::radiance::{
    Pair, RadianceReport, albedo_y, lambert_table, pairs, run_radiance, tabulate, tinted, xy,
};
use glam::DVec3;
use gonio_brdf::formats::{pabopto, radiance_xml};
use gonio_brdf::models::{Model, Ward};
use gonio_brdf::table::coords::dir;
use gonio_brdf::table::{BrdfTable, Channels, Resolution, TableBuilder};
use serde_json::json;
use std::f64::consts::PI;

/// The albedo of the Lambert table.
const RHO: f64 = 0.5;

/// Write `table` as a tensor tree of `order` (default: the export's) and run Radiance on it
/// with `queries` (see `tests/radiance.py`); the report and the tree, or `None` without
/// pyradiance.
fn radiance_xml(
    table: &BrdfTable,
    order: Option<u32>,
    mut queries: serde_json::Value,
) -> Option<(RadianceReport, radiance_xml::TensorTree)> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xml");
    let tree = radiance_xml::write(table, &path, "t", order).unwrap();
    queries["xml"] = json!(path);
    for key in ["pairs", "dhr_theta"] {
        if queries.get(key).is_none() {
            queries[key] = json!([]);
        }
    }
    let report = run_radiance(None, queries)?;
    Some((report, tree))
}

/// Direction of a pair's angles in degrees.
fn d(theta: f64, phi: f64) -> DVec3 {
    dir(theta.to_radians(), phi.to_radians())
}

/// gonio's own CIE XYZ (relative to the equal-energy white, as the export writes it; X = Y = Z
/// for a monochrome table) for the light at (p[0], p[1]) seen from (p[2], p[3]).
fn own_xyz(table: &BrdfTable, p: &Pair) -> [f64; 3] {
    let mut buf = vec![0.0; table.channel_count()];
    table.eval_channels(d(p[2], p[3]), d(p[0], p[1]), &mut buf);
    match pabopto::xyz_weights(table.channels()).unwrap() {
        None => [buf[0]; 3],
        Some(w) => std::array::from_fn(|k| w.iter().zip(&buf).map(|(w, v)| w[k] * v).sum()),
    }
}

/// Lights at 70° and 80° (and 75°, 85°), azimuth 0, seen from every view: 0° to 85° in steps
/// of 5°, at every relative azimuth in steps of 15° (the diagonals of Radiance's square, where
/// the PAB-Opto route goes wrong, among them).
fn grazing_pairs() -> Vec<Pair> {
    let mut out = vec![];
    for light in [70.0, 75.0, 80.0, 85.0] {
        for view in (0..=17).map(|k| 5.0 * k as f64) {
            for k in 0..24 {
                out.push([light, 0.0, view, 15.0 * k as f64]);
            }
        }
    }
    out
}

/// The relative error of largest magnitude, with its sign, of Radiance's values against the
/// Lambert table's `RHO / PI`, and the pair where it is.
fn worst_lambert(pairs: &[Pair], y: &[f64]) -> (f64, Pair) {
    let f = RHO / PI;
    pairs
        .iter()
        .zip(y)
        .map(|(p, y)| (y / f - 1.0, *p))
        .fold(
            (0.0, [0.0; 4]),
            |w, e| if e.0.abs() > w.0.abs() { e } else { w },
        )
}

/// A Lambert table written as a tensor tree comes back at every view for grazing light: each
/// cell holds the mean of a constant, which Radiance splits off whole as its diffuse part
/// (`extract_diffuse`: the tree's least value, here every value) and returns to its float
/// rounding; its position-dependent perturbation of at most 1e-4 (`SDqueryTre`) multiplies the
/// zero that remains in the tree. So the 3% of the issue is met with room: measured 3.3e-7 at
/// worst. The reflectance is the albedo at any light, 80° too,
/// and `rtrace` renders the pairs where the PAB-Opto route is 20% high (light 75°, view 30° on
/// a diagonal) as the table.
#[test]
fn radiance_reads_the_xml_lambert_table_at_grazing_light() {
    let table = lambert_table(RHO);
    let pairs = grazing_pairs();
    let render: [Pair; 3] = [
        [75.0, 0.0, 30.0, 45.0],
        [80.0, 0.0, 45.0, 135.0],
        [70.0, 90.0, 12.0, 225.0],
    ];
    let queries = json!({"pairs": pairs, "render": render, "dhr_theta": [0.0, 60.0, 80.0]});
    let Some((report, _)) = radiance_xml(&table, None, queries) else {
        return;
    };
    let (worst, at) = worst_lambert(&pairs, &report.y);
    println!("XML: worst {worst:+.2e} at {at:?}; DHR {:?}", report.dhr);
    assert!(worst.abs() < 0.03, "worst {worst:+.4} at {at:?}");
    for (theta, dhr) in [0.0, 60.0, 80.0].iter().zip(&report.dhr) {
        assert!(
            (dhr / RHO - 1.0).abs() < 1e-3,
            "DHR at {theta}°: {dhr}, albedo {RHO}"
        );
    }
    for (p, r) in render.iter().zip(&report.rendered) {
        let e = r / (RHO / PI) - 1.0;
        println!("rtrace {p:?}: {r:.5} ({e:+.2e})");
        // rtrace's source, 0.5° across, is sampled at its centre (-dj 0): the same rounding.
        assert!(e.abs() < 1e-3, "{p:?}: rtrace {r}");
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// The check of `radiance_reads_the_xml_lambert_table_at_grazing_light`, on the PAB-Opto
    /// route (`pabopto2bsdf` and `bsdf2ttree` with their defaults): it fails there, by the
    /// 34% that `radiance_grazing` pins (+0.34 measured), which the XML removes.
    #[test]
    fn the_pabopto_route_fails_the_same_lambert_check() {
        let table = lambert_table(RHO);
        let pairs = grazing_pairs();
        let queries = json!({"pairs": pairs, "dhr_theta": []});
        let source = Some((&table, &pabopto::DEFAULT_THETA_I_DEG[..]));
        let Some(report) = run_radiance(source, queries) else {
            return;
        };
        let (worst, at) = worst_lambert(&pairs, &report.y);
        println!("PAB-Opto: worst {worst:+.4} at {at:?}");
        assert!(worst.abs() > 0.2, "worst {worst:+.4} at {at:?}");
    }

    /// Radiance returns what the tree holds: at 400 random pairs (lights and views up to 85°)
    /// of a Ward + Lambert table, monochrome (`TensorTree3`) and RGB (`TensorTree4`),
    /// `SDevalBSDF`'s X, Y, Z equal the tree's own lookup
    /// ([`radiance_xml::TensorTree::eval_xyz`]) to the text's six digits, Radiance's
    /// perturbation (1e-4) and its colour arithmetic in f32 (measured 4.2e-4 at worst): the
    /// file is laid out as Radiance reads it, cell for cell. Against the table itself the tree
    /// is within what a cell's mean can be from the value at a point of it (reported).
    #[test]
    fn radiance_returns_what_the_tree_holds() {
        let ward = Model::diffuse_specular(
            DVec3::new(0.25, 0.2, 0.1),
            Model::Ward(Ward::isotropic(DVec3::new(0.6, 0.4, 0.2), 0.2)),
        );
        let pairs = pairs(400, (0.0, 85.0), (0.0, 85.0), 11);
        for mono in [true, false] {
            let table = tabulate(&ward, Resolution::isotropic(90, 64, 64), mono);
            let Some((report, tree)) = radiance_xml(&table, None, json!({"pairs": pairs})) else {
                return;
            };
            let (mut worst, mut worst_table) = (0.0f64, vec![]);
            for (p, got) in pairs.iter().zip(&report.query_xyz) {
                let want = tree.eval_xyz(d(p[2], p[3]), d(p[0], p[1]));
                for k in 0..3 {
                    let e = (got[k] / want[k] - 1.0).abs();
                    assert!(e < 1e-3, "{p:?}: Radiance {got:?}, tree {want:?}");
                    worst = worst.max(e);
                }
                worst_table.push(got[1] / own_xyz(&table, p)[1] - 1.0);
            }
            worst_table.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
            println!(
                "TensorTree{}: Radiance vs tree: {worst:.1e}; tree vs table: median {:+.4}, \
                 worst {:+.4}",
                tree.rank(),
                worst_table[worst_table.len() / 2],
                worst_table[worst_table.len() - 1]
            );
        }
    }

    /// A table that is not reciprocal and lobed toward the light (a retro-reflection lobe over
    /// a base that grows with the light's cosine): `rtrace` renders gonio's
    /// `f(wo = view, wi = light)`, not its transpose and not its mirror. The view and the
    /// light at 40° on the same side: the lobe's peak, 0.33 + 0.05 + 0.3 cos 40° = 0.61 /sr; on
    /// opposite sides (the mirror pair) 0.28; the two pairs lit at 10° and 60° and seen from the
    /// other angle differ by the base, 0.05 + 0.3 cos θ_light (0.35 against 0.20). Each pair
    /// within 5% of gonio's value: the cell means of the lobe (0.25 rad wide) near its peak are
    /// up to 3% below the peak (cells 2.3° wide in θ at 40°, view and light; measured 0.5% at
    /// the peak, 1.7% at most), while the transpose and the mirror miss by 40% and more.
    #[test]
    fn radiance_renders_the_view_and_the_light_the_right_way_round() {
        let mut b = TableBuilder::new(Resolution::isotropic(45, 90, 90), Channels::Mono).unwrap();
        b.fill(|c, out| {
            let angle = c.wo.dot(c.wi).clamp(-1.0, 1.0).acos();
            out[0] = 0.05 + 0.3 * c.wi.z + 0.33 * (-(angle / 0.25).powi(2)).exp();
        });
        let table = b.build().unwrap();
        let render: [Pair; 4] = [
            [40.0, 30.0, 40.0, 30.0],
            [40.0, 30.0, 40.0, 210.0],
            [10.0, 100.0, 60.0, 300.0],
            [60.0, 300.0, 10.0, 100.0],
        ];
        let queries = json!({"pairs": render, "render": render});
        let Some((report, tree)) = radiance_xml(&table, None, queries) else {
            return;
        };
        for ((p, r), q) in render.iter().zip(&report.rendered).zip(&report.y) {
            let own = own_xyz(&table, p)[1];
            let held = tree.eval_xyz(d(p[2], p[3]), d(p[0], p[1]))[1];
            let transpose = own_xyz(&table, &[p[2], p[3], p[0], p[1]])[1];
            let mirror = own_xyz(&table, &[p[0], p[1], p[2], p[3] + 180.0])[1];
            println!(
                "{p:?}: rtrace {r:.4}, SDevalBSDF {q:.4}, tree {held:.4}, gonio {own:.4} \
                 (transpose {transpose:.4}, mirror {mirror:.4})"
            );
            assert!(
                (r / held - 1.0).abs() < 1e-3,
                "{p:?}: rtrace {r}, tree {held}"
            );
            assert!(
                (r / own - 1.0).abs() < 0.05,
                "{p:?}: rtrace {r}, gonio {own}"
            );
        }
    }

    /// An anisotropic table without mirror symmetry (a Ward lobe α 0.15 × 0.45, axes turned by
    /// 30°, over 0.1/π): Radiance returns the tree's values (order 5, `TensorTree4`) and
    /// `rtrace` renders the lobe in the material's frame (up vector +y: gonio's y), at views in
    /// all four quadrants of azimuth and lights 25° either side of the mirror azimuth, where
    /// the lobe's turn makes the two differ by up to 2.3 times. Against gonio's table within
    /// 25%: the view cells of an order-5 tree are 3.6° to 7° across at 40° and the lobe's
    /// narrow axis (α 0.15, 8.6°) changes by up to 20% across one (measured -13.4% at worst);
    /// a mirrored or turned frame swaps the pairs, 2.3 times.
    #[test]
    fn radiance_renders_an_anisotropic_table_in_the_materials_frame() {
        use gonio_brdf::Brdf;
        use gonio_brdf::table::coords::turn_about_z;
        let ward = Ward {
            specular: gonio_brdf::Rgb::splat(0.5),
            alpha_x: 0.15,
            alpha_y: 0.45,
        };
        let turn = 30f64.to_radians();
        let mut b =
            TableBuilder::new(Resolution::anisotropic(32, 32, 64, 36), Channels::Mono).unwrap();
        b.fill(|cell, out| {
            let (wi, wo) = (turn_about_z(cell.wi, -turn), turn_about_z(cell.wo, -turn));
            out[0] = 0.1 / PI + ward.eval(wo, wi).x;
        });
        let table = b.build().unwrap();
        let mut render = vec![];
        for phi_v in [45.0f64, 135.0, 225.0, 315.0, 20.0, 160.0] {
            for dphi in [-25.0f64, 25.0] {
                render.push([40.0, (phi_v + 180.0 + dphi).rem_euclid(360.0), 40.0, phi_v]);
            }
        }
        let queries = json!({"pairs": render, "render": render});
        let Some((report, tree)) = radiance_xml(&table, None, queries) else {
            return;
        };
        assert_eq!(tree.rank(), 4);
        for ((p, r), q) in render.iter().zip(&report.rendered).zip(&report.y) {
            let own = own_xyz(&table, p)[1];
            let held = tree.eval_xyz(d(p[2], p[3]), d(p[0], p[1]))[1];
            println!(
                "{p:?}: rtrace {r:.4}, SDevalBSDF {q:.4}, tree {held:.4}, gonio {own:.4} ({:+.3})",
                r / own - 1.0
            );
            assert!(
                (q / held - 1.0).abs() < 1e-3,
                "{p:?}: Radiance {q}, tree {held}"
            );
            assert!(
                (r / held - 1.0).abs() < 1e-3,
                "{p:?}: rtrace {r}, tree {held}"
            );
            assert!(
                (r / own - 1.0).abs() < 0.25,
                "{p:?}: rtrace {r}, gonio {own}"
            );
        }
    }

    /// Colour tables keep their colour in Radiance's BSDF library and in `rtrace`'s picture:
    /// an RGB and a spectral table of one chromaticity each (`radiance::tinted`), compared with
    /// gonio's own XYZ of the table at each pair (relative to the equal-energy white). The
    /// tree (a `TensorTree4`, see `formats::radiance_xml`, "Which rank") holds Y and u′ v′ of
    /// each cell's mean, to six digits: the chromaticity within 1e-4 of gonio's (measured 5e-5
    /// from `SDevalBSDF` and from `rtrace`'s RGB), the luminance within 1e-3 of the tree's own
    /// lookup, and within what a cell's mean can be from the value at a point of it of gonio's:
    /// the order-5 tree's cells are 3.6° across at the pole and the lobe (Ward α 0.2 over a
    /// base that varies with both angles) changes by up to 15% across one (measured 7.2% at
    /// worst), so 8%. Through `pabopto2bsdf` and `bsdf2ttree`, `SDevalBSDF` returned x, y =
    /// 0.67, 0.33 for the RGB table (docs/brdf-tables.md); a `TensorTree3` written by gonio
    /// returns 0.675, 0.326: Radiance drops the u′ v′ trees of every coloured `TensorTree3`.
    #[test]
    fn radiance_keeps_the_colour_of_rgb_and_spectral_tables() {
        let bands: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let ramp: Vec<f64> = bands
            .iter()
            .map(|l| 0.1 + 0.7 * (l - 400.0) / 300.0)
            .collect();
        let tables = [
            (
                "RGB (0.7, 0.35, 0.1)",
                tinted(Channels::Rgb, &[0.7, 0.35, 0.1]),
            ),
            (
                "spectral ramp 0.1 to 0.8",
                tinted(
                    Channels::Spectral {
                        wavelengths_nm: bands,
                    },
                    &ramp,
                ),
            ),
        ];
        // Off the cells' edges, where `rtrace`'s ray and the query may fall either side (the
        // azimuths 0° and 180°, and 30°, whose sine 1/2 is the edge of rings in sin θ).
        let pairs: [Pair; 3] = [
            [33.0, 10.0, 33.0, 193.0],
            [33.0, 5.0, 24.0, 97.0],
            [75.0, 48.0, 50.0, 200.0],
        ];
        for (what, table) in &tables {
            let queries = json!({"pairs": pairs, "render": pairs});
            let Some((report, tree)) = radiance_xml(table, None, queries) else {
                return;
            };
            assert!(tree.has_colour());
            for (k, p) in pairs.iter().enumerate() {
                let own = own_xyz(table, p);
                let want = xy(own);
                let held = tree.eval_xyz(d(p[2], p[3]), d(p[0], p[1]));
                for (how, got) in [
                    ("SDevalBSDF", report.query_xyz[k]),
                    ("rtrace", report.rendered_xyz[k]),
                ] {
                    let c = xy(got);
                    println!(
                        "{what} {p:?}: {how} x, y = {c:.5?}, Y {:.4}; tree Y {:.4}; gonio \
                         {want:.5?}, Y {:.4}",
                        got[1], held[1], own[1]
                    );
                    assert!(
                        (c[0] - want[0]).abs() < 1e-4 && (c[1] - want[1]).abs() < 1e-4,
                        "{what} {p:?}: {how} {c:?}, gonio {want:?}"
                    );
                    assert!(
                        (got[1] / held[1] - 1.0).abs() < 1e-3,
                        "{what} {p:?}: {how} Y {}, tree {}",
                        got[1],
                        held[1]
                    );
                    assert!(
                        (got[1] / own[1] - 1.0).abs() < 0.08,
                        "{what} {p:?}: {how} Y {}, gonio {}",
                        got[1],
                        own[1]
                    );
                }
            }
        }
    }

    /// The tree keeps the reflectance: each light cell holds the mean of the table over its
    /// projected solid angle, so `SDdirectHemi` (the sum over a view's cells) is gonio's albedo
    /// averaged over the view's cell, for a monochrome Ward + Lambert table (a `TensorTree3` of
    /// order 6) and its RGB table (a `TensorTree4` of order 5). Up to 60° the albedo is nearly
    /// linear across a view cell and the mean is the value at its centre within its curvature
    /// (measured 0.8% at worst): 1%. Beyond, a view cell reaches from 69.6° to 75.5° (order 6)
    /// or to 90° (order 5, the square's outer ring), over which the albedo falls by up to 4%:
    /// within 5% at 70° and 80° (measured -1.0% and -2.8% at 70°). The PAB-Opto route: -2.3%
    /// at 0°.
    #[test]
    fn radiance_keeps_the_reflectance_of_a_ward_table() {
        let ward = Model::diffuse_specular(
            DVec3::new(0.25, 0.2, 0.1),
            Model::Ward(Ward::isotropic(DVec3::new(0.6, 0.4, 0.2), 0.2)),
        );
        let thetas = [0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0];
        for mono in [true, false] {
            let table = tabulate(&ward, Resolution::isotropic(90, 64, 64), mono);
            let queries = json!({"dhr_theta": thetas});
            let Some((report, tree)) = radiance_xml(&table, None, queries) else {
                return;
            };
            for (theta, dhr) in thetas.iter().zip(&report.dhr) {
                let own = albedo_y(&table, *theta);
                let e = dhr / own - 1.0;
                println!(
                    "TensorTree{}: DHR at {theta}°: Radiance {dhr:.5}, gonio {own:.5} ({e:+.4})",
                    tree.rank()
                );
                let bound = if *theta <= 60.0 { 0.01 } else { 0.05 };
                assert!(
                    e.abs() < bound,
                    "DHR at {theta}°: Radiance {dhr}, gonio {own}"
                );
            }
        }
    }
}
