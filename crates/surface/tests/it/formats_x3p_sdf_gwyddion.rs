//! The X3P, SDF, GSF and Gwyddion ASCII readers on real files (tests/data, provenance in its
//! README): grid, spacing, heights and plane-levelled Sq against the reference values; the X3P
//! and GSF writers in round trips.

use crate::fixture_tools::{fixture, rel, rezip, rms_about_mean, sq_plane};
use gonio_surface::{HeightMap, io};
use ndarray::Array2;
use std::path::Path;

fn read(name: &str) -> HeightMap {
    io::read(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn read_bytes_err(name: &str, bytes: &[u8]) -> String {
    match io::read_bytes(Path::new(name), bytes) {
        Ok(_) => panic!("{name}: read although it is broken"),
        Err(e) => e.to_string(),
    }
}

/// The 16 `<Datum>` values of the openGPS sample ISO5436-sample1.x3p, `None` for the empty one.
const OPENGPS_SAMPLE1: [Option<f64>; 16] = [
    Some(4.86219120804151E-0001),
    Some(3.46341436648013E-0003),
    Some(-8.08368571682830E-0001),
    Some(-5.79793099037002E-0001),
    Some(8.57622027393310E-0001),
    Some(1.04759602566142E+0000),
    Some(1.01879225277798E+0000),
    None,
    Some(8.23683772970184E-0001),
    Some(7.97872489327661E-0001),
    Some(-5.57459388341694E-0001),
    Some(-2.33247858849220E-0001),
    Some(6.75397146760858E-0001),
    Some(4.20737549074718E-0001),
    Some(6.42069248110950E-0001),
    Some(-2.15696638464903E-0001),
];

fn check_opengps_grid(map: &HeightMap) {
    assert_eq!((map.nx(), map.ny()), (4, 4));
    assert_eq!((map.dx(), map.dy()), (1.6016e-2, 1.6016e-2));
    assert_eq!(map.valid_count(), 15);
    assert!(
        !map.is_valid(3, 1),
        "the empty <Datum/> / valid.bin bit 7 is invalid"
    );
    assert_eq!(map.meta.instrument.as_deref(), Some("NanoFocus AG µSurf X"));
    assert_eq!(
        map.meta.date.as_deref(),
        Some("2007-04-30T13:58:02.6+02:00")
    );
    assert_eq!(map.meta.warnings().count(), 0, "{:?}", map.meta.extra);
}

#[test]
fn x3p_opengps_xml_and_binary_float64_samples() {
    for name in ["ISO5436-sample1.x3p", "ISO5436-sample1_bin.x3p"] {
        let map = read(name);
        check_opengps_grid(&map);
        for (i, expected) in OPENGPS_SAMPLE1.iter().enumerate() {
            assert_eq!(map.get(i % 4, i / 4), *expected, "{name} point {i}");
        }
    }
}

#[test]
fn x3p_opengps_int16_sample_applies_increment_and_offset() {
    // CZ of ISO5436-sample4_bin.x3p: DataType I (int16), Increment 0.001, Offset -0.5; its
    // data.bin starts with the raw values 986 and 503 (0x03da, 0x01f7).
    let map = read("ISO5436-sample4_bin.x3p");
    check_opengps_grid(&map);
    assert_eq!(map.get(0, 0), Some(-0.5 + 0.001 * 986.0));
    assert_eq!(map.get(1, 0), Some(-0.5 + 0.001 * 503.0));
    // The same surface as sample 1, quantised to steps of 0.001 m.
    for (i, expected) in OPENGPS_SAMPLE1.iter().enumerate() {
        match (map.get(i % 4, i / 4), expected) {
            (Some(h), Some(e)) => assert!((h - e).abs() <= 0.0005 + 1e-12, "point {i}: {h} {e}"),
            (h, e) => assert_eq!(h, *e, "point {i}"),
        }
    }
}

#[test]
fn x3p_mountainsmap_export() {
    let map = read("x3p-2.x3p");
    assert_eq!((map.nx(), map.ny()), (650, 650));
    // Record1/Axes/CX and CY Increment.
    assert_eq!(map.dx(), 1.27656509837346e-7);
    assert_eq!(map.dy(), 3.14582113527746e-7);
    assert_eq!(map.valid_count(), 650 * 650);
    // float64 values at offsets 0, 8 × (650·100 + 200) and the last 8 bytes of bindata/data.bin.
    assert_eq!(map.get(0, 0), Some(6.579781341223288e-08));
    assert_eq!(map.get(200, 100), Some(-1.0945968658776711e-07));
    assert_eq!(map.get(649, 649), Some(-3.276918658776711e-08));
    assert_eq!(
        map.meta.instrument.as_deref(),
        Some("DIGITAL SURF Mountains Map Technology Software")
    );
    assert_eq!(map.meta.warnings().count(), 0);
    // SurfaceTopography: Sq = 77.28 nm after removing the mean plane.
    let sq = sq_plane(&map);
    assert!(rel(sq, 77.28e-9) < 0.005, "Sq {sq:e} m");
}

#[test]
fn x3p_alicona_float32_with_infinite_invalid_points() {
    let map = read("SkiInfiniteFocus.x3p");
    assert_eq!((map.nx(), map.ny()), (1197, 940));
    assert_eq!(map.dx(), 3.678887926e-6);
    assert_eq!(map.dy(), 3.680270397e-6);
    // Alicona writes +inf for the points it did not measure: 4272 of them, the first at (0, 0).
    assert_eq!(map.nx() * map.ny() - map.valid_count(), 4272);
    assert!(!map.is_valid(0, 0));
    assert_eq!(map.get(600, 500), Some(1.222858190885745e-05));
    assert_eq!(map.meta.date.as_deref(), Some("2009-06-09T13:51:45"));
    // The plane-levelled Sq of the finite values of data.bin, computed with a separate pure
    // Python least-squares script: 1.815495440424042e-05 m.
    let sq = sq_plane(&map);
    assert!(rel(sq, 1.815495440424042e-05) < 1e-6, "Sq {sq:e} m");
}

#[test]
fn x3p_checksum_mismatch_is_a_warning() {
    let original = std::fs::read(fixture("ISO5436-sample1_bin.x3p")).unwrap();
    let damaged_data = rezip(&original, |name, mut bytes| {
        if name == "bindata/data.bin" {
            bytes[0] ^= 1;
        }
        bytes
    });
    let map = io::read_bytes(Path::new("damaged.x3p"), &damaged_data).unwrap();
    let warnings: Vec<&str> = map.meta.warnings().collect();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("damaged.x3p") && warnings[0].contains("data.bin"));

    let edited_xml = rezip(&original, |name, bytes| {
        if name == "main.xml" {
            String::from_utf8(bytes)
                .unwrap()
                .replace("user comment", "edited note")
                .into_bytes()
        } else {
            bytes
        }
    });
    let map = io::read_bytes(Path::new("edited.x3p"), &edited_xml).unwrap();
    let warnings: Vec<&str> = map.meta.warnings().collect();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("main.xml"), "{}", warnings[0]);
}

