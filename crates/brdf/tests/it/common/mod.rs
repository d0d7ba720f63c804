//! The hold-out split shared by the tests on the Cornell Cayman measurement
//! (tests/data/cayman.astm, Cornell University Program of Computer Graphics reflectance data).
// Each test binary uses its own subset of these helpers.
#![allow(dead_code)]

use gonio_brdf::formats::astm::{self, AstmFile};
use gonio_brdf::formats::scattered::{Sample, ScatteredFit};
use gonio_brdf::table::{BrdfTable, Channels};
use std::path::{Path, PathBuf};
use std::sync::LazyLock;

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
pub fn cayman_table() -> (&'static AstmFile, &'static BrdfTable) {
    astm_table(&cayman_path())
}

/// Fit every geometry of the Cayman file but each tenth, which is held out (once per test run,
/// shared by the tests that use it).
pub fn cayman_held_out() -> &'static HeldOut {
    static HELD_OUT: LazyLock<HeldOut> = LazyLock::new(hold_out);
    &HELD_OUT
}

fn hold_out() -> HeldOut {
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

/// Path of tests/data/garnet_red.astm.
pub fn garnet_red_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/garnet_red.astm")
}

/// An ASTM file of `tests/data` (Cayman, Krylon blue or Garnet red), the fit of all its
/// geometries and the fit's spectral table, made once per test run: the tests that read a
/// paint's fit or table share it (the fit takes seconds, and up to seven tests read a paint's).
struct Imported {
    file: AstmFile,
    fit: ScatteredFit,
    table: BrdfTable,
}

fn imported(path: &Path) -> &'static Imported {
    fn import(path: &Path) -> Imported {
        let file = astm::read(path).unwrap();
        let (fit, table) = fit_and_table(&file, &file.samples);
        Imported { file, fit, table }
    }
    static CAYMAN: LazyLock<Imported> = LazyLock::new(|| import(&cayman_path()));
    static KRYLON_BLUE: LazyLock<Imported> = LazyLock::new(|| import(&krylon_blue_path()));
    static GARNET_RED: LazyLock<Imported> = LazyLock::new(|| import(&garnet_red_path()));
    if path == cayman_path() {
        &CAYMAN
    } else if path == krylon_blue_path() {
        &KRYLON_BLUE
    } else if path == garnet_red_path() {
        &GARNET_RED
    } else {
        panic!("{}: not a paint of tests/data", path.display())
    }
}

/// A paint of `tests/data` (Cayman, Krylon blue or Garnet red) and the spectral table of the
/// fit of all its geometries (shared: [`Imported`]).
pub fn astm_table(path: &Path) -> (&'static AstmFile, &'static BrdfTable) {
    let paint = imported(path);
    (&paint.file, &paint.table)
}

/// The fit of all the geometries of a paint of `tests/data` (shared: [`Imported`]).
pub fn astm_fit(path: &Path) -> &'static ScatteredFit {
    &imported(path).fit
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
