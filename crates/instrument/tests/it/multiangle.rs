//! The multi-angle spectrophotometer on a measured paint: the Cornell Cayman metallic
//! (crates/brdf/tests/data/cayman.astm, Cornell University Program of Computer Graphics
//! reflectance data), imported as `gonio brdf import` imports it.
//!
//! For each geometry of ASTM E2194 and the 45° ones of E2539, the in-plane measured geometry
//! nearest to it (the Cornell gonioreflectometer measured at illumination angles every 10°, so
//! 40° or 50° stands for 45°). The instrument, given that geometry as illumination and
//! aspecular angles, must read what the table holds at the measurement's own direction vectors
//! (independently built from the file's angles): the same CIELAB to rounding, through another
//! path to colour (`Colorimetry::of_reflectance`, 1 nm weighting of the linearly interpolated
//! spectrum, against the instrument's band weights). And it must agree with the measured
//! spectrum there within the import's residual: the import's acceptance bound is a median
//! CIEDE2000 under 2 over all 1439 geometries (`crates/brdf/tests/it/cayman_colour.rs`), and
//! each of these geometries must be within it (measured: 0.02 to 0.49).

mod slow {
    use glam::DVec3;
    use gonio_brdf::formats::astm;
    use gonio_brdf::formats::scattered::Sample;
    use gonio_color::{Colorimetry, Illuminant, Lab, Observer, Spectrum, ciede2000};
    use gonio_instrument::multiangle::{self, E2194, E2539, Geometry, Settings};
    use std::f64::consts::PI;
    use std::path::Path;

    /// An in-plane measured geometry: its direction vectors turned so that the light is on the
    /// +x side and put exactly in the plane (the file's azimuths, 0 or 3.141593 to six decimals,
    /// leave a y component below 1e-6), with its illumination and aspecular angles in degrees.
    struct InPlane<'a> {
        sample: &'a Sample,
        wi: DVec3,
        wo: DVec3,
        illumination_deg: f64,
        aspecular_deg: f64,
    }

    fn in_plane(s: &Sample) -> Option<InPlane<'_>> {
        if s.wi.y.abs() > 1e-5 || s.wo.y.abs() > 1e-5 {
            return None;
        }
        let flip = if s.wi.x < 0.0 { -1.0 } else { 1.0 };
        let wi = DVec3::new(flip * s.wi.x, 0.0, s.wi.z).normalize();
        let wo = DVec3::new(flip * s.wo.x, 0.0, s.wo.z).normalize();
        let theta_i = wi.x.atan2(wi.z).to_degrees();
        let theta_v = wo.x.atan2(wo.z).to_degrees();
        Some(InPlane {
            sample: s,
            wi,
            wo,
            illumination_deg: theta_i,
            aspecular_deg: theta_v + theta_i,
        })
    }

    fn lab(wavelengths_nm: &[f64], brdf: &[f64], settings: &Settings) -> Lab {
        let r = Spectrum::new(
            wavelengths_nm.to_vec(),
            brdf.iter().map(|f| PI * f).collect(),
        )
        .unwrap();
        Colorimetry::of_reflectance(&r, settings.illuminant, settings.observer).lab
    }

    #[test]
    fn cayman_reads_as_measured_at_the_nearest_geometries() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../brdf/tests/data/cayman.astm");
        let file = astm::read(&path).unwrap();
        let (table, _) = astm::import(&path, astm::default_resolution()).unwrap();
        let settings = Settings::default();
        assert_eq!(settings.illuminant, Illuminant::D65);
        assert_eq!(settings.observer, Observer::Cie1964TenDegree);
        let wl = &file.wavelengths_nm;
        let in_plane: Vec<InPlane> = file.samples.iter().filter_map(in_plane).collect();
        assert!(in_plane.len() > 120, "{}", in_plane.len());
        let mut targets: Vec<Geometry> = E2194.to_vec();
        targets.extend(
            E2539
                .iter()
                .filter(|g| g.illumination_deg == 45.0 && !E2194.contains(g)),
        );
        let mut residuals = Vec::new();
        for target in targets {
            let distance = |g: &InPlane| {
                (g.illumination_deg - target.illumination_deg)
                    .hypot(g.aspecular_deg - target.aspecular_deg)
            };
            let nearest = in_plane
                .iter()
                .min_by(|a, b| distance(a).total_cmp(&distance(b)))
                .unwrap();
            let (sample, sample_wi, sample_wo) = (nearest.sample, nearest.wi, nearest.wo);
            let (ti, asp) = (nearest.illumination_deg, nearest.aspecular_deg);
            let measured_geometry = Geometry::new(ti, asp);
            let reading = multiangle::read_table(&table, &[measured_geometry], &settings).unwrap();
            let got = reading.geometries[0].lab;
            // The instrument's directions are the measurement's, and it reads what the table
            // holds there.
            let (wi, wo) = measured_geometry.directions();
            assert!(
                (wi - sample_wi).length() < 1e-12 && (wo - sample_wo).length() < 1e-12,
                "{target}: {wi} {wo} vs {sample_wi} {sample_wo}"
            );
            let mut f = vec![0.0; wl.len()];
            table.eval_channels(sample_wo, sample_wi, &mut f);
            let direct = lab(wl, &f, &settings);
            let same = ciede2000(got, direct);
            assert!(same < 1e-6, "{target} at {measured_geometry}: {same}");
            let measured = lab(wl, &sample.values, &settings);
            let residual = ciede2000(got, measured);
            println!(
                "{target}: measured at {ti:.1}as{asp:.1} (detector {:.1}°): L* {:.2} (measured \
                 {:.2}), CIEDE2000 {residual:.2}",
                measured_geometry.viewing_deg(),
                got.l,
                measured.l
            );
            residuals.push(residual);
        }
        assert!(residuals.iter().all(|&r| r < 2.0), "{residuals:?}");
        // A metallic: much lighter near the specular direction than far from it.
        let e2194 = multiangle::read_table(&table, &E2194, &settings).unwrap();
        let fi = e2194.flop_index().unwrap();
        println!("Cayman flop index {fi:.2}");
        assert!(fi > 5.0, "flop index {fi}");
    }
}
