//! The demo report's texture section: the sparkle and graininess of the silver metallic at a
//! fine and a coarse flake size, read by the virtual texture camera from pictures of its flakes
//! drawn one by one ([`gonio_render::texture`]), and the orange peel of a glossy clear coat: a
//! synthetic `q^-4` height map ([`gonio_surface::synth_psd`]) at two levels of slope, its
//! wave-scan bands ([`gonio_surface::waviness`]) and DOI, and a dark panel carrying it as a
//! mesoscale map ([`gonio_render::mesoscale`]) mirroring a row of tubes.

use super::pictures::{EXAMPLES, options};
use crate::Result;
use crate::error::Context;
use crate::html::{Block, Section};
use crate::orange_peel::{DEFAULT_EXPONENT, DEFAULT_LONG_MM, DEFAULT_SHORT_MM};
use crate::output::{read_text, write_bytes};
use crate::texture_pictures::{median_grey, write_pictures};
use gonio_instrument::meter::{MapMethod, read_height_map};
use gonio_io::Progress;
use gonio_plot::render_png;
use gonio_render::texture::{LAMP_RADIUS_DEG, TextureCamera, TextureReading, measure};
use gonio_render::{ColourMode, Display, Image, Scene, ToneCurve, render_picture};
use gonio_surface::synth_psd::{PsdSurface, Spectrum, Target};
use gonio_surface::waviness::{self, BandReading, Direction, Quantity};
use plotters::prelude::*;
use std::path::Path;

/// The flake diameters of the close-ups, µm: a fine and a coarse grade of aluminium effect
/// pigment (automotive grades span roughly 10 to 35 µm, `Flakes::DEFAULT_DIAMETER_UM`).
const DIAMETERS_UM: [f64; 2] = [12.0, 35.0];

/// The linear value at which the sparkle pictures show the surround between the spots (a dark
/// grey, so that the spots, ten times as bright or more, stand out as they do in a texture
/// camera's picture).
const SURROUND_SHOWN: f64 = 0.04;

/// The orange peel's levels: rms slope along x, mrad (1 is `gonio surface gen`'s default, a
/// good automotive finish; 3 a visible orange peel).
const PEEL_SLOPES_MRAD: [f64; 2] = [1.0, 3.0];

/// The seed of the orange-peel maps (one map, scaled).
const PEEL_SEED: u64 = 3;

/// The clear coat's refractive index for the DOI meter.
const COAT_INDEX: f64 = 1.5;

/// The pictures the texture camera takes of a coating: the lamp at three angles, diffuse
/// light, and diffuse light again with independent samples (`gonio_render::texture::measure`).
const TEXTURE_PICTURES: u64 = 5;

/// The sizes of the section's computations.
struct Plan {
    camera: TextureCamera,
    /// Points a side of the orange-peel map and their spacing, µm.
    peel_points: usize,
    peel_dx_um: f64,
    /// The panel picture's size, pixels, and samples per pixel.
    panel_px: (usize, usize),
    panel_spp: u32,
}

impl Plan {
    fn new(quick: bool) -> Plan {
        if quick {
            Plan {
                camera: TextureCamera {
                    field_mm: 1.5,
                    pixel_um: 15.0,
                    spp: 4,
                    ..TextureCamera::default()
                },
                peel_points: 256,
                peel_dx_um: 100.0,
                panel_px: (192, 128),
                panel_spp: 4,
            }
        } else {
            Plan {
                camera: TextureCamera {
                    field_mm: 4.0,
                    pixel_um: 10.0,
                    spp: 8,
                    ..TextureCamera::default()
                },
                peel_points: 1024,
                peel_dx_um: 100.0,
                panel_px: (480, 320),
                panel_spp: 16,
            }
        }
    }
}

pub(super) fn texture_section(dir: &Path, quick: bool, work: &Progress) -> Result<Section> {
    let plan = Plan::new(quick);
    let mut blocks = sparkle_blocks(dir, &plan, work)?;
    blocks.extend(orange_peel_blocks(dir, &plan, work)?);
    Ok(Section {
        title: "Texture: sparkle, graininess and orange peel".into(),
        blocks,
        seconds: 0.0,
    })
}

