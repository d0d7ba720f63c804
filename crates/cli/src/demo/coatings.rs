//! The demo report's coatings section: the multi-angle colour (ASTM E2194, D65/10°) of a red
//! under a smooth clear coat, computed from its constituents, and of the two paints measured at
//! Cornell, with their flop indices.

use super::pictures::EXAMPLES;
use crate::report::{Block, Section};
use anyhow::{Context, Result};
use gonio_brdf::formats::astm;
use gonio_coating::{clear_coat, description};
use gonio_instrument::multiangle::{self, E2194, MultiangleReading, Settings};
use std::f64::consts::PI;
use std::path::Path;

/// The 31 bands 400, 410, ..., 700 nm.
fn bands() -> Vec<f64> {
    (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
}

fn f2(v: f64) -> String {
    format!("{v:.2}")
}

pub(super) fn coatings_section(dir: &Path) -> Result<Section> {
    let wl = bands();
    let settings = Settings::default();
    let toml = Path::new(EXAMPLES).join("coatings/red_solid.toml");
    let stack = description::read(&toml, &wl)?
        .clear_coat()
        .context("red_solid.toml: a smooth coat over a diffuse base")?;
    std::fs::copy(&toml, dir.join("red_solid.toml"))?;
    let optics = wl
        .iter()
        .map(|&w| stack.at(w))
        .collect::<gonio_coating::Result<Vec<_>>>()?;
    // The bare base: a Lambertian surface of the patch's reflectance.
    let bare = multiangle::read(
        &|_, _, out: &mut [f64]| {
            for (o, at) in out.iter_mut().zip(&optics) {
                *o = at.rho / PI;
            }
        },
        &wl,
        &E2194,
        &settings,
    )?;
    // The coated red as `gonio coating compute` tabulates it and `gonio multiangle` reads the
    // table: the numbers the commands shown below print.
    let table = stack.body_table(
        astm::default_resolution(),
        &wl,
        clear_coat::body_provenance("red_solid.toml"),
    )?;
    gonio_brdf::gbrdf::write(&table, &dir.join("red.gbrdf"))?;
    let coated = multiangle::read_table(&table, &E2194, &settings)?;
    let differences = multiangle::differences(&coated, &bare)?;
    let red_rows = bare
        .geometries
        .iter()
        .zip(&coated.geometries)
        .zip(&differences)
        .map(|((b, c), d)| {
            vec![
                b.geometry.to_string(),
                f2(b.lab.l),
                f2(b.lab.chroma()),
                format!("{:.1}", b.lab.hue_deg()),
                f2(c.lab.l),
                f2(c.lab.chroma()),
                format!("{:.1}", c.lab.hue_deg()),
                f2(d.de00),
            ]
        })
        .collect();

    let mut paints = Vec::new();
    for (file, name) in [
        ("cayman.astm", "Cayman metallic"),
        ("garnet_red.astm", "Garnet Red"),
    ] {
        let path = Path::new(EXAMPLES)
            .join("../crates/brdf/tests/data")
            .join(file);
        let (table, _) = astm::import(&path, astm::default_resolution())?;
        paints.push((name, multiangle::read_table(&table, &E2194, &settings)?));
    }
    let paint_rows = |r: &MultiangleReading| -> Vec<Vec<String>> {
        r.geometries
            .iter()
            .map(|g| {
                vec![
                    g.geometry.to_string(),
                    format!("{:.0}", g.geometry.viewing_deg()),
                    f2(g.lab.l),
                    f2(g.lab.a),
                    f2(g.lab.b),
                    f2(g.lab.chroma()),
                    format!("{:.1}", g.lab.hue_deg()),
                ]
            })
            .collect()
    };
    let flop = |r: &MultiangleReading| r.flop_index().map_or("—".into(), |f| format!("{f:.1}"));
    // 45as45, the third E2194 geometry.
    let (b45, c45) = (bare.geometries[2].lab, coated.geometries[2].lab);

    let mut blocks = vec![
        Block::Text(format!(
            "What a multi-angle spectrophotometer reads (ASTM E2194: light at 45°, the detector \
             15, 25, 45, 75 and 110° from the specular direction towards the light; CIELAB \
             under D65 with the 10° observer; docs/instruments.md). First a coating gonio \
             computes from its constituents (docs/coatings.md): the ColorChecker red patch \
             (measured reflectance) as the base under a smooth acrylic clear coat 40 µm thick, \
             every reflection between the coat's surface and the base counted. The coat's \
             mirror reflection is 15° or more from every geometry, so the instrument reads the \
             body reflection. Under the coat the red deepens: at 45as45 L* {:.2} → {:.2} at \
             nearly the same chroma ({:.2} → {:.2}), C*/L* {:.2} → {:.2}: light leaves the coat \
             into a wider cone, and what its surface sends back meets the red base again. A \
             smooth coat over a diffuse base has almost no flop (index {}); only near grazing \
             (45as110, the detector at 65°) does the coat's Fresnel transmission darken it.",
            b45.l,
            c45.l,
            b45.chroma(),
            c45.chroma(),
            b45.chroma() / b45.l,
            c45.chroma() / c45.l,
            flop(&coated)
        )),
        Block::Table {
            headers: [
                "geometry",
                "bare L*",
                "bare C*ab",
                "bare hab °",
                "coated L*",
                "coated C*ab",
                "coated hab °",
                "ΔE00",
            ]
            .map(String::from)
            .to_vec(),
            rows: red_rows,
        },
        Block::Code(
            "gonio coating info red_solid.toml\n\
             gonio coating compute red_solid.toml -o red.gbrdf\n\
             gonio multiangle red.gbrdf"
                .into(),
        ),
        Block::Text(format!(
            "The paints measured at Cornell (Cornell University Program of Computer Graphics \
             reflectance data), imported as spectral tables and read at the same geometries. \
             The Cayman metallic is bright near the specular direction and dark away from it: \
             flop index {} (Alman; near 0 for a solid colour, above 10 for a strong metallic). \
             Garnet Red, a metallic red: {}. At the measured geometries nearest these (40° or 50° light) the \
             readings agree with the measured spectra within CIEDE2000 0.5 (the test of \
             docs/instruments.md).",
            flop(&paints[0].1),
            flop(&paints[1].1)
        )),
    ];
    for (name, reading) in &paints {
        blocks.push(Block::Text(format!("{name}:")));
        blocks.push(Block::Table {
            headers: [
                "geometry",
                "detector θv °",
                "L*",
                "a*",
                "b*",
                "C*ab",
                "hab °",
            ]
            .map(String::from)
            .to_vec(),
            rows: paint_rows(reading),
        });
    }
    blocks.push(Block::Text(
        "Not computed yet from constituents: a rough clear coat (which whitens the colour), \
         aluminium and interference flakes (the flop and colour travel of the paints above); \
         docs/coatings.md says what exists."
            .into(),
    ));
    Ok(Section {
        title: "Coatings and multi-angle colour".into(),
        blocks,
        seconds: 0.0,
    })
}
