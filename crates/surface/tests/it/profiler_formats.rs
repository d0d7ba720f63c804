//! The profiler and text readers added after the first set (FRT MicroProf, MountainsMap
//! documents, NanoFocus NMS, TrueMap TMD, `x y z` lists, `h= w=` header matrices) on real files
//! (tests/data, provenance in its README): grid, lateral size, valid fraction and plane-levelled
//! Sq against SurfaceTopography 1.27.1, and, where the two disagree, a test that shows from the
//! file's bytes which is right.
//!
//! Reference values: `SurfaceTopography.read_topography(path)`, then `nb_grid_pts`,
//! `physical_sizes` (in its `unit`), the masked fraction of `heights()` and
//! `detrend('height').rms_height_from_area()` (Sq after removing the least-squares plane, over
//! valid points), printed with `repr`.

use crate::fixture_tools::{fixture, rel, sq_plane};
use gonio_surface::HeightMap;
use gonio_surface::io::{self, Format};
use std::path::Path;

fn read(name: &str) -> HeightMap {
    io::read(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn bytes(name: &str) -> Vec<u8> {
    std::fs::read(fixture(name)).unwrap()
}

/// The error message of reading `bytes` as the file `name`; it must fail.
fn error_of(name: &str, bytes: &[u8]) -> String {
    match io::read_bytes(Path::new(name), bytes) {
        Ok(_) => panic!("{name}: read although it is broken"),
        Err(e) => e.to_string(),
    }
}

/// Grid, field size (m) and Sq within 0.5% of the reference.
fn check(map: &HeightMap, grid: (usize, usize), size: (f64, f64), sq: f64) {
    assert_eq!((map.nx(), map.ny()), grid);
    let got = (map.nx() as f64 * map.dx(), map.ny() as f64 * map.dy());
    assert!(
        rel(got.0, size.0) < 1e-6 && rel(got.1, size.1) < 1e-6,
        "size {got:?} m, expected {size:?} m"
    );
    let got = sq_plane(map);
    assert!(rel(got, sq) < 0.005, "Sq {got:e} m, expected {sq:e} m");
}

#[test]
fn tmd_truemap() {
    let map = read("tmd-1.tmd");
    assert_eq!(
        io::detect(&fixture("tmd-1.tmd"), &bytes("tmd-1.tmd")),
        Some(Format::Tmd)
    );
    // SurfaceTopography: (300, 300), 18.956600189208984 mm square, Sq 0.07434087951791002 mm.
    let size = 18.956600189208984e-3;
    check(&map, (300, 300), (size, size), 7.434087951791002e-5);
    assert_eq!(map.valid_fraction(), 1.0);
    // The first f32 after the 24-byte header (offset 80): 0.22351792 mm.
    assert!(rel(map.get(0, 0).unwrap(), 0.22351792e-3) < 1e-7);
    assert!(
        map.meta
            .extra
            .contains(&("comment".into(), "Created by TrueMap v6".into()))
    );
}

#[test]
fn mnt_mountains_document() {
    let map = read("mnt-1.mnt");
    assert_eq!(
        io::detect(&fixture("mnt-1.mnt"), &bytes("mnt-1.mnt")),
        Some(Format::Mnt)
    );
    // SurfaceTopography: (960, 600), (1779.257393117831, 1112.7325542570952) µm,
    // Sq 0.024367248912793675 µm, no masked points, channel 'A48_10x_P1'.
    check(
        &map,
        (960, 600),
        (1779.257393117831e-6, 1112.7325542570952e-6),
        2.4367248912793675e-8,
    );
    assert_eq!(map.valid_fraction(), 1.0);
    assert!(
        map.meta
            .extra
            .contains(&("surface".into(), "A48_10x_P1".into()))
    );
}

#[test]
fn nms_nanofocus() {
    let map = read("nms-1.nms");
    // SurfaceTopography: (512, 512), Sq 0.033514914588842294 µm, no masked points (its size is
    // wrong, see below).
    check(&map, (512, 512), (160e-6, 160e-6), 3.3514914588842294e-8);
    assert_eq!(map.valid_fraction(), 1.0);
    assert_eq!(map.meta.date.as_deref(), Some("2022-02-09T13:25"));
    assert!(
        map.meta
            .extra
            .contains(&("channel".into(), "Intensity".into()))
    );
    // The counts run from 0 (zmin = 2.689... µm, f64 at 16) to 65535 (zmax, f64 at 24).
    let b = bytes("nms-1.nms");
    let zmin = f64::from_le_bytes(b[16..24].try_into().unwrap()) * 1e-6;
    let lowest = map.heights().iter().copied().fold(f64::INFINITY, f64::min);
    assert!(rel(lowest, zmin) < 1e-12, "{lowest:e} m vs {zmin:e} m");
}

/// SurfaceTopography 1.27 reports the field of nms-1.nms as 159999995.47 µm (160 m) square:
/// it reads the steps at offsets 1376 and 1384 as millimetres. The bytes say nanometres.
#[test]
fn nms_lateral_size_is_160_um_not_160_m() {
    let b = bytes("nms-1.nms");
    let f64_at = |o: usize| f64::from_le_bytes(b[o..o + 8].try_into().unwrap());
    let u32_at = |o: usize| u32::from_le_bytes(b[o..o + 4].try_into().unwrap());
    // Version OM_MS_2.0 at 32, 512 × 512 points at 1368, steps 312.49999 at 1376 and 1384.
    assert_eq!(&b[32..41], b"OM_MS_2.0");
    assert_eq!((u32_at(1368), u32_at(1372)), (512, 512));
    let step = f64_at(1376);
    assert_eq!(step, f64_at(1384));
    // 512 steps make 160 000 units: a round 160 µm field in nanometres, while in
    // SurfaceTopography's millimetres it would be 160 m across, a 31 cm pixel in a confocal
    // microscope image, for heights that span 3.3 (zmax − zmin at 24 and 16, in µm).
    assert!((512.0 * step - 160_000.0).abs() < 0.01, "{}", 512.0 * step);
    assert!((f64_at(24) - f64_at(16) - 3.318).abs() < 0.001);
    // D. Mendroch's musurf_reader, written for this OM_MS_2.0 layout, converts these steps to
    // µm by dividing by 1000, i.e. they are nm; the reader does the same.
    let map = read("nms-1.nms");
    assert_eq!(map.dx(), step * 1e-9);
    assert!(rel(map.nx() as f64 * map.dx(), 160e-6) < 1e-7);
}

#[test]
fn frt_microprof() {
    let map = read("frt-1.frt");
    // SurfaceTopography: (500, 500), 0.012 m square; the Sq differs, see below.
    assert_eq!((map.nx(), map.ny()), (500, 500));
    assert!(rel(map.nx() as f64 * map.dx(), 0.012) < 1e-12);
    assert!(rel(map.ny() as f64 * map.dy(), 0.012) < 1e-12);
    // 76456 points hold the count 1 (SurfaceTopography masks them: valid 0.694176) and the 500
    // of the last stored line hold 0, below the file's first valid count.
    assert_eq!(map.valid_count(), 250_000 - 76_456 - 500);
    // Sq over the valid points after levelling, from a numpy plane fit over the counts in
    // [5, 65529] times 9.765923032319103e-09 m: 1.6098844768043211e-06 m.
    let sq = sq_plane(&map);
    assert!(rel(sq, 1.6098844768043211e-6) < 0.005, "Sq {sq:e} m");
    assert_eq!(map.meta.date.as_deref(), Some("2023-03-10T15:57:20Z"));
    assert!(map.meta.instrument.as_deref().unwrap().contains("SN_1036"));
    assert!(
        map.meta
            .extra
            .contains(&("channel".into(), "Intensity".into()))
    );
}

/// SurfaceTopography 1.27 reports Sq 4.396 µm for frt-1.frt, the reader 1.610 µm. The file
/// decides: its last stored line (the top row of the map) holds the count 0 at all 500
/// points, and block 0x0070 states that the valid counts run from 5 to 65529. A line of 0s is
/// 78 µm below the surface around it: the scan never measured it. SurfaceTopography masks only
/// the count 1 and keeps the line as heights of 0 m; putting that line back reproduces its Sq.
#[test]
fn frt_zero_line_is_outside_the_valid_range() {
    let b = bytes("frt-1.frt");
    let u16_at = |o: usize| u16::from_le_bytes([b[o], b[o + 1]]);
    let u32_at = |o: usize| u32::from_le_bytes(b[o..o + 4].try_into().unwrap());
    // Block 0x0070 (first, last valid count) at offset 500404; its content starts 6 bytes on.
    assert_eq!(u16_at(500_404), 0x0070);
    assert_eq!((u32_at(500_410), u32_at(500_414)), (5, 65_529));
    // Block 0x000b at 118 holds 500 × 500 u16 counts from 124; the last line is all 0.
    assert_eq!(u16_at(118), 0x000b);
    let last_line = 124 + 2 * 500 * 499;
    assert!((0..500).all(|i| u16_at(last_line + 2 * i) == 0));
    let map = read("frt-1.frt");
    assert!((0..500).all(|ix| !map.is_valid(ix, 0)));
    // With that line back at 0 m, the Sq is SurfaceTopography's 4.396005581656494e-06 m.
    let mut heights = map.heights().clone();
    heights.row_mut(0).fill(0.0);
    let st = map.with_heights(heights).unwrap();
    let sq = sq_plane(&st);
    assert!(rel(sq, 4.396005581656494e-6) < 0.005, "Sq {sq:e} m");
    assert_eq!(st.valid_count(), 250_000 - 76_456);
}

/// Without block 0x000b the reader takes the topography image of the multi-image block 0x007d,
/// which in this file holds the same counts.
#[test]
fn frt_topography_from_the_multi_image_block() {
    let mut b = bytes("frt-1.frt");
    assert_eq!(u16::from_le_bytes([b[118], b[119]]), 0x000b);
    // An unknown block type (0x00ff) in place of 0x000b: the block is skipped.
    b[118..120].copy_from_slice(&0x00ffu16.to_le_bytes());
    let from_multi = io::read_bytes(Path::new("multi.frt"), &b).unwrap();
    let from_single = read("frt-1.frt");
    assert_eq!(from_multi.heights().shape(), from_single.heights().shape());
    assert_eq!(from_multi.valid_count(), from_single.valid_count());
    assert!(
        from_multi
            .heights()
            .iter()
            .zip(from_single.heights())
            .all(|(a, b)| a == b || (a.is_nan() && b.is_nan()))
    );
    // The intensity image is still listed as another channel.
    assert!(
        from_multi
            .meta
            .extra
            .contains(&("channel".into(), "Intensity".into()))
    );
}

#[test]
fn header_matrix() {
    let map = read("matrix-4.txt");
    assert_eq!(
        io::detect(&fixture("matrix-4.txt"), &bytes("matrix-4.txt")),
        Some(Format::HeaderMatrix)
    );
    // SurfaceTopography: (75, 305), (2.773965e-05, 0.00011280791) m, Sq 7.373059301217378e-08 m.
    check(
        &map,
        (75, 305),
        (2.773965e-5, 1.1280791e-4),
        7.373059301217378e-8,
    );
    assert_eq!(map.valid_fraction(), 1.0);
    // First value −4.448661 rad × 2.91818e-8 m/rad; SurfaceTopography: -1.298199355698e-07 m.
    assert!(rel(map.get(0, 0).unwrap(), -1.298199355698e-7) < 1e-9);
    assert!(rel(map.get(1, 0).unwrap(), -1.341206325266e-7) < 1e-9);
    assert!(map.meta.extra.contains(&("data unit".into(), "rad".into())));
}

#[test]
fn xyz_point_list() {
    let map = read("xyz-1.txt");
    assert_eq!(
        io::detect(&fixture("xyz-1.txt"), &bytes("xyz-1.txt")),
        Some(Format::XyzList)
    );
    // SurfaceTopography: (4, 4), physical size (4.0, 4.0) with unit None, Sq 0.32596012026013244
    // (in the file's unit); the reader takes the unit as metres and says so.
    check(&map, (4, 4), (4.0, 4.0), 0.32596012026013244);
    assert_eq!((map.dx(), map.dy()), (1.0, 1.0));
    assert_eq!(map.valid_fraction(), 1.0);
    // "1 1 2", "1 2 2", "2 1 1": x slowest in the file, ix along x in the map.
    assert_eq!(
        (map.get(1, 1), map.get(1, 2), map.get(2, 1)),
        (Some(2.0), Some(2.0), Some(1.0))
    );
    let warnings: Vec<&str> = map.meta.warnings().collect();
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("no units") && w.contains("metres")),
        "{warnings:?}"
    );
}

