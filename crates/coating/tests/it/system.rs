//! The coating system: the method follows the stack, tables do not depend on the thread count,
//! a layered table is reciprocal.

use glam::DVec3;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
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
    assert_eq!(red.method(8), Method::ClosedForm);
    let exact = red.clear_coat().unwrap().at(550.0).unwrap();
    let albedo = red.evaluator(&wl).unwrap().albedo(0.8, 1);
    assert!((albedo[1] - exact.specular(0.8) - exact.body_albedo(0.8)).abs() < 1e-15);
    let silver = example("silver_metallic.toml", &wl);
    assert_eq!(silver.method(8), Method::RandomWalk { samples: 8 });
    assert!(
        silver
            .evaluator(&wl)
            .unwrap()
            .mirror(0.8)
            .iter()
            .all(|&r| r == 0.0)
    );
}

/// The table is the same, bit for bit, on one thread and on two.
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
            .install(|| pearl.table(res, &wl, 4, Provenance::default()).unwrap())
    };
    let bits = |t: &BrdfTable| t.values().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let (one, two) = (on(1), on(2));
    assert!(bits(&one) == bits(&two), "the tables differ");
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
                32,
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
