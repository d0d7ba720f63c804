//! What the lab shows of a target (`lab_target`): a formulation's own readings written as a CSV
//! target are ΔE00 0 from it, a CSV's geometries outside the standard are listed, not dropped
//! silently, and (slow) the Cornell Cayman measurement read as the lab reads it agrees with
//! `gonio coating match`'s target and, along its in-plane BRDF, with the measurement itself.

use crate::matching::example;
use gonio_formulation::lab_target::{comparison_json, read_lab_target};
use gonio_instrument::coating_readings::{Readings, ReadingsRequest, readings};
use gonio_instrument::multiangle::{Geometry, Standard};
use gonio_io::Cancel;

fn quick(standard: Standard) -> ReadingsRequest {
    ReadingsRequest {
        standard,
        walks: 64,
        brdf_walks: 4,
        gloss_walks: 2,
        albedo_samples: 256,
        ..ReadingsRequest::default()
    }
}

/// The reading's CIELAB as a target CSV (`{}` prints the shortest text that reads back to the
/// same f64), and its reflectance factors as a spectral one.
fn write_targets(r: &Readings, dir: &std::path::Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let m = &r.brdf.multiangle;
    let mut lab = String::from("geometry,L,a,b\n");
    let mut spectral = String::from("geometry");
    for w in &m.wavelengths_nm {
        spectral.push_str(&format!(",R_{w}nm"));
    }
    spectral.push('\n');
    for g in &m.geometries {
        lab.push_str(&format!(
            "{},{},{},{}\n",
            g.geometry, g.lab.l, g.lab.a, g.lab.b
        ));
        spectral.push_str(&g.geometry.to_string());
        for v in &g.reflectance_factor {
            spectral.push_str(&format!(",{v}"));
        }
        spectral.push('\n');
    }
    let (a, b) = (dir.join("lab.csv"), dir.join("spectral.csv"));
    std::fs::write(&a, lab).unwrap();
    std::fs::write(&b, spectral).unwrap();
    (a, b)
}

/// A formulation against its own reading as the target: ΔE00 0 at every geometry (to 1e-9:
/// the CSV's numbers read back exactly, and the spectral CSV's colour is computed as the
/// reading's), at E2194 and E2539; the target's swatches and flop index are the reading's.
#[test]
fn a_formulation_is_zero_from_its_own_reading() {
    let silver = example("silver_metallic.toml");
    let dir = tempfile::tempdir().unwrap();
    for standard in [Standard::E2194, Standard::E2539] {
        let r = readings(&silver, &quick(standard), &Cancel::default()).unwrap();
        for path in [
            write_targets(&r, dir.path()).0,
            write_targets(&r, dir.path()).1,
        ] {
            let t = read_lab_target(&path, standard, 45.0, &Cancel::default()).unwrap();
            assert!(t.left_out.is_empty() && t.brdf.is_none());
            let de = t.de00(&r).unwrap();
            assert_eq!(de.len(), standard.geometries().len());
            assert!(de.iter().all(|(_, d)| *d < 1e-9), "{standard:?}: {de:?}");
            let flop = (t.flop_index.unwrap() - r.brdf.flop_index.unwrap()).abs();
            assert!(flop < 1e-9, "{flop}");
            for (a, b) in t.swatches.iter().zip(&r.brdf.swatches) {
                assert_eq!(a.hex, b.hex);
            }
            let json = comparison_json(&de);
            assert!(json["max_de00"].as_f64().unwrap() < 1e-9);
        }
    }
}

/// A CSV with a geometry outside the standard keeps the standard's and lists the other; one with
/// none of the standard's is refused, naming the file; a reading at another standard that lacks
/// a target's geometry is refused by the comparison.
#[test]
fn csv_geometries_outside_the_standard_are_listed() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    std::fs::write(
        &path,
        "geometry,L,a,b\n45as15,90,1,2\n15as15,80,1,2\n45as110,20,1,2\n",
    )
    .unwrap();
    let none = Cancel::default();
    let t = read_lab_target(&path, Standard::E2194, 45.0, &none).unwrap();
    assert_eq!(
        t.target.geometries(),
        vec![Geometry::new(45.0, 15.0), Geometry::new(45.0, 110.0)]
    );
    assert_eq!(t.left_out, vec![Geometry::new(15.0, 15.0)]);
    assert_eq!(t.flop_index, None);
    assert_eq!(t.to_json()["left_out"][0], "15as15");
    let t = read_lab_target(&path, Standard::E2539, 45.0, &none).unwrap();
    assert!(t.left_out.is_empty());
    let red = example("red_solid.toml");
    let r = readings(&red, &quick(Standard::E2194), &none).unwrap();
    let e = t.de00(&r).unwrap_err().to_string();
    assert!(e.contains("15as15"), "{e}");
    std::fs::write(&path, "geometry,L,a,b\n15as80,80,1,2\n").unwrap();
    let e = read_lab_target(&path, Standard::E2194, 45.0, &none)
        .unwrap_err()
        .to_string();
    assert!(e.contains("t.csv") && e.contains("15as80"), "{e}");
}

