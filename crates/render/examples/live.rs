//! The lab's pictures of coating descriptions (`gonio_render::panel::live`): for each file, the
//! table and the picture at a quality under a lighting, their figures printed and the PNG
//! written. With `--resolution TH,TD,PD --walks N` the table is computed at those nodes and walks
//! instead of the quality's (to choose the levels: docs/render.md, "The lab's pictures").
//!
//! ```text
//! cargo run --release -p gonio-render --features studies --example live -- \
//!     examples/coatings/silver_metallic.toml --quality converged --lighting booth --out /tmp
//! ```

use gonio_brdf::table::{Provenance, Resolution, SampledTable};
use gonio_coating::description;
use gonio_io::Cancel;
use gonio_render::panel::Lighting;
use gonio_render::panel::live::{LiveTable, Quality, live_table, picture};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

fn main() {
    let mut files = Vec::new();
    let (mut quality, mut lighting, mut out) =
        (Quality::Preview, Lighting::Studio, PathBuf::from("."));
    let (mut resolution, mut walks, mut table_only) = (None, None, false);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--quality" => quality = Quality::from_name(&value()).expect("preview or converged"),
            "--lighting" => lighting = Lighting::from_name(&value()).expect("a lighting"),
            "--out" => out = value().into(),
            "--resolution" => {
                let n: Vec<usize> = value().split(',').map(|v| v.parse().unwrap()).collect();
                resolution = Some(Resolution::isotropic(n[0], n[1], n[2]));
            }
            "--walks" => walks = Some(value().parse::<usize>().unwrap()),
            "--table-only" => table_only = true,
            _ => files.push(PathBuf::from(a)),
        }
    }
    let cancel = Cancel::new();
    for file in &files {
        let coating = description::read(file, &quality.bands()).unwrap();
        let table = match (resolution, walks) {
            (None, None) => live_table(&coating, quality, &cancel).unwrap(),
            (r, w) => {
                let start = Instant::now();
                let w = w.unwrap_or(quality.walks());
                let t = coating
                    .table(
                        r.unwrap_or(quality.resolution(&coating)),
                        &quality.bands(),
                        w,
                        Provenance::default(),
                    )
                    .unwrap();
                let base = live_table(&coating, Quality::Preview, &cancel).unwrap();
                LiveTable {
                    table: Arc::new(SampledTable::new(t)),
                    walks: w,
                    seconds: start.elapsed().as_secs_f64(),
                    ..base
                }
            }
        };
        let stem = file.file_stem().unwrap().to_string_lossy();
        if table_only {
            println!("{stem}: table {:.2} s", table.seconds);
            continue;
        }
        let shown = picture(&table, lighting, quality, &cancel).unwrap();
        let f = shown.figures;
        let png = out.join(format!("{stem}-{}-{}.png", quality.name(), lighting.name()));
        std::fs::write(&png, &shown.png).unwrap();
        println!(
            "{stem}: table {}x{}x{} {} walks {} bands {:.2} s; picture {}x{} {} spp {:.2} s, {:.2e} rays; mean {:.4} -> {}",
            f.resolution.theta_h,
            f.resolution.theta_d,
            f.resolution.phi_d,
            f.walks,
            f.bands,
            f.table_seconds,
            f.size.0,
            f.size.1,
            f.spp,
            f.render_seconds,
            f.rays as f64,
            shown.image.luminance_mean(),
            png.display()
        );
    }
}
