//! `gonio surface ...`: inspect, synthesise, convert, level, crop, rotate and plot height maps.
//! Lengths on the command line are in the unit their flag names (`--sq-nm`, `--dx-um`); files
//! and JSON hold SI metres.

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use gonio_report::plots::plot_height_map;
use gonio_report::units::length;
use gonio_surface::profile_stats::profile_statistics;
use gonio_surface::stats::{self, Statistics};
use gonio_surface::{ChannelSelector, HeightMap, io, ops};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Height maps: statistics, synthesis and editing.
///
/// Formats read (detected from the content): X3P, SDF, Gwyddion GSF and ASCII, Zygo .dat,
/// Wyko .opd, Sensofar .plu, Digital Surf .sur, MountainsMap .mnt, Alicona .al3d, FRT .frt,
/// NanoFocus .nms, TrueMap .tmd, Bruker Nanoscope .spm/.di, Nanosurf .nid, Igor .ibw, PicoView
/// .mi, WSxM .top/.stp, Bruker .opdx profiles, text x y z lists and h= w= matrices
/// (docs/formats.md). Multi-channel files: `--channel NAME|INDEX`. Written: .x3p and .gsf,
/// chosen by the output file's extension.
#[derive(Subcommand)]
pub enum SurfaceCommand {
    /// Print the grid, metadata, the rms height as read and the ISO 25178-2 statistics after
    /// plane levelling of a file.
    Info(InfoArgs),
    /// Synthesise a periodic Gaussian random surface (FFT spectral filtering): a Gaussian or
    /// exponential ACF, a power-law PSD (an orange peel), or a measured PSD table.
    ///
    /// `--corr-um T --sq-nm S` gives an ACF surface; `--psd FILE` a measured PSD's; otherwise a
    /// power-law PSD C(q) ∝ q^-n between two wavelengths, by default an automotive clear coat's
    /// orange peel: n = 4 between 0.3 and 10 mm with an rms slope along x of 1 mrad
    /// (docs/surface.md). Lengths in the unit each flag names; the map is written in metres.
    Gen(crate::surface_gen::GenArgs),
    /// Convert a height map to another format (the output extension picks .x3p or .gsf).
    Convert(ConvertArgs),
    /// Subtract the least-squares plane.
    Level(EditArgs),
    /// Cut out a rectangle, given in micrometres or in points.
    Crop(CropArgs),
    /// Rotate about the centre (bicubic resampling; points that leave the map become invalid).
    Rotate(RotateArgs),
    /// Draw a false-colour height image (levelled) with a scale bar and a colour bar.
    Plot(PlotArgs),
    /// Wave-scan bands (Wa-We, SW, LW) of the slope along x or y: rms slope per band (mrad).
    Waviness(crate::surface_waviness::WavinessArgs),
}

#[derive(Args)]
pub struct InfoArgs {
    /// Height-map file.
    file: PathBuf,
    /// Print one JSON object (lengths in metres: keys ending in _m).
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct ConvertArgs {
    /// Input height-map file.
    input: PathBuf,
    /// Output file, .x3p or .gsf (or give it with -o, as the other commands take it).
    #[arg(
        value_name = "OUTPUT",
        required_unless_present = "output",
        conflicts_with = "output"
    )]
    target: Option<PathBuf>,
    /// Output file, .x3p or .gsf.
    #[arg(short, long)]
    output: Option<PathBuf>,
}

#[derive(Args)]
pub struct EditArgs {
    /// Input height-map file.
    input: PathBuf,
    /// Output file, .x3p or .gsf.
    #[arg(short, long)]
    output: PathBuf,
}

#[derive(Args)]
pub struct CropArgs {
    /// Input height-map file.
    input: PathBuf,
    /// Left edge in micrometres from the first column (default 0).
    #[arg(long)]
    x_um: Option<f64>,
    /// Bottom edge in micrometres from the first row (default 0).
    #[arg(long)]
    y_um: Option<f64>,
    /// Width in micrometres (default: to the right edge).
    #[arg(long)]
    width_um: Option<f64>,
    /// Height in micrometres (default: to the top edge).
    #[arg(long)]
    height_um: Option<f64>,
    /// Left edge in points (instead of --x-um).
    #[arg(long, conflicts_with_all = ["x_um", "y_um", "width_um", "height_um"])]
    x_px: Option<usize>,
    /// Bottom edge in points (instead of --y-um).
    #[arg(long, conflicts_with_all = ["x_um", "y_um", "width_um", "height_um"])]
    y_px: Option<usize>,
    /// Width in points (instead of --width-um).
    #[arg(long, conflicts_with_all = ["x_um", "y_um", "width_um", "height_um"])]
    width_px: Option<usize>,
    /// Height in points (instead of --height-um).
    #[arg(long, conflicts_with_all = ["x_um", "y_um", "width_um", "height_um"])]
    height_px: Option<usize>,
    /// Output file, .x3p or .gsf.
    #[arg(short, long)]
    output: PathBuf,
}

