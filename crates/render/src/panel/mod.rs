//! Pictures of coatings on a curved, bonnet-like panel: the coating's spectral table (computed
//! for the picture), the panel scene, and the rendered picture. The `gonio` command (`coating
//! study`, the demo) and the Python package write the scene and its files into a folder, which
//! `gonio render` runs as written ([`table`], [`scene`], [`render`]); the lab makes the same
//! scene in memory, a coarse picture first and finer ones while nothing changes ([`live`]).
//! Several coatings sit side by side on identical panels, seen from one camera, so that a
//! picture compares them at the same angles: the bright reflection of the light near the
//! specular direction, the flop colour where the panel turns away.
//!
//! The panel is the repository's `examples/panel.obj` (made by `examples/metallic_assets.py`),
//! embedded in the program. The lights are environment maps drawn by the program
//! ([`Lighting`]): by default a dark studio with two softboxes.

mod lighting;
pub mod live;

pub use lighting::Lighting;
pub(crate) use lighting::booth_map;

use crate::error::{RenderError, Result};
use crate::geometry::Shape;
use crate::{ColourMode, Display, Image, RenderOptions, RenderStats, Scene, render_picture};
use gonio_brdf::table::Resolution;
use gonio_coating::system::{Coating, default_bands};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

const PANEL_OBJ: &[u8] = include_bytes!("../../../../examples/panel.obj");

/// Random walks per table cell of a picture's table (`gonio coating compute`'s default).
pub const WALKS: usize = gonio_coating::system::TABLE_WALKS;

/// One coating on a panel: the name of its table file (beside the scene), and the index of its
/// smooth top, whose mirror reflection the renderer adds (`None` for a rough top, whose
/// reflection is in the table).
pub struct Panel {
    pub table: String,
    pub coat_index: Option<f64>,
}

/// The resolution of a picture's table: 45 × 45 × 24 nodes, with more θh nodes where a rough
/// top's reflection is so narrow that the first node off the specular direction would miss it.
/// The nodes lie at θh = 90° (j/N)², so the first is at 90°/N²; it is kept within a third of
/// the lobe's width atan α, up to 90 nodes (α ≥ 0.0006).
pub fn resolution(coating: &Coating) -> Resolution {
    let theta_h = coating.roughness.map_or(45, |m| {
        let lobe_deg = m.alpha_x.min(m.alpha_y).atan().to_degrees();
        ((270.0 / lobe_deg).sqrt().ceil() as usize).clamp(45, 90)
    });
    Resolution::isotropic(theta_h, 45, 24)
}

/// Compute `coating`'s table for a picture into `dir/NAME.gbrdf` (from the description
/// `source`), returning the panel that shows it.
pub fn table(coating: &Coating, source: &str, dir: &Path, name: &str) -> Result<Panel> {
    let bands = default_bands();
    let method = coating.method(WALKS);
    let table = coating.table(
        resolution(coating),
        &bands,
        WALKS,
        coating.provenance(source, method),
    )?;
    let file = format!("{name}.gbrdf");
    gonio_brdf::gbrdf::write(&table, &dir.join(&file))?;
    Ok(Panel::new(coating, file))
}

impl Panel {
    /// The panel of `coating` whose table is the file `table`.
    fn new(coating: &Coating, table: String) -> Panel {
        Panel {
            table,
            coat_index: coat_index(coating),
        }
    }
}

/// The index of `coating`'s smooth top, whose mirror the renderer adds (at the coat's index at
/// 550 nm, its dispersion left out of the mirror); `None` for a rough top, whose reflection is
/// in the table.
pub fn coat_index(coating: &Coating) -> Option<f64> {
    coating
        .roughness
        .is_none()
        .then(|| coating.coat.index.at(550.0))
}

