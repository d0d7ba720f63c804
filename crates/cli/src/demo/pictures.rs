//! The demo report's pictures: the example scenes rendered by the path tracer, and the
//! metallic paint rendered spectrally and compared with the tristimulus shortcut.

use crate::report::{Block, Section};
use anyhow::{Context, Result};
use gonio_render::difference::{SeededComparison, Spread, heat_map, linear_display};
use gonio_render::{ColourMode, Display, Image, RenderOptions, RenderStats};
use std::path::{Path, PathBuf};

/// Render the scene file `scene` in colour mode `colour` with `seed` (`None`: the scene's),
/// showing progress.
fn render(
    scene: &Path,
    colour: ColourMode,
    seed: Option<u32>,
) -> Result<(Image, Display, RenderStats)> {
    let options = RenderOptions {
        progress: true,
        colour,
        seed,
        ..Default::default()
    };
    gonio_render::render_scene_file(scene, &options)
        .with_context(|| format!("rendering {}", scene.display()))
}

/// The metallic scene rendered spectrally (hero wavelengths) and compared with the tristimulus
/// picture `tristimulus` (rendered with the scene's seed): each mode is rendered once more with
/// another seed, so that the colour difference comes with a noise reference of the same noise
/// and no systematic part ([`SeededComparison`]).
fn spectral_blocks(
    dir: &Path,
    scene: &Path,
    tristimulus: &Image,
    display: Display,
) -> Result<Vec<Block>> {
    const SECOND_SEED: Option<u32> = Some(0x9e37_79b9);
    let (spectral, _, stats) = render(scene, ColourMode::Spectral, None)?;
    let (spectral_b, ..) = render(scene, ColourMode::Spectral, SECOND_SEED)?;
    let (tristimulus_b, ..) = render(scene, ColourMode::Tristimulus, SECOND_SEED)?;
    let c = SeededComparison::new(
        [tristimulus, &tristimulus_b],
        [&spectral, &spectral_b],
        display,
    );
    let png = dir.join("metallic-spectral.png");
    c.second.write(&png, display)?;
    let heat = dir.join("metallic-delta-e00.png");
    heat_map(&c.delta_e00, c.first.width, c.first.height, 2.0).write(&heat, linear_display())?;
    let spread = |v: &[f64]| Spread::of(v).context("the picture has no pixels");
    let (de, noise) = (spread(&c.delta_e00)?, spread(&c.noise_reference)?);
    Ok(vec![
        Block::Image {
            path: png,
            caption: format!(
                "The same scene rendered spectrally (mean of two seeds): four hero wavelengths \
                 per path, the measured spectra evaluated at them, colour formed at the film \
                 (D65, 2° observer); {:.2e} rays in {:.0} s per render",
                stats.rays as f64, stats.seconds
            ),
        },
        Block::Image {
            path: heat,
            caption: format!(
                "CIEDE2000 between the spectral and the tristimulus pictures, each the mean of \
                 two seeds (black 0, white 2 or more): median {:.2}, 95th percentile {:.2}, max \
                 {:.2}. The noise reference (the same noise, no systematic part): median {:.2}, \
                 95th percentile {:.2}, max {:.2}. docs/color.md has the comparison at \
                 2 × 4096 samples per pixel and where the difference comes from",
                de.median, de.p95, de.max, noise.median, noise.p95, noise.max
            ),
        },
        Block::Code("gonio render metallic.toml --spectral -o metallic-spectral.png".into()),
    ])
}

/// The example scenes of the repository, rendered as the report's pictures.
const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");

/// Copy the scene file `scene` into `dir`, with every file it names (quoted strings that are
/// paths of existing files, relative to the scene) copied beside it and named there by its bare
/// file name, so that `gonio render SCENE` runs as written in `dir`. Returns the copy's path.
fn copy_scene(scene: &Path, dir: &Path) -> Result<PathBuf> {
    let text = std::fs::read_to_string(scene)
        .with_context(|| format!("{}: cannot read the scene", scene.display()))?;
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
                    std::fs::copy(&named, dir.join(name)).with_context(|| {
                        format!("{}: cannot copy beside the report", named.display())
                    })?;
                    copy.push_str(&name.to_string_lossy());
                }
                None => copy.push_str(part),
            }
        }
    }
    let path = dir.join(scene.file_name().context("a scene file has a name")?);
    crate::output::write_atomic(&path, |w| {
        Ok(std::io::Write::write_all(w, copy.as_bytes())?)
    })?;
    Ok(path)
}

pub(super) fn render_section(dir: &Path) -> Result<Section> {
    let mut blocks = vec![Block::Text(
        "Pictures by gonio's path tracer (next-event estimation with multiple importance \
         sampling; tabulated BRDFs sampled by the alias method). First the NIST figure 6: two \
         black epoxy panels whose BRDFs the ray method computed from the 201 nm (left) and \
         805 nm (right) surfaces, under a bright window. Then the metallic paints measured at \
         Cornell (Cornell University Program of Computer Graphics reflectance data): the Ford \
         Cayman metallic lacquer, whose colour travels with angle, and Garnet Red, rendered \
         with the tristimulus shortcut (the measured spectra reduced to RGB before rendering, \
         as the NIST work did) and spectrally, with the difference between the two."
            .into(),
    )];
    for (scene, caption) in [
        (
            "epoxy.toml",
            "NIST figure 6: 201 nm (left) and 805 nm (right) epoxy panels",
        ),
        (
            "metallic.toml",
            "Cayman metallic (sphere and panel) and Garnet Red (sphere)",
        ),
    ] {
        let path = copy_scene(&Path::new(EXAMPLES).join(scene), dir)?;
        let (image, display, stats) = render(&path, ColourMode::Tristimulus, None)?;
        let png = dir.join(scene.replace(".toml", ".png"));
        image.write(&png, display)?;
        blocks.push(Block::Image {
            path: png,
            caption: format!(
                "{caption} ({} × {} px, {:.2e} rays in {:.0} s)",
                image.width, image.height, stats.rays as f64, stats.seconds
            ),
        });
        blocks.push(Block::Code(format!(
            "gonio render {scene} -o {}",
            scene.replace(".toml", ".png")
        )));
        if scene == "metallic.toml" {
            blocks.extend(spectral_blocks(dir, &path, &image, display)?);
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