#[derive(Args)]
pub struct RotateArgs {
    /// Input height-map file.
    input: PathBuf,
    /// Angle in degrees, counter-clockwise (from +x toward +y).
    #[arg(long, allow_hyphen_values = true)]
    angle_deg: f64,
    /// Output file, .x3p or .gsf.
    #[arg(short, long)]
    output: PathBuf,
}

#[derive(Args)]
pub struct PlotArgs {
    /// Height-map file.
    file: PathBuf,
    /// Output image (.png).
    #[arg(short, long)]
    output: PathBuf,
}

/// Run a `gonio surface` command.
pub fn run(cmd: SurfaceCommand) -> Result<()> {
    match cmd {
        SurfaceCommand::Info(a) => info(&a),
        SurfaceCommand::Gen(a) => crate::surface_gen::run(&a),
        SurfaceCommand::Convert(a) => {
            let output = a
                .output
                .or(a.target)
                .context("name the output file: -o OUTPUT")?;
            write(&read(&a.input)?, &output)
        }
        SurfaceCommand::Level(a) => write(&ops::level(&read(&a.input)?)?, &a.output),
        SurfaceCommand::Crop(a) => crop(&a),
        SurfaceCommand::Rotate(a) => {
            let map = read(&a.input)?;
            let rotated = busy("rotating", || ops::rotate(&map, a.angle_deg.to_radians()))?;
            write(&rotated, &a.output)
        }
        SurfaceCommand::Plot(a) => plot_map(&a),
        SurfaceCommand::Waviness(a) => crate::surface_waviness::run(&a),
    }
}

/// The channel that the global `--channel` flag chose for every file read; unset, each file's
/// first height channel is read.
static CHANNEL: OnceLock<ChannelSelector> = OnceLock::new();

/// Read every file's channel `selector` (`main` calls this once, from `--channel`).
pub fn choose_channel(selector: ChannelSelector) {
    // Set once, before any file is read; a second call could only repeat the same flag.
    let _ = CHANNEL.set(selector);
}

/// Read a height map or line profile in the channel `--channel` chose, printing the reader's
/// warnings (e.g. a checksum mismatch) to stderr.
pub fn read_any(path: &Path) -> Result<HeightMap> {
    let options = io::ReadOptions {
        channel: CHANNEL.get().cloned(),
    };
    let map = io::read_with(path, &options)?;
    for w in map.meta.warnings() {
        eprintln!("warning: {w}");
    }
    Ok(map)
}

/// Read an areal height map ([`read_any`]); a file that holds a line profile is refused with a
/// message that says so, since scattering, gloss and rendering need an areal map.
pub fn read(path: &Path) -> Result<HeightMap> {
    let map = read_any(path)?;
    if map.is_profile() {
        bail!(
            "{}: the file holds a line profile ({} points), not an areal height map; this \
             command needs an areal map (`gonio surface info` gives the profile's ISO 21920-2 \
             statistics)",
            path.display(),
            map.nx()
        );
    }
    Ok(map)
}

pub fn write(map: &HeightMap, path: &Path) -> Result<()> {
    io::write(map, path)?;
    Ok(())
}

/// Run `work` with a spinner on a terminal (nothing when stderr is a pipe).
pub fn busy<T>(message: &str, work: impl FnOnce() -> T) -> T {
    let bar = crate::progress::spinner(message);
    let out = work();
    bar.finish_and_clear();
    out
}

fn info(a: &InfoArgs) -> Result<()> {
    let map = read_any(&a.file)?;
    if map.is_profile() {
        return profile_info(a, &map);
    }
    let st = busy("computing statistics", || stats::statistics(&map))
        .with_context(|| format!("{}: statistics", a.file.display()))?;
    let raw = rms_as_read(&map);
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&info_json(&map, &st, raw))?
        );
    } else {
        print!("{}", info_text(&a.file, &map, &st, raw));
    }
    Ok(())
}

