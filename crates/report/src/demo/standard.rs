//! The demo report's standard of appearance (issue 44, `docs/standard.md`): a silver metallic
//! and a red solid in the virtual viewing booth (`gonio_render::booth`), their three named
//! views as pictures of absolute CIE XYZ written with their display renderings, masks and
//! manifest as `gonio booth` writes them (`gonio_render::booth::write_booth_of`, from the
//! section's own tables), and the closure table: at each ASTM E2194 geometry, what
//! a picture of a flat panel reads against what the multi-angle instrument reads of the same
//! table ([`crate::closure`]); and the summary of the appearance conformance suite on gonio's
//! renderer (`gonio_conformance`, `docs/conformance.md`).

use super::pictures::EXAMPLES;
use crate::Result;
use crate::closure::{ClosureRow, closure};
use crate::error::Context;
use crate::html::{Block, Section};
use crate::output::{copy, create_dir};
use gonio_brdf::table::Resolution;
use gonio_coating::description;
use gonio_coating::system::default_bands;
use gonio_conformance::{Options, Renderer};
use gonio_instrument::multiangle::E2194;
use gonio_io::Progress;
use gonio_render::booth::closure::ClosurePicture;
use gonio_render::booth::{self, BoothSpec, Run, Specimen};
use gonio_render::material::Material;
use gonio_render::panel;
use gonio_render::picture::DisplaySpace;
use serde_json::json;
use std::path::Path;

/// The coatings shown: the file in `examples/coatings` and what the report calls it.
const COATINGS: [(&str, &str); 2] = [
    ("silver_metallic", "silver metallic"),
    ("red_solid", "red solid"),
];

/// How large the section's computations are.
struct Plan {
    /// The booth pictures' size and samples.
    width: usize,
    height: usize,
    spp: u32,
    /// The coatings' tables: `None` for the panel pictures' resolution
    /// ([`panel::resolution`]), and the walks per cell.
    resolution: Option<Resolution>,
    walks: usize,
    /// The closure's pictures.
    closure: ClosurePicture,
    /// The conformance suite's samples per pixel.
    conformance_spp: u32,
}

impl Plan {
    /// The full demo: the standard's own picture (480 × 320 pixels, 64 samples per pixel,
    /// `docs/standard.md`) from the panel pictures' tables, and the closure tests' pictures
    /// (24 × 24 pixels, 32 samples: noise bound about 0.1 ΔE00 on a solid, 0.3 on a metallic
    /// near the specular). Cost, measured 2026-12-06 with the machine shared (load 7–8): the
    /// whole section 79 s of CPU (158 s wall), about 40 s on the quiet 2-core machine at the
    /// demo's 1.9 cores, which keeps the demo (223 s before it) within its five minutes; half
    /// the samples would save about 15 s and show more grain, so the standard's own picture is
    /// kept. The quick run: small pictures of coarse tables, the same steps (6.6 s wall, loaded).
    fn new(quick: bool) -> Plan {
        if quick {
            Plan {
                width: 96,
                height: 64,
                spp: 4,
                resolution: Some(Resolution::isotropic(12, 12, 6)),
                walks: 2,
                closure: ClosurePicture {
                    size: 12,
                    spp: 8,
                    ..ClosurePicture::default()
                },
                conformance_spp: 8,
            }
        } else {
            Plan {
                width: 480,
                height: 320,
                spp: 64,
                resolution: None,
                walks: panel::WALKS,
                closure: ClosurePicture::default(),
                conformance_spp: 64,
            }
        }
    }
}

fn f2(v: f64) -> String {
    format!("{v:.2}")
}