#[test]
fn x3p_absolute_lateral_axes_give_the_spacing() {
    // The XML sample rewritten with absolute x and y axes: each <Datum> holds x;y;z in metres.
    let original = std::fs::read(fixture("ISO5436-sample1.x3p")).unwrap();
    let absolute = rezip(&original, |name, bytes| {
        if name != "main.xml" {
            return bytes;
        }
        let xml = String::from_utf8(bytes).unwrap();
        let xml = xml
            .replacen("<AxisType>I</AxisType>", "<AxisType>A</AxisType>", 2)
            .replace("<Datum/>", "<Datum></Datum>");
        let mut index = 0;
        let mut out = String::new();
        for piece in xml.split_inclusive("</Datum>") {
            if let Some((head, value)) = piece.rsplit_once("<Datum>") {
                let value = value.trim_end_matches("</Datum>");
                let (x, y) = ((index % 4) as f64 * 2.5e-6, (index / 4) as f64 * 4e-6);
                out += &format!("{head}<Datum>{x:e};{y:e};{value}</Datum>");
                index += 1;
            } else {
                out += piece;
            }
        }
        out.replace("<Increment>1.60160000000000E-0002</Increment>", "")
            .into_bytes()
    });
    let map = io::read_bytes(Path::new("absolute.x3p"), &absolute).unwrap();
    assert!(rel(map.dx(), 2.5e-6) < 1e-12 && rel(map.dy(), 4e-6) < 1e-12);
    assert_eq!(map.get(2, 3), OPENGPS_SAMPLE1[14]);
    assert!(!map.is_valid(3, 1));
}