/// The silver metallic's description with its flakes `diameter_um` across, written into `dir`
/// as `silver_{d}um.toml` (so that `gonio texture` runs on it there), and its name.
fn silver_with_diameter(dir: &Path, diameter_um: f64) -> Result<String> {
    let source = Path::new(EXAMPLES).join("coatings/silver_metallic.toml");
    let text = read_text(&source)?;
    let at = text
        .find("[flakes]\n")
        .with_context(|| format!("{}: no [flakes] table", source.display()))?
        + "[flakes]\n".len();
    let name = format!("silver_{diameter_um}um.toml");
    let text = format!(
        "{}diameter_um = {diameter_um}            # set by gonio demo (default 20)\n{}",
        &text[..at],
        &text[at..]
    );
    write_bytes(&dir.join(&name), text.as_bytes())?;
    Ok(name)
}

fn sparkle_blocks(dir: &Path, plan: &Plan, work: &Progress) -> Result<Vec<Block>> {
    let camera = &plan.camera;
    let wl = gonio_coating::system::default_bands();
    let mut readings = Vec::new();
    let mut commands = Vec::new();
    let mut pictures = Vec::new();
    for &d in &DIAMETERS_UM {
        let name = silver_with_diameter(dir, d)?;
        let coating = gonio_coating::description::read(&dir.join(&name), &wl)?;
        let reading = measure(&coating, &name, camera, &|k, what| {
            work.report(what, k.saturating_sub(1) as u64, TEXTURE_PICTURES)
        })?;
        let folder = format!("texture-{d}um");
        write_pictures(&reading, &dir.join(&folder))?;
        commands.push(format!(
            "gonio texture {name} --field-mm {} --pixel-um {} --spp {} -o {folder}",
            camera.field_mm, camera.pixel_um, camera.spp
        ));
        let png = dir.join(format!("texture-{d}um.png"));
        let lamp = &reading.sparkle[0];
        side_by_side(
            &png,
            &[
                (
                    format!("lamp at {}°", lamp.angle_deg),
                    &lamp.image,
                    Display {
                        exposure: (SURROUND_SHOWN / lamp.sparkle.surround).log2(),
                        tone: ToneCurve::Filmic,
                    },
                ),
                (
                    "diffuse light".to_string(),
                    &reading.diffuse,
                    median_grey(&reading.diffuse),
                ),
            ],
            Some(camera.pixel_um),
        )?;
        pictures.push(Block::Image {
            path: png,
            caption: format!(
                "Silver metallic, flakes {d} µm across: the camera's {} mm field ({} × {} \
                 pixels of {} µm, {} samples each) under the lamp at {}° (left; {} spots, \
                 sparkle grade {:.1}%), exposed so that the base between the spots shows dark \
                 grey and every spot, ten times as bright or more, near white; and under diffuse \
                 light (right; graininess {:.2}%), exposed so that its median shows mid-grey. \
                 The bar is 1 mm",
                camera.field_mm,
                camera.pixels(),
                camera.pixels(),
                camera.pixel_um,
                camera.spp,
                lamp.angle_deg,
                lamp.sparkle.spots,
                lamp.sparkle.grade,
                reading.graininess,
            ),
        });
        readings.push((d, reading));
    }
    // The text's paragraphs, one block each.
    let mut blocks: Vec<Block> = sparkle_text(camera, &readings)
        .split('\n')
        .map(|p| Block::Text(p.to_string()))
        .collect();
    blocks.extend(pictures);
    blocks.push(Block::Table {
        headers: [
            "flake Ø (µm)",
            "lamp (°)",
            "spots",
            "density (1/mm²)",
            "area (%)",
            "intensity (contrast)",
            "grade (%)",
        ]
        .map(String::from)
        .to_vec(),
        rows: readings
            .iter()
            .flat_map(|(d, r)| {
                r.sparkle.iter().map(move |s| {
                    let p = &s.sparkle;
                    vec![
                        format!("{d}"),
                        format!("{}", s.angle_deg),
                        format!("{}", p.spots),
                        format!("{:.1}", p.density_per_mm2),
                        format!("{:.3}", p.area_percent),
                        // The mean peak contrast of no spot is none.
                        if p.spots > 0 {
                            format!("{:.0}", p.intensity)
                        } else {
                            "—".into()
                        },
                        format!("{:.1}", p.grade),
                    ]
                })
            })
            .collect(),
    });
    blocks.push(Block::Table {
        headers: ["flake Ø (µm)", "graininess (%)"]
            .map(String::from)
            .to_vec(),
        rows: readings
            .iter()
            .map(|(d, r)| vec![format!("{d}"), format!("{:.2}", r.graininess)])
            .collect(),
    });
    blocks.push(Block::Code(commands.join("\n")));
    Ok(blocks)
}

