//! The `gonio` command: parses flags, calls into the gonio crates and formats their results.
//! No physics lives here.
//!
//! The doc comments of the flags are the help text clap prints (`gonio booth --help`), written
//! for a terminal: `[render]` there is a TOML table, `<angle>` a placeholder, not rustdoc links
//! or HTML, so rustdoc is told not to read them as such.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

mod booth;
mod brdf;
mod brdf_compute;
mod coating;
mod coating_predict;
mod color;
mod compare;
mod conformance;
mod demo;
mod gloss;
mod inplane;
mod isotropy;
mod lab;
mod multiangle;
mod pigments;
mod progress;
mod render;
mod study;
mod surface;
mod surface_gen;
mod surface_waviness;
mod texture;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// gonio: predict how a coated surface looks from its measured topography.
///
/// Units are SI inside; every flag and output column names its unit (`--sq-nm`, `--dx-um`,
/// `_deg`, `_per_sr`). Errors exit with status 2.
#[derive(Parser)]
#[command(name = "gonio", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Channel of a multi-channel instrument file to read (AFM files store height, phase,
    /// amplitude, trace and retrace): a name, compared without regard to case, or a 0-based
    /// index. Default: the file's first height channel. `gonio surface info FILE` lists them.
    #[arg(long, global = true, value_name = "NAME|INDEX")]
    channel: Option<gonio_surface::ChannelSelector>,
}

#[derive(Subcommand)]
enum Command {
    /// Height maps: statistics, synthesis, conversion, levelling, cropping, rotation, plots.
    #[command(subcommand)]
    Surface(surface::SurfaceCommand),
    /// Compare measured and computed in-plane curves (RMS of log reflectance, peaks, FWHM).
    Compare(compare::CompareArgs),
    /// In-plane BRDF curves of a height map (ray method), written to CSV:
    /// `gonio inplane SURFACE --incidence-deg 20,45,60,70 --scatter-deg=-75:75:1 -o OUT.csv`.
    Inplane(inplane::InplaneArgs),
    /// Colorimetry of spectra: `gonio color xyz --spectrum FILE.csv` prints CIE XYZ, xyY,
    /// CIELAB and sRGB.
    Color(color::ColorArgs),
    /// The roughness study: curves, statistics and peaks across a series of surfaces.
    Study(study::StudyArgs),
    /// Run the whole pipeline on the embedded default data and write out/report.html.
    Demo(demo::DemoArgs),
    /// Tabulated BRDFs (.gbrdf): info, import (Cornell ASTM, MERL, CSV), export (MERL, Mitsuba
    /// tensor, PAB-Opto, CSV), plot, tabulate an analytic model, fit a model.
    #[command(subcommand)]
    Brdf(brdf::BrdfCommand),
    /// Render a scene file with the path tracer:
    /// `gonio render SCENE.toml [--spp N] [--seed S] -o OUT.{exr,hdr,png}` (docs/render.md).
    Render(render::RenderArgs),
    /// Gloss (ISO 2813, 20/60/85°), haze and DOI (ASTM E430) of a height map or BRDF table.
    Gloss(gloss::GlossArgs),
    /// Isotropy check: in-plane curves of a height map and of the map turned by 90° (or any
    /// angle), with their differences: `gonio isotropy SURFACE --angle-deg 90,45 -o PLOT.png`.
    Isotropy(isotropy::IsotropyArgs),
    /// Multi-angle colour of a spectral BRDF table (ASTM E2194, E2539): CIELAB at each
    /// geometry, the flop index and differences from a reference:
    /// `gonio multiangle T.gbrdf [--standard e2539] [--reference R.gbrdf] [--json]`.
    Multiangle(multiangle::MultiangleArgs),
    /// Coatings from their constituents (docs/coatings.md): `gonio coating compute COATING.toml
    /// -o T.gbrdf` tabulates the body reflection, `gonio coating info COATING.toml` summarises.
    #[command(subcommand)]
    Coating(coating::CoatingCommand),
    /// gonio's built-in library of measured pigments (docs/coatings.md, "The pigment library"):
    /// `gonio pigments` lists them; `gonio pigments NAME [-o DIR] [--json]` shows one, its
    /// masstone and 1:10 tint with titanium white, and writes its K/S plot and swatches.
    Pigments(pigments::PigmentsArgs),
    /// The formulation lab: a web page on this machine where a coating's formulation is changed
    /// with sliders and its readings, colour and picture follow (docs/lab.md):
    /// `gonio lab [--port 8765]`, then open http://127.0.0.1:8765/.
    Lab(lab::LabArgs),
    /// The virtual texture camera (docs/instruments.md, "Texture"): sparkle under a lamp at
    /// 15°, 45° and 75° and graininess under diffuse light, from pictures of a coating's flakes
    /// drawn one by one: `gonio texture COATING.toml [--json] [-o DIR]`.
    Texture(texture::TextureArgs),
    /// Appearance conformance (docs/conformance.md): test scenes with analytic references on
    /// gonio, Mitsuba 3 and Radiance: `gonio conformance [-o DIR] [--renderers ...] [--json]`.
    Conformance(conformance::ConformanceArgs),
    /// The virtual viewing booth (docs/standard.md): `gonio booth COATING.toml|T.gbrdf|SPEC.toml
    /// -o DIR` writes each view's absolute XYZ OpenEXR, sRGB and P3 PNGs, masks and a manifest.
    Booth(booth::BoothArgs),
}