#[test]
fn xyz_lists_in_any_order_with_missing_heights() {
    let text = "0.5 1 nan\n0 1 3\n0.5 0 2\n0 0 1\n";
    let map = io::read_bytes(Path::new("shuffled.txt"), text.as_bytes()).unwrap();
    assert_eq!((map.nx(), map.ny(), map.dx(), map.dy()), (2, 2, 0.5, 1.0));
    assert_eq!(
        (map.get(0, 0), map.get(1, 0), map.get(0, 1)),
        (Some(1.0), Some(2.0), Some(3.0))
    );
    assert!(!map.is_valid(1, 1));
}

/// Each text layout is detected on its own, and a broken file of each layout gets that
/// layout's message, not another's.
#[test]
fn each_text_layout_has_its_own_errors() {
    let xyz = |name, text: &str| {
        let e = error_of(name, text.as_bytes());
        assert!(e.contains(name) && e.contains("x y z point list"), "{e}");
        e
    };
    let e = xyz("gap.txt", "0 0 1\n0 1 1\n1 0 1\n");
    assert!(e.contains("not a complete regular grid"), "{e}");
    let e = xyz("word.txt", "0 0 1\n0 1 1\n1 0 1\n1 1 z\n");
    assert!(e.contains("line 4") && e.contains("three numbers"), "{e}");
    let e = xyz("uneven.txt", "0 0 1\n0 1 1\n1 0 1\n1 1 1\n3 0 1\n3 1 1\n");
    assert!(e.contains("evenly spaced"), "{e}");
    let e = xyz("twice.txt", "0 0 1\n0 1 1\n1 0 1\n0 0 1\n");
    assert!(e.contains("already listed"), "{e}");

    let matrix = |name, text: &str| {
        let e = error_of(name, text.as_bytes());
        assert!(
            e.contains(name) && e.contains("text matrix with h= w= header"),
            "{e}"
        );
        e
    };
    let e = matrix("nopixel.txt", "h=1 w=2\ndata unit=nm\n1 2\n");
    assert!(e.contains("pixel size"), "{e}");
    let e = matrix("short.txt", "h=2 w=2\npixel size=1 um\ndata unit=nm\n1 2\n");
    assert!(e.contains("h=2 rows of w=2") && e.contains("1 rows"), "{e}");
    let e = matrix("rad.txt", "h=1 w=2\npixel size=1 um\ndata unit=rad\n1 2\n");
    assert!(e.contains("height scale is unknown"), "{e}");
    let e = matrix(
        "ragged.txt",
        "h=2 w=2\npixel size=1 um\ndata unit=nm\n1 2\n3\n",
    );
    assert!(e.contains("line 5"), "{e}");

    let e = error_of("bare.txt", b"1 2 3 4\n5 6 7 8\n");
    assert!(
        e.contains("bare.txt") && e.contains("Gwyddion ASCII matrix") && e.contains("Width"),
        "{e}"
    );
    let e = error_of("gwy.txt", b"# Width: 1 mm\n# Height: 1 mm\n1 2\nx 3\n");
    assert!(
        e.contains("Gwyddion ASCII matrix") && e.contains("line 4"),
        "{e}"
    );
}

#[test]
fn header_matrix_in_a_length_unit() {
    let text = "h=2\nw=3\npixel size=2 nm\ndata unit=nm\n1 2 3\n4 5 6\n";
    let map = io::read_bytes(Path::new("nm.txt"), text.as_bytes()).unwrap();
    assert_eq!((map.nx(), map.ny(), map.dx()), (3, 2, 2e-9));
    assert!(rel(map.get(2, 1).unwrap(), 6e-9) < 1e-15);
}

#[test]
fn binary_profiler_files_with_broken_headers() {
    let mut frt = bytes("frt-1.frt");
    frt[12..16].copy_from_slice(b"2.00");
    let e = error_of("v2.frt", &frt);
    assert!(e.contains("v2.frt") && e.contains("2.00"), "{e}");
    let mut nms = bytes("nms-1.nms");
    nms[0] = 3;
    let e = error_of("type.nms", &nms);
    assert!(e.contains("type.nms") && e.contains("data type 3"), "{e}");
    let tmd = bytes("tmd-1.tmd");
    let e = error_of("cut.tmd", &tmd[..40]);
    assert!(e.contains("cut.tmd") && e.contains("NUL"), "{e}");
}
