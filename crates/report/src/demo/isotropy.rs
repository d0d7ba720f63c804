//! The demo report's isotropy section: the real instrument file's in-plane curves against
//! those of the same map turned by 90° and 45° ([`gonio_instrument::isotropy`]), what
//! `gonio isotropy` prints and writes.

use super::{REAL_FILE, REAL_FILE_NAME};
use crate::Result;
use crate::html::{Block, Section};
use crate::isotropy_files::{plot_check, write_csv};
use gonio_instrument::isotropy::{self, IsotropyConfig};
use gonio_io::Progress;
use gonio_surface::io;
use std::path::Path;

/// The isotropy check on the real file: its in-plane curves (ray method) and those of the map
/// turned by 90° (exact) and 45° (spline, both cropped to the inscribed square), compared.
pub(super) fn isotropy_section(dir: &Path) -> Result<Section> {
    let map = io::read_bytes(Path::new(REAL_FILE_NAME), REAL_FILE)?;
    let config = IsotropyConfig {
        angles_deg: vec![90.0, 45.0],
        ..IsotropyConfig::starr(isotropy::Method::Ray)
    };
    let checks = isotropy::check(&map, &config, &Progress::silent())?;
    let mut blocks = vec![Block::Text(format!(
        "An isotropic surface scatters the same whatever its azimuth. The in-plane curves of \
         {REAL_FILE_NAME} (ray method, STARR geometry, the plane of incidence along x) against \
         those of the same map turned about its normal: by 90° exactly (the grid transposed, no \
         interpolation) and by 45° (bicubic spline, both maps cropped to the largest square \
         inside the turned one, so that both are read over the same area). The lobe's width \
         follows the rms slope along the plane of incidence; Str is the ISO 25178 texture \
         aspect ratio (1 for an isotropic surface). For isotropic synthetic maps (256 × 256 \
         points, 40 correlation lengths across) the RMS difference of log10 reflectance is about \
         0.15, mostly from the few rays in the tails (docs/instruments.md)."
    ))];
    let slope_rows = checks
        .iter()
        .flat_map(|c| {
            [("original", &c.original), ("turned", &c.rotated)].map(|(name, o)| {
                vec![
                    format!("{}°", c.angle_deg),
                    name.to_string(),
                    format!("{} × {}", o.nx, o.ny),
                    format!("{:.4}", o.rms_slope_x),
                    format!("{:.4}", o.rms_slope_y),
                    o.str.map_or("-".into(), |v| format!("{v:.3}")),
                ]
            })
        })
        .collect();
    blocks.push(Block::Table {
        headers: [
            "turn",
            "map",
            "points",
            "rms slope along x (plane of incidence)",
            "rms slope along y",
            "Str",
        ]
        .map(String::from)
        .to_vec(),
        rows: slope_rows,
    });
    let fwhm = |v: Option<f64>| v.map_or("-".into(), |w| format!("{w:.2}"));
    let rows = checks
        .iter()
        .flat_map(|c| {
            c.comparisons.iter().map(|x| {
                vec![
                    format!("{}°", c.angle_deg),
                    format!("{}", x.incidence_deg),
                    format!("{:.3}", x.rms_log10),
                    format!("{} / {}", x.peak_a.position_deg, x.peak_b.position_deg),
                    format!(
                        "{:.3e} / {:.3e}",
                        x.peak_a.reflectance, x.peak_b.reflectance
                    ),
                    format!("{} / {}", fwhm(x.peak_a.fwhm_deg), fwhm(x.peak_b.fwhm_deg)),
                ]
            })
        })
        .collect();
    blocks.push(Block::Table {
        headers: [
            "turn",
            "incidence (°)",
            "RMS Δlog10 ρ",
            "peak at (°) original / turned",
            "peak reflectance original / turned",
            "FWHM (°) original / turned",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    });
    write_csv(&dir.join("isotropy.csv"), &checks)?;
    for c in &checks {
        let png = dir.join(format!("isotropy_rot{}.png", c.angle_deg));
        plot_check(&png, c)?;
        blocks.push(Block::Image {
            path: png,
            caption: format!(
                "{REAL_FILE_NAME}: in-plane reflectance of the original (lines) and of the map \
                 turned by {}° (dots)",
                c.angle_deg
            ),
        });
    }
    blocks.push(Block::Code(format!(
        "gonio isotropy {REAL_FILE_NAME} --angle-deg 90,45 -o isotropy.png --csv isotropy.csv"
    )));
    Ok(Section {
        title: format!("Isotropy of {REAL_FILE_NAME}"),
        blocks,
        seconds: 0.0,
    })
}
