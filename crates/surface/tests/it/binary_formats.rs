//! The binary instrument readers (Zygo MetroPro, Wyko OPD, Sensofar PLu, Digital Surf, Alicona
//! AL3D) on real files (tests/data, provenance in its README): grid, spacing, heights at chosen
//! points, non-measured points, metadata, and Sq against the reference values.
//!
//! Reference values: heights at points and the plane-levelled Sq come from a separate pure-Python
//! script that decodes the raw bytes with `struct` (no code shared with the readers). The
//! "Sq" column of the shared data README is what SurfaceTopography reports, and for these files
//! that is the rms height about the mean, without levelling: it matches SurfaceTopography's own
//! test assertions to 7 digits (metropro-1.dat 7.528822e-8 m, plu-1.plu 2.834391e-6 m,
//! al3d-1.al3d 7.688266e-6 m), while the plane-levelled Sq of these tilted maps is smaller by
//! factors up to 150. So the README values are checked against the unlevelled rms, and the
//! levelled Sq against the Python script.

use crate::fixture_tools::{fixture, rel, rms_about_mean, sq_plane, valid_heights};
use gonio_surface::io::{self, Format};
use gonio_surface::{HeightMap, ops, stats};
use std::io::Write;
use std::path::Path;

fn read(name: &str) -> HeightMap {
    io::read(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn bytes(name: &str) -> Vec<u8> {
    std::fs::read(fixture(name)).unwrap()
}

/// Sq of the crate's statistics (after its least-squares levelling), checked against the
/// independent plane fit of the test helpers and against `expected` from the Python script.
fn check_levelled_sq(map: &HeightMap, expected: f64) {
    let (sq, ..) = stats::height_parameters(&ops::level(map).unwrap());
    assert!(
        rel(sq, expected) < 1e-9,
        "levelled Sq {sq:e} m, expected {expected:e} m"
    );
    assert!(rel(sq_plane(map), expected) < 1e-9);
}

/// The error message of reading `bytes` as the file `name`; it must fail.
fn error_of(name: &str, bytes: &[u8]) -> String {
    match io::read_bytes(Path::new(name), bytes) {
        Ok(_) => panic!("{name}: read although it is broken"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn metropro_phase_map() {
    let map = read("metropro-1.dat");
    assert_eq!((map.nx(), map.ny()), (640, 480));
    // lateral_res, f32 at header offset 184: 1.098 µm in the README.
    assert_eq!(map.dx(), 1.0982520279867458e-6);
    assert_eq!(map.dy(), map.dx());
    assert_eq!(map.valid_count(), 640 * 480);
    // Counts × S·O·λ/R with S = 0.5, O = 1, λ = 570 nm, R = 32768 (phase_res 1).
    for (ix, iy, h) in [
        (0, 0, 5.05753145602552e-05),
        (639, 479, 5.085188667204241e-05),
        (100, 200, 5.065004356382373e-05),
    ] {
        let got = map.get(ix, iy).unwrap();
        assert!(rel(got, h) < 1e-12, "({ix}, {iy}): {got:e} m");
    }
    assert!(rel(rms_about_mean(&map), 75.29e-9) < 0.005);
    assert!(rel(rms_about_mean(&map), 7.528822e-8) < 1e-6);
    check_levelled_sq(&map, 1.3334981370330678e-08);
    // Time stamp 1311439776 s (`date -u -d @1311439776`).
    assert_eq!(map.meta.date.as_deref(), Some("2011-07-23T16:49:36Z"));
    assert!(map.meta.instrument.as_deref().unwrap().starts_with("Zygo"));
    assert!(
        map.meta
            .extra
            .contains(&("objective".into(), "20X  Mirau".into()))
    );
    assert_eq!(map.meta.format.as_deref(), Some("Zygo MetroPro"));
}

#[test]
fn wyko_opd_with_dropouts() {
    let map = read("opd-1.opd");
    assert_eq!((map.nx(), map.ny()), (640, 480));
    // Pixel_size 1.9673303e-4 mm (README: 0.1967 µm), Aspect 1.
    assert_eq!(map.dx(), 1.9673303177114576e-7);
    assert_eq!(map.dy(), map.dx());
    // 116 values of 1.7e38 (BAD_PIXEL); the first is the 39878th of the column-major data.
    assert_eq!(map.nx() * map.ny() - map.valid_count(), 116);
    assert!(!map.is_valid(83, 441));
    // Heights scale by Wavelength / Mult = 577.295 nm (the README's 0.000577295 mm); each
    // column runs from the last row up.
    let first = map.get(0, 479).unwrap();
    assert!(rel(first, -2.8399285465906725e-07) < 1e-12, "{first:e}");
    let next_column_top = map.get(1, 0).unwrap();
    assert!(rel(next_column_top, -2.6905433065838587e-07) < 1e-12);
    assert!(rel(rms_about_mean(&map), 8.37e-9) < 0.005);
    check_levelled_sq(&map, 6.711198050967856e-09);
    assert_eq!(map.meta.date.as_deref(), Some("7/7/2015 16:19:48"));
}

#[test]
fn sensofar_plu_topography() {
    let map = read("plu-1.plu");
    assert_eq!((map.nx(), map.ny()), (768, 576));
    // 1.66 µm per pixel (f32 1.6600000858306885).
    assert!(rel(map.dx(), 1.6600000858306885e-6) < 1e-15);
    assert_eq!(map.dy(), map.dx());
    assert_eq!(map.valid_count(), 768 * 576);
    assert_eq!(map.get(0, 0), Some(-111.2265625e-6));
    assert!(rel(map.get(767, 575).unwrap(), -101.21484375e-6) < 1e-15);
    assert!(rel(rms_about_mean(&map), 2834e-9) < 0.005);
    assert!(rel(rms_about_mean(&map), 2.834391e-6) < 1e-6);
    check_levelled_sq(&map, 1.828195583424616e-08);
    assert_eq!(map.meta.date.as_deref(), Some("Fri Mar 10 16:35:59 2023"));
}

#[test]
fn alicona_al3d_depth_image() {
    let map = read("al3d-1.al3d");
    assert_eq!((map.nx(), map.ny()), (200, 296));
    assert_eq!(map.dx(), 4.38027e-07);
    assert_eq!(map.dy(), 4.38027e-07);
    assert_eq!(map.valid_count(), 200 * 296);
    assert_eq!(map.get(0, 0), Some(0.07635815441608429));
    assert_eq!(map.get(199, 295), Some(0.07632320374250412));
    assert!(rel(rms_about_mean(&map), 7688e-9) < 0.005);
    assert!(rel(rms_about_mean(&map), 7.688266e-6) < 1e-6);
    check_levelled_sq(&map, 2.898221027836311e-07);
    assert_eq!(
        map.meta.instrument.as_deref(),
        Some("Alicona MeasureSuite 5.3.6")
    );
}

#[test]
fn digital_surf_with_non_measured_points() {
    let map = read("sur-2.sur");
    assert_eq!((map.nx(), map.ny()), (563, 484));
    // dx = dy = 0.003484 mm.
    assert_eq!(map.dx(), 0.0034840002190321684 * 1e-3);
    assert_eq!(map.dy(), map.dx());
    // Point (0, 0) holds 101477 counts of dz = 1e-7 mm.
    assert!(rel(map.get(0, 0).unwrap(), 101477.0 * 1.0000000116860974e-10) < 1e-12);
    assert_eq!(map.nx() * map.ny() - map.valid_count(), 117);
    assert!(!map.is_valid(301, 0));
    check_levelled_sq(&map, 1.7104139236637136e-08);
    assert_eq!(map.meta.warnings().count(), 0);

    // An inversion flag is reported, not applied.
    let mut inverted = bytes("sur-2.sur");
    inverted[290] = 1;
    let flagged = io::read_bytes(Path::new("i.sur"), &inverted).unwrap();
    assert_eq!(flagged.get(0, 0), map.get(0, 0));
    assert!(flagged.meta.warnings().any(|w| w.contains("inversion")));
}

/// The README lists 17.7 nm for sur-2.sur; the file's own header shows why 17.52 nm is right.
#[test]
fn digital_surf_listed_sq_does_not_follow_the_header() {
    let raw = bytes("sur-2.sur");
    let i32_at = |at: usize| i32::from_le_bytes(raw[at..at + 4].try_into().unwrap());
    // Header: special points flag 1 (the file has non-measured points), zmin 89120 and zmax
    // 103880 counts, 32-bit points, dz = 1e-7 mm.
    assert_eq!(i16::from_le_bytes([raw[86], raw[87]]), 1);
    let (zmin, zmax) = (i32_at(100), i32_at(104));
    assert_eq!((zmin, zmax), (89120, 103880));
    let points: Vec<i32> = (0..563 * 484).map(|k| i32_at(512 + 4 * k)).collect();
    // Exactly 117 stored values lie outside the stated range, all at zmin − 2: the
    // non-measured marker. The reader drops exactly those.
    let outside: Vec<i32> = points
        .iter()
        .copied()
        .filter(|&v| v < zmin || v > zmax)
        .collect();
    assert_eq!(outside.len(), 117);
    assert!(outside.iter().all(|&v| v == zmin - 2));
    let map = read("sur-2.sur");
    assert_eq!(map.nx() * map.ny() - map.valid_count(), outside.len());
    // The valid heights then span exactly (zmax − zmin)·dz, as the header states.
    let valid = valid_heights(&map);
    let span = valid.iter().cloned().fold(f64::MIN, f64::max)
        - valid.iter().cloned().fold(f64::MAX, f64::min);
    assert!(rel(span, f64::from(zmax - zmin) * 1.0000000116860974e-10) < 1e-9);
    // Unlevelled rms over the measured points: 17.52 nm (Python: 1.7517881243590857e-08 m);
    // counting the markers as heights would give 31.19 nm. Neither is the listed 17.7 nm.
    let rms = rms_about_mean(&map);
    assert!(rel(rms, 1.7517881243590857e-08) < 1e-9, "{rms:e}");
    assert!(rel(rms, 17.7e-9) > 0.009);
}

#[test]
fn digital_surf_compressed_points_read_like_plain_ones() {
    // DSCOMPRESSED: the same header and points, deflated into two zlib streams preceded by
    // the stream count and (raw, compressed) sizes, as RosettaSciIO writes them.
    let raw = bytes("sur-2.sur");
    let points = &raw[512..];
    let (a, b) = points.split_at(points.len() / 2);
    let deflate = |data: &[u8]| {
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(data).unwrap();
        z.finish().unwrap()
    };
    let (za, zb) = (deflate(a), deflate(b));
    let mut file = raw[..512].to_vec();
    file[..12].copy_from_slice(b"DSCOMPRESSED");
    file.extend(2u32.to_le_bytes());
    for (plain, zipped) in [(a, &za), (b, &zb)] {
        file.extend((plain.len() as u32).to_le_bytes());
        file.extend((zipped.len() as u32).to_le_bytes());
    }
    file.extend(&za);
    file.extend(&zb);
    let compressed = io::read_bytes(Path::new("c.sur"), &file).unwrap();
    let plain = read("sur-2.sur");
    assert_eq!(compressed.mask(), plain.mask());
    let same = |a: &f64, b: &f64| a == b || (a.is_nan() && b.is_nan());
    assert!(
        compressed
            .heights()
            .iter()
            .zip(plain.heights())
            .all(|(a, b)| same(a, b))
    );

    // A stream that inflates to less than its header claims is an error, as is a header that
    // claims more than zlib can inflate the compressed bytes to.
    let mut short = file.clone();
    let size_at = 512 + 4;
    short[size_at..size_at + 4].copy_from_slice(&(a.len() as u32 + 4).to_le_bytes());
    assert!(error_of("c.sur", &short).contains("c.sur"));
    let mut greedy = file[..512 + 4].to_vec();
    greedy[108..116].copy_from_slice(&[0x00, 0x40, 0, 0, 0x00, 0x40, 0, 0]);
    greedy[116..120].copy_from_slice(&(1u32 << 28).to_le_bytes());
    greedy.extend((1u32 << 30).to_le_bytes());
    greedy.extend(16u32.to_le_bytes());
    greedy.extend([0u8; 16]);
    greedy[512..516].copy_from_slice(&1u32.to_le_bytes());
    let e = error_of("g.sur", &greedy);
    assert!(e.contains("cannot inflate"), "{e}");
}

#[test]
fn formats_are_detected_by_content_whatever_the_name() {
    for (name, format) in [
        ("metropro-1.dat", Format::Zygo),
        ("opd-1.opd", Format::Wyko),
        ("plu-1.plu", Format::Plu),
        ("sur-2.sur", Format::Sur),
        ("al3d-1.al3d", Format::Al3d),
    ] {
        assert_eq!(
            io::detect(Path::new("renamed.bin"), &bytes(name)),
            Some(format),
            "{name}"
        );
    }
}

#[test]
fn headers_that_claim_more_than_the_file_holds_are_errors() {
    // MetroPro: phase data 640 × 481 (the byte count to match) in a file sized for 480 rows.
    let mut zygo = bytes("metropro-1.dat");
    zygo[70..72].copy_from_slice(&481u16.to_be_bytes());
    zygo[72..76].copy_from_slice(&(640u32 * 481 * 4).to_be_bytes());
    let e = error_of("z.dat", &zygo);
    assert!(e.starts_with("z.dat") && e.contains("truncated"), "{e}");
    // ... and a byte count that disagrees with the grid.
    let mut zygo = bytes("metropro-1.dat");
    zygo[72..76].copy_from_slice(&1u32.to_be_bytes());
    assert!(error_of("z.dat", &zygo).contains("phase data"));

    // Sensofar: 2^16 × 2^16 heights claimed.
    let mut plu = bytes("plu-1.plu");
    plu[500..508].copy_from_slice(&[0, 0, 1, 0, 0, 0, 1, 0]);
    assert!(error_of("p.plu", &plu).contains("p.plu"));

    // Digital Surf: a comment zone running past the end of a cut file.
    let mut sur = bytes("sur-2.sur")[..600].to_vec();
    sur[334..336].copy_from_slice(&4000u16.to_le_bytes());
    assert!(error_of("s.sur", &sur).contains("s.sur"));

    // Alicona: the depth image moved to the end of the file.
    let mut al3d = bytes("al3d-1.al3d");
    let tag = al3d
        .windows(16)
        .position(|w| w == b"DepthImageOffset")
        .unwrap();
    al3d[tag + 20..tag + 26].copy_from_slice(b"470000");
    assert!(error_of("a.al3d", &al3d).contains("a.al3d"));

    // Wyko: a directory longer than the file.
    let mut opd = bytes("opd-1.opd");
    opd[20..24].copy_from_slice(&(24u32 * 1_000_000).to_le_bytes());
    assert!(error_of("w.opd", &opd).contains("w.opd"));
}

#[test]
fn zero_negative_and_nan_spacings_are_errors() {
    // (file, offset of the x spacing, whether the file is big-endian)
    for (name, offset, big_endian) in [
        ("metropro-1.dat", 184, true),
        ("plu-1.plu", 404, false),
        ("sur-2.sur", 120, false),
    ] {
        for bad in [0.0f32, -1.0, f32::NAN, f32::INFINITY] {
            let mut file = bytes(name);
            let encoded = if big_endian {
                bad.to_be_bytes()
            } else {
                bad.to_le_bytes()
            };
            file[offset..offset + 4].copy_from_slice(&encoded);
            let e = error_of(name, &file);
            assert!(
                e.contains(name) && e.contains("positive"),
                "{name} with {bad}: {e}"
            );
        }
    }
    let mut al3d = bytes("al3d-1.al3d");
    let tag = al3d
        .windows(15)
        .position(|w| w == b"PixelSizeXMeter")
        .unwrap();
    al3d[tag + 20..tag + 31].copy_from_slice(b"-4.38027e-7");
    assert!(error_of("a.al3d", &al3d).contains("PixelSizeXMeter"));
}

#[test]
fn nan_heights_where_the_format_forbids_them_are_errors() {
    // Sensofar marks missing points with 1000001, never NaN.
    let mut plu = bytes("plu-1.plu");
    plu[508..512].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(error_of("p.plu", &plu).contains("finite"));
    // Alicona marks them with NaN (allowed) but never with infinity.
    let mut al3d = bytes("al3d-1.al3d");
    al3d[1261..1265].copy_from_slice(&f32::NAN.to_le_bytes());
    let map = io::read_bytes(Path::new("a.al3d"), &al3d).unwrap();
    assert!(!map.is_valid(0, 0));
    al3d[1261..1265].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert!(error_of("a.al3d", &al3d).contains("infinite"));
}
