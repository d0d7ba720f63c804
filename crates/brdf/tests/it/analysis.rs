//! Table analysis: albedo by quadrature against closed forms (Lambert, a narrow lobe) and the
//! reciprocity error and its enforcement.

use gonio_brdf::table::{Channels, Resolution, TableBuilder};

/// Normalised Phong lobe about the mirror direction, `(n + 2)/(2π) cos^n(alpha)`: its albedo
/// at normal incidence is exactly 1 (∫ cos^(n+1) dω = 2π/(n+2)).
fn phong_table(n: f64, res: Resolution) -> gonio_brdf::table::BrdfTable {
    let mut b = TableBuilder::new(res, Channels::Mono).unwrap();
    b.fill(|c, out| {
        let mirror = glam::DVec3::new(-c.wi.x, -c.wi.y, c.wi.z);
        out[0] = (n + 2.0) / std::f64::consts::TAU * mirror.dot(c.wo).max(0.0).powf(n);
    });
    b.build().unwrap()
}

#[test]
fn lambert_albedo_is_rho() {
    let mut b = TableBuilder::new(Resolution::isotropic(16, 16, 32), Channels::Rgb).unwrap();
    b.fill(|_, out| {
        out.copy_from_slice(&[0.8 / std::f64::consts::PI, 0.5 / std::f64::consts::PI, 0.1])
    });
    let t = b.build().unwrap();
    for theta in [0.0f64, 30.0, 60.0, 80.0] {
        let a = t.albedo(theta.to_radians(), 0.3);
        assert!((a[0] - 0.8).abs() < 2e-3, "{theta}: {a:?}");
        assert!((a[1] - 0.5).abs() < 2e-3, "{theta}: {a:?}");
        assert!(
            (a[2] - 0.1 * std::f64::consts::PI).abs() < 2e-3,
            "{theta}: {a:?}"
        );
    }
}

/// A lobe about 1.4° wide (cos^5000) at normal incidence: the square-root theta_h spacing
/// must resolve it, so that its albedo comes out as 1.
#[test]
fn narrow_lobe_albedo_is_one() {
    let t = phong_table(5000.0, Resolution::isotropic(90, 8, 4));
    let a = t.albedo(0.0, 0.0)[0];
    assert!((a - 1.0).abs() < 0.02, "albedo {a}");
}

#[test]
fn reciprocity_error_and_enforcement() {
    let res = Resolution::isotropic(8, 8, 16);
    let mut b = TableBuilder::new(res, Channels::Mono).unwrap();
    b.fill(|c, out| out[0] = 1.0 + c.wi.z);
    let mut t = b.build().unwrap();
    assert!(t.reciprocity_error() > 0.01);
    t.enforce_reciprocity();
    assert!(t.reciprocity_error() < 1e-7);
    let mut sym = TableBuilder::new(res, Channels::Mono).unwrap();
    sym.fill(|c, out| out[0] = 1.0 + c.wi.z * c.wo.z);
    assert!(sym.build().unwrap().reciprocity_error() < 1e-6);
    // Light only from one side of each pair: every pair is one-sided, the error is 1.
    let mut one = TableBuilder::new(res, Channels::Mono).unwrap();
    one.fill(|c, out| out[0] = if c.angles.phi_d < 3.1 { 1.0 } else { 0.0 });
    assert!((one.build().unwrap().reciprocity_error() - 1.0).abs() < 1e-12);
}
