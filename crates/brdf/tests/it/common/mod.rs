//! The hold-out split shared by the tests on the Cornell Cayman measurement
//! (tests/data/cayman.astm, Cornell University Program of Computer Graphics reflectance data).
// Each test binary uses its own subset of these helpers.
#![allow(dead_code)]

use gonio_brdf::formats::astm::{self, AstmFile};
use gonio_brdf::formats::scattered::{Sample, ScatteredFit};
use gonio_brdf::table::{BrdfTable, Channels};
use std::path::{Path, PathBuf};

/// The Cayman file, its every tenth geometry held out, and the fit of the others with its
/// spectral table at the import resolution.
pub struct HeldOut {
    pub file: AstmFile,
    pub held: Vec<Sample>,
    pub fit: ScatteredFit,
    pub table: BrdfTable,
}

/// Path of tests/data/cayman.astm.
pub fn cayman_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cayman.astm")
}

/// The fit of `samples` and its spectral table at the import resolution.
fn fit_and_table(file: &AstmFile, samples: &[Sample]) -> (ScatteredFit, BrdfTable) {
    let fit = ScatteredFit::new(samples, None).unwrap();
    let channels = Channels::Spectral {
        wavelengths_nm: file.wavelengths_nm.clone(),
    };
    let table = fit
        .to_table(astm::default_resolution(), channels, Default::default())
        .unwrap();
    (fit, table)
}

/// The Cayman file and the spectral table of the fit of all its geometries.
pub fn cayman_table() -> (AstmFile, BrdfTable) {
    let file = astm::read(&cayman_path()).unwrap();
    let (_, table) = fit_and_table(&file, &file.samples);
    (file, table)
}

/// Fit every geometry of the Cayman file but each tenth, which is held out.
pub fn cayman_held_out() -> HeldOut {
    let file = astm::read(&cayman_path()).unwrap();
    let (mut held, mut train) = (Vec::new(), Vec::new());
    for (i, sample) in file.samples.iter().enumerate() {
        let part = if i % 10 == 0 { &mut held } else { &mut train };
        part.push(sample.clone());
    }
    let (fit, table) = fit_and_table(&file, &train);
    HeldOut {
        file,
        held,
        fit,
        table,
    }
}

/// Path of tests/data/krylon_blue.astm.
pub fn krylon_blue_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/krylon_blue.astm")
}

/// An ASTM file and the spectral table of the fit of all its geometries.
pub fn astm_table(path: &Path) -> (AstmFile, BrdfTable) {
    let file = astm::read(path).unwrap();
    let (_, table) = fit_and_table(&file, &file.samples);
    (file, table)
}

/// An oracle (an independent implementation run by a test: Mitsuba 3, Radiance) is missing:
/// say why and skip the check, or fail when `GONIO_REQUIRE_ORACLES=1` (set by `.ci/run`)
/// demands the oracle.
pub fn oracle_missing(oracle: &str, why: &str) {
    assert!(
        std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
        "GONIO_REQUIRE_ORACLES=1 but {why}"
    );
    eprintln!("skipping the {oracle} check: {why}");
}
