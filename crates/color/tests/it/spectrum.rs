//! Spectra: linear interpolation held at the ends, the uniform-grid fast path against the binary
//! search, exact resampling of a linear spectrum, bad samples and CSV errors named.

use gonio_color::spectrum::*;
use std::path::Path;

#[test]
fn interpolates_linearly_and_holds_the_ends() {
    let s = Spectrum::new(vec![400.0, 500.0, 700.0], vec![1.0, 3.0, 2.0]).unwrap();
    assert_eq!(s.uniform_step_nm(), None);
    assert_eq!(s.value_at(450.0), 2.0);
    assert_eq!(s.value_at(600.0), 2.5);
    assert_eq!(s.value_at(500.0), 3.0);
    assert_eq!(s.value_at(300.0), 1.0);
    assert_eq!(s.value_at(800.0), 2.0);
}

#[test]
fn uniform_fast_path_matches_the_binary_search() {
    let values: Vec<f64> = (0..81).map(|i| ((i * 37) % 11) as f64 * 0.1).collect();
    let uniform = Spectrum::uniform(380.0, 5.0, values.clone()).unwrap();
    assert_eq!(uniform.uniform_step_nm(), Some(5.0));
    // The same samples with one wavelength nudged so that the grid is irregular.
    let mut wavelengths = uniform.wavelengths_nm().to_vec();
    wavelengths[80] += 1e-6;
    let irregular = Spectrum::new(wavelengths, values).unwrap();
    assert_eq!(irregular.uniform_step_nm(), None);
    for k in 0..4000 {
        let w = 370.0 + k as f64 * 0.1;
        let (a, b) = (uniform.value_at(w), irregular.value_at(w));
        assert!((a - b).abs() < 1e-6, "at {w} nm: {a} vs {b}");
    }
}

#[test]
fn resampling_a_linear_spectrum_is_exact() {
    let s = Spectrum::uniform(
        400.0,
        10.0,
        (0..31).map(|i| 0.5 + 0.01 * i as f64).collect(),
    )
    .unwrap();
    let r = s.resample_uniform(400.0, 1.0, 301).unwrap();
    for (w, v) in r.wavelengths_nm().iter().zip(r.values()) {
        assert!((v - (0.5 + 0.001 * (w - 400.0))).abs() < 1e-12);
    }
    let back = r.resample(s.wavelengths_nm()).unwrap();
    for (a, b) in back.values().iter().zip(s.values()) {
        assert!((a - b).abs() < 1e-12);
    }
}

#[test]
fn rejects_bad_samples() {
    assert!(Spectrum::new(vec![400.0, 500.0], vec![1.0]).is_err());
    assert!(Spectrum::new(vec![400.0], vec![1.0]).is_err());
    assert!(Spectrum::new(vec![500.0, 400.0], vec![1.0, 1.0]).is_err());
    assert!(Spectrum::new(vec![400.0, 500.0], vec![1.0, f64::NAN]).is_err());
}

#[test]
fn csv_errors_name_the_file_and_line() {
    let path = Path::new("paint.csv");
    let ok = Spectrum::parse_csv("wavelength_nm,reflectance\n400,0.1\n\n500, 0.2\n", path);
    assert_eq!(ok.unwrap().values(), &[0.1, 0.2]);
    let cases = [
        ("", "paint.csv, line 1: the file is empty"),
        (
            "wavelength_um,value\n0.4,1\n",
            "paint.csv, line 1: expected the header",
        ),
        (
            "wavelength_nm,value\n400,0.1\n500,abc\n",
            "paint.csv, line 3: column 2: `abc`",
        ),
        (
            "wavelength_nm,value\n400,0.1\n500\n",
            "paint.csv, line 3: expected 2",
        ),
        (
            "wavelength_nm,value\n400,0.1\n390,0.2\n",
            "paint.csv, line 3: wavelength 390",
        ),
        (
            "wavelength_nm,value\n400,0.1\n",
            "paint.csv, line 1: 1 sample(s)",
        ),
    ];
    for (text, expected) in cases {
        let err = Spectrum::parse_csv(text, path).unwrap_err().to_string();
        assert!(
            err.starts_with(expected),
            "{err:?} should start with {expected:?}"
        );
    }
}
