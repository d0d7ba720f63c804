//! `gonio pigments [NAME]`: gonio's built-in pigment library ([`gonio_coating::pigment_library`]).
//! Without a name, the list (name, Colour Index name, masstone colour); with one, the pigment's
//! masstone and 1:10 tint with titanium white, and with `-o DIR` its K and S plot and swatches.

use crate::color::{parse_illuminant, parse_observer};
use anyhow::{Context, Result};
use clap::Args;
use gonio_coating::pigment_library::{
    self as library, LibraryPigment, SAUNDERSON_K1, SAUNDERSON_K2, SCALE_PER_UM, TINT_PARTS_WHITE,
    WHITE,
};
use gonio_color::{Colorimetry, Illuminant, Observer, Spectrum};
use gonio_plot::{LinePlot, Series, palette};
use plotters::prelude::*;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct PigmentsArgs {
    /// A pigment of the library (e.g. phthalo_blue_green_shade): its masstone and its tint of 1
    /// part to 10 parts of titanium white. Without it: the list of the library's pigments.
    name: Option<String>,
    /// Write NAME_ks.png (its relative K, S and K/S over wavelength) and NAME_swatches.png (its
    /// masstone and tint, through the paint's surface and inside it) into this folder.
    #[arg(short, long, value_name = "DIR", requires = "name")]
    output: Option<PathBuf>,
    /// CIE standard illuminant of the colours: D65 (daylight) or A (tungsten).
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    illuminant: Illuminant,
    /// CIE standard observer by field size in degrees: 2 (CIE 1931) or 10 (CIE 1964).
    #[arg(long, value_name = "DEG", default_value = "10", value_parser = parse_observer)]
    observer: Observer,
    /// Print the result as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: PigmentsArgs) -> Result<()> {
    match &a.name {
        None => list(&a),
        Some(name) => one(&a, library::find(name)?),
    }
}

/// A reflectance's colour, inside the paint's surface (Kubelka-Munk's R∞) and through it
/// (Saunderson's correction with the database's k1, k2).
struct Seen {
    inside: Spectrum,
    measured: Spectrum,
    inside_colour: Colorimetry,
    measured_colour: Colorimetry,
}

impl Seen {
    fn new(inside: Spectrum, a: &PigmentsArgs) -> Self {
        let measured = library::as_measured(&inside);
        Seen {
            inside_colour: Colorimetry::of_reflectance(&inside, a.illuminant, a.observer),
            measured_colour: Colorimetry::of_reflectance(&measured, a.illuminant, a.observer),
            inside,
            measured,
        }
    }

    fn to_json(&self) -> Value {
        json!({
            "inside": colour_json(&self.inside_colour, &self.inside),
            "through_surface": colour_json(&self.measured_colour, &self.measured),
        })
    }
}

fn colour_json(c: &Colorimetry, r: &Spectrum) -> Value {
    json!({
        "cielab": { "l_star": c.lab.l, "a_star": c.lab.a, "b_star": c.lab.b },
        "srgb_8bit": c.srgb.to_u8(),
        "srgb_hex": c.srgb.to_hex(),
        "srgb_in_gamut": c.linear_srgb.in_gamut(),
        "reflectance": r.values(),
    })
}

/// What the library is and how its colours are computed, for both outputs.
fn library_json(a: &PigmentsArgs) -> Value {
    json!({
        "source": "golden_heavy_body_ks.csv: RIT Artist Paint Spectral Database (Okumura 2005, \
                   Berns' group), as repackaged in waacton/Unicolour (MIT, commit 4bf3d8cf)",
        "units": "relative: titanium white's S = 1",
        "scale_per_um": SCALE_PER_UM,
        "saunderson_k1": SAUNDERSON_K1,
        "saunderson_k2": SAUNDERSON_K2,
        "illuminant": a.illuminant.name(),
        "observer_deg": a.observer.field_deg(),
    })
}

fn heading(a: &PigmentsArgs) -> String {
    format!(
        "K and S in relative units (titanium white's S = 1); in a layer, K and S per µm = \
         {SCALE_PER_UM} × concentration × these.\n\
         \"through the surface\": Saunderson's correction, k1 {SAUNDERSON_K1}, k2 {SAUNDERSON_K2}, \
         specular excluded (the database's instrument); \"inside\": Kubelka-Munk's R∞.\n\
         Colours under {}, {} observer.\n",
        a.illuminant, a.observer
    )
}

