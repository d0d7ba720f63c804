//! The texture camera's exact glint ([`gonio_render::texture_glint`]) and the flakes' cells
//! cut by a plane ([`FlakeField::sections`]) that it integrates over: the cells are those that
//! [`FlakeField::flake_at`] finds, and the glint is the path tracer's in expectation.

use crate::common::opts;
use crate::flakes::{dir, glint, patch, with_flakes};
use glam::{DVec2, DVec3};
use gonio_render::ColourMode;
use gonio_render::flakes::FlakeField;
use gonio_render::integrator::render_estimate;
use gonio_render::texture_glint::glint_picture;
use gonio_render::texture_metrics::luminance;
use std::collections::HashMap;

/// The pieces of cells in a rectangle (60 × 39 µm of flakes 20 µm across, on a plane 40 µm
/// deep) add up to the rectangle, and each site's area is the share of a fine grid of points
/// (spacing h = 0.05 µm, 1200 × 780) that `flake_at` gives to it. The grid's count of a
/// region errs by at most the cells its boundary meets, `4 (ℓ/h + 1)` for a boundary of
/// length ℓ, each by at most h²: a site's region is at most 4 convex pieces here, each of
/// perimeter at most the rectangle's, 198 µm, so `|error| ≤ 4 · 4 (198 µm · h + h²)` = 160 µm²
/// at most (a wrong cell, some 300 µm², or a wrong site, fails). The gaps' total, whose
/// boundary is all the cells', is compared with the same grid within 1%.
#[test]
fn sections_are_the_cells_that_flake_at_finds() {
    let field = FlakeField::new(glint(20.0), 9).unwrap();
    let (lo, hi, z) = (DVec2::new(-31e-6, -17e-6), DVec2::new(29e-6, 22e-6), -40e-6);
    let mut exact: HashMap<Option<[i64; 3]>, f64> = HashMap::new();
    let mut pieces: HashMap<Option<[i64; 3]>, usize> = HashMap::new();
    let mut total = 0.0;
    field.sections(
        z,
        lo,
        hi,
        |_| true,
        |flake, area| {
            let key = flake.map(|f| f.site);
            *exact.entry(key).or_default() += area;
            *pieces.entry(key).or_default() += 1;
            total += area;
        },
    );
    let rect = (hi.x - lo.x) * (hi.y - lo.y);
    assert!((total - rect).abs() < 1e-9 * rect, "{total} against {rect}");
    let h = 0.05e-6;
    let (nx, ny) = (
        ((hi.x - lo.x) / h).round() as usize,
        ((hi.y - lo.y) / h).round() as usize,
    );
    let mut grid: HashMap<Option<[i64; 3]>, f64> = HashMap::new();
    for i in 0..nx {
        for j in 0..ny {
            let p = DVec3::new(lo.x + (i as f64 + 0.5) * h, lo.y + (j as f64 + 0.5) * h, z);
            *grid.entry(field.flake_at(p).map(|f| f.site)).or_default() += h * h;
        }
    }
    let flakes = exact.keys().filter(|k| k.is_some()).count();
    assert!(flakes >= 3, "{flakes} flakes in the rectangle");
    for (site, &area) in &exact {
        let counted = grid.get(site).copied().unwrap_or(0.0);
        if site.is_none() {
            assert!(
                (counted - area).abs() < 0.01 * rect,
                "gaps: {counted} against {area}"
            );
            continue;
        }
        assert!(pieces[site] <= 4, "{site:?}: {} pieces", pieces[site]);
        let bound = 16.0 * (198e-6 * h + h * h);
        assert!(
            (counted - area).abs() < bound,
            "{site:?}: {:.1} µm² counted, {:.1} µm² exact",
            counted * 1e12,
            area * 1e12
        );
    }
    for site in grid.keys() {
        assert!(exact.contains_key(site), "{site:?} found by flake_at only");
    }
}

/// The exact glint is the path tracer's glint in expectation: a 0.6 mm field of flakes 20 µm
/// across in 30 µm pixels over a black base, under a lamp of 2° at 15°, rendered with 1024
/// samples per pixel, against `glint_picture`. A sample lands on a flake's piece of area
/// share f with probability f, follows its mirror with probability ½ and then carries 2 g L
/// (g its weight, at most 1.5: reflectance and transmittances under 1, the projected-area
/// factors `(wo'·h)/(h_z N(wo'))` and `wi'_z/N(wi')` close to 1 for tilts of 12°), so a
/// pixel's variance is at most `E[X²]/spp ≤ 2 · 1.5 · Y/spp` for its exact value Y: each
/// pixel within 5 such standard deviations, the picture's sum within 4 of its own.
#[test]
fn the_exact_glint_is_the_path_tracers_in_expectation() {
    let (px, spp) = (20, 1024);
    let field = FlakeField::new(glint(20.0), 4).unwrap();
    let s = with_flakes(
        patch(dir(0.0, 0.0), dir(15.0, 180.0), 0.6e-3, px, 2.0),
        field,
    );
    let traced = render_estimate(&s, &opts(spp, 3, ColourMode::Tristimulus)).unwrap();
    let exact = glint_picture(&s, None).unwrap();
    let (mut sum_traced, mut sum_exact, mut var) = (0.0, 0.0, 0.0);
    for (t, e) in traced.image.pixels.iter().zip(&exact.pixels) {
        let (t, e) = (luminance(*t), luminance(*e));
        let sigma2 = 2.0 * 1.5 * e / f64::from(spp);
        assert!(
            (t - e).abs() <= 5.0 * sigma2.sqrt() + 1e-12,
            "traced {t}, exact {e}"
        );
        sum_traced += t;
        sum_exact += e;
        var += sigma2;
    }
    assert!(sum_exact > 0.0, "some flake glints");
    assert!(
        (sum_traced - sum_exact).abs() < 4.0 * var.sqrt(),
        "traced {sum_traced}, exact {sum_exact} ± {}",
        var.sqrt()
    );
}
