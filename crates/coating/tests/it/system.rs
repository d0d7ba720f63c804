//! The coating system: the method follows the stack, tables do not depend on the thread count,
//! a layered table is reciprocal.

use glam::DVec3;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_coating::cell::CellWalks;
use gonio_coating::description;
use gonio_coating::system::*;
use rand::{RngExt, SeedableRng};
use std::path::Path;

fn example(name: &str, wl: &[f64]) -> Coating {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/coatings")
        .join(name);
    description::read(&path, wl).unwrap()
}

/// A smooth coat over a diffuse base goes through the exact series, anything else through
/// the walks; the exact albedo is the mirror plus the body's.
#[test]
fn method_follows_the_system() {
    let wl = [450.0, 550.0, 650.0];
    let red = example("red_solid.toml", &wl);
    assert_eq!(red.method(CellWalks::fixed(8)), Method::ClosedForm);
    let exact = red.clear_coat().unwrap().at(550.0).unwrap();
    let albedo = red.evaluator(&wl).unwrap().albedo(0.8, 1);
    assert!((albedo[1] - exact.specular(0.8) - exact.body_albedo(0.8)).abs() < 1e-15);
    let silver = example("silver_metallic.toml", &wl);
    assert_eq!(
        silver.method(CellWalks::fixed(8)),
        Method::RandomWalk(CellWalks::fixed(8))
    );
    assert!(
        silver
            .evaluator(&wl)
            .unwrap()
            .mirror(0.8)
            .iter()
            .all(|&r| r == 0.0)
    );
}

/// The table is the same, bit for bit, on one thread and on two, with walks added where the
/// noise is (4 walks per cell before: most cells take more); and each cell equals its
/// reciprocal cell (the same pair with `wi` and `wo` swapped) to rounding, so both took the
/// same walks: a cell taken on to twice the walks of its reciprocal would differ from it by
/// the walks' noise, a relative standard deviation of several percent at these counts, not
/// 1e-5 (the values are stored as f32, 6e-8, and the two cells' directions are computed apart).
#[test]
fn table_does_not_depend_on_the_thread_count() {
    let wl = [450.0, 550.0, 650.0];
    let pearl = example("pearl_interference.toml", &wl);
    let res = Resolution::isotropic(10, 10, 6);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                pearl
                    .table_cells(
                        res,
                        &wl,
                        CellWalks::adaptive(4, TARGET_DL),
                        Provenance::default(),
                        |_| true,
                    )
                    .unwrap()
            })
    };
    let bits = |t: &BrdfTable| t.values().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let ((one, spent), (two, _)) = (on(1), on(2));
    assert!(bits(&one) == bits(&two), "the tables differ");
    assert!(spent.max > 4, "no walks were added: {spent:?}");
    let values = one.values();
    for cell in 0..res.cell_count() {
        let (a, b) = (
            values[cell * 3 + 1],
            values[res.reciprocal_cell(cell) * 3 + 1],
        );
        if !a.is_nan() {
            assert!(
                (a - b).abs() <= 1e-5 * a.abs().max(1e-3),
                "cell {cell}: {a} against {b}"
            );
        }
    }
}

mod slow {
    use super::*;

    /// Reciprocity of a layered table (the silver metallic, 32 walks per cell at 45 × 45 ×
    /// 24): f(a, b) and f(b, a) read from the table at 400 random pairs within 60° of the
    /// normal where the BRDF exceeds 1% of its largest value there: the rms relative
    /// difference is within 2% (the cells' estimates are reciprocal; what differs is the
    /// interpolation between cells). The walk's own reciprocity, with independent
    /// estimates each way, is tested in `layered`.
    #[test]
    fn layered_table_is_reciprocal() {
        let wl = [550.0, 560.0];
        let silver = example("silver_metallic.toml", &wl);
        let table = silver
            .table(
                Resolution::isotropic(45, 45, 24),
                &wl,
                CellWalks::fixed(32),
                Provenance::default(),
            )
            .unwrap();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(21);
        let dir = |rng: &mut rand_pcg::Pcg64| {
            let t = rng.random::<f64>() * 60f64.to_radians();
            let p = rng.random::<f64>() * 2.0 * std::f64::consts::PI;
            DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
        };
        let pairs: Vec<(DVec3, DVec3)> =
            (0..4000).map(|_| (dir(&mut rng), dir(&mut rng))).collect();
        let value = |a: DVec3, b: DVec3| {
            let mut v = [0.0; 2];
            table.eval_channels(a, b, &mut v);
            v[0]
        };
        let peak = pairs.iter().map(|&(a, b)| value(a, b)).fold(0.0, f64::max);
        let (mut sum2, mut count) = (0.0, 0);
        for &(a, b) in &pairs {
            let (x, y) = (value(a, b), value(b, a));
            if x.min(y) > 0.01 * peak && count < 400 {
                sum2 += ((x - y) / (0.5 * (x + y))).powi(2);
                count += 1;
            }
        }
        let rms = (sum2 / count as f64).sqrt();
        eprintln!("reciprocity: rms relative difference {rms:.4} over {count} pairs");
        assert!(count == 400 && rms < 0.02, "{rms} over {count}");
    }
}

