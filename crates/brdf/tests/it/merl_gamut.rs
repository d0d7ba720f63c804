//! Measured paints through a MERL file: Cayman's linear sRGB is outside the sRGB
//! gamut in most cells (Krylon blue's in a third), which MERL readers would take as "not measured"; the export maps those
//! colours into the gamut at constant luminance, and reading the file back keeps no cell lost
//! and the luminance albedo within 1%.
//!
//! The issue asked for 10% per channel; for this paint no in-gamut file can give it: the
//! table's own linear sRGB albedo at 0° is (-0.035, 0.060, 0.089), a negative red. Raising red
//! to 0 at constant luminance must take 0.2126 × 0.035 = 0.0073 of luminance from green and
//! blue, at best 15% of each (at least that much below them); clipping red to 0 instead keeps
//! green and blue but raises the luminance by 17% and shifts the hue. The luminance is what the
//! mapping keeps exactly, cell by cell. Even a paint whose albedo is inside the gamut loses
//! chroma: Krylon blue's linear sRGB albedo at 0° (0.012, 0.076, 0.267) reads back as (0.021,
//! 0.076, 0.241), each of its out-of-gamut cells (deep blue, a negative red) moved toward grey.
//! Data: tests/data/cayman.astm (Cornell University Program of Computer Graphics).

use gonio_brdf::formats::merl;

fn round_trip(path: &std::path::Path) {
    let (_, table) = crate::common::astm_table(path);
    let dir = tempfile::tempdir().unwrap();
    let merl_path = dir.path().join("paint.binary");
    let report = merl::write(table, &merl_path).unwrap();
    let share = report.out_of_gamut as f64 / report.cells as f64;
    println!(
        "{}: {} of {} cells out of the sRGB gamut ({:.0}%)",
        path.display(),
        report.out_of_gamut,
        report.cells,
        100.0 * share
    );
    // The case the mapping exists for: a large share of a saturated paint is out of gamut.
    assert!(share > 0.3, "{report:?}");
    let back = merl::read(&merl_path).unwrap();
    // Every cell above the horizon holds a value: none reads as "not measured".
    let res = back.resolution();
    for cell in 0..res.cell_count() {
        let a = res.cell_angles(cell);
        let (wi, wo) = a.to_dirs();
        if wi.z > 0.01 && wo.z > 0.01 {
            assert!(!back.cell_values(cell)[0].is_nan(), "cell {cell} lost");
        }
    }
    // MERL stores one value for a pair and its swap (the mean of both): the reference is the
    // table made reciprocal the same way, so that what is compared is the gamut mapping (which
    // keeps each cell's luminance exactly) and the resampling onto MERL's grid.
    let mut reciprocal = table.clone();
    reciprocal.enforce_reciprocity();
    let lum = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    for ti in [0.0f64, 30.0, 60.0, 80.0] {
        let t = ti.to_radians();
        let want = reciprocal.to_rgb(&reciprocal.albedo(t, 0.0)).to_array();
        let got = back.albedo(t, 0.0);
        let got = [got[0], got[1], got[2]];
        println!(
            "albedo at {ti}°: reciprocal table (linear sRGB) {:.4} {:.4} {:.4} (Y {:.4}), MERL file {:.4} {:.4} {:.4} (Y {:.4})",
            want[0],
            want[1],
            want[2],
            lum(want),
            got[0],
            got[1],
            got[2],
            lum(got)
        );
        // 1%: the interpolation of the 90 × 90 × 48 table at MERL's 90 × 90 × 180 nodes and
        // back, second order in steps of 1° (theta_d) and 7.5° (phi_d) over lobes tens of
        // degrees wide.
        assert!(
            (lum(got) / lum(want) - 1.0).abs() < 0.01,
            "{ti}°: luminance albedo {} vs {}",
            lum(got),
            lum(want)
        );
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn saturated_paints_survive_a_merl_round_trip() {
        // Cayman: 81% of cells out of gamut, a negative red albedo; Krylon blue: 34%, an albedo
        // inside the gamut.
        for path in [
            crate::common::cayman_path(),
            crate::common::krylon_blue_path(),
        ] {
            round_trip(&path);
        }
    }
}