#[test]
fn x3p_round_trip_is_bit_exact() {
    for name in ["x3p-2.x3p", "SkiInfiniteFocus.x3p", "ISO5436-sample1.x3p"] {
        let map = read(name);
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("copy.x3p");
        io::write(&map, &out).unwrap();
        let back = io::read(&out).unwrap();
        assert_same(&map, &back, name);
        assert_eq!(
            back.meta.warnings().count(),
            0,
            "{name}: {:?}",
            back.meta.extra
        );
        assert_eq!(back.meta.instrument, map.meta.instrument, "{name}");
        assert_eq!(back.meta.date, map.meta.date, "{name}");
    }
}

#[test]
fn gsf_reads_a_file_written_to_the_specification() {
    // gsf-1.gsf was written by the Python script in tests/data/README.md: 16 × 12 float32
    // values z = 2e-8 sin(2π ix/8) + 1e-8 cos(2π iy/6) + 3e-9 ix, NaN at (3, 2) and (10, 7).
    let map = read("gsf-1.gsf");
    assert_eq!((map.nx(), map.ny()), (16, 12));
    assert!(rel(map.dx(), 1e-6) < 1e-15 && rel(map.dy(), 1e-6) < 1e-15);
    assert_eq!(map.valid_count(), 16 * 12 - 2);
    assert!(!map.is_valid(3, 2) && !map.is_valid(10, 7));
    for ((iy, ix), &h) in map.heights().indexed_iter() {
        if (ix, iy) == (3, 2) || (ix, iy) == (10, 7) {
            continue;
        }
        let (x, y) = (ix as f64, iy as f64);
        let tau = std::f64::consts::TAU;
        let z = 2e-8 * (tau * x / 8.0).sin() + 1e-8 * (tau * y / 6.0).cos() + 3e-9 * x;
        assert_eq!(h, f64::from(z as f32), "({ix}, {iy})");
    }
    assert!(
        map.meta
            .extra
            .contains(&("Title".into(), "gonio GSF fixture".into()))
    );
}

fn gsf_bytes(header: &str, values: &[f32]) -> Vec<u8> {
    let mut bytes = format!("Gwyddion Simple Field 1.0\n{header}").into_bytes();
    bytes.resize(bytes.len() + 4 - bytes.len() % 4, 0);
    values
        .iter()
        .for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
    bytes
}

#[test]
fn gsf_units_convert_to_metres() {
    let header = "XRes = 2\nYRes = 1\nXReal = 3\nYReal = 0.5\nXYUnits = um\nZUnits = nm\n";
    let map = io::read_bytes(Path::new("u.gsf"), &gsf_bytes(header, &[1.0, -2.0])).unwrap();
    assert!(rel(map.dx(), 1.5e-6) < 1e-15 && rel(map.dy(), 0.5e-6) < 1e-15);
    assert_eq!(map.get(1, 0), Some(-2e-9));
    let header = "XRes = 2\nYRes = 1\nZUnits = V\n";
    let err = read_bytes_err("volts.gsf", &gsf_bytes(header, &[1.0, 2.0]));
    assert!(err.contains("volts.gsf") && err.contains("'V'"), "{err}");
    let err = read_bytes_err(
        "inf.gsf",
        &gsf_bytes("XRes = 2\nYRes = 1\n", &[1.0, f32::INFINITY]),
    );
    assert!(err.contains("infinite"), "{err}");
}

