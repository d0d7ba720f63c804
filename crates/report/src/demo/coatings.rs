//! The demo report's coatings section: the multi-angle colour (ASTM E2194, D65/10°) of a red
//! under a smooth clear coat, computed from its constituents, and of the two paints measured at
//! Cornell, with their flop indices.

use super::pictures::EXAMPLES;
use crate::Result;
use crate::error::Context;
use crate::html::{Block, Section};
use crate::output::copy;
use gonio_brdf::formats::astm;
use gonio_coating::system::Coating;
use gonio_coating::{clear_coat, description};
use gonio_instrument::coating_study::Constituent;
use gonio_instrument::multiangle::{self, E2194, E2539, Geometry, MultiangleReading, Settings};
use std::path::Path;

fn f2(v: f64) -> String {
    format!("{v:.2}")
}

pub(super) fn coatings_section(dir: &Path, pictures: bool) -> Result<Section> {
    let wl = gonio_coating::system::default_bands();
    let settings = Settings::default();
    let toml = Path::new(EXAMPLES).join("coatings/red_solid.toml");
    let stack = description::read(&toml, &wl)?
        .clear_coat()
        .context("red_solid.toml: a smooth coat over a diffuse base")?;
    copy(&toml, &dir.join("red_solid.toml"))?;
    let optics = wl
        .iter()
        .map(|&w| stack.at(w))
        .collect::<gonio_coating::Result<Vec<_>>>()?;
    // The bare base: a Lambertian surface of the patch's reflectance.
    let rho: Vec<f64> = optics.iter().map(|at| at.rho).collect();
    let bare = multiangle::read_lambertian(&rho, &wl, &E2194, &settings)?;
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
    blocks.extend(effect_coatings(dir, &wl, &flop(&paints[0].1), pictures)?);
    Ok(Section {
        title: "Coatings and multi-angle colour".into(),
        blocks,
        seconds: 0.0,
    })
}

/// Walks per geometry for the layered coatings' readings: the spread of L* between repeated
/// readings is about 0.3 at this count (`gonio multiangle --samples`).
const WALKS: usize = 16384;

/// The coating of `examples/coatings/NAME`, as the commands read it, copied into `dir` beside
/// the report so that the commands shown run there.
fn example_coating(dir: &Path, name: &str, wl: &[f64]) -> Result<Coating> {
    let path = Path::new(EXAMPLES).join("coatings").join(name);
    copy(&path, &dir.join(name))?;
    Ok(description::read(&path, wl)?)
}

/// Its multi-angle reading at `geometries`, its BRDF evaluated there (no table).
fn read_coating(
    coating: &Coating,
    wl: &[f64],
    geometries: &[Geometry],
) -> Result<MultiangleReading> {
    Ok(gonio_instrument::coating_study::multiangle_reading(
        &coating.evaluator(wl)?,
        wl,
        geometries,
        WALKS,
        0,
    )?)
}

/// `coatings` (each a coating and the name of its description) side by side on curved panels
/// in the dark studio ([`gonio_render::panel`]): the picture `dir/NAME.png`, its caption `what`, and
/// the commands that make it again.
fn panel_picture(
    dir: &Path,
    name: &str,
    what: &str,
    coatings: &[(&Coating, &str)],
    study: Option<&str>,
) -> Result<Vec<Block>> {
    let mut panels = Vec::new();
    let mut commands: Vec<String> = study.into_iter().map(String::from).collect();
    for (i, (coating, source)) in coatings.iter().enumerate() {
        let table = format!("{name}-{}", i + 1);
        panels.push(gonio_render::panel::table(coating, source, dir, &table)?);
        // A variant of a description (the silver's spreads) has no file of its own to compute
        // from; its table is beside the scene all the same.
        if coatings.iter().filter(|(_, s)| s == source).count() == 1 {
            let res = gonio_render::panel::resolution(coating);
            commands.push(format!(
                "gonio coating compute {source} -o {table}.gbrdf --resolution {},{},{}",
                res.theta_h, res.theta_d, res.phi_d
            ));
        }
    }
    let scene = gonio_render::panel::scene(dir, name, &panels)?;
    let (png, stats) = gonio_render::panel::render(&scene)?;
    commands.push(format!("gonio render {name}.toml --spectral -o {name}.png"));
    Ok(vec![
        Block::Image {
            path: png,
            caption: format!(
                "{what}. Each panel's spectral table was computed for the picture (45 × 45 × \
                 24 nodes, smaller than gonio coating compute's default; {} walks per cell, or \
                 exactly for a smooth coat over a diffuse base, whose mirror the renderer adds); \
                 rendered spectrally (four hero wavelengths per path, D65), 16 samples per \
                 pixel, {:.2e} rays in {:.0} s, denoised (docs/render.md)",
                gonio_render::panel::WALKS,
                stats.rays as f64,
                stats.seconds
            ),
        },
        Block::Code(commands.join("\n")),
    ])
}