/// Write the scene `dir/NAME.toml` with `panels` side by side (left to right) in the dark
/// studio, the panel mesh and the studio's map beside it. Returns the scene's path.
pub fn scene(dir: &Path, name: &str, panels: &[Panel]) -> Result<PathBuf> {
    let lighting = Lighting::Studio;
    write_file(&dir.join(MESH), PANEL_OBJ)?;
    lighting
        .map()
        .write(&dir.join(lighting.map_file()), Display::default())?;
    let text = description(name, panels, lighting, Shot::FILE);
    let path = dir.join(format!("{name}.toml"));
    write_file(&path, text.as_bytes())?;
    Ok(path)
}

/// The file name of the panel mesh in a panel scene.
const MESH: &str = "panel.obj";

/// The panel mesh's triangles, parsed once.
pub(crate) fn mesh() -> Arc<Vec<Shape>> {
    static MESH_TRIANGLES: OnceLock<Arc<Vec<Shape>>> = OnceLock::new();
    MESH_TRIANGLES
        .get_or_init(|| {
            let triangles = crate::mesh::parse_obj(PANEL_OBJ, Path::new(MESH))
                .expect("the embedded panel mesh is valid OBJ (tested by every panel picture)");
            Arc::new(triangles)
        })
        .clone()
}

/// A picture's size and samples: its height in pixels (the width follows from the number of
/// panels) and the samples per pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shot {
    height: usize,
    spp: u32,
}

impl Shot {
    /// The pictures of `gonio coating study` and the demo: 280 px high, 16 samples per pixel.
    const FILE: Shot = Shot {
        height: 280,
        spp: 16,
    };
}

/// The panel scene (TOML, as `gonio render` reads it): `panels` side by side, each a mesh
/// `panel.obj` with its table, on a floor under `lighting`'s map, seen from the camera that
/// `shot` sizes. The one description of the panel scene, whether written into a folder
/// ([`scene`]) or built in memory ([`live::picture`]).
fn description(name: &str, panels: &[Panel], lighting: Lighting, shot: Shot) -> String {
    let k = panels.len() as f64;
    // Panels 2.4 m wide with 0.3 m between them, in a picture as wide as the row needs
    // (1.5 times its height for one panel). The camera looks down at 40° from a range that
    // fits the row into the horizontal field (30° vertical) with a fifth to spare, and no
    // closer than 4.5 m.
    let pitch = 2.7;
    let height = shot.height as f64;
    let width = (height * (0.6 + 0.9 * k)).round();
    let half_row = (pitch * (k - 1.0) + 2.4) / 2.0;
    let half_field = width / height * 15f64.to_radians().tan();
    let range = (1.2 * half_row / half_field).max(4.5);
    let (sin_e, cos_e) = 40f64.to_radians().sin_cos();
    let mut text = format!(
        "# {k} coating panel(s) in the {lighting} lighting, written by gonio (the tables beside \
         it come from `gonio coating compute`).\n#\n#   gonio render {name}.toml --spectral -o \
         {name}.png\n\n\
         [camera]\nposition = [0.0, {:.2}, {:.2}]\nlook_at = [0.0, 0.3, 0.0]\n\
         fov_deg = 30\nwidth = {width}\nheight = {height}\nexposure = 1.0\ntone = \"filmic\"\n\n\
         [render]\nspp = {}\nmax_bounces = 4\ndenoise = true\n\n\
         [materials.floor]\nbrdf = {{ model = \"lambert\", albedo = {} }}\n",
        0.3 + range * sin_e,
        range * cos_e,
        shot.spp,
        lighting.floor_albedo(),
    );
    for (i, p) in panels.iter().enumerate() {
        text.push_str(&format!(
            "\n[materials.coating{i}]\ntable = \"{}\"\n",
            p.table
        ));
        if let Some(n) = p.coat_index {
            text.push_str(&format!("coat_index = {n}\n"));
        }
    }
    for i in 0..panels.len() {
        let x = pitch * (i as f64 - (k - 1.0) / 2.0);
        text.push_str(&format!(
            "\n[[shapes]]\ntype = \"mesh\"\nfile = \"{MESH}\"\ntranslate = [{x:.2}, 0.55, 0.0]\n\
             material = \"coating{i}\"\n"
        ));
    }
    text.push_str(&format!(
        "\n[[shapes]]\ntype = \"rectangle\"\nsize = [200.0, 200.0]\nrotate_deg = [-90.0, 0.0, 0.0]\n\
         material = \"floor\"\n\n[[lights]]\ntype = \"environment\"\nfile = \"{}\"\n\
         scale = 1.0\n",
        lighting.map_file()
    ));
    text
}

