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

/// Fit every geometry of the Cayman file but each tenth, which is held out.
pub fn cayman_held_out() -> HeldOut {
    let file = astm::read(&cayman_path()).unwrap();
    let (mut held, mut train) = (Vec::new(), Vec::new());
    for (i, sample) in file.samples.iter().enumerate() {
        let part = if i % 10 == 0 { &mut held } else { &mut train };
        part.push(sample.clone());
    }
    let fit = ScatteredFit::new(&train, None).unwrap();
    let channels = Channels::Spectral {
        wavelengths_nm: file.wavelengths_nm.clone(),
    };
    let table = fit
        .to_table(astm::default_resolution(), channels, Default::default())
        .unwrap();
    HeldOut {
        file,
        held,
        fit,
        table,
    }
}
