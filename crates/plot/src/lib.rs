//! gonio-plot: the plots every front end draws (the `gonio` command, the Python package, the
//! report): an embedded font, line plots on linear or log axes with the legend beside the data,
//! false-colour rasters with a colour bar, and PNG output written atomically (temporary file,
//! then rename; [`gonio_io::write_atomic`]).

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// What went wrong drawing or writing a plot.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Nothing finite (or positive, on a logarithmic axis) to draw, or data of the wrong shape.
    #[error("{0}")]
    Data(String),
    /// The drawing backend failed.
    #[error("drawing the plot: {0}")]
    Draw(String),
    /// The file could not be written.
    #[error("{}: cannot write: {error}", path.display())]
    Write {
        path: std::path::PathBuf,
        error: String,
    },
}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for PlotError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        PlotError::Draw(e.to_string())
    }
}

/// The plot functions' result.
pub type Result<T> = std::result::Result<T, PlotError>;

static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// Register the embedded DejaVu Sans as the "sans-serif" family (once per process).
pub fn init_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Registration only fails if the bytes are not a font, which include_bytes! rules out.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// A colour from a palette that stays distinguishable for up to ten series.
pub fn palette(i: usize) -> RGBColor {
    const COLOURS: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    COLOURS[i % COLOURS.len()]
}

/// One curve of a line plot.
pub struct Series {
    /// Legend label (empty: not in the legend).
    pub label: String,
    /// (x, y) points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line colour.
    pub colour: RGBColor,
    /// Draw markers instead of a line (for measured data).
    pub markers: bool,
}

/// Axes and title of a line plot.
pub struct LinePlot<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    /// Logarithmic y axis (non-positive values are dropped).
    pub log_y: bool,
}

/// The x axis of a line plot when it is not the plain linear one: logarithmic, and with named
/// positions (the samples of a study) written above the plot with a faint guide line each.
#[derive(Default)]
pub struct XAxis {
    /// Logarithmic x axis (non-positive values are dropped).
    pub log: bool,
    /// (x, name): a name written above the plot at x.
    pub marks: Vec<(f64, String)>,
}

/// On a logarithmic y axis, the smallest value shown relative to the largest: values below it
/// (numerical noise twelve decades under the peak) are left out, not piled up on the axis.
const LOG_Y_DECADES: f64 = 1e-12;

/// Draw `series` into a PNG of `size` pixels at `path`.
pub fn line_plot_png(
    path: &Path,
    size: (u32, u32),
    plot: &LinePlot,
    series: &[Series],
) -> Result<()> {
    render_png(path, size, |root| {
        draw_line_plot_x(root, plot, &XAxis::default(), series)
    })
}

/// [`line_plot_png`] with the x axis `x` (logarithmic, with named positions).
pub fn line_plot_png_x(
    path: &Path,
    size: (u32, u32),
    plot: &LinePlot,
    x: &XAxis,
    series: &[Series],
) -> Result<()> {
    render_png(path, size, |root| draw_line_plot_x(root, plot, x, series))
}

/// Draw a line plot into any drawing area (so that several plots can share one image).
pub fn draw_line_plot<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plot: &LinePlot,
    series: &[Series],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    draw_line_plot_x(root, plot, &XAxis::default(), series)
}

