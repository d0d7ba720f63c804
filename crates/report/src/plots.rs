//! The plots the reports and the commands share, drawn by gonio_plot: a height map in false
//! colour, in-plane BRDF curves, and pairs of curves (measured against computed, original
//! against turned) on one logarithmic axis.

use crate::Result;
use crate::error::Context;
use crate::units::length;
use gonio_plot::{self as plot, LinePlot, Raster, Series};
use gonio_scatter::InplaneCurve;
use gonio_surface::{HeightMap, ops, stats};
use std::path::Path;

/// A false-colour image of the levelled heights of `map` with a scale bar and a colour bar.
pub fn plot_height_map(map: &HeightMap, name: &str, output: &Path) -> Result<()> {
    let lev = ops::level(map).with_context(|| format!("{name}: levelling"))?;
    let heights = lev.heights();
    let mut valid: Vec<f64> = heights.iter().copied().filter(|z| !z.is_nan()).collect();
    valid.sort_unstable_by(f64::total_cmp);
    // Colour range from the 0.1 and 99.9 percentiles, so that a few spikes do not wash it out.
    let pick = |p: f64| valid[((valid.len() - 1) as f64 * p).round() as usize];
    let (lo, hi) = (pick(0.001), pick(0.999));
    let (unit, factor) = if hi - lo >= 1e-5 {
        ("µm", 1e6)
    } else {
        ("nm", 1e9)
    };
    // Row 0 of the map is y = 0, drawn at the bottom; heights() is already row-major.
    let values: Vec<f64> = heights.iter().map(|z| z * factor).collect();
    let width_um = map.dx() * map.nx() as f64 * 1e6;
    let bar_um = plot::nice_number(width_um / 5.0);
    let sq = stats::height_parameters(&lev).0;
    let title = format!(
        "{name}: {} × {} points, Sq = {} (levelled)",
        map.nx(),
        map.ny(),
        length(sq)
    );
    let raster = Raster {
        title: &title,
        values: &values,
        width: map.nx(),
        height: map.ny(),
        cell_aspect: map.dy() / map.dx(),
        range: (lo * factor, hi * factor),
        colour_label: &format!("height ({unit})"),
        scale_bar: Some((bar_um * 1e-6 / map.dx(), format!("{bar_um} µm"))),
    };
    // Image box 690 pixels high, as wide as the map's true aspect ratio asks (within limits),
    // plus room for the colour bar.
    let aspect = (map.nx() as f64 * map.dx()) / (map.ny() as f64 * map.dy());
    let width = (690.0 * aspect).clamp(360.0, 1400.0) as u32 + 190;
    Ok(plot::raster_png(output, (width, 760), &raster)?)
}

/// In-plane BRDF curves on a logarithmic axis, one colour per curve.
pub fn plot_curves(path: &Path, curves: &[InplaneCurve]) -> Result<()> {
    let series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| Series {
            label: format!("{} {}°", c.method, c.incidence_deg),
            points: c
                .points
                .iter()
                .map(|p| (p.scatter_deg, p.brdf_per_sr))
                .collect(),
            colour: plot::palette(i),
            markers: false,
        })
        .collect();
    let plot = LinePlot {
        title: "In-plane BRDF",
        x_label: "scattering angle (deg)",
        y_label: "BRDF (1/sr)",
        log_y: true,
    };
    Ok(plot::line_plot_png(path, (900, 600), &plot, &series)?)
}

/// Pairs of curves on a log axis of reflectance, one colour per pair: the first curve of each
/// pair as dots, the second as a line; `label(curve, first)` names each in the legend.
pub fn plot_pairs(
    path: &Path,
    title: &str,
    pairs: &[(&InplaneCurve, &InplaneCurve)],
    label: impl Fn(&InplaneCurve, bool) -> String,
) -> Result<()> {
    let mut series = Vec::new();
    for (i, (a, b)) in pairs.iter().enumerate() {
        let colour = plot::palette(i);
        for (curve, first) in [(a, true), (b, false)] {
            series.push(Series {
                label: label(curve, first),
                points: curve
                    .points
                    .iter()
                    .map(|p| (p.scatter_deg, p.reflectance))
                    .collect(),
                colour,
                markers: first,
            });
        }
    }
    let spec = LinePlot {
        title,
        x_label: "scatter angle (deg)",
        y_label: "reflectance per detector",
        log_y: true,
    };
    Ok(plot::line_plot_png(path, (1000, 650), &spec, &series)?)
}