/// The section: the booth pictures of each coating, their files, and the closure table.
pub(super) fn standard_section(dir: &Path, quick: bool, work: &Progress) -> Result<Section> {
    let plan = Plan::new(quick);
    let bands = default_bands();
    let mut blocks = vec![Block::Text(format!(
        "The virtual viewing booth is gonio's standard of appearance (docs/standard.md): a \
         normative scene after ASTM D1729 and ISO 3668 (CIE D65 at 2000 lx on the specimen, half \
         of it diffuse from an overhead diffuser over a Munsell N6 interior and half collimated \
         from 45°, a flat panel 150 × 100 mm, the CIE 1964 10° observer) whose pictures are \
         absolute CIE XYZ in cd/m² per pixel, so that a picture is a measurement. Each coating is \
         seen from the three named views of ASTM E2194's 45° illumination: near-specular \
         (45as15, the camera 30° past the normal), 45 (45as45, along the normal: the face) and \
         flank (45as110, 65° from the normal on the light's side: the flop). Shown here is the \
         sRGB rendering, the booth's white (the perfect diffuser, Y = E/π = {:.0} cd/m²) shown as \
         the display's white; beside each are the absolute XYZ (OpenEXR), the Display P3 \
         rendering, the masks of what each display cannot show, and a manifest of every file's \
         SHA-256 with the settings. The pictures are {} × {} pixels at {} samples per pixel, \
         rendered spectrally and not denoised: their grain is the Monte Carlo noise of the \
         samples' wavelengths, not the coating's texture; the coatings' flakes are in their \
         tables (no discrete sparkle).",
        BoothSpec::default().light.illuminance_lux / std::f64::consts::PI,
        plan.width,
        plan.height,
        plan.spp
    ))];
    let mut closure_rows = Vec::new();
    for (file, label) in COATINGS {
        let source = Path::new(EXAMPLES).join(format!("coatings/{file}.toml"));
        let out = dir.join("standard").join(file);
        create_dir(&out)?;
        let toml = out.join(format!("{file}.toml"));
        copy(&source, &toml)?;
        // Read from the copy, so that the manifest's input (and the files it names, beside
        // it) is what the table was made from.
        let coating = description::read(&toml, &bands)?;
        let resolution = plan
            .resolution
            .unwrap_or_else(|| panel::resolution(&coating));
        let method = coating.method(plan.walks);
        let table = coating
            .table(
                resolution,
                &bands,
                plan.walks,
                coating.provenance(format!("{file}.toml"), method),
            )
            .with_context(|| format!("{file}.toml: its table"))?;
        let coat = panel::coat_index(&coating);
        let mut material = Material::from_table("specimen", table.clone());
        if let Some(n) = coat {
            material = material.with_coat(n);
        }
        let mut spec = BoothSpec::default();
        spec.render.width = plan.width;
        spec.render.height = plan.height;
        spec.render.spp = plan.spp;
        let run = Run {
            progress: work.clone(),
            ..Run::default()
        };
        let made = json!({
            "table": {
                "resolution": [resolution.theta_h, resolution.theta_d, resolution.phi_d],
                "walks_per_cell": plan.walks,
            },
            "coat_index": coat,
        });
        let specimen = Specimen {
            material: &material,
            file: &toml,
            made: Some(&made),
        };
        let summary = booth::write_booth_of(&spec, None, &specimen, &out, &run)
            .with_context(|| format!("{file}: the booth's pictures"))?;
        for view in &summary.views {
            let files = &view.files;
            let srgb = files
                .displays
                .iter()
                .find(|d| d.space == DisplaySpace::Srgb)
                .context("write_view wrote no sRGB rendering")?;
            let p3 = files
                .displays
                .iter()
                .find(|d| d.space == DisplaySpace::DisplayP3)
                .context("write_view wrote no Display P3 rendering")?;
            blocks.push(Block::Image {
                path: srgb.png.clone(),
                caption: format!(
                    "{label}, view {} (aspecular {}°): mean luminance of the panel {:.0} \
                     cd/m²; beyond sRGB's gamut {:.1}% of the pixels, over its white {:.1}% (Display \
                     P3: {:.1}%, {:.1}%).",
                    view.name,
                    view.aspecular_deg,
                    view.specimen_luminance,
                    100.0 * srgb.out_of_gamut_fraction,
                    100.0 * srgb.over_range_fraction,
                    100.0 * p3.out_of_gamut_fraction,
                    100.0 * p3.over_range_fraction,
                ),
            });
            let rel = |p: &Path| -> String {
                p.strip_prefix(dir)
                    .unwrap_or(p)
                    .to_string_lossy()
                    .into_owned()
            };
            blocks.push(Block::Links {
                lead: format!("{label}, {}:", view.name),
                links: vec![
                    ("absolute XYZ (OpenEXR)".into(), rel(&files.exr)),
                    ("Display P3".into(), rel(&p3.png)),
                    ("sRGB mask".into(), rel(&srgb.mask)),
                    ("Display P3 mask".into(), rel(&p3.mask)),
                ],
            });
        }
        blocks.push(Block::Links {
            lead: format!("{label}: the files' SHA-256 and the settings:"),
            links: vec![(
                "manifest.json".into(),
                format!("standard/{file}/manifest.json"),
            )],
        });
        let rows = closure(
            &table,
            coat,
            &E2194,
            &plan.closure,
            &Run {
                progress: work.clone(),
                ..Run::default()
            },
        )
        .with_context(|| format!("{file}: the closure"))?;
        closure_rows.push((label, rows));
    }
    if let Some((label, row)) = closure_rows
        .iter()
        .flat_map(|(label, rows)| rows.iter().map(move |r| (label, r)))
        .filter(|(_, r)| r.instrument.l > 100.0)
        .max_by(|a, b| a.1.instrument.l.total_cmp(&b.1.instrument.l))
    {
        blocks.push(Block::Text(format!(
            "The {label} is brighter than the white where it is seen near the specular (L* {:.1} \
             at {}, in the table below): its renderings clip there, as the over-range masks \
             show, and the OpenEXR keeps its luminance.",
            row.instrument.l, row.geometry
        )));
    }
    blocks.extend(closure_blocks(&closure_rows, &plan.closure));
    blocks.extend(conformance_blocks(dir, plan.conformance_spp)?);
    Ok(Section {
        title: "Standard of appearance: the viewing booth".into(),
        blocks,
        seconds: 0.0,
    })
}

