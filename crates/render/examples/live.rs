//! The lab's pictures of coating descriptions (`gonio_render::panel::live`): for each file, the
//! table and the picture at a quality under a lighting, their figures printed and the PNG
//! written (`--table-only`: the table alone).
//!
//! With `--compare TH,TD,PD,WALKS ...` (several), the first coating's converged picture is
//! rendered from tables at each of those nodes and walks instead, and each is compared with
//! the first one given (the reference) by CIEDE2000 over the panel's pixels: how the converged
//! table was chosen (docs/render.md, "The lab's pictures").
//!
//! ```text
//! cargo run --release -p gonio-render --features studies --example live -- \
//!     examples/coatings/silver_metallic.toml --quality converged --lighting booth --out /tmp
//! cargo run --release -p gonio-render --features studies --example live -- \
//!     examples/coatings/silver_metallic.toml --compare 45,45,24,128 45,45,24,32 45,24,16,32
//! ```

use gonio_brdf::table::{Provenance, Resolution, SampledTable};
use gonio_coating::description;
use gonio_io::Cancel;
use gonio_render::difference::{Spread, delta_e00};
use gonio_render::panel::Lighting;
use gonio_render::panel::live::{self, LiveTable, Quality, live_table, panel_pixels, picture};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

fn main() {
    let mut files = Vec::new();
    let (mut quality, mut lighting, mut out) =
        (Quality::Preview, Lighting::Studio, PathBuf::from("."));
    let (mut compare, mut table_only) = (Vec::new(), false);
    let mut args = std::env::args().skip(1).peekable();
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quality" => {
                quality =
                    Quality::from_name(&args.next().unwrap()).expect("preview, refined, converged")
            }
            "--lighting" => {
                lighting = Lighting::from_name(&args.next().unwrap()).expect("a lighting")
            }
            "--out" => out = args.next().unwrap().into(),
            "--table-only" => table_only = true,
            "--compare" => {
                while let Some(v) = args.next_if(|v| !v.starts_with("--")) {
                    let n: Vec<usize> = v.split(',').map(|x| x.parse().unwrap()).collect();
                    compare.push((Resolution::isotropic(n[0], n[1], n[2]), n[3]));
                }
            }
            _ => files.push(PathBuf::from(a)),
        }
    }
    let cancel = Cancel::new();
    if !compare.is_empty() {
        let q = Quality::Converged;
        let coating = description::read(&files[0], &q.bands()).unwrap();
        let base = live_table(&coating, Quality::Preview, &cancel).unwrap();
        let mut reference = None;
        for (resolution, walks) in compare {
            let start = Instant::now();
            let t = coating
                .table(resolution, &q.bands(), walks, Provenance::default())
                .unwrap();
            let table = LiveTable {
                table: Arc::new(SampledTable::new(t)),
                walks,
                seconds: start.elapsed().as_secs_f64(),
                ..base.clone()
            };
            let shown = picture(&table, lighting, q, &cancel).unwrap();
            let label = format!(
                "{}x{}x{} {walks} walks",
                resolution.theta_h, resolution.theta_d, resolution.phi_d
            );
            let png = out.join(format!("compare-{}-{walks}.png", resolution.theta_d));
            std::fs::write(&png, &shown.png).unwrap();
            let Some((ref_label, ref_image)) = &reference else {
                println!("{label}: table {:.2} s (reference)", table.seconds);
                reference = Some((label, shown.image));
                continue;
            };
            let mask = panel_pixels(&live::scene(&table, lighting, q).unwrap());
            let de = delta_e00(&shown.image, ref_image, shown.display);
            let panel: Vec<f64> = mask.iter().map(|&i| de[i]).collect();
            let s = Spread::of(&panel).unwrap();
            let mean = panel.iter().sum::<f64>() / panel.len() as f64;
            println!(
                "{label}: table {:.2} s; against {ref_label}: ΔE00 over the panel mean {mean:.2}, \
                 median {:.2}, p95 {:.2}, max {:.2}",
                table.seconds, s.median, s.p95, s.max
            );
        }
        return;
    }
    for file in &files {
        let coating = description::read(file, &quality.bands()).unwrap();
        let table = live_table(&coating, quality, &cancel).unwrap();
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
            "{stem}: table {}x{}x{}, {} walks, {} bands, {:.2} s; picture {}x{}, {} spp, \
             {:.2} s, {:.2e} rays -> {}",
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
            png.display()
        );
    }
}