fn list(a: &PigmentsArgs) -> Result<()> {
    let rows = library::pigments()
        .iter()
        .map(|p| Ok((p, Seen::new(p.masstone()?, a))))
        .collect::<Result<Vec<_>>>()?;
    if a.json {
        let out = json!({
            "library": library_json(a),
            "pigments": rows.iter().map(|(p, seen)| json!({
                "name": p.name,
                "colour_index": p.colour_index,
                "masstone": seen.to_json(),
            })).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    print!(
        "gonio's pigment library: {} pigments, Golden Heavy Body acrylics (RIT Artist Paint \
         Spectral Database, via Unicolour).\n{}\n\
         masstone through the surface\n\
         {:<28} {:<6} {:>6} {:>7} {:>7}  sRGB\n",
        rows.len(),
        heading(a),
        "name",
        "C.I.",
        "L*",
        "a*",
        "b*"
    );
    for (p, seen) in &rows {
        let c = &seen.measured_colour;
        println!(
            "{:<28} {:<6} {:>6.2} {:>7.2} {:>7.2}  {}",
            p.name,
            p.colour_index,
            c.lab.l,
            c.lab.a,
            c.lab.b,
            c.srgb.to_hex()
        );
    }
    println!("\n`gonio pigments NAME [-o DIR]` shows one: its K and S, masstone and tint.");
    Ok(())
}

fn one(a: &PigmentsArgs, p: &LibraryPigment) -> Result<()> {
    let masstone = Seen::new(p.masstone()?, a);
    let tint = Seen::new(p.tint()?, a);
    let mut written = Vec::new();
    if let Some(dir) = &a.output {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the folder", dir.display()))?;
        let ks = dir.join(format!("{}_ks.png", p.name));
        plot_ks(&ks, p)?;
        let swatches = dir.join(format!("{}_swatches.png", p.name));
        draw_swatches(&swatches, p, &masstone, &tint)?;
        written = vec![ks, swatches];
    }
    if a.json {
        let out = json!({
            "library": library_json(a),
            "name": p.name,
            "colour_index": p.colour_index,
            "wavelengths_nm": library::wavelengths_nm(),
            "k_relative": p.k.values(),
            "s_relative": p.s.values(),
            "masstone": masstone.to_json(),
            "tint": {
                "white": WHITE,
                "parts_white_per_part": TINT_PARTS_WHITE,
                "colour": tint.to_json(),
            },
            "files": written.iter().map(|f| f.display().to_string()).collect::<Vec<_>>(),
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    print!(
        "{} ({}), gonio's pigment library\n{}\n{:<46} {:>6} {:>7} {:>7}  sRGB\n",
        p.name,
        p.colour_index,
        heading(a),
        "",
        "L*",
        "a*",
        "b*"
    );
    let tint_name = format!("tint 1:{TINT_PARTS_WHITE} with {WHITE}");
    for (what, c) in [
        ("masstone, through the surface", &masstone.measured_colour),
        ("masstone, inside (R∞)", &masstone.inside_colour),
        (
            &format!("{tint_name}, through surface")[..],
            &tint.measured_colour,
        ),
        (&format!("{tint_name}, inside")[..], &tint.inside_colour),
    ] {
        let gamut = if c.linear_srgb.in_gamut() {
            ""
        } else {
            " (outside sRGB: clipped)"
        };
        println!(
            "{what:<46} {:>6.2} {:>7.2} {:>7.2}  {}{gamut}",
            c.lab.l,
            c.lab.a,
            c.lab.b,
            c.srgb.to_hex()
        );
    }
    for f in &written {
        println!("wrote {}", f.display());
    }
    Ok(())
}

/// The pigment's relative K, S and K/S over wavelength, on a logarithmic axis (K/S spans
/// decades between a pigment's absorption band and its clear side).
fn plot_ks(path: &Path, p: &LibraryPigment) -> Result<()> {
    let wl = library::wavelengths_nm();
    let series = |label: &str, i: usize, y: &dyn Fn(usize) -> f64| Series {
        label: label.into(),
        points: (0..wl.len()).map(|j| (wl[j], y(j))).collect(),
        colour: palette(i),
        markers: false,
    };
    let (k, s) = (p.k.values(), p.s.values());
    let title = format!(
        "{} ({}): Kubelka-Munk K and S, relative (titanium white's S = 1)",
        p.name, p.colour_index
    );
    gonio_plot::line_plot_png(
        path,
        (900, 560),
        &LinePlot {
            title: &title,
            x_label: "wavelength, nm",
            y_label: &format!("relative units (× {SCALE_PER_UM} /µm in a layer)"),
            log_y: true,
        },
        &[
            series("K", 1, &|j| k[j]),
            series("S", 0, &|j| s[j]),
            series("K/S", 7, &|j| k[j] / s[j]),
        ],
    )?;
    Ok(())
}

/// Four swatches: the masstone and the 1:10 tint (columns), through the paint's surface and
/// inside it (rows), each filled with its encoded sRGB and labelled.
fn draw_swatches(path: &Path, p: &LibraryPigment, masstone: &Seen, tint: &Seen) -> Result<()> {
    const SIZE: (u32, u32) = (640, 570);
    const CELL: i32 = 220;
    const LEFT: i32 = 170;
    const TOP: i32 = 70;
    let fill = |c: &Colorimetry| {
        let [r, g, b] = c.srgb.to_u8();
        RGBColor(r, g, b)
    };
    let cells = [
        (0, 0, fill(&masstone.measured_colour)),
        (1, 0, fill(&tint.measured_colour)),
        (0, 1, fill(&masstone.inside_colour)),
        (1, 1, fill(&tint.inside_colour)),
    ];
    let title = format!("{} ({})", p.name, p.colour_index);
    gonio_plot::render_png(path, SIZE, |root| {
        let font = |px: u32| ("sans-serif", px).into_font();
        root.draw(&Text::new(title.as_str(), (16, 14), font(20)))?;
        for (col, label) in [
            (0, "masstone".to_string()),
            (1, format!("1:{TINT_PARTS_WHITE} with white")),
        ] {
            let x = LEFT + col * (CELL + 20);
            root.draw(&Text::new(label, (x, TOP - 24), font(16)))?;
        }
        for (row, label) in [(0, "through the surface"), (1, "inside (R∞)")] {
            let y = TOP + row * (CELL + 10) + CELL / 2 - 8;
            root.draw(&Text::new(label, (12, y), font(15)))?;
        }
        root.draw(&Text::new(
            format!(
                "through the surface: Saunderson k1 {SAUNDERSON_K1}, k2 {SAUNDERSON_K2}, \
                 specular excluded; encoded sRGB"
            ),
            (12, TOP + 2 * CELL + 10 + 16),
            font(13),
        ))?;
        for &(col, row, colour) in &cells {
            let x = LEFT + col * (CELL + 20);
            let y = TOP + row * (CELL + 10);
            root.draw(&Rectangle::new(
                [(x, y), (x + CELL, y + CELL)],
                colour.filled(),
            ))?;
        }
        Ok(())
    })?;
    Ok(())
}
