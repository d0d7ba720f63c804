//! Scene files: every shape and light kind loads, OBJ meshes are read and transformed, and bad
//! files give errors that name the file and the problem.

use glam::{DVec2, DVec3};
use gonio_render::Scene;
use gonio_render::geometry::Shape;
use std::path::Path;

const HEADER: &str = r#"
[camera]
position = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 40
width = 8
height = 8

[materials.m]
brdf = { model = "lambert", albedo = 0.5 }
"#;

fn load(body: &str, dir: &Path) -> gonio_render::Result<Scene> {
    let path = dir.join("scene.toml");
    std::fs::write(&path, format!("{HEADER}{body}")).unwrap();
    Scene::from_file(&path)
}

#[test]
fn obj_mesh_is_read_transformed_and_hit() {
    let dir = tempfile::tempdir().unwrap();
    // A unit square of two triangles in the x-y plane with +z normals.
    std::fs::write(
        dir.path().join("quad.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
    )
    .unwrap();
    let s = load(
        r#"
[[shapes]]
type = "mesh"
file = "quad.obj"
material = "m"
scale = 2.0
translate = [-1.0, -1.0, 0.0]
"#,
        dir.path(),
    )
    .unwrap();
    assert_eq!(s.accel.shapes().len(), 2);
    for shape in s.accel.shapes() {
        let Shape::Triangle { p, n } = shape else {
            panic!("{shape:?}")
        };
        assert!(
            p.iter()
                .all(|q| q.x.abs() <= 1.0 && q.y.abs() <= 1.0 && q.z == 0.0)
        );
        assert_eq!(n.unwrap()[0], DVec3::Z);
    }
    // The centre ray meets the quad (now centred at the origin, 2 m wide) at distance 5.
    let hit = s
        .accel
        .intersect(&s.camera.ray(DVec2::new(4.0, 4.0)), 0.0, f64::INFINITY)
        .unwrap();
    assert!((hit.t - 5.0).abs() < 1e-9 && (hit.ng - DVec3::Z).length() < 1e-12);
}

#[test]
fn every_shape_and_light_kind_loads() {
    let dir = tempfile::tempdir().unwrap();
    let mut env = gonio_render::Image::new(8, 4);
    env.pixels.iter_mut().for_each(|p| *p = [0.5, 0.5, 0.5]);
    env.write(&dir.path().join("env.hdr"), Default::default())
        .unwrap();
    let s = load(
        r#"
[[shapes]]
type = "sphere"
material = "m"
[[shapes]]
type = "disk"
radius = 0.5
translate = [0.0, 0.0, 1.0]
material = "m"
[[shapes]]
type = "rectangle"
size = [3.0, 1.0]
rotate_deg = [0.0, 45.0, 0.0]
material = "m"
[[lights]]
type = "point"
position = [0.0, 3.0, 0.0]
intensity = [1.0, 2.0, 3.0]
[[lights]]
type = "sphere"
center = [0.0, 3.0, 0.0]
radius = 0.5
radiance = 2.0
[[lights]]
type = "rectangle"
radiance = 1.0
[[lights]]
type = "environment"
file = "env.hdr"
[[lights]]
type = "sky"
radiance = 0.1
"#,
        dir.path(),
    )
    .unwrap();
    assert_eq!(s.lights.len(), 5);
    assert_eq!(s.accel.shapes().len(), 5, "3 shapes and 2 area lights");
    let opts = gonio_render::RenderOptions {
        spp: Some(4),
        ..Default::default()
    };
    let (img, stats) = gonio_render::render(&s, &opts).unwrap();
    assert!(stats.rays >= 64 * 4);
    assert!(
        img.pixels
            .iter()
            .flatten()
            .all(|c| c.is_finite() && *c >= 0.0)
    );
}

#[test]
fn errors_name_the_file_and_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[[shapes]]\ntype = \"sphere\"\nmaterial = \"nope\"\n",
            "`nope` is not defined",
        ),
        ("[[shapes]]\ntype = \"cube\"\nmaterial = \"m\"\n", "cube"),
        (
            "[[shapes]]\ntype = \"sphere\"\nmaterial = \"m\"\nradius = -1\n",
            "`radius`",
        ),
        (
            "[[shapes]]\ntype = \"sphere\"\nmaterial = \"m\"\nscale = [1, 2, 1]\n",
            "uniform scale",
        ),
        (
            "[[shapes]]\ntype = \"mesh\"\nmaterial = \"m\"\nfile = \"missing.obj\"\n",
            "missing.obj",
        ),
        (
            "[[lights]]\ntype = \"environment\"\nfile = \"none.exr\"\n",
            "none.exr",
        ),
        (
            "[materials.x]\nbrdf = { model = \"ggx\", alpha = -1, index = 1.5 }\n",
            "`alpha`",
        ),
        ("[materials.y]\ntable = \"t.xyz\"\n", "extension"),
        (
            "[materials.z]\nsurface = { epoxy_sq_nm = 100, method = \"wave\" }\n",
            "`wave`",
        ),
        ("[materials.w]\n", "exactly one of"),
        (
            "[[lights]]\ntype = \"sky\"\nradiance = 1\ncolour = 2\n",
            "colour",
        ),
        // A field another kind of shape takes, or none takes, is named.
        (
            "[[shapes]]\ntype = \"rectangle\"\nmaterial = \"m\"\nradius = 2\n",
            "a rectangle takes `size` and the transform (`translate`, `rotate_deg`, `scale`), not `radius`",
        ),
        (
            "[[shapes]]\ntype = \"disk\"\nmaterial = \"m\"\nrotate = [0, 0, 1]\n",
            "rotate",
        ),
        (
            "[[shapes]]\ntype = \"mesh\"\nmaterial = \"m\"\n",
            "a mesh needs `file`",
        ),
    ];
    for (body, want) in cases {
        let err = load(body, dir.path()).err().expect(body).to_string();
        assert!(err.contains(want), "{body}: {err}");
        assert!(
            err.contains("scene.toml")
                || err.contains(".obj")
                || err.contains(".exr")
                || err.contains(".xyz"),
            "{body}: {err}"
        );
    }
    // A TOML syntax error gives the line.
    let err = load("[[shapes]\n", dir.path()).err().unwrap().to_string();
    assert!(err.contains("line 11"), "{err}");
    std::fs::write(dir.path().join("bad.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    let err = load(
        "[[shapes]]\ntype = \"mesh\"\nmaterial = \"m\"\nfile = \"bad.obj\"\n",
        dir.path(),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(err.contains("bad.obj"), "{err}");
}
