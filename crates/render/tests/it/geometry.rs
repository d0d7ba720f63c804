//! Ray-shape intersections where the geometry says, and the bounding-volume hierarchy finding
//! the same hits as testing every shape.

use glam::DVec3;
use gonio_render::geometry::*;

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray {
        origin: DVec3::from_array(o),
        dir: DVec3::from_array(d).normalize(),
    }
}

#[test]
fn shapes_are_hit_where_geometry_says() {
    let sphere = Shape::Sphere {
        centre: DVec3::new(0.0, 0.0, 5.0),
        radius: 2.0,
    };
    let r = ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    assert!((sphere.intersect(&r, 1e-9, f64::INFINITY).unwrap() - 3.0).abs() < 1e-12);
    let h = sphere.hit(&r, 3.0, 0);
    assert!((h.ng - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    // A grazing ray at distance 2.1 from the centre misses.
    assert!(
        sphere
            .intersect(&ray([2.1, 0.0, 0.0], [0.0, 0.0, 1.0]), 0.0, f64::INFINITY)
            .is_none()
    );
    let disk = Shape::Planar {
        origin: DVec3::ZERO,
        u: DVec3::X,
        v: DVec3::Y * 2.0,
        disk: true,
    };
    // An ellipse with semi-axes 1 (x) and 2 (y): (0, 1.9) is inside, (0.9, 0.9) is not.
    assert!(
        disk.intersect(&ray([0.0, 1.9, 1.0], [0.0, 0.0, -1.0]), 0.0, 9.0)
            .is_some()
    );
    assert!(
        disk.intersect(&ray([0.9, 0.9, 1.0], [0.0, 0.0, -1.0]), 0.0, 9.0)
            .is_none()
    );
    assert!((disk.area() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    let tri = Shape::Triangle {
        p: [DVec3::ZERO, DVec3::X, DVec3::Y],
        n: None,
    };
    assert!(
        tri.intersect(&ray([0.2, 0.2, 1.0], [0.0, 0.0, -1.0]), 0.0, 9.0)
            .is_some()
    );
    assert!(
        tri.intersect(&ray([0.6, 0.6, 1.0], [0.0, 0.0, -1.0]), 0.0, 9.0)
            .is_none()
    );
}

#[test]
fn accel_finds_the_same_nearest_hit_as_brute_force() {
    let mut shapes = vec![];
    for i in 0..200 {
        let x = (i as f64 * 0.618).fract() * 10.0 - 5.0;
        let y = (i as f64 * 0.414).fract() * 10.0 - 5.0;
        let z = (i as f64 * 0.732).fract() * 10.0 - 5.0;
        shapes.push(match i % 3 {
            0 => Shape::Sphere {
                centre: DVec3::new(x, y, z),
                radius: 0.3,
            },
            1 => Shape::Planar {
                origin: DVec3::new(x, y, z),
                u: DVec3::new(0.3, 0.1, 0.0),
                v: DVec3::new(0.0, 0.2, 0.3),
                disk: i % 2 == 0,
            },
            _ => Shape::Triangle {
                p: [
                    DVec3::new(x, y, z),
                    DVec3::new(x + 0.5, y, z),
                    DVec3::new(x, y + 0.5, z + 0.2),
                ],
                n: None,
            },
        });
    }
    let hits = nearest_hits_agree(&shapes);
    assert!(hits > 100 && hits < 1900, "{hits}");
    // Large spheres around the rays' origin, overlapping along many rays: 4, which a scene
    // tests one by one, and 5, through the BVH again.
    let big: Vec<Shape> = (0..5)
        .map(|i| {
            let a = i as f64 * 1.3;
            Shape::Sphere {
                centre: DVec3::new(3.0 * a.cos(), 0.5 * i as f64 - 1.0, 3.0 * a.sin()),
                radius: 1.5,
            }
        })
        .collect();
    for n in [4, 5] {
        let hits = nearest_hits_agree(&big[..n]);
        assert!(hits > 300 && hits < 1900, "{n} spheres: {hits}");
    }
}

/// Rays through `shapes` find the same nearest hit and occlusion as testing every shape;
/// returns how many hit.
fn nearest_hits_agree(shapes: &[Shape]) -> usize {
    let accel = Accel::new(shapes.to_vec());
    let mut hits = 0;
    for k in 0..2000 {
        let a = k as f64 * 0.7548776662;
        let b = k as f64 * 0.5698402910;
        let d = DVec3::new(
            (a * std::f64::consts::TAU).cos(),
            (b * 3.0).sin(),
            (a * std::f64::consts::TAU).sin() + 0.1,
        );
        let r = ray([0.1, -0.2, 0.3], d.to_array());
        let brute = shapes
            .iter()
            .enumerate()
            .filter_map(|(i, s)| s.intersect(&r, 1e-9, f64::INFINITY).map(|t| (t, i)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let got = accel.intersect(&r, 1e-9, f64::INFINITY);
        assert_eq!(got.map(|h| h.prim), brute.map(|b| b.1));
        assert_eq!(accel.occluded(&r, 1e-9, f64::INFINITY), brute.is_some());
        hits += usize::from(brute.is_some());
    }
    hits
}
