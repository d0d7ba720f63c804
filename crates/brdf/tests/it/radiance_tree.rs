//! The tensor tree of the Radiance XML export (`formats::radiance_xml`) on its own, without
//! Radiance: a constant table is held exactly; a pair reads the cell computed for it (the
//! tree's lookup, `TensorTree::eval_xyz`, is Radiance's `SDqueryTre`, which `radiance_xml`
//! checks against Radiance itself); colour comes back as XYZ; the file has the shape Radiance's
//! loader requires.

use glam::{DVec2, DVec3};
use gonio_brdf::formats::pabopto;
use gonio_brdf::formats::radiance_xml::{self, TensorTree};
use gonio_brdf::sampling::cosine_hemisphere;
use gonio_brdf::table::coords::{TurnAboutZ, dir};
use gonio_brdf::table::{BrdfTable, Channels, Resolution, TableBuilder};
use std::f64::consts::PI;

/// The table of `f(wo, wi, out)` on `res`.
fn table(
    res: Resolution,
    channels: Channels,
    f: impl Fn(DVec3, DVec3, &mut [f64]) + Sync,
) -> BrdfTable {
    let mut b = TableBuilder::new(res, channels).unwrap();
    b.fill(|c, out| f(c.wo, c.wi, out));
    b.build().unwrap()
}

/// A constant table is held exactly, at every pair, the grazing ones included; below the
/// horizon the tree holds nothing.
#[test]
fn a_constant_table_is_held_exactly_at_every_pair() {
    let t = table(Resolution::isotropic(8, 8, 8), Channels::Mono, |_, _, o| {
        o[0] = 0.5 / PI
    });
    let tree = TensorTree::from_table(&t, 4).unwrap();
    assert!(tree.rank() == 3 && !tree.has_colour());
    for tl in [0.0f64, 30.0, 70.0, 80.0, 89.0] {
        for tv in [0.0f64, 45.0, 85.0] {
            for pv in [0.0f64, 100.0, 250.0] {
                let got = tree.eval_xyz(
                    dir(tv.to_radians(), pv.to_radians()),
                    dir(tl.to_radians(), 0.3),
                );
                for g in got {
                    assert!((g * PI / 0.5 - 1.0).abs() < 1e-6, "{tl} {tv} {pv}: {got:?}");
                }
            }
        }
    }
    assert_eq!(
        tree.eval_xyz(dir(0.3, 0.0), DVec3::new(0.0, 0.6, -0.8)),
        [0.0; 3]
    );
}

/// The cell of a pair is the one whose values were computed for it: at the centres of cells
/// (of the view's and the light's coordinates), a table that depends on both angles, the
/// relative azimuth and, for the anisotropic one (a `TensorTree4`), the view's azimuth comes
/// back as the table there. A cell holds the mean over its sub-cells, which differs from the
/// value at its centre by the second order of the cell's size (the functions are smooth:
/// measured 0.45% at worst for order 6, 1.8% for order 4, whose cells are four times as wide
/// and reach 12° at 60°), plus the table's interpolation of them; a view or light read from
/// the wrong cell, mirrored or turned the wrong way, misses by up to 30%. The light at a cell's
/// centre is `cosine_hemisphere` of it (the same map), a `TensorTree4`'s view its mirror
/// image through the normal.
#[test]
fn pairs_read_the_cells_computed_for_them() {
    // Smooth everywhere: sin θo sin θi cos(φo - φi) has no kink at either pole.
    let f = |wo: DVec3, wi: DVec3| {
        0.2 + 0.3 * wo.z + 0.2 * wi.z * wi.z + 0.15 * wo.truncate().dot(wi.truncate())
    };
    let g = |wo: DVec3, wi: DVec3| f(wo, wi) + 0.3 * wo.x * wo.x;
    let iso = table(
        Resolution::isotropic(32, 32, 64),
        Channels::Mono,
        |o, i, out| out[0] = f(o, i),
    );
    let aniso = table(
        Resolution::anisotropic(16, 16, 32, 32),
        Channels::Mono,
        |o, i, out| out[0] = g(o, i),
    );
    let mut seed = 7u64;
    let mut next = move |n: usize| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) as usize % n
    };
    let centre = |i: usize, j: usize, res: usize| {
        DVec2::new((i as f64 + 0.5) / res as f64, (j as f64 + 0.5) / res as f64)
    };
    for (t, order, want) in [
        (&iso, 6, &f as &dyn Fn(DVec3, DVec3) -> f64),
        (&aniso, 4, &g as &dyn Fn(DVec3, DVec3) -> f64),
    ] {
        let tree = TensorTree::from_table(t, order).unwrap();
        let res = 1 << order;
        let mut worst = 0.0f64;
        for _ in 0..300 {
            let light = cosine_hemisphere(centre(next(res), next(res), res));
            let (view, light) = if tree.rank() == 3 {
                // The tree's view is at azimuth 180°: turn both by any angle.
                let sin = 1.0 - 2.0 * (next(res / 2) as f64 + 0.5) / res as f64;
                let turn = TurnAboutZ::new(next(360) as f64);
                (
                    turn.apply(DVec3::new(-sin, 0.0, (1.0 - sin * sin).sqrt())),
                    turn.apply(light),
                )
            } else {
                let q = centre(next(res), next(res), res);
                let h = cosine_hemisphere(q);
                (DVec3::new(-h.x, -h.y, h.z), light)
            };
            if view.z < 0.35 || light.z < 0.35 {
                continue; // beyond 70°, where the table's nodes are sparse
            }
            let got = tree.eval_xyz(view, light)[1];
            worst = worst.max((got / want(view, light) - 1.0).abs());
        }
        let bound = if order == 6 { 0.01 } else { 0.025 };
        assert!(worst < bound, "order {order}: worst {worst}");
    }
}