/// What the sparkle readings mean, with this run's numbers: paragraphs separated by newlines.
fn sparkle_text(camera: &TextureCamera, readings: &[(f64, TextureReading)]) -> String {
    let at15 = |k: usize| &readings[k].1.sparkle[0].sparkle;
    let (fine, coarse) = (at15(0), at15(1));
    format!(
        "Up close a metallic sparkles: single flakes that face the lamp flash, and under \
         diffuse light the finish looks grainy. gonio's virtual texture camera draws the flakes \
         of a coating one by one (positions, sizes and tilts drawn from the description's \
         coverage, rms tilt and mean diameter; docs/render.md) in the geometry of the \
         multi-angle texture cameras: the camera along the normal, a lamp {LAMP_RADIUS_DEG}° in \
         radius at 15°, 45° and 75° from it, then a uniform hemisphere. Here the silver \
         metallic of the coatings section (aluminium flakes covering 60% of a grey base, 12° rms \
         tilt, under a glossy clear coat) with fine flakes {} µm across and coarse ones {} µm \
         across at the same coverage, in a {} mm field at {} µm per pixel.\n\
         What the readings mean (gonio's own scales, defined from the published descriptions of \
         the CIE work on sparkle and graininess: docs/instruments.md, section \"Texture\"; they \
         are not a commercial instrument's numbers and do not convert to them). A spot is a \
         group of pixels at least ten times as bright as the surround (the mean of the pixels \
         outside spots). Density: spots per mm². Area: the share of the field in spots, %. \
         Intensity: the spots' mean peak contrast to the surround; a flake that mirrors the \
         lamp is thousands of times as bright as the base around it, hence the large numbers. \
         Grade: by how much the spots raise the field's mean luminance over the surround, % \
         (area and intensity in one number, so it exceeds 100% when a fraction of a percent of \
         the field shines thousands of times brighter). Graininess: the coefficient of \
         variation of the luminance under diffuse light, %, with the renders' own noise taken \
         out; at this pixel the flakes are resolved, so it is the contrast between flakes and \
         the gaps between them (tens of %), and it falls as a coarser pixel averages more \
         flakes.\n\
         What grows with what. At constant coverage coarse flakes are fewer and each brighter: \
         under the lamp at 15° {} spots against {} ({:.1} against {:.1} per mm²), intensity \
         {:.0} against {:.0}, grade {:.1}% against {:.1}%, and graininess {:.2}% against {:.2}%, \
         coarse against fine. As the lamp moves to 45° and 75° a flake must tilt by half that \
         angle to mirror it into the camera, and fewer of the 12° spread do: the spots thin out, \
         while each stands out more against a base that the oblique lamp lights less. A wider \
         tilt spread puts fewer flakes near the normal: fewer spots and a lower grade at 15° \
         (the texture camera's tests at 6°, 12° and 24°, crates/render/tests/it/texture.rs).\n\
         Limits: the flakes lie flat at one depth under a flat coat (no stacking, no \
         orientation from the spray), the lamp is a disc of fixed size (a larger lamp lights \
         more flakes), the readings use the pictures' luminance only (not the sparkle's colour), and a \
         field of a few mm² holds tens to hundreds of spots, so their count varies by about its \
         square root from one field to the next.",
        DIAMETERS_UM[0],
        DIAMETERS_UM[1],
        camera.field_mm,
        camera.pixel_um,
        coarse.spots,
        fine.spots,
        coarse.density_per_mm2,
        fine.density_per_mm2,
        coarse.intensity,
        fine.intensity,
        coarse.grade,
        fine.grade,
        readings[1].1.graininess,
        readings[0].1.graininess,
    )
}