fn main() -> ExitCode {
    die_quietly_on_closed_stdout();
    let matches = accept_negative_numbers(Cli::command()).get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    if let Some(selector) = &cli.channel {
        surface::choose_channel(selector.clone());
    }
    let result: anyhow::Result<()> = match cli.command {
        Command::Surface(cmd) => surface::run(cmd),
        Command::Compare(args) => compare::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Gloss(args) => gloss::run(args),
        Command::Brdf(cmd) => brdf::run(cmd),
        Command::Study(args) => study::run(args),
        Command::Inplane(args) => inplane::run(args),
        Command::Color(args) => color::run(args),
        Command::Render(_) if cli.channel.is_some() => Err(anyhow::anyhow!(
            "--channel: `gonio render` reads the height maps its scene names; give a surface's \
             channel in the scene, `surface = {{ file = \"...\", channel = \"Height\" }}`"
        )),
        Command::Render(args) => render::run(args),
        Command::Isotropy(args) => isotropy::run(args),
        Command::Multiangle(args) => multiangle::run(args),
        Command::Lab(args) => lab::run(args),
        Command::Coating(cmd) => coating::run(cmd),
        Command::Pigments(args) => pigments::run(args),
        Command::Texture(args) => texture::run(args),
        Command::Conformance(args) => conformance::run(args),
        Command::Booth(args) => booth::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {}", message(&err));
            ExitCode::from(2)
        }
    }
}

/// Let every flag and positional value of every subcommand take a negative number
/// (`--sq-nm -5`, `--exposure -1`), so that the command's own range check explains what is
/// wrong instead of clap reading `-5` as an unknown flag.
fn accept_negative_numbers(cmd: clap::Command) -> clap::Command {
    cmd.mut_args(|arg| {
        if arg.get_action().takes_values() {
            arg.allow_negative_numbers(true)
        } else {
            arg
        }
    })
    .mut_subcommands(accept_negative_numbers)
}

/// The error and its causes, outermost first, joined by ": ", each said once: a cause whose
/// text the message already contains (an error type that prints its source and also returns it
/// as `source()`) is left out.
fn message(err: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in err.chain() {
        let part = cause.to_string();
        if text.contains(&part) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

/// When the reader of stdout goes away (`gonio inplane ... --json | head -c 10`), end the process
/// silently by SIGPIPE, as `cat` and other Unix tools do: the shell reports status 141 (128 + 13)
/// and prints nothing. Rust ignores SIGPIPE by default, which turns the failed write into a panic
/// ("failed printing to stdout"); restoring the default action fixes every command at once.
fn die_quietly_on_closed_stdout() {
    #[cfg(unix)]
    // SAFETY: `signal` with `SIG_DFL` installs no handler code; this runs first in `main`, before
    // any other thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// [`gonio_report::units::comma_list`] as the one default of an argument that takes a list (`value_delimiter =
/// ','`). clap splits it as it splits what a user types; `default_values_t` would show the list
/// joined by spaces ("20 45 60 70"), which the argument does not accept from a user who copies
/// it. Made once per argument as the command is built (clap keeps a default for the life of the
/// process).
fn list_default<T: std::fmt::Display>(values: &[T]) -> &'static str {
    Box::leak(gonio_report::units::comma_list(values).into_boxed_str())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cause_printed_by_its_error_is_not_repeated() {
        let io = std::io::Error::from(std::io::ErrorKind::NotFound);
        let said = io.to_string();
        let err = anyhow::Error::new(gonio_surface::SurfaceError::io("a.x3p", io))
            .context("reading the map");
        assert_eq!(message(&err), format!("reading the map: a.x3p: {said}"));
    }

    /// Every list argument shows its default as one comma-separated value, the form it takes
    /// ("--resolution 90,90,48"), and clap splits that default as it splits a typed list.
    #[test]
    fn list_defaults_are_shown_as_a_user_types_them() {
        fn check(cmd: &clap::Command, lists: &mut usize) {
            for arg in cmd.get_arguments() {
                if arg.get_value_delimiter().is_some() && !arg.get_default_values().is_empty() {
                    *lists += 1;
                    assert_eq!(
                        arg.get_default_values().len(),
                        1,
                        "{} --{}: {:?}",
                        cmd.get_name(),
                        arg.get_id(),
                        arg.get_default_values()
                    );
                }
            }
            for sub in cmd.get_subcommands() {
                check(sub, lists);
            }
        }
        let mut lists = 0;
        check(&Cli::command(), &mut lists);
        assert!(lists >= 10, "{lists} list arguments with a default");
        let help = Cli::command()
            .find_subcommand_mut("brdf")
            .and_then(|b| b.find_subcommand_mut("import"))
            .expect("gonio brdf import")
            .render_long_help()
            .to_string();
        assert!(help.contains("[default: 90,90,48]"), "{help}");
        let m = Cli::command()
            .try_get_matches_from(["gonio", "inplane", "map.x3p"])
            .unwrap();
        let incidences: Vec<f64> = m
            .subcommand_matches("inplane")
            .unwrap()
            .get_many::<f64>("incidence_deg")
            .unwrap()
            .copied()
            .collect();
        assert_eq!(incidences, gonio_scatter::geometry::STARR_INCIDENCES_DEG);
    }

    #[test]
    fn distinct_causes_are_all_shown() {
        let err = anyhow::anyhow!("disk full")
            .context("b.png: cannot write")
            .context("plotting");
        assert_eq!(message(&err), "plotting: b.png: cannot write: disk full");
    }
}