/// A colour table's X, Y, Z (relative to the equal-energy white, the PAB-Opto export's weights)
/// come back from the Y and u′ v′ the tree holds, to the f32 storage.
#[test]
fn colour_comes_back_as_xyz_relative_to_the_equal_energy_white() {
    let rgb = table(Resolution::isotropic(8, 8, 8), Channels::Rgb, |_, _, o| {
        o.copy_from_slice(&[0.3, 0.2, 0.05])
    });
    let tree = TensorTree::from_table(&rgb, 3).unwrap();
    assert!(tree.has_colour());
    let got = tree.eval_xyz(dir(0.5, 0.0), dir(0.3, 2.0));
    let w = pabopto::xyz_weights(&Channels::Rgb).unwrap().unwrap();
    for k in 0..3 {
        let want = 0.3 * w[0][k] + 0.2 * w[1][k] + 0.05 * w[2][k];
        // u′ v′ and Y are stored as f32.
        assert!(
            (got[k] / want - 1.0).abs() < 1e-5,
            "{got:?}, channel {k}: {want}"
        );
    }
}

/// The written tree has the shape Radiance's `load_tree_data` requires: a root of eight
/// children for TensorTree3, the four covering the upper half of the view axis a single
/// zero and the others (2^(order-1))³ values; one grid of 2^(4 order) values for
/// TensorTree4, which colour tables get. A grid's value count must be a power of 2^rank.
#[test]
fn the_xml_holds_trees_of_the_shape_radiance_reads() {
    let grey = table(Resolution::isotropic(8, 8, 8), Channels::Mono, |_, _, o| {
        o[0] = 0.2
    });
    let dir_out = tempfile::tempdir().unwrap();
    let path = dir_out.path().join("t.xml");
    radiance_xml::write(&grey, &path, "a <b> & c", Some(4)).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("<Name>a &lt;b&gt; &amp; c</Name>"));
    assert!(text.contains("<IncidentDataStructure>TensorTree3</IncidentDataStructure>"));
    assert!(text.contains("<AngleBasis>LBNL/Shirley-Chiu</AngleBasis>"));
    assert_eq!(text.matches("<WavelengthData>").count(), 1);
    let data = text
        .split("<ScatteringData>")
        .nth(1)
        .unwrap()
        .split("</ScatteringData>")
        .next()
        .unwrap();
    let grids: Vec<usize> = data
        .trim()
        .trim_start_matches('{')
        .trim_end_matches('}')
        .split('}')
        .filter(|g| g.contains('{'))
        .map(|g| g.split('{').nth(1).unwrap().split_whitespace().count())
        .collect();
    assert_eq!(grids, [512, 1, 512, 1, 512, 1, 512, 1]);
    // A colour table, isotropic too, is a TensorTree4 (see "Which rank").
    let aniso = table(Resolution::isotropic(8, 8, 8), Channels::Rgb, |_, _, o| {
        o.fill(0.2)
    });
    assert_eq!(radiance_xml::rank(&aniso), 4);
    let path = dir_out.path().join("a.xml");
    radiance_xml::write(&aniso, &path, "a", Some(3)).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("TensorTree4"));
    for name in ["Visible", "CIE-u", "CIE-v"] {
        assert!(text.contains(&format!(">{name}</Wavelength>")), "{name}");
    }
    for block in text.split("<ScatteringData>").skip(1) {
        let data = block.split("</ScatteringData>").next().unwrap();
        assert_eq!(data.matches('{').count(), 1);
        assert_eq!(
            data.replace(['{', '}'], " ").split_whitespace().count(),
            4096
        );
    }
    assert!(TensorTree::from_table(&aniso, 7).is_err());
    assert!(TensorTree::from_table(&grey, 1).is_err());
}