pub(crate) mod slow {
    use super::*;
    use gonio_brdf::formats::astm;
    use gonio_color::{Illuminant, Lab, Observer, SpectralToXyz, ciede2000, white};
    use gonio_formulation::target::read_target;
    use std::path::Path;

    /// The Cornell Cayman metallic (crates/brdf/tests/data/cayman.astm, Cornell University
    /// Program of Computer Graphics reflectance data) read as the lab reads an uploaded target:
    /// - its multi-angle colour is `gonio coating match`'s target (`read_target`, the same
    ///   import and the same reading: equal to 1e-12);
    /// - its in-plane luminance BRDF at 40° (a measured illumination angle), interpolated
    ///   linearly between the views, against the measured in-plane samples at 40°: the grey
    ///   ΔE00 of their L* within the import's acceptance bound, a median of 2 over the
    ///   geometries (crates/brdf/tests/it/cayman_colour.rs), the bound the import promises;
    /// - the L* curve through its E2194 readings.
    #[test]
    fn cayman_reads_as_the_match_target_and_as_measured() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../brdf/tests/data/cayman.astm");
        let t = read_lab_target(&path, Standard::E2194, 40.0, &Cancel::default()).unwrap();
        let matched = read_target(&path, Standard::E2194.geometries()).unwrap();
        for ((g, a), (h, b)) in t.target.colours.iter().zip(&matched.colours) {
            assert_eq!(g, h);
            assert!(ciede2000(*a, *b) < 1e-12, "{g}");
        }
        let brdf = t.brdf.as_ref().unwrap();
        let curve = &brdf.lightness;
        for g in &brdf.multiangle.geometries {
            let k = curve
                .aspecular_deg
                .iter()
                .position(|&a| a == g.geometry.aspecular_deg)
                .unwrap();
            assert_eq!(curve.lightness[k], g.lab.l);
        }
        let file = astm::read(&path).unwrap();
        let to_xyz = SpectralToXyz::new(
            &file.wavelengths_nm,
            Illuminant::D65,
            Observer::Cie1964TenDegree,
        )
        .unwrap();
        let reference = white(Illuminant::D65, Observer::Cie1964TenDegree);
        let lightness = |y: f64| {
            gonio_color::Xyz::new(reference.x * y / 100.0, y, reference.z * y / 100.0)
                .to_lab(reference)
                .l
        };
        let inplane = &brdf.inplane;
        let mut residuals = Vec::new();
        for s in &file.samples {
            if s.wi.y.abs() > 1e-5 || s.wo.y.abs() > 1e-5 {
                continue;
            }
            let flip = if s.wi.x < 0.0 { -1.0 } else { 1.0 };
            let theta_i = (flip * s.wi.x).atan2(s.wi.z).to_degrees();
            // The scattering angle, positive on the specular side (away from the light).
            let scatter = -(flip * s.wo.x).atan2(s.wo.z).to_degrees();
            if (theta_i - 40.0).abs() > 0.5 || scatter.abs() > 85.0 {
                continue;
            }
            let k = inplane
                .scatter_deg
                .partition_point(|&v| v <= scatter)
                .clamp(1, inplane.scatter_deg.len() - 1);
            let (x0, x1) = (inplane.scatter_deg[k - 1], inplane.scatter_deg[k]);
            let (f0, f1) = (inplane.brdf_per_sr[k - 1], inplane.brdf_per_sr[k]);
            let f = f0 + (f1 - f0) * (scatter - x0) / (x1 - x0);
            let measured: Vec<f64> = s.values.iter().map(|v| std::f64::consts::PI * v).collect();
            let y_measured = to_xyz.xyz(&measured).unwrap().y;
            let y_read = 100.0 * std::f64::consts::PI * f;
            let grey = |l| Lab { l, a: 0.0, b: 0.0 };
            residuals.push(ciede2000(
                grey(lightness(y_read)),
                grey(lightness(y_measured)),
            ));
        }
        residuals.sort_by(f64::total_cmp);
        let median = residuals[residuals.len() / 2];
        eprintln!(
            "Cayman in-plane at 40°: {} measured views, grey ΔE00 median {median:.2}, max {:.2}",
            residuals.len(),
            residuals.last().unwrap()
        );
        assert!(residuals.len() > 10, "{}", residuals.len());
        assert!(median < 2.0, "{residuals:?}");
    }
}