/// The red under a smooth and a rough coat, a silver metallic with a narrow and a wide flake
/// spread, and a pearlescent's colour travel: readings computed from the descriptions, and,
/// with `pictures`, the coatings drawn on curved panels.
fn effect_coatings(
    dir: &Path,
    wl: &[f64],
    cayman_flop: &str,
    pictures: bool,
) -> Result<Vec<Block>> {
    let smooth = example_coating(dir, "red_solid.toml", wl)?;
    let rough = example_coating(dir, "red_rough.toml", wl)?;
    let (smooth_r, rough_r) = (
        read_coating(&smooth, wl, &E2194)?,
        read_coating(&rough, wl, &E2194)?,
    );
    let diff = multiangle::differences(&rough_r, &smooth_r)?;
    let red_rows = smooth_r
        .geometries
        .iter()
        .zip(&rough_r.geometries)
        .zip(&diff)
        .map(|((s, r), d)| {
            vec![
                s.geometry.to_string(),
                f2(s.lab.l),
                f2(s.lab.chroma()),
                f2(r.lab.l),
                f2(r.lab.chroma()),
                f2(d.de00),
            ]
        })
        .collect();
    let silver = example_coating(dir, "silver_metallic.toml", wl)?;
    // The description with its flakes' tilt changed, as `gonio coating study --vary tilt` does.
    let spreads = [6.0, 12.0, 24.0]
        .iter()
        .map(|&tilt| Constituent::FlakeTilt.apply(&silver, tilt))
        .collect::<gonio_instrument::Result<Vec<Coating>>>()?;
    let [narrow, medium, wide] = [0, 1, 2].map(|i| read_coating(&spreads[i], wl, &E2194));
    let (narrow, medium, wide) = (narrow?, medium?, wide?);
    let flop = |r: &MultiangleReading| r.flop_index().map_or("—".into(), |f| format!("{f:.1}"));
    let silver_rows = narrow
        .geometries
        .iter()
        .zip(&medium.geometries)
        .zip(&wide.geometries)
        .map(|((n, m), w)| {
            vec![
                n.geometry.to_string(),
                f2(n.lab.l),
                f2(m.lab.l),
                f2(w.lab.l),
            ]
        })
        .collect();
    let pearl_coating = example_coating(dir, "pearl_interference.toml", wl)?;
    let pearl = read_coating(&pearl_coating, wl, &E2539)?;
    let hues: Vec<f64> = pearl
        .geometries
        .iter()
        .filter(|g| g.lab.chroma() > 10.0)
        .map(|g| g.lab.hue_deg())
        .collect();
    let hue_range = hues.iter().cloned().fold(f64::INFINITY, f64::min)
        ..hues.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let pearl_rows = pearl
        .geometries
        .iter()
        .map(|g| {
            vec![
                g.geometry.to_string(),
                f2(g.lab.l),
                f2(g.lab.a),
                f2(g.lab.b),
                f2(g.lab.chroma()),
                format!("{:.1}", g.lab.hue_deg()),
            ]
        })
        .collect();
    let (s15, r15) = (smooth_r.geometries[0].lab, rough_r.geometries[0].lab);
    let mut blocks = vec![
        Block::Text(format!(
            "The same red under a rough clear coat (examples/coatings/red_rough.toml: the \
             coat's surface a Beckmann microfacet surface of rms slope 0.15, about 8.5°). Light \
             now crosses the rough surface in every direction and the coat's own reflection \
             spreads from the mirror direction into the geometries the instrument reads: near \
             the specular direction the rough coat whitens the red (45as15: L* {:.1} → {:.1}, \
             C*ab {:.1} → {:.1}), while far from it the body colour is the smooth coat's \
             (45as45: ΔE00 {:.2}). These readings, like those below, evaluate the coating's \
             BRDF at each geometry by {WALKS} random walks (docs/coatings.md, \
             \"Transport\"), not through a table.",
            s15.l,
            r15.l,
            s15.chroma(),
            r15.chroma(),
            diff[2].de00,
        )),
        Block::Table {
            headers: [
                "geometry",
                "smooth L*",
                "smooth C*ab",
                "rough L*",
                "rough C*ab",
                "ΔE00",
            ]
            .map(String::from)
            .to_vec(),
            rows: red_rows,
        },
        Block::Text(format!(
            "A silver metallic (examples/coatings/silver_metallic.toml): aluminium flakes \
             covering 60% of a grey basecoat under a glossy clear coat, with three spreads of \
             the flakes' tilt (rms 6°, 12° and 24°). The flakes throw the light near the \
             specular direction; the narrower their spread, the brighter the face and the \
             darker the flank: flop index {} (6°), {} (12°), {} (24°). The measured Cayman \
             metallic above has {}. (At 45as45, L* {:.1} with the 12° spread.)",
            flop(&narrow),
            flop(&medium),
            flop(&wide),
            cayman_flop,
            medium.geometries[2].lab.l,
        )),
        Block::Table {
            headers: ["geometry", "L* (6°)", "L* (12°)", "L* (24°)"]
                .map(String::from)
                .to_vec(),
            rows: silver_rows,
        },
        Block::Text(format!(
            "A pearlescent (examples/coatings/pearl_interference.toml): mica flakes with 120 nm \
             of rutile on both faces over a black basecoat, read at the ASTM E2539 geometries \
             (45° and 15° illumination). The flakes' thin-film reflectance shifts to shorter \
             wavelengths as the angle inside the film grows, so the hue travels with the \
             geometry: hab from {:.0}° to {:.0}° where the colour is saturated (C*ab above 10); \
             far from the specular direction only the black base and the coat's surface remain.",
            hue_range.start, hue_range.end
        )),
        Block::Table {
            headers: ["geometry", "L*", "a*", "b*", "C*ab", "hab °"]
                .map(String::from)
                .to_vec(),
            rows: pearl_rows,
        },
        Block::Code(
            "gonio multiangle red_rough.toml --reference red_solid.toml\n\
             gonio multiangle silver_metallic.toml\n\
             gonio multiangle pearl_interference.toml --standard e2539\n\
             gonio coating study silver_metallic.toml --vary tilt --values 6,12,24"
                .into(),
        ),
    ];
    if !pictures {
        blocks.push(Block::Text(
            "The pictures of these coatings on curved panels are left out of the quick run.".into(),
        ));
        return Ok(blocks);
    }
    blocks.push(Block::Text(
        "The same coatings drawn on a curved, bonnet-like panel in a dark studio with two \
         softboxes: one behind the panels, which they mirror toward the camera (the face, near \
         the specular direction), one behind the camera (the flank, far from it). The red: \
         the smooth coat mirrors the softbox sharply over a deep red; the rough coat spreads \
         its reflection into a white sheen. The silver: the narrow spread is brilliant where \
         the panel mirrors the softbox and dark where it turns away (the flop); the wide \
         spread is evenly light. The pearlescent: its colour changes across the panel with \
         the angles."
            .into(),
    ));
    let red = [(&smooth, "red_solid.toml"), (&rough, "red_rough.toml")];
    blocks.extend(panel_picture(
        dir,
        "coatings-red",
        "The red under a smooth (left) and a rough (right) clear coat",
        &red,
        None,
    )?);
    let silver: Vec<(&Coating, &str)> = spreads
        .iter()
        .map(|c| (c, "silver_metallic.toml"))
        .collect();
    blocks.extend(panel_picture(
        dir,
        "coatings-silver",
        "The silver metallic with flake tilt spreads of 6° (left), 12° and 24° (right): \
         its description with the tilt changed, as the study below draws each on its own panel \
         (the grain on the 6° panel is the walks' noise in its table's flank, not sparkle)",
        &silver,
        Some(
            "gonio coating study silver_metallic.toml --vary tilt --values 6,12,24 -o silver-study",
        ),
    )?);
    blocks.extend(panel_picture(
        dir,
        "coatings-pearl",
        "The pearlescent (TiO2 120 nm on mica over black)",
        &[(&pearl_coating, "pearl_interference.toml")],
        None,
    )?);
    Ok(blocks)
}