#[test]
fn gsf_round_trip_is_bit_exact() {
    // GSF stores float32: a map whose heights are float32 values comes back bit for bit, with
    // its mask and its spacing, even where XReal / XRes misses dx in the last bit.
    let (nx, ny, dx, dy) = (37, 23, 1.27656509837346e-7, 1.1e-7);
    assert_ne!(dy * ny as f64 / ny as f64, dy);
    let heights = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
        if (ix * 7 + iy * 3) % 19 == 0 {
            f64::NAN
        } else {
            f64::from(((ix as f32) * 0.37).sin() * 1e-7 + (iy as f32) * 3e-9)
        }
    });
    let map = HeightMap::with_invalid(heights, dx, dy).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("copy.gsf");
    io::write(&map, &out).unwrap();
    assert_same(&map, &io::read(&out).unwrap(), "synthetic map");
}

fn assert_same(a: &HeightMap, b: &HeightMap, what: &str) {
    assert_eq!((a.nx(), a.ny()), (b.nx(), b.ny()), "{what}");
    assert_eq!(
        (a.dx().to_bits(), a.dy().to_bits()),
        (b.dx().to_bits(), b.dy().to_bits())
    );
    assert_eq!(a.mask(), b.mask(), "{what}: mask");
    for (x, y) in a.heights().iter().zip(b.heights()) {
        assert!(
            x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
            "{what}: {x} {y}"
        );
    }
}

#[test]
fn sdf_ascii_iso_sample() {
    let map = read("sdf-1.sdf");
    assert_eq!((map.nx(), map.ny()), (7, 4));
    assert_eq!((map.dx(), map.dy()), (1e-6, 1e-6));
    // Zscale = 1.0E-6: the text values are micrometres.
    assert_eq!(map.get(0, 0), Some(1.0 * 1e-6));
    assert_eq!(map.get(4, 3), Some(0.96012 * 1e-6));
    assert_eq!(map.meta.instrument.as_deref(), Some("ISOTC213"));
    assert_eq!(map.meta.date.as_deref(), Some("2010-01-04T08:53"));
    assert!(
        map.meta
            .extra
            .contains(&("OperatorName".into(), "Tom Jones".into()))
    );
}

#[test]
fn sdf_listed_sq_is_the_unlevelled_rms() {
    // The shared README lists Sq = 13.6 nm for sdf-1.sdf "after removing the mean plane". The
    // file's 7 × 4 values (Zscale 1e-6 m, Xscale = Yscale = 1e-6 m) give 13.60 nm only about
    // their mean; after removing the least-squares plane Sq is 10.29 nm (a separate Python
    // least-squares script gives 1.0289929442289465e-08 m). The listed value was not levelled.
    let map = read("sdf-1.sdf");
    assert!(rel(rms_about_mean(&map), 13.6e-9) < 0.005);
    let sq = sq_plane(&map);
    assert!(rel(sq, 1.0289929442289465e-08) < 1e-9, "Sq {sq:e} m");
    assert!(rel(sq, 13.6e-9) > 0.2);
}

/// A binary SDF laid out as ISO 25178-71 / Gwyddion's sdfile.c read it: the 81-byte header,
/// int16 values, then a trailer.
fn binary_sdf(nx: u16, ny: u16, values: &[i16]) -> Vec<u8> {
    let mut b = b"bBCR-1.0".to_vec();
    b.extend_from_slice(b"Gonio Test");
    b.extend_from_slice(b"221120260000");
    b.extend_from_slice(b"221120260000");
    b.extend_from_slice(&nx.to_le_bytes());
    b.extend_from_slice(&ny.to_le_bytes());
    for scale in [2e-6f64, 3e-6, 1e-9, 1e-9] {
        b.extend_from_slice(&scale.to_le_bytes());
    }
    b.extend_from_slice(&[0, 5, 0]);
    assert_eq!(b.len(), 81);
    values
        .iter()
        .for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
    b.extend_from_slice(b"*\nOperator = someone\n*");
    b
}

