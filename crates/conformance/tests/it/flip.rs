//! FLIP through the `nv-flip` bindings against PyPI's `flip-evaluator` on the same pictures.

use crate::common::python;
use gonio_conformance::compare;
use gonio_conformance::scene::{Scene, SceneId};

/// The coat's reference picture against the same picture made 20% brighter in its left half:
/// the mean FLIP of nv-flip and of flip-evaluator (LDR, 67 pixels per degree) agree within 1%
/// (both NVIDIA's implementation; the Python package is a later release of it).
#[test]
fn nv_flip_agrees_with_flip_evaluator() {
    let scene = Scene::new(SceneId::Coat).unwrap();
    let reference = scene.reference().unwrap().rgb;
    let test: Vec<[f64; 3]> = reference
        .iter()
        .enumerate()
        .map(|(k, c)| if k % 64 < 32 { c.map(|v| v * 1.2) } else { *c })
        .collect();
    let (_, ours) = compare::flip(&reference, &test, scene.white);
    assert!(ours > 0.005, "{ours}");
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("ref.png"), dir.path().join("test.png"));
    std::fs::write(&a, compare::png(compare::srgb8(&reference, 1.0)).unwrap()).unwrap();
    std::fs::write(&b, compare::png(compare::srgb8(&test, 1.0)).unwrap()).unwrap();
    let code = format!(
        "import flip_evaluator as f\n_, m, _ = f.evaluate({:?}, {:?}, 'LDR')\nprint(m)",
        a.display().to_string(),
        b.display().to_string()
    );
    let Some(out) = python("flip_evaluator", &code) else {
        return;
    };
    let theirs: f64 = out.trim().parse().unwrap();
    println!("mean FLIP: nv-flip {ours:.5}, flip-evaluator {theirs:.5}");
    assert!((ours / theirs - 1.0).abs() < 0.01, "{ours} {theirs}");
}