/// [`draw_line_plot`] with the x axis `x`. The title is drawn across the top, the legend in a
/// column to the right of the axes, so that it never covers data.
pub fn draw_line_plot_x<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plot: &LinePlot,
    x_axis: &XAxis,
    series: &[Series],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let usable = |&(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (!plot.log_y || y > 0.0) && (!x_axis.log || x > 0.0)
    };
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied().filter(usable))
        .collect();
    if all.is_empty() {
        return Err(PlotError::Data(format!(
            "nothing to plot in '{}'",
            plot.title
        )));
    }
    let (mut x0, mut x1) = min_max(all.iter().map(|p| p.0));
    let (mut y0, mut y1) = min_max(all.iter().map(|p| p.1));
    if x_axis.log {
        if x1 <= x0 {
            x1 = x0 * 10.0;
        }
        // A little room beyond the first and last points, so that no marker sits on the frame.
        let pad = (x1 / x0).powf(0.04);
        (x0, x1) = (x0 / pad, x1 * pad);
    } else if x1 <= x0 {
        x0 -= 0.5;
        x1 += 0.5;
    }
    let floor = if plot.log_y {
        y0 = y0.max(y1 * LOG_Y_DECADES);
        if y1 <= y0 {
            y1 = y0 * 10.0;
        }
        y0
    } else {
        f64::NEG_INFINITY
    };
    let shown = |p: &(f64, f64)| usable(p) && p.1 >= floor;
    let title_font = ("sans-serif", 20).into_font();
    let area = root.titled(plot.title, title_font)?;
    let (area, legend) = split_legend(&area, series);
    let xs = x0..x1;
    let xl = (x0..x1).log_scale();
    let chart = Chart {
        plot,
        log_x: x_axis.log,
        marks: &x_axis.marks,
        series,
        shown: &shown,
    };
    if plot.log_y {
        let ys = (y0 / 1.5..y1 * 1.5).log_scale();
        if x_axis.log {
            chart.draw(&area, xl, ys)?;
        } else {
            chart.draw(&area, xs, ys)?;
        }
    } else {
        if y1 <= y0 {
            y0 -= 0.5;
            y1 += 0.5;
        }
        let pad = 0.05 * (y1 - y0);
        let ys = y0 - pad..y1 + pad;
        if x_axis.log {
            chart.draw(&area, xl, ys)?;
        } else {
            chart.draw(&area, xs, ys)?;
        }
    }
    if let Some(legend) = legend {
        draw_legend(&legend, series)?;
    }
    Ok(())
}

/// What [`draw_line_plot_x`] draws once its axis ranges are known.
struct Chart<'a, F: Fn(&(f64, f64)) -> bool> {
    plot: &'a LinePlot<'a>,
    log_x: bool,
    marks: &'a [(f64, String)],
    series: &'a [Series],
    /// Whether a point is drawn (finite, positive on a log axis, above the floor).
    shown: &'a F,
}

/// Font size of the legend, the tick labels and the marks.
const SMALL: u32 = 13;

impl<F: Fn(&(f64, f64)) -> bool> Chart<'_, F> {
    /// Mesh with the axis labels (powers of ten on a log y axis), the marks, then the series:
    /// lines are broken where a point is not shown, markers of such points are left out.
    fn draw<DB, X, Y>(&self, area: &DrawingArea<DB, Shift>, x: X, y: Y) -> Result<()>
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
        X: AsRangedCoord<Value = f64>,
        X::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let mark_band = self
            .marks
            .iter()
            .map(|(_, name)| text_width(area, name))
            .max()
            .map_or(0, |w| w + 10);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .margin_top(12 + mark_band)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x, y)?;
        let power_of_ten = |v: &f64| format!("{v:.0e}");
        // Plain numbers on a log x axis (1, 10, 100 rather than 1e0, 1e1, 1e2).
        let plain = |v: &f64| format!("{}", (v * 1e3).round() / 1e3);
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(self.plot.x_label)
            .y_desc(self.plot.y_label)
            .label_style(("sans-serif", SMALL));
        if self.plot.log_y {
            mesh.y_label_formatter(&power_of_ten);
        }
        if self.log_x {
            mesh.x_label_formatter(&plain);
        }
        mesh.draw()?;
        let (y_lo, y_hi) = {
            let r = chart.y_range();
            (r.start, r.end)
        };
        let base = area.get_base_pixel();
        let font = ("sans-serif", SMALL)
            .into_font()
            .transform(FontTransform::Rotate270);
        for (x, name) in self.marks {
            let guide = [(*x, y_lo), (*x, y_hi)];
            chart.draw_series(std::iter::once(PathElement::new(
                guide.to_vec(),
                RGBColor(200, 200, 200),
            )))?;
            let (px, top) = chart.backend_coord(&guide[1]);
            area.draw(&Text::new(
                name.clone(),
                (px - base.0 - SMALL as i32 / 2, top - base.1 - 4),
                font.clone(),
            ))?;
        }
        for s in self.series {
            let colour = s.colour;
            if s.markers {
                let pts = s.points.iter().copied().filter(|p| (self.shown)(p));
                chart.draw_series(pts.map(|p| Circle::new(p, 3, colour.filled())))?;
            } else {
                for run in s.points.split(|p| !(self.shown)(p)) {
                    chart.draw_series(LineSeries::new(run.to_vec(), colour.stroke_width(2)))?;
                }
            }
        }
        Ok(())
    }
}