/// The orange-peel map of rms slope `slope_mrad` (along x): `gonio surface gen`'s default
/// power law, `plan.peel_points` a side at `plan.peel_dx_um`.
fn peel_map(plan: &Plan, slope_mrad: f64) -> Result<gonio_surface::HeightMap> {
    let dx = plan.peel_dx_um * 1e-6;
    Ok(PsdSurface {
        spectrum: Spectrum::PowerLaw {
            exponent: DEFAULT_EXPONENT,
            long: DEFAULT_LONG_MM * 1e-3,
            short: DEFAULT_SHORT_MM * 1e-3,
        },
        target: Target::SlopeX(slope_mrad * 1e-3),
        nx: plan.peel_points,
        ny: plan.peel_points,
        dx,
        dy: dx,
        seed: PEEL_SEED,
    }
    .generate()?)
}

/// The panel scene of `examples/orange_peel.toml` with the map `map_file`, framed closer on
/// the tubes' reflection, at `plan`'s size.
fn peel_scene(plan: &Plan, map_file: &str) -> String {
    let (w, h) = plan.panel_px;
    let tubes: String = [0.4, 0.5, 0.6, 0.7, 0.8]
        .iter()
        .map(|y| {
            format!(
                "[[lights]]\ntype = \"rectangle\"\nsize = [1.6, 0.02]\n\
                 rotate_deg = [0.0, 180.0, 0.0]\ntranslate = [0.0, {y}, 2.0]\nradiance = 20.0\n\n"
            )
        })
        .collect();
    format!(
        "# A dark glossy panel whose clear coat carries the orange-peel map {map_file}, mirroring\n\
         # five fluorescent tubes behind the camera (examples/orange_peel.toml, written by gonio demo).\n\n\
         [camera]\nposition = [0.0, -0.3, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 16\n\
         width = {w}\nheight = {h}\nexposure = 0.0\ntone = \"filmic\"\n\n\
         [render]\nspp = {}\nmax_bounces = 3\ndenoise = true\n\n\
         [materials.paint]\n\
         brdf = {{ model = \"ggx\", alpha = 0.0005, index = {COAT_INDEX}, diffuse = [0.03, 0.012, 0.01] }}\n\
         mesoscale = {{ file = \"{map_file}\" }}\n\n\
         [[shapes]]\ntype = \"rectangle\"\nsize = [0.5, 0.33]\nmaterial = \"paint\"\n\n\
         {tubes}[[lights]]\ntype = \"sky\"\nradiance = 0.03\n",
        plan.panel_spp
    )
}

/// One orange-peel map: its rms slope, what the meters read, and its picture.
struct PeelLevel {
    slope_mrad: f64,
    bands: Vec<BandReading>,
    gloss: gonio_instrument::gloss::GlossReport,
    image: Image,
    display: Display,
    stats: gonio_render::RenderStats,
}

