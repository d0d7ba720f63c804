//! The demo report's pictures: the example scenes rendered by the path tracer, and the
//! metallic paint rendered spectrally and compared with the tristimulus shortcut.

use crate::Result;
use crate::error::Context;
use crate::html::{Block, Section};
use crate::output::{self, read_text, write_bytes};
use gonio_io::Progress;
use gonio_plot::Raster;
use gonio_render::difference::{SeededComparison, Spread};
use gonio_render::{ColourMode, Image, RenderOptions, RenderStats, Scene, render_picture};
use std::path::{Path, PathBuf};

/// The options of the report's renders: colour mode `colour`, seed `seed` (`None`: the
/// scene's), reporting to `work`.
pub(super) fn options(colour: ColourMode, seed: Option<u32>, work: &Progress) -> RenderOptions {
    RenderOptions {
        progress: work.clone(),
        colour,
        seed,
        ..Default::default()
    }
}

/// Pixels per side of the blocks over which the spectral and tristimulus renders are compared:
/// a 4 × 4 block of 16-sample pixels holds 256 samples, so that the difference map shows the
/// colour difference rather than the noise of single pixels.
const COMPARISON_BIN: usize = 4;

/// The metallic scene rendered spectrally (hero wavelengths) and compared with the tristimulus
/// render `tristimulus` (raw, with the scene's seed): each mode is rendered once more with
/// another seed, so that the colour difference comes with a noise reference of the same noise
/// and no systematic part ([`SeededComparison`]). The comparison is between the raw estimates
/// binned [`COMPARISON_BIN`]² (linear averages, so the noise reference holds); the spectral
/// picture shown is denoised like the tristimulus one.
fn spectral_blocks(
    dir: &Path,
    scene: &Scene,
    tristimulus: &Image,
    work: &Progress,
) -> Result<Vec<Block>> {
    const SECOND_SEED: Option<u32> = Some(0x9e37_79b9);
    let (shown, spectral) = render_picture(scene, &options(ColourMode::Spectral, None, work))?;
    let second = |colour| -> Result<Image> {
        let e = gonio_render::render_estimate(scene, &options(colour, SECOND_SEED, work))?;
        Ok(e.image.binned(COMPARISON_BIN))
    };
    let spectral_b = second(ColourMode::Spectral)?;
    let tristimulus_b = second(ColourMode::Tristimulus)?;
    let display = scene.display;
    let c = SeededComparison::new(
        [&tristimulus.binned(COMPARISON_BIN), &tristimulus_b],
        [&spectral.image.binned(COMPARISON_BIN), &spectral_b],
        display,
    );
    let png = dir.join("metallic-spectral.png");
    shown.write(&png, display)?;
    let heat = dir.join("metallic-delta-e00.png");
    delta_e_map(
        &heat,
        &c.delta_e00,
        (c.first.width, c.first.height),
        tristimulus.width,
    )?;
    let spread = |v: &[f64]| Spread::of(v).context("the picture has no pixels");
    let (de, noise) = (spread(&c.delta_e00)?, spread(&c.noise_reference)?);
    let stats = spectral.stats;
    Ok(vec![
        Block::Image {
            path: png,
            caption: format!(
                "The same scene rendered spectrally: four hero wavelengths per path, the \
                 measured spectra evaluated at them, colour formed at the film (D65, 2° \
                 observer); {:.2e} rays in {:.0} s{}",
                stats.rays as f64,
                stats.seconds,
                denoised_note(&stats)
            ),
        },
        Block::Image {
            path: heat,
            caption: format!(
                "CIEDE2000 between the spectral and the tristimulus renders, per block of \
                 {COMPARISON_BIN} × {COMPARISON_BIN} pixels (raw estimates, each the mean of \
                 two seeds: {} samples per block and mode): median {:.2}, 95th percentile \
                 {:.2}, max {:.2}. The noise reference (the same noise, no systematic part): \
                 median {:.2}, 95th percentile {:.2}, max {:.2}. docs/color.md has the \
                 comparison at 2 × 4096 samples per pixel and where the difference comes from",
                2 * COMPARISON_BIN
                    * COMPARISON_BIN
                    * options(ColourMode::Spectral, None, work).samples_per_pixel(scene) as usize,
                de.median,
                de.p95,
                de.max,
                noise.median,
                noise.p95,
                noise.max
            ),
        },
        Block::Code("gonio render metallic.toml --spectral -o metallic-spectral.png".into()),
    ])
}

/// The colour difference map `delta_e` (row-major, row 0 at the top, `width × height` blocks)
/// as a false-colour PNG as wide as the pictures (`shown_width` pixels) with a colour bar from
/// 0 to 2 (larger values drawn as 2).
fn delta_e_map(
    path: &Path,
    delta_e: &[f64],
    (width, height): (usize, usize),
    shown_width: usize,
) -> Result<()> {
    // The raster draws its row 0 at the bottom.
    let rows: Vec<f64> = (0..height)
        .rev()
        .flat_map(|y| delta_e[y * width..(y + 1) * width].iter().copied())
        .collect();
    let raster = Raster {
        title: "CIEDE2000, spectral against tristimulus",
        values: &rows,
        width,
        height,
        cell_aspect: 1.0,
        range: (0.0, 2.0),
        colour_label: "ΔE00 (≥ 2 at top)",
        scale_bar: None,
    };
    let shown_height = shown_width * height / width.max(1);
    Ok(gonio_plot::raster_png(
        path,
        (shown_width as u32 + 190, shown_height as u32 + 90),
        &raster,
    )?)
}

