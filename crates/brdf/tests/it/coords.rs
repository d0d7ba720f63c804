//! Rusinkiewicz half/difference coordinates: round trips, reciprocity, cells, the
//! interpolation stencil, and the table's interpolation against the definitions written out.

use glam::DVec3;
use gonio_brdf::table::coords::*;
use gonio_brdf::table::{BrdfTable, Channels, Provenance};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A linear congruential generator's uniforms in [0, 1), fixed for reproducible tests.
fn uniforms(seed: u64) -> impl FnMut() -> f64 {
    let mut rng = seed;
    move || {
        rng = rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (rng >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The angles as Rusinkiewicz defines them, written out: `phi_h` and `theta_h` from `h`, then
/// `d = Ry(-theta_h) Rz(-phi_h) wi` by the rotations of those angles.
fn half_diff_by_rotations(wi: DVec3, wo: DVec3) -> HalfDiff {
    let h = (wi + wo).normalize();
    let theta_h = h.z.clamp(-1.0, 1.0).acos();
    let phi_h = h.y.atan2(h.x).rem_euclid(TAU);
    let (s, c) = (-phi_h).sin_cos();
    let v = DVec3::new(wi.x * c - wi.y * s, wi.x * s + wi.y * c, wi.z);
    let (s, c) = (-theta_h).sin_cos();
    let d = DVec3::new(v.x * c + v.z * s, v.y, -v.x * s + v.z * c);
    HalfDiff {
        theta_h,
        phi_h,
        theta_d: d.z.clamp(-1.0, 1.0).acos(),
        phi_d: d.y.atan2(d.x).rem_euclid(TAU),
    }
}

/// Difference of two azimuths, the short way round.
fn azimuth_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

/// `from_dirs` reads the turns' sines and cosines off `h` instead of taking them of the angles:
/// the same angles up to rounding. Tolerance: each component of `d` is a sum of a few products
/// of unit-sized numbers, exact to ~1e-15 in both forms; `acos` and `atan2` turn that into an
/// angle error of at most 1e-15 / sin(theta) and 1e-15 / |d_xy| = 1e-15 / sin(theta_d). The
/// pairs below keep theta_d and theta_h above 1e-3 (the rare pair closer is skipped), so the
/// angles agree to 1e-12 rad: 3e-11 of a node step at 180 phi_d nodes, a change of the
/// interpolated value far below the f32 rounding of the table (6e-8 relative).
#[test]
fn half_diff_matches_the_rotations_of_the_definition() {
    let mut next = uniforms(777);
    let mut compared = 0;
    for _ in 0..5000 {
        let wi = dir(next() * 1.55, next() * TAU);
        let wo = dir(next() * 1.55, next() * TAU);
        let want = half_diff_by_rotations(wi, wo);
        if want.theta_d < 1e-3 || want.theta_h < 1e-3 {
            continue;
        }
        let got = HalfDiff::from_dirs(wi, wo).unwrap();
        assert!(
            (got.theta_h - want.theta_h).abs() < 1e-12,
            "{got:?} {want:?}"
        );
        assert!(
            (got.theta_d - want.theta_d).abs() < 1e-12,
            "{got:?} {want:?}"
        );
        assert!(
            azimuth_gap(got.phi_h, want.phi_h) < 1e-12,
            "{got:?} {want:?}"
        );
        assert!(
            azimuth_gap(got.phi_d, want.phi_d) < 1e-12,
            "{got:?} {want:?}"
        );
        compared += 1;
    }
    assert!(compared > 4900, "only {compared} pairs compared");
    // The mirror pair: h on the pole (its x and y exactly 0; h.z within an ulp of 1, whose acos
    // is up to sqrt(2 × 1.1e-16) = 1.5e-8), phi_h = 0, d = wi.
    let wi = dir(0.7, 2.0);
    let a = HalfDiff::from_dirs(wi, DVec3::new(-wi.x, -wi.y, wi.z)).unwrap();
    assert!(a.theta_h < 2e-8 && a.phi_h == 0.0, "{a:?}");
    assert!(
        (a.theta_d - 0.7).abs() < 1e-12 && (a.phi_d - 2.0).abs() < 1e-12,
        "{a:?}"
    );
}

/// The interpolation of a table (isotropic and anisotropic, with cells without data) against
/// its definition written out: the angles by the rotations, the 16 corners of the stencil by
/// `cell_index` with the product of the four axes' weights, the corners with data averaged.
/// Tolerance: the angles agree to 1e-12 rad (test above), so each axis' weight to 1e-12 × the
/// nodes per radian (< 60 here): the corners' weights agree to 4 × 6e-11 = 2.4e-10 each, and
/// the mean of values below 1 over corners of total weight `wsum` to 16 × 2.4e-10 / wsum ≈
/// 4e-9 / wsum.
#[test]
fn table_interpolation_matches_its_definition() {
    let mut next = uniforms(4242);
    for res in [
        Resolution::isotropic(9, 7, 12),
        Resolution::anisotropic(9, 7, 12, 6),
    ] {
        let values: Vec<f32> = (0..res.cell_count() * 3)
            .map(|k| {
                if k % 3 == 0 && next() < 0.1 {
                    f32::NAN
                } else {
                    next() as f32
                }
            })
            .collect();
        // A NaN in a cell's first channel marks it without data; fill the others too.
        let values: Vec<f32> = values
            .chunks(3)
            .flat_map(|c| {
                if c[0].is_nan() {
                    [f32::NAN; 3]
                } else {
                    [c[0], c[1], c[2]]
                }
            })
            .collect();
        let table =
            BrdfTable::from_values(res, Channels::Rgb, Provenance::default(), values.clone())
                .unwrap();
        let mut compared = 0;
        for _ in 0..2000 {
            let wi = dir(next() * 1.55, next() * TAU);
            let wo = dir(next() * 1.55, next() * TAU);
            let a = half_diff_by_rotations(wi, wo);
            if a.theta_d < 1e-3 || a.theta_h < 1e-3 {
                continue;
            }
            let axis = |x: f64, n: usize, periodic: bool| {
                if periodic {
                    let x = x.rem_euclid(n as f64);
                    let i = (x.floor() as usize).min(n - 1);
                    (i, (i + 1) % n, x - i as f64)
                } else if x >= (n - 1) as f64 {
                    (n - 1, n - 1, 0.0)
                } else {
                    (x.floor() as usize, x.floor() as usize + 1, x - x.floor())
                }
            };
            let s = [
                if res.is_isotropic() {
                    (0, 0, 0.0)
                } else {
                    axis(a.phi_h / TAU * res.phi_h as f64, res.phi_h, true)
                },
                axis(
                    (a.theta_h / FRAC_PI_2).sqrt() * res.theta_h as f64,
                    res.theta_h,
                    false,
                ),
                axis(
                    a.theta_d / FRAC_PI_2 * res.theta_d as f64,
                    res.theta_d,
                    false,
                ),
                axis(a.phi_d / TAU * res.phi_d as f64, res.phi_d, true),
            ];
            let (mut want, mut wsum) = ([0.0; 3], 0.0);
            for corner in 0..16 {
                let mut w = 1.0;
                let mut idx = [0; 4];
                for (k, (i0, i1, t)) in s.iter().enumerate() {
                    let upper = corner & (8 >> k) != 0;
                    idx[k] = if upper { *i1 } else { *i0 };
                    w *= if upper { *t } else { 1.0 - t };
                }
                let cell = res.cell_index(idx[0], idx[1], idx[2], idx[3]);
                if w == 0.0 || values[cell * 3].is_nan() {
                    continue;
                }
                wsum += w;
                for (o, v) in want.iter_mut().zip(&values[cell * 3..cell * 3 + 3]) {
                    *o += w * f64::from(*v);
                }
            }
            let mut got = [0.0; 3];
            table.eval_channels(wo, wi, &mut got);
            if wsum == 0.0 {
                assert_eq!(got, [0.0; 3]);
                continue;
            }
            for (g, w) in got.iter().zip(want) {
                let w = w / wsum;
                assert!(
                    (g - w).abs() < 4e-9 / wsum,
                    "{} at {a:?}: {g} vs {w}",
                    res.describe()
                );
            }
            compared += 1;
        }
        assert!(compared > 1900, "only {compared} pairs compared");
    }
}

#[test]
fn half_diff_round_trip_and_reciprocity() {
    let mut next = uniforms(12345);
    for _ in 0..1000 {
        let wi = dir(next() * 1.5, next() * TAU);
        let wo = dir(next() * 1.5, next() * TAU);
        let a = HalfDiff::from_dirs(wi, wo).unwrap();
        let (wi2, wo2) = a.to_dirs();
        assert!((wi - wi2).length() < 1e-12 && (wo - wo2).length() < 1e-12);
        let b = HalfDiff::from_dirs(wo, wi).unwrap();
        assert!((a.theta_h - b.theta_h).abs() < 1e-12 && (a.theta_d - b.theta_d).abs() < 1e-12);
        let dphi = (b.phi_d - a.phi_d).rem_euclid(TAU);
        assert!((dphi - PI).abs() < 1e-9, "phi_d does not turn by π: {dphi}");
    }
}

#[test]
fn cell_indices_and_reciprocal_cells() {
    let r = Resolution::anisotropic(5, 4, 6, 3);
    for node in 0..r.cell_count() {
        let [ph, th, td, pd] = r.cell_indices(node);
        assert_eq!(r.cell_index(ph, th, td, pd), node);
        let rec = r.reciprocal_cell(node);
        assert_eq!(r.reciprocal_cell(rec), node);
        let (a, b) = (r.cell_angles(node), r.cell_angles(rec));
        assert!(((b.phi_d - a.phi_d).rem_euclid(TAU) - PI).abs() < 1e-12);
    }
    assert!(Resolution::isotropic(4, 4, 5).validate().is_err());
    assert!(Resolution::isotropic(1, 4, 4).validate().is_err());
}

#[test]
fn stencil_hits_nodes_exactly() {
    let r = Resolution::anisotropic(9, 7, 8, 4);
    for node in 0..r.cell_count() {
        let s = r.stencil(&r.cell_angles(node));
        let [ph, th, td, pd] = r.cell_indices(node);
        for (k, want) in [ph, th, td, pd].into_iter().enumerate() {
            let (i0, i1, t) = s[k];
            let got = if t < 0.5 { i0 } else { i1 };
            assert!(!(1e-9..=1.0 - 1e-9).contains(&t), "weight {t}");
            assert_eq!(got, want, "axis {k} of node {node}");
        }
    }
}

/// The mirror image of a node is the pair reflected through the plane of incidence (y → −y:
/// the cosines and the angle between the directions kept, the azimuths negated); a node's
/// representative is the lowest of its class `{node, reciprocal, mirror, mirror of the
/// reciprocal}`, the same for every member, and an isotropic grid of phi_d = 4m nodes has
/// m + 1 representatives per (theta_h, theta_d) row (phi_d nodes 0..=m), an anisotropic one
/// half its cells (reciprocity only).
#[test]
fn mirror_cells_and_symmetry_classes() {
    let r = Resolution::isotropic(5, 4, 16);
    let mut representatives = 0;
    for node in 0..r.cell_count() {
        let m = r.mirror_cell(node);
        assert_eq!(r.mirror_cell(m), node);
        let (wi, wo) = r.cell_angles(node).to_dirs();
        let (mi, mo) = r.cell_angles(m).to_dirs();
        for (a, b) in [(wi, mi), (wo, mo)] {
            assert!((a.x - b.x).abs() < 1e-12 && (a.y + b.y).abs() < 1e-12);
            assert!((a.z - b.z).abs() < 1e-12);
        }
        let rep = r.representative_cell(node, true);
        assert!(rep <= node);
        for member in [node, r.reciprocal_cell(node), m, r.reciprocal_cell(m)] {
            assert_eq!(r.representative_cell(member, true), rep);
        }
        assert_eq!(
            r.representative_cell(node, false),
            node.min(r.reciprocal_cell(node))
        );
        representatives += usize::from(rep == node);
    }
    assert_eq!(representatives, 5 * 4 * (16 / 4 + 1));
    let a = Resolution::anisotropic(3, 3, 8, 4);
    let halves = (0..a.cell_count())
        .filter(|&n| a.representative_cell(n, true) == n)
        .count();
    assert_eq!(halves, a.cell_count() / 2);
}
