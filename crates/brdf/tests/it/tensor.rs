//! The Mitsuba 3 tensor file: round trip and refusal of truncated files.

use gonio_brdf::formats::tensor::*;
use std::collections::BTreeMap;

#[test]
fn round_trip_and_truncation() {
    let mut fields = BTreeMap::new();
    fields.insert("description".to_string(), Field::u8(b"test"));
    fields.insert("theta_i".to_string(), Field::f32(&[3], &[0.0, 0.5, 1.0]));
    fields.insert(
        "grid".to_string(),
        Field::f32(&[2, 3], &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.bsdf");
    write(&path, &fields).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..12], b"tensor_file\0");
    assert_eq!(read(&path).unwrap(), fields);
    std::fs::write(&path, &bytes[..bytes.len() - 3]).unwrap();
    let e = read(&path).unwrap_err().to_string();
    assert!(e.contains("t.bsdf") && e.contains("past the end"), "{e}");
}