#[test]
fn sdf_binary_int16_with_missing_point() {
    let bytes = binary_sdf(3, 2, &[10, -20, 30, i16::MIN, 0, 7]);
    let map = io::read_bytes(Path::new("b.sdf"), &bytes).unwrap();
    assert_eq!((map.nx(), map.ny(), map.dx(), map.dy()), (3, 2, 2e-6, 3e-6));
    assert_eq!(map.get(1, 0), Some(-20.0 * 1e-9));
    assert!(!map.is_valid(0, 1), "int16 minimum marks a missing point");
    assert_eq!(map.get(2, 1), Some(7.0 * 1e-9));
    assert_eq!(map.meta.instrument.as_deref(), Some("Gonio Test"));
    assert!(
        map.meta
            .extra
            .contains(&("Operator".into(), "someone".into()))
    );
    let err = read_bytes_err("short.sdf", &bytes[..81 + 11]);
    assert!(
        err.contains("short.sdf") && err.contains("6 points"),
        "{err}"
    );
}

#[test]
fn gwyddion_ascii_matrix_with_header() {
    let map = read("matrix-3.txt");
    assert_eq!((map.nx(), map.ny()), (256, 256));
    // "# Width: 10.00 µm", "# Height: 10.00 µm" are the size of the whole field.
    assert!(rel(map.dx(), 10e-6 / 256.0) < 1e-15 && rel(map.dy(), 10e-6 / 256.0) < 1e-15);
    assert_eq!(map.get(0, 0), Some(1.8823e-8));
    assert!(
        map.meta
            .extra
            .contains(&("channel".into(), "ZSensor".into()))
    );
    // SurfaceTopography: Sq = 35.22 nm.
    let sq = sq_plane(&map);
    assert!(rel(sq, 35.22e-9) < 0.005, "Sq {sq:e} m");
}

#[test]
fn gwyddion_ascii_export_with_units() {
    let map = read("gwyddion-export-english.txt");
    assert_eq!((map.nx(), map.ny()), (3, 4));
    // Width 12.34 µm over 3 columns, Height 5678.9 nm over 4 rows.
    assert!(rel(map.dx(), 12.34e-6 / 3.0) < 1e-15, "{}", map.dx());
    assert!(rel(map.dy(), 5678.9e-9 / 4.0) < 1e-15, "{}", map.dy());
    let rows = [
        [1.0, 1.5, 3.0],
        [-2.0, -3.0, -6.0],
        [0.0, 0.0, 0.0],
        [9.0, 9.0, 9.0],
    ];
    for (iy, row) in rows.iter().enumerate() {
        for (ix, &z) in row.iter().enumerate() {
            assert_eq!(map.get(ix, iy), Some(z));
        }
    }
}

#[test]
fn gwyddion_ascii_errors_say_what_is_missing() {
    let err = read_bytes_err("bare.txt", b"1 2 3 4\n5 6 7 8\n");
    assert!(err.contains("bare.txt") && err.contains("Width"), "{err}");
    let err = read_bytes_err(
        "ragged.txt",
        "# Width: 1 mm\n# Height: 1 mm\n1 2\n3\n".as_bytes(),
    );
    assert!(
        err.contains("ragged.txt") && err.contains("line 4"),
        "{err}"
    );
    let text = "# Width: 1 furlong\n# Height: 1 mm\n1 2\n";
    let err = read_bytes_err("furlong.txt", text.as_bytes());
    assert!(err.contains("furlong"), "{err}");
    let text = "# Width: 2,5 mm\n# Height: 1 mm\n# Value units: nm\n1,5 nan\n";
    let map = io::read_bytes(Path::new("comma.txt"), text.as_bytes()).unwrap();
    assert_eq!(
        (map.dx(), map.get(0, 0), map.is_valid(1, 0)),
        (1.25e-3, Some(1.5 * 1e-9), false)
    );
}
