//! Rusinkiewicz half/difference coordinates: round trips, reciprocity, cells and the
//! interpolation stencil.

use gonio_brdf::table::coords::*;
use std::f64::consts::{PI, TAU};

#[test]
fn half_diff_round_trip_and_reciprocity() {
    let mut rng = 12345u64;
    let mut next = || {
        rng = rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
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