/// The width in pixels of `text` in the small font.
fn text_width<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str) -> i32 {
    area.estimate_text_size(text, &TextStyle::from(("sans-serif", SMALL).into_font()))
        .map_or(text.len() as i32 * 8, |(w, _)| w as i32)
}

/// Width of a legend entry's symbol and the gap after it, in pixels.
const LEGEND_SYMBOL: i32 = 22;

/// The axes' area and the legend's, if there is a legend.
type Areas<DB> = (DrawingArea<DB, Shift>, Option<DrawingArea<DB, Shift>>);

/// Split `area` into the axes and, when some series has a label, a legend column on the right
/// as wide as the longest label.
fn split_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, series: &[Series]) -> Areas<DB> {
    let widest = series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| text_width(area, &s.label))
        .max();
    match widest {
        Some(w) => {
            let width = area.dim_in_pixel().0 as i32;
            let (axes, legend) = area.split_horizontally(width - (w + LEGEND_SYMBOL + 24));
            (axes, Some(legend))
        }
        None => (area.clone(), None),
    }
}

/// The legend: one entry per labelled series, its symbol as the series is drawn (a line or a
/// dot) and its label, from the top of `area` down.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, series: &[Series]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let mut y = 20;
    for s in series.iter().filter(|s| !s.label.is_empty()) {
        let colour = s.colour;
        if s.markers {
            area.draw(&Circle::new(
                (4 + LEGEND_SYMBOL / 2 - 3, y),
                3,
                colour.filled(),
            ))?;
        } else {
            area.draw(&PathElement::new(
                vec![(4, y), (4 + LEGEND_SYMBOL - 6, y)],
                colour.stroke_width(2),
            ))?;
        }
        area.draw(&Text::new(
            s.label.clone(),
            (4 + LEGEND_SYMBOL, y - SMALL as i32 / 2 - 1),
            ("sans-serif", SMALL).into_font(),
        ))?;
        y += SMALL as i32 + 7;
    }
    Ok(())
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Render with `draw` into an RGB buffer of `size` and write it to `path` as PNG, atomically.
pub fn render_png(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend, Shift>) -> Result<()>,
) -> Result<()> {
    init_font();
    let mut buf = vec![255u8; size.0 as usize * size.1 as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root)?;
        root.present()?;
    }
    let img = image::RgbImage::from_raw(size.0, size.1, buf)
        .ok_or_else(|| PlotError::Draw("the plot buffer has the wrong size".into()))?;
    save_image_atomic(path, &image::DynamicImage::ImageRgb8(img))
}

/// Write an image (format from the extension) atomically ([`gonio_io::write_atomic`]).
pub fn save_image_atomic(path: &Path, img: &image::DynamicImage) -> Result<()> {
    let write_error = |error: String| PlotError::Write {
        path: path.to_path_buf(),
        error,
    };
    let format = image::ImageFormat::from_path(path)
        .map_err(|_| write_error("unknown image extension (use .png)".into()))?;
    gonio_io::write_atomic(
        path,
        |w| {
            img.write_to(w, format)
                .map_err(|e| write_error(e.to_string()))
        },
        |e| write_error(e.to_string()),
    )
}

