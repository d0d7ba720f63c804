//! The scenes' reference pictures and regions.

use gonio_conformance::scene::{SIZE, Scene, SceneId};

/// Every region holds enough pixels for its mean (at least 150) and no region pixel is in two
/// regions; the furnace's reference is ρL on its region exactly.
#[test]
fn regions_are_large_and_references_sane() {
    for id in SceneId::ALL {
        let scene = Scene::new(id).unwrap();
        let r = scene.reference().unwrap();
        assert_eq!(r.rgb.len(), SIZE * SIZE);
        for k in 0..scene.regions.len() {
            let n = r.region.iter().filter(|&&g| g == Some(k)).count();
            assert!(n >= 150, "{}: region {k} has {n} pixels", id.name());
        }
        if id == SceneId::GreyFurnace {
            for (p, g) in r.rgb.iter().zip(&r.region) {
                if g.is_some() {
                    assert!(p.iter().all(|&c| (c - 0.5).abs() < 1e-12));
                }
            }
        }
    }
}

/// gonio's scene file of each scene parses and builds (its coating and tables load).
#[test]
fn gonio_scene_files_build() {
    let dir = tempfile::tempdir().unwrap();
    for id in SceneId::ALL {
        let scene = Scene::new(id).unwrap();
        let text = gonio_conformance::gonio::scene_toml(&scene, dir.path()).unwrap();
        let path = dir.path().join("s.toml");
        gonio_render::Scene::from_toml(&text, &path)
            .unwrap_or_else(|e| panic!("{}: {e}\n{text}", id.name()));
    }
}