fn orange_peel_blocks(dir: &Path, plan: &Plan, work: &Progress) -> Result<Vec<Block>> {
    let mut levels = Vec::new();
    let mut commands = Vec::new();
    for &slope in &PEEL_SLOPES_MRAD {
        let map = peel_map(plan, slope)?;
        let stem = format!("peel-{slope}mrad");
        let map_file = format!("{stem}.x3p");
        gonio_surface::io::write(&map, &dir.join(&map_file))?;
        let bands = waviness::waviness(&map, Direction::X, Quantity::Slope)?;
        let gloss = read_height_map(&map, MapMethod::Ray, COAT_INDEX)?.report;
        let scene_file = format!("orange_peel_{slope}mrad.toml");
        let text = peel_scene(plan, &map_file);
        write_bytes(&dir.join(&scene_file), text.as_bytes())?;
        let scene = Scene::from_file(&dir.join(&scene_file))?;
        let (image, estimate) =
            render_picture(&scene, &options(ColourMode::Tristimulus, None, work))?;
        let png = format!("orange_peel_{slope}mrad.png");
        image.write(&dir.join(&png), scene.display)?;
        commands.push(format!(
            "gonio surface gen --psd-exponent {DEFAULT_EXPONENT} --long-mm {DEFAULT_LONG_MM} \
             --short-mm {DEFAULT_SHORT_MM} --slope-mrad {slope} --size {n} --dx-um {dx} \
             --seed {PEEL_SEED} -o {map_file}\n\
             gonio surface waviness {map_file}\n\
             gonio gloss {map_file} --index {COAT_INDEX}\n\
             gonio render {scene_file} -o {png}",
            n = plan.peel_points,
            dx = plan.peel_dx_um,
        ));
        levels.push(PeelLevel {
            slope_mrad: slope,
            bands,
            gloss,
            image,
            display: scene.display,
            stats: estimate.stats,
        });
    }
    let png = dir.join("orange_peel.png");
    let panels: Vec<(String, &Image, Display)> = levels
        .iter()
        .map(|l| {
            (
                format!("{} mrad rms slope, DOI {:.0}", l.slope_mrad, l.gloss.doi),
                &l.image,
                l.display,
            )
        })
        .collect();
    side_by_side(&png, &panels, None)?;
    let side = plan.peel_points as f64 * plan.peel_dx_um * 1e-3;
    let rays: f64 = levels.iter().map(|l| l.stats.rays as f64).sum();
    let seconds: f64 = levels.iter().map(|l| l.stats.seconds).sum();
    let mut headers = vec!["band".to_string(), "wavelengths (mm)".to_string()];
    for l in &levels {
        headers.push(format!(
            "rms slope (mrad), {} mrad map (DOI {})",
            l.slope_mrad,
            super::doi_text(&l.gloss)
        ));
    }
    let rows = waviness::BANDS
        .iter()
        .enumerate()
        .map(|(k, band)| {
            let mut row = vec![
                band.name.to_string(),
                format!("{}–{}", band.short_m * 1e3, band.long_m * 1e3),
            ];
            row.extend(levels.iter().map(|l| band_cell(&l.bands[k])));
            row
        })
        .collect();
    let text = format!(
        "At arm's length a glossy clear coat shows orange peel: the coat's surface undulates at \
         millimetre scale, and the reflection of a window or a lamp comes back wavy. A synthetic \
         orange peel: a periodic Gaussian height map whose power spectral density falls as \
         q^-{DEFAULT_EXPONENT} (equal mean square slope in every octave) between {DEFAULT_SHORT_MM} \
         and {DEFAULT_LONG_MM} mm, {n} × {n} points at {dx} µm ({side:.1} mm square), scaled \
         to an rms slope along x of {a} mrad (gonio surface gen's default, a smooth finish) \
         and of {b} mrad (a visible orange peel). Its wave-scan bands: the profiles' slope \
         filtered by ISO 16610 Gaussian filters into the wavelength bands of the scanning wave \
         meters (Wa–We, short wave SW and long wave LW), the rms of each band in mrad \
         (docs/surface.md, \"Waviness\"; the meters' 0–100 scales are not public, gonio's own \
         is the value column of gonio surface waviness). A band the map cannot hold says why. \
         The DOI (ASTM E430, docs/instruments.md) is the virtual meter's reading of the map's \
         mirror-like coat (the ray method on the map, index {COAT_INDEX}): the side slits 0.3° \
         off the specular direction collect the light the map's slopes spread, so DOI falls \
         as the slopes grow. Limits: the map is isotropic and Gaussian (a real coat's peel \
         can be directional and is not Gaussian), and both the bands and DOI read its slope \
         only, not the coat's micro-roughness.",
        n = plan.peel_points,
        dx = plan.peel_dx_um,
        a = PEEL_SLOPES_MRAD[0],
        b = PEEL_SLOPES_MRAD[1],
    );
    Ok(vec![
        Block::Text(text),
        Block::Table { headers, rows },
        Block::Image {
            path: png,
            caption: format!(
                "A dark glossy panel (a clear coat of index {COAT_INDEX}, GGX α 0.0005, over a \
                 dark base) carrying each map as its mesoscale height map, mirroring five \
                 fluorescent tubes 2 m in front of it (examples/orange_peel.toml, framed \
                 closer). The tubes' straight edges come back ragged and wavy: each point's \
                 reflection moves by twice its slope times the distance to the tube (4 mm rms \
                 at 1 mrad, 2 m away); the waves under a millimetre, a pixel or two here, fray \
                 the edge, the longer ones bend it. The map ({side:.1} mm) repeats across the 0.5 m panel without a seam \
                 (it is periodic). {} × {} pixels, {} samples per pixel, denoised; {rays:.2e} \
                 rays in {seconds:.0} s",
                plan.panel_px.0, plan.panel_px.1, plan.panel_spp
            ),
        },
        Block::Code(commands.join("\n")),
    ])
}

