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

/// The coat's table whose error gonio's own route counts is the one the renderer computes on
/// loading (the same resolution, `gonio_render::panel::resolution`), and that error, interpolating
/// a smooth reflection between nodes 2° apart in θh and θd, is above zero and below 0.2% of the
/// region's mean (the table's reflection under the sky is within 0.18% of the closed form at
/// every view angle of the region, 0–60°).
#[test]
fn own_coat_loss_is_the_renderers_table() {
    use gonio_conformance::scene::{COAT, Material};
    use gonio_conformance::{Route, loss::loss};
    let bands = gonio_coating::system::default_bands();
    let coating = gonio_coating::description::parse(&COAT.description(), &bands).unwrap();
    assert_eq!(
        gonio_conformance::export::table(&Material::Coat(COAT))
            .unwrap()
            .resolution(),
        gonio_render::panel::resolution(&coating)
    );
    let dir = tempfile::tempdir().unwrap();
    let scene = Scene::new(SceneId::Coat).unwrap();
    let l = loss(
        gonio_conformance::Renderer::Gonio,
        Route::Own,
        &scene,
        &scene.reference().unwrap(),
        dir.path(),
    )
    .unwrap()
    .unwrap();
    println!("{}", l.text);
    assert!(!l.cannot);
    assert!(l.tolerance > 0.0 && l.tolerance < 2e-3, "{}", l.tolerance);
    let plate = Scene::new(SceneId::Plate).unwrap();
    assert!(
        loss(
            gonio_conformance::Renderer::Gonio,
            Route::Own,
            &plate,
            &plate.reference().unwrap(),
            dir.path()
        )
        .unwrap()
        .is_none()
    );
}