/// One bar of a [`bar_chart_png`]: its label, its length and the half-width of its error bar
/// (0: none).
pub struct Bar {
    pub label: String,
    pub value: f64,
    pub error: f64,
}

/// Horizontal bars (a tornado of sensitivity indices), in the order given from the top, each
/// with its error bar, on an x axis from `min(0, smallest bar)` to the largest end of a bar or
/// an error bar (an error bar reaching below the axis is cut there: an interval wider than its
/// estimate says the estimate is not known to be above 0), the labels left of the axis, into a
/// PNG of `size` at `path`.
pub fn bar_chart_png(
    path: &Path,
    size: (u32, u32),
    title: &str,
    x_label: &str,
    bars: &[Bar],
) -> Result<()> {
    let finite = bars
        .iter()
        .filter(|b| b.value.is_finite() && b.error.is_finite());
    let lo = finite.clone().map(|b| b.value).fold(0.0f64, f64::min);
    let hi = finite.map(|b| b.value + b.error).fold(0.0f64, f64::max);
    if bars.is_empty() || hi <= lo {
        return Err(PlotError::Data(format!("nothing to plot in '{title}'")));
    }
    let pad = 0.05 * (hi - lo);
    let n = bars.len();
    render_png(path, size, |root| {
        let area = root.titled(title, ("sans-serif", 20))?;
        let x0 = lo - if lo < 0.0 { pad } else { 0.0 };
        let mut chart = ChartBuilder::on(&area)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(150)
            .build_cartesian_2d(x0..(hi + pad), 0.0..n as f64)?;
        chart
            .configure_mesh()
            .disable_y_mesh()
            .y_labels(0)
            .x_desc(x_label)
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .draw()?;
        for (i, bar) in bars.iter().enumerate() {
            let top = (n - i) as f64 - 0.15;
            let bottom = (n - i - 1) as f64 + 0.15;
            let middle = (top + bottom) / 2.0;
            if bar.value.is_finite() {
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(0.0, bottom), (bar.value, top)],
                    palette(0).filled(),
                )))?;
            }
            if bar.error > 0.0 && bar.error.is_finite() {
                let (a, b) = ((bar.value - bar.error).max(x0), bar.value + bar.error);
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(a, middle), (b, middle)],
                    BLACK.stroke_width(2),
                )))?;
                let ends = if a > x0 { vec![a, b] } else { vec![b] };
                for x in ends {
                    chart.draw_series(std::iter::once(PathElement::new(
                        vec![(x, middle - 0.12), (x, middle + 0.12)],
                        BLACK.stroke_width(2),
                    )))?;
                }
            }
            // In the backend's pixels, so drawn on the root (the title shifts `area`).
            let (x, y) = chart.backend_coord(&(x0, middle));
            root.draw(&Text::new(
                bar.label.clone(),
                (x - 8, y),
                TextStyle::from(("sans-serif", 15).into_font()).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Right,
                        plotters::style::text_anchor::VPos::Center,
                    ),
                ),
            ))?;
        }
        Ok(())
    })
}

/// A false-colour image of a grid of values (heights, BRDF maps, ...) with a colour bar.
pub struct Raster<'a> {
    /// Title above the image.
    pub title: &'a str,
    /// Values row-major, `width × height`; row 0 is drawn at the bottom (y up). NaN is grey.
    pub values: &'a [f64],
    pub width: usize,
    pub height: usize,
    /// Physical height over physical width of one cell (dy/dx), so that the image keeps the
    /// true aspect ratio.
    pub cell_aspect: f64,
    /// Values mapped to the ends of the colour scale (others are clamped).
    pub range: (f64, f64),
    /// Label of the colour bar, with its unit ("height (nm)").
    pub colour_label: &'a str,
    /// A scale bar: its length in cell widths and its label ("50 µm").
    pub scale_bar: Option<(f64, String)>,
}