/// A band's rms slope in mrad, or why the map cannot hold it.
fn band_cell(r: &BandReading) -> String {
    match (r.rms, &r.unresolved) {
        (Some(s), _) => format!("{:.3}", s * 1e3),
        (None, Some(why)) => why.split(':').next().unwrap_or(why).to_string(),
        (None, None) => "—".into(),
    }
}

/// Pictures side by side in one PNG at `path`, each under its label, in its own display; with
/// `pixel_um`, a 1 mm scale bar under the first (the pictures' pixels are `pixel_um` across).
fn side_by_side(
    path: &Path,
    panels: &[(String, &Image, Display)],
    pixel_um: Option<f64>,
) -> Result<()> {
    const MARGIN: i32 = 8;
    const GAP: i32 = 16;
    const LABEL: i32 = 26;
    let bar = if pixel_um.is_some() { 30 } else { 0 };
    let w: i32 = panels.iter().map(|p| p.1.width as i32).sum::<i32>()
        + GAP * (panels.len() as i32 - 1)
        + 2 * MARGIN;
    let h = panels.iter().map(|p| p.1.height as i32).max().unwrap_or(0) + LABEL + bar + MARGIN;
    render_png(path, (w as u32, h as u32), |root| {
        let mut x0 = MARGIN;
        for (label, image, display) in panels {
            root.draw(&Text::new(
                label.clone(),
                (x0, 5),
                ("sans-serif", 17).into_font(),
            ))?;
            let rgb = image.to_srgb8(*display);
            for (k, px) in rgb.chunks_exact(3).enumerate() {
                let (x, y) = ((k % image.width) as i32, (k / image.width) as i32);
                root.draw_pixel((x0 + x, LABEL + y), &RGBColor(px[0], px[1], px[2]))?;
            }
            x0 += image.width as i32 + GAP;
        }
        if let Some(um) = pixel_um {
            let y = LABEL + panels[0].1.height as i32 + 10;
            let len = (1000.0 / um).round() as i32;
            root.draw(&Rectangle::new(
                [(MARGIN, y), (MARGIN + len, y + 6)],
                BLACK.filled(),
            ))?;
            root.draw(&Text::new(
                "1 mm".to_string(),
                (MARGIN + len + 8, y - 4),
                ("sans-serif", 15).into_font(),
            ))?;
        }
        Ok(())
    })?;
    Ok(())
}