/// A dispersive coat (Schott N-BK7 by Sellmeier's formula) under a rough top: each band has its
/// own index, so its own walk and its own stream of random numbers (the groups' seeds overflowed
/// in a build with overflow checks, so that such a table could not be made there). Each band's
/// albedo is that of a coat of the band's index held constant: the base is dark in one band and
/// light in the other, so bands given each other's walk would differ by a factor of several.
/// Bound: each estimate has a standard error of about 0.5/√N of the value (`Evaluator::albedo`),
/// the two are independent walks (their seeds differ), so their difference has a standard
/// deviation of 0.5 √(2/N) = 1.1% of the value at N = 4000; 5% is 4.4 of those.
#[test]
fn dispersive_rough_coat_has_a_walk_per_band() {
    let wl = [450.0, 650.0];
    let coating = |index: &str, wl: &[f64]| {
        description::parse(
            &format!(
                "[top]\nroughness = {{ alpha = 0.15 }}\n[coat]\nindex = {index}\n\
                 thickness_um = 40\n[base]\nkind = \"diffuse\"\n\
                 reflectance = {{ nm = [450, 650], values = [0.1, 0.8] }}\n"
            ),
            wl,
        )
        .unwrap()
    };
    let bk7 = "{ sellmeier_b = [1.03961212, 0.231792344, 1.01046945], \
               sellmeier_c_um2 = [0.00600069867, 0.0200179144, 103.560653] }";
    let dispersive = coating(bk7, &wl);
    let table = dispersive
        .table(
            Resolution::isotropic(6, 6, 4),
            &wl,
            CellWalks::fixed(2),
            Provenance::default(),
        )
        .unwrap();
    // NaN marks the nodes below the horizon, in every table.
    let values = table.values();
    assert!(values.iter().all(|v| v.is_nan() || *v >= 0.0));
    assert!(values.iter().filter(|v| **v > 0.0).count() > values.len() / 2);
    let evaluator = dispersive.evaluator(&wl).unwrap();
    match &evaluator {
        Evaluator::Walks(groups) => assert_eq!(groups.len(), 2),
        Evaluator::Exact(_) => panic!("a rough top takes the walks"),
    }
    let n = 4000;
    let albedo = evaluator.albedo(0.8, n);
    for (band, &w) in wl.iter().enumerate() {
        let index = dispersive.coat.index.at(w);
        let constant = coating(&format!("{index}"), &[w]);
        let expected = constant.evaluator(&[w]).unwrap().albedo(0.8, n)[0];
        assert!(
            (albedo[band] / expected - 1.0).abs() < 0.05,
            "{w} nm (index {index}): {} against {expected}",
            albedo[band]
        );
    }
}

/// The white furnace through the albedo: a lossless glossy coat (GGX α 0.03, n 1.5) over a
/// white Lambertian base conserves energy, so its directional-hemispherical reflectance is 1 up
/// to what the walks lose at this roughness: 0.983 at 0° and 45° (measured, the same with the
/// top's lobe sampled apart or found by the cosine-weighted directions, which agree there).
/// Bound 0.025: that 0.017 and three standard deviations of the body's estimate at 4096
/// directions (0.003). Before the top's lobe was sampled apart the glossy reflection at 75°
/// (F(75°) = 0.25 of the light, in a lobe a few degrees wide) was found only by the
/// cosine-weighted directions, which rarely hit it: 0.927 (and on the silver metallic at 2048
/// directions 0.41 ± 0.15 over 16 estimates, against 0.49 ± 0.008 now).
#[test]
fn glossy_coat_over_white_albedo_is_one() {
    let wl = [550.0];
    let coating = description::parse(
        "[top]\nroughness = { distribution = \"ggx\", alpha = 0.03 }\n\
         [coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 1\n",
        &wl,
    )
    .unwrap();
    let evaluator = coating.evaluator(&wl).unwrap();
    for deg in [0.0_f64, 45.0, 75.0] {
        let a = evaluator.albedo(deg.to_radians().cos(), 4096)[0];
        eprintln!("{deg}°: albedo {a:.4}");
        assert!((a - 1.0).abs() < 0.025, "{deg}°: {a}");
    }
}