/// ", denoised" for a denoised picture, else nothing.
pub(super) fn denoised_note(stats: &RenderStats) -> &'static str {
    if stats.denoised {
        ", denoised (docs/render.md)"
    } else {
        ""
    }
}

/// The example scenes of the repository, rendered as the report's pictures.
pub(super) const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");

/// Copy the scene file `scene` into `dir`, with every file it names (quoted strings that are
/// paths of existing files, relative to the scene) copied beside it and named there by its bare
/// file name, so that `gonio render SCENE` runs as written in `dir`. Returns the copy's path.
pub(super) fn copy_scene(scene: &Path, dir: &Path) -> Result<PathBuf> {
    let text = read_text(scene).context("reading the scene")?;
    let base = scene.parent().unwrap_or(Path::new("."));
    let mut copy = String::with_capacity(text.len());
    // Quoted strings sit between the odd and even quotes of each line.
    for line in text.split_inclusive('\n') {
        for (i, part) in line.split('"').enumerate() {
            if i > 0 {
                copy.push('"');
            }
            let named = base.join(part);
            match named.file_name().filter(|_| i % 2 == 1 && named.is_file()) {
                Some(name) => {
                    output::copy(&named, &dir.join(name)).context("copying beside the report")?;
                    copy.push_str(&name.to_string_lossy());
                }
                None => copy.push_str(part),
            }
        }
    }
    let path = dir.join(scene.file_name().context("a scene file has a name")?);
    write_bytes(&path, copy.as_bytes())?;
    Ok(path)
}

pub(super) fn render_section(dir: &Path, work: &Progress) -> Result<Section> {
    let mut blocks = vec![Block::Text(
        "Pictures by gonio's path tracer (next-event estimation with multiple importance \
         sampling; tabulated BRDFs sampled through the visible normals of a GGX fitted to \
         each table), 16 samples per pixel, \
         denoised by an edge-avoiding filter steered by each pixel's noise (measured: within \
         3% relative RMSE of the same pictures with four times the samples, \
         docs/performance.md). First the NIST figure 6: two black epoxy panels whose BRDFs the \
         ray method computed from the 201 nm (left) and 805 nm (right) surfaces, standing in \
         front of a window of four panes behind the camera: the smoother panel mirrors the \
         panes, blurred by its facets; the rougher one spreads them into an even sheen. Then \
         the metallic paints measured at \
         Cornell (Cornell University Program of Computer Graphics reflectance data): the Ford \
         Cayman metallic lacquer, whose colour travels with angle, and Garnet Red, rendered \
         with the tristimulus shortcut (the measured spectra reduced to RGB before rendering, \
         as the NIST work did) and spectrally, with the difference between the two."
            .into(),
    )];
    for (scene, caption) in [
        (
            "epoxy.toml",
            "NIST figure 6: 201 nm (left) and 805 nm (right) epoxy panels mirroring a window",
        ),
        (
            "metallic.toml",
            "Cayman metallic (sphere and panel) and Garnet Red (sphere)",
        ),
    ] {
        let path = copy_scene(&Path::new(EXAMPLES).join(scene), dir)?;
        let loaded = Scene::from_file(&path)?;
        let (image, estimate) =
            render_picture(&loaded, &options(ColourMode::Tristimulus, None, work))?;
        let png = dir.join(scene.replace(".toml", ".png"));
        image.write(&png, loaded.display)?;
        let stats = estimate.stats;
        blocks.push(Block::Image {
            path: png,
            caption: format!(
                "{caption} ({} × {} px, {:.2e} rays in {:.0} s{})",
                image.width,
                image.height,
                stats.rays as f64,
                stats.seconds,
                denoised_note(&stats)
            ),
        });
        blocks.push(Block::Code(format!(
            "gonio render {scene} -o {}",
            scene.replace(".toml", ".png")
        )));
        if scene == "metallic.toml" {
            blocks.extend(spectral_blocks(dir, &loaded, &estimate.image, work)?);
        }
    }
    Ok(Section {
        title: "Pictures".into(),
        blocks,
        seconds: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
    mod slow {
        use super::*;

        #[test]
        fn a_copied_scene_builds_from_the_files_beside_it() {
            let dir = tempfile::tempdir().unwrap();
            let copy = copy_scene(&Path::new(EXAMPLES).join("metallic.toml"), dir.path()).unwrap();
            let text = std::fs::read_to_string(&copy).unwrap();
            for name in ["cayman.astm", "garnet_red.astm", "panel.obj", "studio.hdr"] {
                assert!(
                    text.contains(&format!("\"{name}\"")),
                    "{name} not named bare"
                );
                assert!(dir.path().join(name).is_file(), "{name} not copied");
            }
            assert!(!text.contains(".."), "a path still leaves the folder");
            gonio_render::scene::Scene::from_file(&copy).unwrap();
        }
    }
}