/// Write `bytes` to `path` atomically ([`gonio_io::write_atomic`]).
fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |error| RenderError::Io {
        path: path.to_path_buf(),
        error,
    };
    gonio_io::write_atomic(path, |w| w.write_all(bytes), std::convert::identity).map_err(io)
}

/// Render the scene at `scene` into the PNG beside it (same name), spectrally (the tables are
/// spectral; colour formed under D65 by the CIE 1931 observer). Returns the PNG and the
/// render's figures.
pub fn render(scene: &Path) -> Result<(PathBuf, RenderStats)> {
    let (image, display, stats) = render_image(scene)?;
    let png = scene.with_extension("png");
    image.write(&png, display)?;
    Ok((png, stats))
}

/// Render the scene at `scene` as [`render`] does, returning the picture (linear sRGB), the
/// scene's display settings (exposure, tone curve) and the render's figures.
pub fn render_image(scene: &Path) -> Result<(Image, Display, RenderStats)> {
    let loaded = Scene::from_file(scene)?;
    let options = RenderOptions {
        colour: ColourMode::Spectral,
        ..Default::default()
    };
    let (image, estimate) = render_picture(&loaded, &options)?;
    Ok((image, loaded.display, estimate.stats))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene written for a smooth-topped and a rough-topped coating loads as written: two
    /// panels side by side, the smooth one's mirror added by its coat index, the rough one's
    /// reflection in its table; the picture's resolution follows the rough top's lobe.
    #[test]
    fn panels_scene_loads_with_each_coatings_table() {
        let dir = tempfile::tempdir().unwrap();
        let red = |top: &str| {
            gonio_coating::description::parse(
                &format!(
                    "{top}[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n"
                ),
                &[500.0, 600.0],
            )
            .unwrap()
        };
        let smooth = red("");
        let rough = red("[top]\nroughness = { alpha = 0.2 }\n");
        assert_eq!(resolution(&smooth).theta_h, 45);
        // α 0.001: a lobe 0.0573° wide; 90°/69² = 0.0189° is within a third of it, 90°/68² not.
        assert_eq!(
            resolution(&red("[top]\nroughness = { alpha = 0.001 }\n")).theta_h,
            69
        );
        let mut panels = Vec::new();
        for (coating, name) in [(&smooth, "smooth"), (&rough, "rough")] {
            let table = coating
                .table(
                    Resolution::isotropic(8, 8, 4),
                    &[500.0, 600.0],
                    1,
                    gonio_brdf::table::Provenance::default(),
                )
                .unwrap();
            let file = format!("{name}.gbrdf");
            gonio_brdf::gbrdf::write(&table, &dir.path().join(&file)).unwrap();
            panels.push(Panel::new(coating, file));
        }
        assert_eq!(panels[0].coat_index, Some(1.5));
        assert_eq!(panels[1].coat_index, None);
        let path = scene(dir.path(), "pair", &panels).unwrap();
        let loaded = Scene::from_file(&path).unwrap();
        let coats: Vec<Option<f64>> = loaded.materials.iter().map(|m| m.coat).collect();
        assert!(
            coats.contains(&Some(1.5)) && coats.contains(&None),
            "{coats:?}"
        );
        assert_eq!(loaded.camera.width, 672);
    }
}
