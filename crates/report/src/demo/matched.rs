//! The formulation section's three Cornell paints matched from the pigment library: each fitted
//! formulation (`examples/coatings/*_fitted.toml`, read when the demo runs) against its measured
//! BRDF at the ASTM E2539 geometries and at every measured sample
//! (`gonio_formulation::prediction`, what `gonio coating predict` prints), a swatch strip of
//! measurement against match at every geometry, and a picture of the measured BRDFs beside the
//! fitted formulations (`examples/cornell_matched.toml`).

use super::pictures::{EXAMPLES, copy_scene, denoised_note, options};
use super::swatch_strip::{self, Pair, Row};
use crate::Result;
use crate::error::Context;
use crate::html::Block;
use crate::output::copy;
use gonio_coating::system::default_bands;
use gonio_formulation::measured_samples::PEAK_DEG;
use gonio_formulation::prediction::{self, Prediction};
use gonio_instrument::multiangle::E2539;
use gonio_io::Progress;
use gonio_render::{ColourMode, Scene, render_picture};
use std::path::Path;

/// A Cornell paint and its match.
struct Paint {
    name: &'static str,
    kind: &'static str,
    /// The fitted formulation, in examples/coatings/.
    fitted: &'static str,
    /// The measured BRDF, in crates/brdf/tests/data/.
    measured: &'static str,
}

const PAINTS: [Paint; 3] = [
    Paint {
        name: "Krylon Blue",
        kind: "a glossy blue solid",
        fitted: "krylon_blue_fitted.toml",
        measured: "krylon_blue.astm",
    },
    Paint {
        name: "Cayman",
        kind: "a blue-green metallic with aluminium flakes inside the basecoat",
        fitted: "cayman_library_fitted.toml",
        measured: "cayman.astm",
    },
    Paint {
        name: "Garnet Red",
        kind: "a red metallic",
        fitted: "garnet_red_fitted.toml",
        measured: "garnet_red.astm",
    },
];

/// The matches were fitted at the E2539 geometries lit at 45° (`gonio coating match`,
/// docs/formulation.md); those lit at 15° are predictions.
const FITTED_ILLUMINATION_DEG: f64 = 45.0;

/// Walks per geometry and per measured sample of the demo's readings: a sixteenth of `gonio
/// coating predict`'s default 4096, so that the three paints take seconds rather than minutes
/// (the 1439 samples dominate). The noise of L* grows by √16 = 4; measured on the three paints'
/// first formulations, the ΔE00 per geometry moved by up to 0.53 from those at 4096 walks (0.03
/// on the solid Krylon Blue) and the whole-BRDF means by up to 0.12.
const WALKS: usize = 256;
/// The quick demo's walks and paints (the first): the tables' layout, not their figures. Each
/// paint costs about 3 s of CPU whatever the walks (reading the measured BRDF).
const WALKS_QUICK: usize = 16;
const PAINTS_QUICK: usize = 1;

/// "fitted" or "predicted" for geometries lit at `illumination_deg`.
fn role(illumination_deg: f64) -> &'static str {
    if illumination_deg == FITTED_ILLUMINATION_DEG {
        "fitted"
    } else {
        "predicted"
    }
}

/// L* a* b* to one decimal.
fn lab_text(l: gonio_color::Lab) -> String {
    format!("{:.1} {:.1} {:.1}", l.l, l.a, l.b)
}