/// The conformance suite on gonio's renderer at `spp` samples per pixel, its report in
/// `dir/conformance`: a paragraph, the summary table (each scene's verdict and its checks) and
/// the link to the suite's own report.
fn conformance_blocks(dir: &Path, spp: u32) -> Result<Vec<Block>> {
    let out = dir.join("conformance");
    let (results, _) = crate::conformance::run(&Options {
        renderers: vec![Renderer::Gonio],
        spp,
        dir: out,
    })?;
    let rows: Vec<Vec<String>> = results
        .scenes
        .iter()
        .flat_map(|s| {
            s.runs.iter().map(move |r| {
                let worst = r
                    .checks
                    .iter()
                    .filter(|c| c.tolerance > 0.0)
                    .map(|c| (c.value - c.reference).abs() / c.tolerance)
                    .fold(0.0, f64::max);
                vec![
                    s.scene.id.name().to_string(),
                    s.scene.title.clone(),
                    crate::conformance::verdict_name(r.verdict).to_string(),
                    format!(
                        "{} of {}",
                        r.checks.iter().filter(|c| c.pass).count(),
                        r.checks.len()
                    ),
                    format!("{worst:.2}"),
                ]
            })
        })
        .collect();
    let passed = results.passed();
    Ok(vec![
        Block::Text(format!(
            "Conformance: the renderer that draws the booth's pictures, on appearance test \
             scenes with analytic references (in the spirit of CIE 171:2006; docs/conformance.md), \
             {0} × {0} pixels at {1} samples per pixel. Each check is a region's value against its \
             closed form within its tolerance (four standard errors of the Monte Carlo mean; for \
             a colour, the ΔE00 that noise allows); the last column is \
             the largest |value − reference| / tolerance of the scene's checks (under 1 passes). \
             {2} The command gonio conformance runs the same suite on Mitsuba 3 and Radiance too, through \
             gonio's exports.",
            results.size,
            results.spp,
            if passed {
                "gonio passes every scene."
            } else {
                "gonio FAILS a scene."
            }
        )),
        Block::Table {
            headers: ["scene", "what", "verdict", "checks holding", "worst / tolerance"]
                .map(String::from)
                .to_vec(),
            rows,
        },
        Block::Links {
            lead: "The suite's own report, with each scene's pictures, difference images and FLIP maps:"
                .into(),
            links: vec![("report.html".into(), "conformance/report.html".into())],
        },
    ])
}

/// The closure's paragraph and table.
fn closure_blocks(rows: &[(&str, Vec<ClosureRow>)], picture: &ClosurePicture) -> Vec<Block> {
    let worst = rows
        .iter()
        .flat_map(|(_, r)| r.iter())
        .map(|r| r.delta_e00)
        .fold(0.0, f64::max);
    let within = rows
        .iter()
        .flat_map(|(_, r)| r.iter())
        .all(|r| r.delta_e00 < 0.5 + r.noise_bound);
    vec![
        Block::Text(format!(
            "Closure: the picture says what the instrument says. A flat panel of each coating's \
             table, lit by the booth's collimated light alone at the geometry's illumination and \
             seen by a distant camera at its aspecular angle ({0} × {0} pixels, {1} samples \
             each), has its specimen pixels averaged and turned into CIELAB against the perfect \
             diffuser under the same light (D65, 10°); beside it, gonio multiangle's reading \
             of the same table (point apertures). The noise bound is the largest ΔE00 from \
             moving the picture's mean by three standard errors (from the pixels' spread) in X, \
             Y or Z. Largest difference here {worst:.3} ΔE00; {2}. The test suite holds every \
             E2539 geometry of three coatings to 0.5 ΔE00 plus the noise bound \
             (crates/render/tests/it/booth.rs).",
            picture.size,
            picture.spp,
            if within {
                "every difference within 0.5 ΔE00 plus its noise bound"
            } else {
                "NOT every difference within 0.5 ΔE00 plus its noise bound"
            }
        )),
        Block::Table {
            headers: [
                "coating",
                "geometry",
                "instrument L*",
                "a*",
                "b*",
                "picture L*",
                "a*",
                "b*",
                "ΔE00",
                "noise bound",
            ]
            .map(String::from)
            .to_vec(),
            rows: rows
                .iter()
                .flat_map(|(label, r)| {
                    r.iter().map(move |r| {
                        vec![
                            label.to_string(),
                            r.geometry.to_string(),
                            f2(r.instrument.l),
                            f2(r.instrument.a),
                            f2(r.instrument.b),
                            f2(r.picture.l),
                            f2(r.picture.a),
                            f2(r.picture.b),
                            format!("{:.3}", r.delta_e00),
                            format!("{:.3}", r.noise_bound),
                        ]
                    })
                })
                .collect(),
        },
    ]
}
