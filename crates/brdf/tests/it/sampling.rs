//! Sampling helpers: orthonormal frames, the area-preserving concentric disk, mirror reflection.

use glam::{DVec2, DVec3};
use gonio_brdf::sampling::*;

#[test]
fn frame_is_orthonormal_for_any_axis() {
    for n in [
        DVec3::Z,
        -DVec3::Z,
        DVec3::X,
        DVec3::new(0.3, -0.4, 0.866).normalize(),
        DVec3::new(1e-9, 0.0, -1.0).normalize(),
    ] {
        let f = Frame::from_z(n);
        for (a, b) in [(f.s, f.t), (f.s, f.n), (f.t, f.n)] {
            assert!(a.dot(b).abs() < 1e-12);
        }
        for v in [f.s, f.t, f.n] {
            assert!((v.length() - 1.0).abs() < 1e-12);
        }
        let v = DVec3::new(0.2, -0.7, 0.1);
        assert!((f.to_world(f.to_local(v)) - v).length() < 1e-12);
        assert!(f.s.cross(f.t).dot(f.n) > 0.0, "right-handed");
    }
}

/// The disk map keeps areas: the fraction of points inside radius r is r².
#[test]
fn concentric_disk_preserves_area() {
    let n = 400;
    let mut inside = 0usize;
    for i in 0..n {
        for j in 0..n {
            let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let d = concentric_disk(u);
            assert!(d.length() <= 1.0 + 1e-12);
            inside += usize::from(d.length() < 0.5);
        }
    }
    let frac = inside as f64 / (n * n) as f64;
    assert!((frac - 0.25).abs() < 5e-3, "{frac}");
}

#[test]
fn reflection_keeps_angle_to_normal() {
    let n = DVec3::new(0.1, 0.2, 0.97).normalize();
    let w = DVec3::new(-0.5, 0.1, 0.8).normalize();
    let r = reflect(w, n);
    assert!((r.length() - 1.0).abs() < 1e-12);
    assert!((r.dot(n) - w.dot(n)).abs() < 1e-12);
    assert!(((w + r).normalize() - n).length() < 1e-12);
}

/// `concentric_square` inverts `concentric_disk` in all eight octants of the disk, at its centre
/// and on its rim. Tolerance: one `atan2` and a division by π/4 lose a few ulps of the unit
/// square; 1e-12 leaves a factor 100 above them.
#[test]
fn concentric_square_inverts_the_disk() {
    for i in 0..=40 {
        for j in 0..=40 {
            let u = DVec2::new(i as f64 / 40.0, j as f64 / 40.0);
            let back = concentric_square(concentric_disk(u));
            assert!((back - u).length() < 1e-12, "{u} -> {back}");
        }
    }
}
