//! Variants of the supported formats that other software writes, made from the real fixtures by
//! the byte-level change that distinguishes them: X3P archives as x3ptools writes them (members
//! under a folder, a root element without the namespace, an empty `<Offset/>`), X3P members
//! damaged inside the archive (the zip CRC-32), ISO 25178-71 `BAD` points as MountainsMap writes
//! them, Digital Surf unit strings in UTF-8, and Gwyddion exports with translated headers.

use crate::fixture_tools::{fixture, members, rel, zip_of};
use gonio_surface::{HeightMap, io};
use std::path::Path;

fn read_bytes(name: &str, bytes: &[u8]) -> HeightMap {
    io::read_bytes(Path::new(name), bytes).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Equal heights, NaN (non-measured) at the same points.
fn same_heights(a: &HeightMap, b: &HeightMap) -> bool {
    a.heights().shape() == b.heights().shape()
        && a.heights()
            .iter()
            .zip(b.heights())
            .all(|(x, y)| x == y || (x.is_nan() && y.is_nan()))
}

fn read_bytes_err(name: &str, bytes: &[u8]) -> String {
    match io::read_bytes(Path::new(name), bytes) {
        Ok(_) => panic!("{name}: read although it is broken"),
        Err(e) => e.to_string(),
    }
}

/// x3p-2.x3p with every member moved under `folder/`, as x3ptools writes its archives.
fn x3p_under_folder(folder: &str) -> Vec<u8> {
    let bytes = std::fs::read(fixture("x3p-2.x3p")).unwrap();
    let moved: Vec<_> = members(&bytes)
        .into_iter()
        .map(|(name, content, method)| (format!("{folder}/{name}"), content, method))
        .collect();
    zip_of(&moved)
}

#[test]
fn x3p_with_members_under_a_folder_reads_like_the_original_with_a_warning() {
    let original = io::read(&fixture("x3p-2.x3p")).unwrap();
    let map = read_bytes("x3ptools.x3p", &x3p_under_folder("x3p-2"));
    assert!(same_heights(&map, &original));
    assert_eq!((map.dx(), map.dy()), (original.dx(), original.dy()));
    let warnings: Vec<_> = map.meta.warnings().collect();
    assert!(
        warnings.iter().any(|w| w.contains("'x3p-2/'")),
        "{warnings:?}"
    );
}

#[test]
fn x3p_with_two_surfaces_in_two_folders_is_refused_as_ambiguous() {
    let mut both = members(&x3p_under_folder("a"));
    both.extend(members(&x3p_under_folder("b")));
    let e = read_bytes_err("two.x3p", &zip_of(&both));
    assert!(
        e.contains("several main.xml") && e.contains("a/main.xml"),
        "{e}"
    );
}

#[test]
fn x3p_without_namespace_and_with_an_empty_offset_reads_with_warnings() {
    let bytes = std::fs::read(fixture("ISO5436-sample4_bin.x3p")).unwrap();
    let original = io::read(&fixture("ISO5436-sample4_bin.x3p")).unwrap();
    let edited: Vec<_> = members(&bytes)
        .into_iter()
        .map(|(name, content, method)| {
            if name != "main.xml" {
                return (name, content, method);
            }
            let xml = String::from_utf8(content).unwrap();
            let start = xml.find("<p:ISO5436_2").unwrap();
            let end = start + xml[start..].find('>').unwrap();
            let xml = format!("{}<ISO5436_2>{}", &xml[..start], &xml[end + 1..])
                .replace("</p:ISO5436_2>", "</ISO5436_2>")
                .replacen("<Offset>0.00000000000000E+0000</Offset>", "<Offset/>", 1);
            assert!(xml.contains("<Offset/>"));
            (name, xml.into_bytes(), method)
        })
        .collect();
    let map = read_bytes("plain.x3p", &zip_of(&edited));
    assert!(same_heights(&map, &original));
    let warnings: Vec<_> = map.meta.warnings().collect();
    assert!(
        warnings.iter().any(|w| w.contains("namespace")),
        "{warnings:?}"
    );
    assert!(
        warnings.iter().any(|w| w.contains("CX/Offset is empty")),
        "{warnings:?}"
    );
}

#[test]
fn x3p_with_an_undeclared_namespace_prefix_reads_with_a_warning() {
    let bytes = std::fs::read(fixture("ISO5436-sample4_bin.x3p")).unwrap();
    let edited: Vec<_> = members(&bytes)
        .into_iter()
        .map(|(name, content, method)| {
            if name != "main.xml" {
                return (name, content, method);
            }
            let xml = String::from_utf8(content).unwrap().replacen(
                "xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"",
                "",
                1,
            );
            (name, xml.into_bytes(), method)
        })
        .collect();
    let map = read_bytes("prefix.x3p", &zip_of(&edited));
    assert_eq!((map.nx(), map.ny()), (4, 4));
    assert!(map.meta.warnings().any(|w| w.contains("prefix 'p'")));
}

/// A damaged byte in a member is an error naming the member, whether or not `main.xml` carries
/// an MD5 of it: before, a stored `data.bin` with one byte changed read as a map (and without an
/// MD5 nothing would have said so).
#[test]
fn a_damaged_x3p_member_fails_its_crc_and_is_named() {
    let bytes = std::fs::read(fixture("ISO5436-sample4_bin.x3p")).unwrap();
    let mut archive = members(&bytes);
    let without_md5: Vec<_> = archive
        .iter()
        .cloned()
        .map(|(name, content, method)| {
            if name != "main.xml" {
                return (name, content, method);
            }
            let xml = String::from_utf8(content).unwrap();
            let start = xml.find("<MD5ChecksumPointData>").unwrap();
            let end = xml.find("</MD5ChecksumPointData>").unwrap() + 23;
            let xml = format!("{}{}", &xml[..start], &xml[end..]);
            (name, xml.into_bytes(), method)
        })
        .collect();
    for (label, members) in [
        ("with MD5", &mut archive),
        ("without MD5", &mut without_md5.clone()),
    ] {
        let data = members
            .iter()
            .position(|(n, _, _)| n == "bindata/data.bin")
            .unwrap();
        assert_eq!(members[data].2, zip::CompressionMethod::Stored);
        let zipped = zip_of(members);
        // The stored member's bytes appear verbatim in the archive: change one of them there,
        // leaving the CRC recorded in the headers as it was.
        let content = &members[data].1;
        let at = zipped
            .windows(content.len())
            .position(|w| w == content.as_slice())
            .expect("stored content in the archive")
            + 5;
        let mut damaged = zipped.clone();
        damaged[at] ^= 0x40;
        let e = read_bytes_err("damaged.x3p", &damaged);
        assert!(
            e.contains("bindata/data.bin") && e.contains("CRC-32") && e.contains("damaged.x3p"),
            "{label}: {e}"
        );
    }
}

/// ISO 25178-71 marks a non-measured point in an ASCII file with the word `BAD`.
#[test]
fn sdf_bad_points_are_invalid() {
    let text = std::fs::read_to_string(fixture("sdf-1.sdf")).unwrap();
    let original = read_bytes("sdf-1.sdf", text.as_bytes());
    let edited = text
        .replacen("0.99748", "BAD", 1)
        .replacen("0.96012", "bad", 1);
    let map = read_bytes("bad.sdf", edited.as_bytes());
    assert_eq!(map.valid_count(), 28 - 2);
    // Row 1, column 1 and row 3, column 4 (the two replaced values).
    assert_eq!(map.get(1, 1), None);
    assert_eq!(map.get(4, 3), None);
    assert_eq!(map.get(0, 0), original.get(0, 0));
    assert_eq!(map.get(6, 3), original.get(6, 3));
}

/// Digital Surf's unit fields are 16 bytes of text at offsets 180 (x), 196 (y) and 212 (z).
/// The instruments write `µm` in Latin-1 (`b5 6d`), other software in UTF-8 (`c2 b5 6d`). The
/// fixture states millimetres; written as micrometres in either encoding, the map reads the same
/// in both, a thousand times smaller than the original in every length.
#[test]
fn sur_unit_strings_in_utf8_read_like_latin1() {
    let bytes = std::fs::read(fixture("sur-2.sur")).unwrap();
    let original = read_bytes("sur-2.sur", &bytes);
    let with_unit = |unit: &[u8]| {
        let mut b = bytes.clone();
        for offset in [180, 196, 212] {
            assert_eq!(
                &b[offset..offset + 2],
                b"mm",
                "the fixture's unit at {offset}"
            );
            b[offset..offset + 16].fill(b' ');
            b[offset..offset + unit.len()].copy_from_slice(unit);
        }
        b
    };
    let latin1 = read_bytes("latin1.sur", &with_unit(&[0xb5, b'm']));
    let utf8 = read_bytes("utf8.sur", &with_unit("µm".as_bytes()));
    assert_eq!((utf8.dx(), utf8.dy()), (latin1.dx(), latin1.dy()));
    assert!(same_heights(&utf8, &latin1));
    assert!(rel(utf8.dx(), original.dx() * 1e-3) < 1e-12);
    let (a, b) = (utf8.get(10, 10).unwrap(), original.get(10, 10).unwrap());
    assert!(rel(a, b * 1e-3) < 1e-12, "{a} vs {b}");
}

/// Gwyddion writes its header in the user interface's language. German keys are known by name;
/// keys of a language gonio does not list are read by position and value.
#[test]
fn gwyddion_exports_with_translated_headers() {
    let english = std::fs::read_to_string(fixture("gwyddion-export-english.txt")).unwrap();
    let reference = read_bytes("english.txt", english.as_bytes());
    let data: String = english
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    let german = format!(
        "# Kanal: Mein Kanal\n# Breite: 12.34 µm\n# Höhe: 5678.9 nm\n# Werteinheiten: m\n{data}"
    );
    // Polish, which gonio does not list: read by position and value.
    let polish = format!(
        "# Kanał: Mój kanał\n# Szerokość: 12.34 µm\n# Wysokość: 5678.9 nm\n# Jednostki wartości: m\n{data}"
    );
    for (label, text) in [("german", german), ("polish", polish)] {
        let map = read_bytes(&format!("{label}.txt"), text.as_bytes());
        assert_eq!(
            (map.nx(), map.ny()),
            (reference.nx(), reference.ny()),
            "{label}"
        );
        assert!(rel(map.dx(), reference.dx()) < 1e-12, "{label}");
        assert!(rel(map.dy(), reference.dy()) < 1e-12, "{label}");
        assert!(same_heights(&map, &reference), "{label}");
    }
    // A value unit in nanometres is applied wherever the line stands.
    let nm = format!("# Kanal: x\n# Breite: 1 µm\n# Höhe: 1 µm\n# Werteinheiten: nm\n{data}");
    let map = read_bytes("nm.txt", nm.as_bytes());
    assert!(rel(map.get(1, 0).unwrap(), 1.5e-9) < 1e-12);
}