/// The rms height of the valid points about their mean, before any levelling: with Sq after
/// levelling it shows how much of the heights was tilt.
fn rms_as_read(map: &HeightMap) -> f64 {
    let valid = || map.heights().iter().filter(|z| !z.is_nan());
    let n = valid().count() as f64;
    let mean = valid().sum::<f64>() / n;
    (valid().map(|z| (z - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// A finite number as JSON, anything else as null.
fn num(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

fn info_json(map: &HeightMap, st: &Statistics, rms_as_read: f64) -> Value {
    let meta = &map.meta;
    let extra: serde_json::Map<String, Value> = meta
        .extra
        .iter()
        .filter(|(k, _)| k != gonio_surface::heightmap::WARNING_KEY)
        .map(|(k, v)| (k.clone(), json!(v)))
        .collect();
    let out = json!({
        "nx": map.nx(),
        "ny": map.ny(),
        "dx_m": map.dx(),
        "dy_m": map.dy(),
        "valid_fraction": map.valid_fraction(),
        "rms_unlevelled_m": num(rms_as_read),
        "sq_m": num(st.sq),
        "sa_m": num(st.sa),
        "ssk": num(st.ssk),
        "sku": num(st.sku),
        "sdq": num(st.sdq),
        "sal_m": st.sal.map_or(Value::Null, num),
        "str": st.str.map_or(Value::Null, num),
        "str_upper_bound": st.str_is_upper_bound,
        "metadata": extra,
    });
    with_file_fields(out, map)
}

/// `out` with what the file says of itself: format, instrument, date, source, its channels and
/// the one read, the reader's warnings.
fn with_file_fields(mut out: Value, map: &HeightMap) -> Value {
    let meta = &map.meta;
    let channels: Vec<Value> = meta
        .channels
        .iter()
        .map(|c| {
            json!({"index": c.index, "name": c.name, "unit": c.unit, "is_height": c.is_height,
                        "problem": c.problem})
        })
        .collect();
    let fields = json!({
        "format": meta.format,
        "instrument": meta.instrument,
        "date": meta.date,
        "source": meta.source.as_ref().map(|p| p.display().to_string()),
        "channels": channels,
        "channel": meta.channel,
        "warnings": meta.warnings().collect::<Vec<_>>(),
    });
    if let (Some(out), Value::Object(fields)) = (out.as_object_mut(), fields) {
        out.extend(fields);
    }
    out
}

/// The file's channels, one line, the one read marked; nothing for a single-channel file.
fn channels_text(map: &HeightMap) -> String {
    let channels = &map.meta.channels;
    if channels.len() < 2 {
        return String::new();
    }
    let list: Vec<String> = channels
        .iter()
        .map(|c| {
            let mark = if c.index == map.meta.channel {
                " ← read"
            } else {
                ""
            };
            match &c.problem {
                Some(problem) => format!("{c} [cannot be read: {problem}]{mark}"),
                None => format!("{c}{mark}"),
            }
        })
        .collect();
    format!(
        "  channels    {} (choose with --channel NAME|INDEX)\n",
        list.join(", ")
    )
}

/// One line of `surface info`: a parameter's name, its value (lengths in the unit that suits
/// them) and what it means, in aligned columns.
fn line(name: &str, value: String, meaning: &str) -> String {
    format!("  {name:<4}{value:>14}   {meaning}\n")
}

/// `surface info` of a line profile: its ISO 21920-2 statistics after removing the
/// least-squares line.
fn profile_info(a: &InfoArgs, map: &HeightMap) -> Result<()> {
    let st =
        profile_statistics(map).with_context(|| format!("{}: statistics", a.file.display()))?;
    let meta = &map.meta;
    let length_m = map.dx() * map.nx() as f64;
    if a.json {
        let out = json!({
            "profile": true,
            "n": map.nx(),
            "dx_m": map.dx(),
            "length_m": length_m,
            "valid_fraction": map.valid_fraction(),
            "rq_m": num(st.rq),
            "ra_m": num(st.ra),
            "rsk": num(st.rsk),
            "rku": num(st.rku),
            "rdq": num(st.rdq),
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&with_file_fields(out, map))?
        );
        return Ok(());
    }
    let mut s = format!("{}\n", a.file.display());
    s += &format!("  format      {}\n", meta.format.as_deref().unwrap_or("?"));
    s += &channels_text(map);
    s += &format!(
        "  profile     {} points, spacing {}, length {}\n",
        map.nx(),
        length(map.dx()),
        length(length_m)
    );
    s += &format!(
        "  valid       {:.2}% of points\n",
        100.0 * map.valid_fraction()
    );
    s += "  after removing the least-squares line (ISO 21920-2, no λc filter):\n";
    s += &line("Rq", length(st.rq), "rms height");
    s += &line("Ra", length(st.ra), "mean absolute height");
    s += &line("Rsk", format!("{:.4}", st.rsk), "skewness");
    s += &line("Rku", format!("{:.4}", st.rku), "kurtosis");
    s += &line("Rdq", format!("{:.5}", st.rdq), "rms slope");
    print!("{s}");
    Ok(())
}

fn info_text(path: &Path, map: &HeightMap, st: &Statistics, rms_as_read: f64) -> String {
    let meta = &map.meta;
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or("undefined".into(), f);
    let mut s = format!("{}\n", path.display());
    s += &format!("  format      {}\n", meta.format.as_deref().unwrap_or("?"));
    s += &channels_text(map);
    if let Some(i) = &meta.instrument {
        s += &format!("  instrument  {i}\n");
    }
    if let Some(d) = &meta.date {
        s += &format!("  date        {d}\n");
    }
    s += &format!(
        "  grid        {} × {} points, spacing {} × {}, field {} × {}\n",
        map.nx(),
        map.ny(),
        length(map.dx()),
        length(map.dy()),
        length(map.dx() * map.nx() as f64),
        length(map.dy() * map.ny() as f64)
    );
    s += &format!(
        "  valid       {:.2}% of points\n",
        100.0 * map.valid_fraction()
    );
    s += "  as read:\n";
    s += &line(
        "rms",
        length(rms_as_read),
        "rms height about the mean, before levelling",
    );
    s += "  after least-squares levelling (ISO 25178-2):\n";
    s += &line("Sq", length(st.sq), "rms height");
    s += &line("Sa", length(st.sa), "mean absolute height");
    s += &line("Ssk", format!("{:.4}", st.ssk), "skewness");
    s += &line("Sku", format!("{:.4}", st.sku), "kurtosis");
    // A damaged header's spacing can make the gradient astronomically large: no run of digits.
    let sdq = if st.sdq.abs() < 1e4 {
        format!("{:.5}", st.sdq)
    } else {
        format!("{:.4e}", st.sdq)
    };
    s += &line("Sdq", sdq, "rms gradient");
    s += &line(
        "Sal",
        opt(st.sal, &|v| length(v)),
        "autocorrelation length (s = 0.2)",
    );
    s += &line(
        "Str",
        opt(st.str, &|v| {
            if st.str_is_upper_bound {
                format!("<= {v:.4}")
            } else {
                format!("{v:.4}")
            }
        }),
        "texture aspect ratio",
    );
    for (k, v) in meta
        .extra
        .iter()
        .filter(|(k, _)| k != gonio_surface::heightmap::WARNING_KEY)
    {
        s += &format!("  {k}: {v}\n");
    }
    s
}

fn crop(a: &CropArgs) -> Result<()> {
    let map = read(&a.input)?;
    let pixels = |start_um: Option<f64>,
                  len_um: Option<f64>,
                  d: f64,
                  name: &str|
     -> Result<(Option<usize>, Option<usize>)> {
        let to_px = |v: f64, flag: &str| -> Result<usize> {
            if !(v.is_finite() && v >= 0.0) {
                bail!("--{flag} = {v}: give a length >= 0 in micrometres");
            }
            Ok((v * 1e-6 / d).round() as usize)
        };
        Ok((
            start_um
                .map(|v| to_px(v, if name == "x" { "x-um" } else { "y-um" }))
                .transpose()?,
            len_um
                .map(|v| to_px(v, if name == "x" { "width-um" } else { "height-um" }))
                .transpose()?,
        ))
    };
    let (x0, w) = match pixels(a.x_um, a.width_um, map.dx(), "x")? {
        (None, None) => (a.x_px, a.width_px),
        um => um,
    };
    let (y0, h) = match pixels(a.y_um, a.height_um, map.dy(), "y")? {
        (None, None) => (a.y_px, a.height_px),
        um => um,
    };
    let (x0, y0) = (x0.unwrap_or(0), y0.unwrap_or(0));
    let w = w.unwrap_or(map.nx().saturating_sub(x0));
    let h = h.unwrap_or(map.ny().saturating_sub(y0));
    let out = ops::crop(&map, x0, y0, w, h).with_context(|| {
        format!(
            "{}: choose a rectangle inside the map (spacing {:.4} × {:.4} µm)",
            a.input.display(),
            map.dx() * 1e6,
            map.dy() * 1e6
        )
    })?;
    write(&out, &a.output)
}

fn plot_map(a: &PlotArgs) -> Result<()> {
    let map = read(&a.file)?;
    let name = a.file.file_name().map_or_else(
        || a.file.display().to_string(),
        |n| n.to_string_lossy().into(),
    );
    Ok(plot_height_map(&map, &name, &a.output)?)
}
