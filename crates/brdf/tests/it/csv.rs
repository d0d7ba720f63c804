//! The BRDF CSV format: export and import round trip, headers that explain what is wrong.

use gonio_brdf::formats::csv::*;
use gonio_brdf::table::coords::dir;
use gonio_brdf::table::{Channels, Resolution, TableBuilder};

/// Export on a grid, import as scattered samples: a smooth BRDF comes back within a few
/// per cent.
#[test]
fn export_import_round_trip() {
    let mut b = TableBuilder::new(Resolution::isotropic(24, 24, 24), Channels::Rgb).unwrap();
    b.fill(|c, out| {
        let h = (c.wi + c.wo).normalize();
        let v = 0.1 + 0.5 * (-(1.0 - h.z * h.z) / (h.z * h.z) / 0.2).exp();
        out.copy_from_slice(&[v, 0.8 * v, 0.5 * v]);
    });
    let t = b.build().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("t.csv");
    write(&t, &path, 15.0).unwrap();
    let (channels, samples) = read_samples(&path).unwrap();
    assert_eq!(channels, Channels::Rgb);
    assert_eq!(samples.len(), 6 * 6 * 24);
    let (back, residual) = import(&path, Resolution::isotropic(24, 24, 24)).unwrap();
    assert!(residual.median_relative < 0.03, "{residual:?}");
    let mut a = [0.0; 3];
    let mut z = [0.0; 3];
    let (wi, wo) = (dir(0.5, 0.0), dir(0.6, 2.8));
    t.eval_channels(wo, wi, &mut a);
    back.eval_channels(wo, wi, &mut z);
    assert!((a[0] - z[0]).abs() < 0.05 * a[0], "{a:?} vs {z:?}");
}

#[test]
fn bad_headers_are_explained() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("bad.csv");
    std::fs::write(&path, "theta_i,phi_i,theta_o,phi_o,f\n1,2,3,4,5\n").unwrap();
    assert!(
        read_samples(&path)
            .unwrap_err()
            .to_string()
            .contains("theta_i_deg")
    );
    std::fs::write(&path, "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,x,y\n").unwrap();
    assert!(read_samples(&path).unwrap_err().to_string().contains("'x'"));
    std::fs::write(
        &path,
        "theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,f_per_sr\n1,2,3\n",
    )
    .unwrap();
    assert!(
        read_samples(&path)
            .unwrap_err()
            .to_string()
            .contains("line 2")
    );
}