/// The largest 1, 2 or 5 × 10^k not above `x > 0` (a round length for scale bars and ticks).
pub fn nice_number(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v <= x * (1.0 + 1e-12))
        .unwrap_or(p)
}

/// Draw `raster` (viridis colours) into a PNG of `size` pixels at `path`.
pub fn raster_png(path: &Path, size: (u32, u32), raster: &Raster) -> Result<()> {
    if raster.values.len() != raster.width * raster.height
        || raster.width == 0
        || raster.height == 0
    {
        return Err(PlotError::Data(format!(
            "raster of {} values is not {} × {}",
            raster.values.len(),
            raster.width,
            raster.height
        )));
    }
    render_png(path, size, |root| draw_raster(root, raster))
}

fn draw_raster(root: &DrawingArea<BitMapBackend, Shift>, r: &Raster) -> Result<()> {
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    root.draw(&Text::new(
        r.title.to_string(),
        (20, 12),
        ("sans-serif", 20).into_font(),
    ))?;
    // Image box: left part, below the title; the colour bar takes the right 130 pixels.
    let (bx, by, bw, bh) = (20, 50, (w - 170).max(10), (h - 70).max(10));
    let phys_w = r.width as f64;
    let phys_h = r.height as f64 * r.cell_aspect;
    let scale = (bw as f64 / phys_w).min(bh as f64 / phys_h);
    let (iw, ih) = (
        (phys_w * scale).round().max(1.0) as i32,
        (phys_h * scale).round().max(1.0) as i32,
    );
    let (lo, hi) = r.range;
    let span = if hi > lo { hi - lo } else { 1.0 };
    let grey = RGBColor(160, 160, 160);
    for py in 0..ih {
        // Pixel row py from the top shows grid row (height - 1) at the top.
        let row = ((ih - 1 - py) as f64 / ih as f64 * r.height as f64) as usize;
        let row = row.min(r.height - 1);
        for px in 0..iw {
            let col = ((px as f64 / iw as f64 * r.width as f64) as usize).min(r.width - 1);
            let v = r.values[row * r.width + col];
            let colour = if v.is_nan() {
                grey
            } else {
                ViridisRGB::get_color_normalized(((v - lo) / span).clamp(0.0, 1.0), 0.0, 1.0)
            };
            root.draw_pixel((bx + px, by + py), &colour)?;
        }
    }
    root.draw(&Rectangle::new(
        [(bx - 1, by - 1), (bx + iw, by + ih)],
        BLACK,
    ))?;
    if let Some((cells, label)) = &r.scale_bar {
        let len = (cells * scale).round() as i32;
        let (x0, y0) = (bx + 12, by + ih - 16);
        root.draw(&Rectangle::new(
            [(x0 - 3, y0 - 22), (x0 + len + 3, y0 + 9)],
            WHITE.mix(0.75).filled(),
        ))?;
        root.draw(&Rectangle::new(
            [(x0, y0), (x0 + len, y0 + 6)],
            BLACK.filled(),
        ))?;
        root.draw(&Text::new(
            label.clone(),
            (x0, y0 - 19),
            ("sans-serif", 14).into_font(),
        ))?;
    }
    // Colour bar with ticks at round values.
    let (cx, cw) = (bx + iw + 25, 22);
    let (cy0, cy1) = (by, by + ih.max(120));
    for py in cy0..cy1 {
        let t = 1.0 - (py - cy0) as f64 / (cy1 - cy0 - 1).max(1) as f64;
        let c = ViridisRGB::get_color_normalized(t, 0.0, 1.0);
        root.draw(&PathElement::new(vec![(cx, py), (cx + cw, py)], c))?;
    }
    root.draw(&Rectangle::new([(cx, cy0), (cx + cw, cy1)], BLACK))?;
    let step = nice_number(span / 4.0);
    let mut tick = (lo / step).ceil() * step;
    while tick <= hi + 1e-9 * span {
        let py = cy1 - 1 - ((tick - lo) / span * (cy1 - cy0 - 1) as f64).round() as i32;
        root.draw(&PathElement::new(
            vec![(cx + cw, py), (cx + cw + 5, py)],
            BLACK,
        ))?;
        let text = format!("{}", (tick / step).round() * step);
        root.draw(&Text::new(
            text,
            (cx + cw + 8, py - 7),
            ("sans-serif", 13).into_font(),
        ))?;
        tick += step;
    }
    root.draw(&Text::new(
        r.colour_label.to_string(),
        (cx - 4, cy1 + 8),
        ("sans-serif", 13).into_font(),
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(points: Vec<(f64, f64)>) -> Series {
        Series {
            label: "a curve".into(),
            points,
            colour: palette(0),
            markers: false,
        }
    }

    const SPEC: LinePlot = LinePlot {
        title: "t",
        x_label: "x",
        y_label: "y",
        log_y: true,
    };

    /// A line plot is a PNG of the requested size with the curve drawn in its colour.
    #[test]
    fn line_plot_draws_the_curve() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("curve.png");
        let points = (1..50).map(|i| (i as f64, (i as f64).powi(2))).collect();
        line_plot_png(&path, (400, 300), &SPEC, &[series(points)]).unwrap();
        let image = image::open(&path).unwrap().to_rgb8();
        assert_eq!(image.dimensions(), (400, 300));
        let blue = image.pixels().filter(|p| p.0 == [31, 119, 180]).count();
        assert!(blue > 100, "{blue} pixels of the curve's colour");
    }

    /// A bar chart draws each bar in the palette's first colour, longer bars with more of it.
    #[test]
    fn bar_chart_draws_bars_in_proportion() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bars.png");
        let bars = [("roughness", 0.9), ("tilt", 0.3)].map(|(l, v)| Bar {
            label: l.into(),
            value: v,
            error: 0.05,
        });
        bar_chart_png(&path, (600, 300), "ST of 60° gloss", "total index", &bars).unwrap();
        let image = image::open(&path).unwrap().to_rgb8();
        let row_count = |y: u32| {
            (0..image.width())
                .filter(|&x| image.get_pixel(x, y).0 == [31, 119, 180])
                .count()
        };
        // The two bars' rows: the widest blue run in the upper and the lower half.
        let widest = |ys: std::ops::Range<u32>| ys.map(row_count).max().unwrap() as f64;
        let (upper, lower) = (widest(40..170), widest(170..260));
        assert!(
            (upper / lower - 3.0).abs() < 0.15,
            "bars {upper} and {lower} px, not 0.9 : 0.3"
        );
        assert!(bar_chart_png(&path, (600, 300), "t", "x", &[]).is_err());
    }

    /// Nothing plottable (only non-positive values on a log axis) is an error naming the plot,
    /// and an unwritable path is an error naming the file; neither leaves a file behind.
    #[test]
    fn bad_plots_are_errors_naming_what_is_wrong() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("empty.png");
        let err = line_plot_png(&path, (400, 300), &SPEC, &[series(vec![(1.0, -1.0)])])
            .unwrap_err()
            .to_string();
        assert!(err.contains("nothing to plot in 't'"), "{err}");
        assert!(!path.exists());
        let missing = dir.path().join("no/such/dir/p.png");
        let err = line_plot_png(&missing, (400, 300), &SPEC, &[series(vec![(1.0, 1.0)])])
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("p.png") && err.contains("cannot write"),
            "{err}"
        );
        let err = line_plot_png(
            &dir.path().join("p.xyz"),
            (400, 300),
            &SPEC,
            &[series(vec![(1.0, 1.0)])],
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("unknown image extension"), "{err}");
    }
}
