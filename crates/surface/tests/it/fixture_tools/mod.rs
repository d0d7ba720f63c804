//! Helpers shared by the integration tests on the fixture files: where the fixtures are, the
//! plane-levelled Sq, and rewriting an entry of a zip container (X3P).
// Each test crate uses a different subset of these helpers.
#![allow(dead_code)]

use gonio_surface::HeightMap;
use std::io::{Cursor, Read, Write};
use std::path::PathBuf;

/// Path of a file in `tests/data`.
pub fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Sq (ISO 25178-2) after removing the least-squares mean plane, over valid points, with the
/// crate's levelling and statistics.
pub fn sq_plane(map: &HeightMap) -> f64 {
    let levelled = gonio_surface::ops::level(map).expect("levelling");
    gonio_surface::stats::height_parameters(&levelled).0
}

/// The heights of the valid (measured, not NaN) points.
pub fn valid_heights(map: &HeightMap) -> Vec<f64> {
    map.heights()
        .iter()
        .copied()
        .filter(|h| !h.is_nan())
        .collect()
}

/// Root-mean-square deviation from the mean height over the valid points, without levelling.
pub fn rms_about_mean(map: &HeightMap) -> f64 {
    let valid = valid_heights(map);
    let n = valid.len() as f64;
    let mean = valid.iter().sum::<f64>() / n;
    (valid.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// Relative difference `|a − b| / |b|`.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The members of a zip archive: name, content and compression method.
pub fn members(bytes: &[u8]) -> Vec<(String, Vec<u8>, zip::CompressionMethod)> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes)).expect("fixture is a zip");
    (0..archive.len())
        .map(|i| {
            let mut entry = archive.by_index(i).expect("entry");
            let mut content = Vec::new();
            entry.read_to_end(&mut content).expect("entry content");
            let method = entry.compression();
            (entry.name().expect("name").to_string(), content, method)
        })
        .collect()
}

/// A zip archive of `members`, each written with its own compression method.
pub fn zip_of(members: &[(String, Vec<u8>, zip::CompressionMethod)]) -> Vec<u8> {
    let mut out = zip::ZipWriter::new(Cursor::new(Vec::new()));
    for (name, content, method) in members {
        let options = zip::write::SimpleFileOptions::default().compression_method(*method);
        if name.ends_with('/') {
            out.add_directory(name.as_str(), options).expect("folder");
        } else {
            out.start_file(name.as_str(), options).expect("start entry");
            out.write_all(content).expect("write entry");
        }
    }
    out.finish().expect("finish zip").into_inner()
}

/// A copy of the zip archive `bytes` in which `edit(name, content)` replaces each entry, every
/// one deflated.
pub fn rezip(bytes: &[u8], edit: impl Fn(&str, Vec<u8>) -> Vec<u8>) -> Vec<u8> {
    let edited: Vec<_> = members(bytes)
        .into_iter()
        .map(|(name, content, _)| {
            let content = edit(&name, content);
            (name, content, zip::CompressionMethod::Deflated)
        })
        .collect();
    zip_of(&edited)
}
