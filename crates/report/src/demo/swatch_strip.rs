//! A multi-angle swatch strip: per geometry a pair of patches, the measurement on the left and
//! the formulation on the right, touching so that the eye compares them across one edge, with
//! the geometry's name above and its ΔE00 below; one row per illumination angle.

use crate::Result;
use gonio_color::{Colorimetry, Illuminant, Lab, LinearSrgb, Observer, white};
use plotters::prelude::*;
use std::path::Path;

/// One geometry's pair.
pub(super) struct Pair {
    /// The geometry's name (`45as15`).
    pub label: String,
    /// CIELAB, D65/10°, of the measurement and of the formulation.
    pub measured: Lab,
    pub matched: Lab,
    pub de00: f64,
}

/// One row of pairs and its label (two lines).
pub(super) struct Row {
    pub label: [String; 2],
    pub pairs: Vec<Pair>,
}

/// Patch width and height, px; gap between pairs; left margin for the row labels.
const PATCH: (i32, i32) = (56, 96);
const GAP: i32 = 24;
const LEFT: i32 = 150;
/// Row pitch: the geometry's name above the patches, ΔE00 and the dimming below.
const ROW: i32 = PATCH.1 + 78;
const TOP: i32 = 52;

/// The linear sRGB (D65, white-balanced from the 10° observer's white) of `lab` (D65/10°).
fn linear(lab: Lab) -> LinearSrgb {
    let (d65, ten) = (Illuminant::D65, Observer::Cie1964TenDegree);
    Colorimetry::of_xyz(lab.to_xyz(white(d65, ten)), d65, ten).linear_srgb
}

/// The pair's two fills and the factor both were dimmed by: a pair lighter than the display's
/// white (a component above 1, near the specular direction) is divided by its largest component,
/// so that it keeps its hue and both patches stay comparable; components below 0 (outside the
/// sRGB gamut) are clipped. Returns also whether one was.
fn fills(pair: &Pair) -> ([RGBColor; 2], f64, bool) {
    let colours = [linear(pair.measured), linear(pair.matched)];
    let top = colours
        .iter()
        .flat_map(|c| [c.r, c.g, c.b])
        .fold(1.0, f64::max);
    let clipped = colours.iter().any(|c| c.r.min(c.g).min(c.b) < 0.0);
    let fill = |c: &LinearSrgb| {
        let [r, g, b] = LinearSrgb {
            r: c.r / top,
            g: c.g / top,
            b: c.b / top,
        }
        .encode()
        .to_u8();
        RGBColor(r, g, b)
    };
    ([fill(&colours[0]), fill(&colours[1])], top, clipped)
}

/// Draw `rows` under `title` into the PNG `path`.
pub(super) fn draw(path: &Path, title: &str, rows: &[Row]) -> Result<()> {
    let columns = rows.iter().map(|r| r.pairs.len()).max().unwrap_or(0) as i32;
    let width = LEFT + columns * (2 * PATCH.0 + GAP) + 8;
    let height = TOP + rows.len() as i32 * ROW + 30;
    let mut any_clipped = false;
    gonio_plot::render_png(path, (width as u32, height as u32), |root| {
        let font = |px: u32| ("sans-serif", px).into_font();
        let grey = |px: u32| font(px).color(&RGBColor(90, 90, 90));
        root.draw(&Text::new(title, (12, 12), font(19)))?;
        for (i, row) in rows.iter().enumerate() {
            let y = TOP + i as i32 * ROW;
            root.draw(&Text::new(
                row.label[0].as_str(),
                (12, y + 18 + PATCH.1 / 2 - 18),
                font(15),
            ))?;
            root.draw(&Text::new(
                row.label[1].as_str(),
                (12, y + 18 + PATCH.1 / 2 + 2),
                grey(14),
            ))?;
            for (k, pair) in row.pairs.iter().enumerate() {
                let x = LEFT + k as i32 * (2 * PATCH.0 + GAP);
                let ([measured, matched], top, clipped) = fills(pair);
                any_clipped |= clipped;
                root.draw(&Text::new(pair.label.as_str(), (x + 2, y), font(15)))?;
                let patch_top = y + 20;
                for (j, colour) in [measured, matched].into_iter().enumerate() {
                    let left = x + j as i32 * PATCH.0;
                    root.draw(&Rectangle::new(
                        [(left, patch_top), (left + PATCH.0, patch_top + PATCH.1)],
                        colour.filled(),
                    ))?;
                }
                root.draw(&Text::new(
                    format!("ΔE00 {:.1}", pair.de00),
                    (x + 2, patch_top + PATCH.1 + 6),
                    font(14),
                ))?;
                if top > 1.0 {
                    root.draw(&Text::new(
                        format!("shown ÷{top:.2}"),
                        (x + 2, patch_top + PATCH.1 + 24),
                        grey(13),
                    ))?;
                }
            }
        }
        let mut note = "each pair: measured (left) | formulation (right); CIELAB D65/10° as sRGB; \
                        a pair lighter than white is shown divided by the factor given"
            .to_string();
        if any_clipped {
            note.push_str("; colours outside sRGB clipped");
        }
        root.draw(&Text::new(note, (12, height - 22), grey(13)))?;
        Ok(())
    })?;
    Ok(())
}