/// One paint's geometry table and swatch strip.
fn paint_blocks(paint: &Paint, p: &Prediction, dir: &Path) -> Result<Vec<Block>> {
    let mut rows: Vec<Vec<String>> = vec![];
    // The strip's rows, one per illumination angle, in the order of the geometries.
    let mut strip: Vec<(f64, Row)> = vec![];
    for ((g, measured), de00) in p.target.colours.iter().zip(&p.de00) {
        let matched = p
            .reading
            .at(*g)
            .with_context(|| format!("{}: no reading at {g}", paint.fitted))?
            .lab;
        rows.push(vec![
            g.to_string(),
            role(g.illumination_deg).into(),
            lab_text(*measured),
            lab_text(matched),
            format!("{de00:.2}"),
        ]);
        let pair = Pair {
            label: g.to_string(),
            measured: *measured,
            matched,
            de00: *de00,
        };
        match strip.last_mut() {
            Some((t, row)) if *t == g.illumination_deg => row.pairs.push(pair),
            _ => strip.push((
                g.illumination_deg,
                Row {
                    label: [
                        format!("lit at {}°", g.illumination_deg),
                        role(g.illumination_deg).into(),
                    ],
                    pairs: vec![pair],
                },
            )),
        }
    }
    for (t, mean, n) in p.by_illumination() {
        rows.push(vec![
            format!("mean, lit at {t}°"),
            format!("{} ({n})", role(t)),
            String::new(),
            String::new(),
            format!("{mean:.2}"),
        ]);
    }
    let stem = paint.fitted.trim_end_matches(".toml");
    let png = dir.join(format!("{stem}_swatches.png"));
    swatch_strip::draw(
        &png,
        &format!("{}: measured | fitted formulation, ASTM E2539", paint.name),
        &strip.into_iter().map(|(_, row)| row).collect::<Vec<_>>(),
    )?;
    Ok(vec![
        Block::Table {
            headers: [
                "geometry",
                "fitted or predicted",
                "measured L* a* b*",
                "formulation L* a* b*",
                "ΔE00",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        },
        Block::Image {
            path: png,
            caption: format!(
                "{}: the measurement (left of each pair) and the fitted formulation (right) at \
                 the E2539 geometries; the row lit at 15° was not fitted",
                paint.name
            ),
        },
    ])
}

/// The whole-BRDF summary of each paint: every measured sample against the formulation.
fn samples_table(paints: &[(&Paint, Prediction)]) -> Block {
    let rows = paints
        .iter()
        .filter_map(|(paint, p)| {
            let s = p.samples.as_ref()?;
            Some(vec![
                paint.name.to_string(),
                s.off_peak.count.to_string(),
                format!("{:.2}", s.off_peak.mean_de00),
                format!("{:.2}", s.off_peak.median_de00),
                format!("{:.2}", s.off_peak.p90_de00),
                format!("{:.2}", 10f64.powf(s.off_peak.median_abs_log10_y)),
                format!("{:.2}", s.peak.mean_de00),
            ])
        })
        .collect();
    Block::Table {
        headers: vec![
            "paint".into(),
            format!("samples off the peak (half vector ≥ {PEAK_DEG}° from the normal)"),
            "mean ΔE00".into(),
            "median ΔE00".into(),
            "90% ΔE00".into(),
            "luminance within a factor (median)".into(),
            "mean ΔE00 on the peak".into(),
        ],
        rows,
    }
}

/// The measured BRDFs beside the fitted formulations in the studio, rendered as the report's
/// other pictures are.
fn picture(dir: &Path, work: &Progress) -> Result<Vec<Block>> {
    const SCENE: &str = "cornell_matched.toml";
    let path = copy_scene(&Path::new(EXAMPLES).join(SCENE), dir)?;
    let scene = Scene::from_file(&path)?;
    let (image, estimate) = render_picture(&scene, &options(ColourMode::Tristimulus, None, work))?;
    let png = dir.join("cornell_matched.png");
    image.write(&png, scene.display)?;
    let stats = estimate.stats;
    Ok(vec![
        Block::Image {
            path: png,
            caption: format!(
                "In each pair the measured BRDF (left) and the fitted formulation (right): \
                 Krylon Blue, Cayman and Garnet Red in the studio of metallic.toml ({} × {} px, \
                 {:.2e} rays in {:.0} s{})",
                image.width,
                image.height,
                stats.rays as f64,
                stats.seconds,
                denoised_note(&stats)
            ),
        },
        Block::Code(format!("gonio render {SCENE} -o cornell_matched.png")),
    ])
}

/// The blocks of the three paints (`quick`: the first): the text, per paint its table and
/// swatch strip, the whole-BRDF table, the commands and (unless `quick`) the picture. The
/// formulations and measurements are copied beside the report so that the commands run as
/// written there.
pub(super) fn blocks(dir: &Path, quick: bool, work: &Progress) -> Result<Vec<Block>> {
    let (walks, paints) = if quick {
        (WALKS_QUICK, &PAINTS[..PAINTS_QUICK])
    } else {
        (WALKS, &PAINTS[..])
    };
    let coatings = Path::new(EXAMPLES).join("coatings");
    let data = Path::new(EXAMPLES).join("../crates/brdf/tests/data");
    let mut predictions = vec![];
    let mut seconds = 0.0;
    for paint in paints {
        let fitted = coatings.join(paint.fitted);
        let measured = data.join(paint.measured);
        for file in [&fitted, &measured] {
            let name = file.file_name().context("a file has a name")?;
            copy(file, &dir.join(name))?;
        }
        let coating = gonio_coating::description::read(&fitted, &default_bands())?;
        let p = prediction::predict(&coating, &measured, &E2539, walks)
            .with_context(|| format!("{} against {}", paint.fitted, paint.measured))?;
        seconds += p.seconds;
        predictions.push((paint, p));
    }
    let mut blocks = vec![Block::Text(format!(
        "From a measurement back to a formulation: paints measured at Cornell (Cornell \
         University Program of Computer Graphics reflectance data) — {} — each matched by a \
         formulation of gonio's pigment library (gonio pigments) in a clear-coated basecoat, \
         from examples/coatings/*_start.toml by gonio coating match. The matches were fitted \
         to the multi-angle colour at the ASTM E2539 geometries lit at 45° (aspecular −15 to \
         110°); the geometries lit at 15° and the 1439 samples of each measured BRDF (θi \
         10–80°, out of the plane included) were not fitted, and show what the formulation \
         predicts. Each table and swatch strip compares the measurement with the formulation \
         (CIELAB D65/10°, ΔE00); the last table every measured sample, off the gloss peak and \
         on it (gonio coating predict, {walks} walks per geometry and per sample, in \
         {seconds:.0} s; at 4096 walks, the default, the metallics' ΔE00 move by a few tenths). \
         docs/formulation.md has the matches' figures at 4096 walks and their times.",
        paints
            .iter()
            .map(|p| format!("{} ({})", p.name, p.kind))
            .collect::<Vec<_>>()
            .join("; ")
    ))];
    for (paint, p) in &predictions {
        blocks.extend(paint_blocks(paint, p, dir)?);
    }
    blocks.push(samples_table(&predictions));
    blocks.push(Block::Code(
        paints
            .iter()
            .map(|p| {
                format!(
                    "gonio coating predict {} --target {} --walks {walks}",
                    p.fitted, p.measured
                )
            })
            .collect::<Vec<_>>()
            .join("\n"),
    ));
    if !quick {
        blocks.extend(picture(dir, work)?);
    }
    Ok(blocks)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The full demo alone reads the second and third paints and renders the scene: here each
    /// paint's files read, and the scene names them all, bare, once copied beside the report.
    #[test]
    fn every_paint_and_the_scene_name_files_that_read() {
        let dir = tempfile::tempdir().unwrap();
        let copy = copy_scene(
            &Path::new(EXAMPLES).join("cornell_matched.toml"),
            dir.path(),
        )
        .unwrap();
        let scene = std::fs::read_to_string(&copy).unwrap();
        assert!(!scene.contains(".."), "a path still leaves the folder");
        for paint in &PAINTS {
            gonio_coating::description::read(&dir.path().join(paint.fitted), &default_bands())
                .unwrap();
            gonio_brdf::formats::astm::read(&dir.path().join(paint.measured)).unwrap();
            for name in [paint.fitted, paint.measured] {
                assert!(
                    scene.contains(&format!("\"{name}\"")),
                    "{name} not in the scene"
                );
            }
        }
    }
}
