//! The demo report's formulation section: the Cornell Cayman matched by a formulation (`gonio
//! coating match`: its fitted constituents and ΔE00 per geometry), and which constituents of the
//! silver metallic drive its gloss, haze, DOI, colour and flop (Morris screening, `gonio coating
//! sensitivity`: the summary in words, the table of μ* and a bar chart), both computed by the
//! library's calls.

use super::pictures::EXAMPLES;
use crate::report::{Block, Section};
use anyhow::Result;
use gonio_coating::description;
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{self, Indices, Method, Settings, Varied};
use gonio_formulation::{fitted_description, matching, target};
use gonio_instrument::multiangle::E2194;
use std::path::Path;

/// The match's constituents and bounds, as `--vary` takes them: flake coverage and tilt spread,
/// and the tinted coat's thickness (the tint's strength).
const MATCH_VARY: &str = "coverage=0.05:0.95,tilt=4:30,thickness=5:400";
/// Walks per geometry of the match's readings (a quarter of the default: about 15 s).
const MATCH_WALKS: usize = 256;

/// The Cornell Cayman matched from `examples/coatings/cayman_tinted_start.toml` at E2194: the
/// blocks that show it, and the fitted description written beside the report.
fn cayman_match(dir: &Path) -> Result<Vec<Block>> {
    let settings = matching::Settings {
        walks: MATCH_WALKS,
        starts: 1,
        ..matching::Settings::default()
    };
    let start_path = Path::new(EXAMPLES).join("coatings/cayman_tinted_start.toml");
    let text = std::fs::read_to_string(&start_path)?;
    let start = description::read(&start_path, &settings.wavelengths_nm)?;
    let cayman = Path::new(EXAMPLES).join("../crates/brdf/tests/data/cayman.astm");
    let target = target::read_target(&cayman, &E2194)?;
    let varied = Varied::parse_list(MATCH_VARY)?;
    let m = matching::run(&start, &target, &[], &varied, &settings, &mut |_| {})?;
    let fitted = fitted_description::with_values(&text, &varied, &m.fitted.values)?;
    crate::output::write_atomic(&dir.join("cayman_fitted.toml"), |w| {
        Ok(std::io::Write::write_all(w, fitted.as_bytes())?)
    })?;
    let fitted_rows = varied
        .iter()
        .enumerate()
        .map(|(i, v)| {
            vec![
                v.constituent.label(),
                format!("{}–{}", v.lo, v.hi),
                format!("{:.3}", m.start.values[i]),
                format!("{:.3}", m.fitted.values[i]),
                m.sigma
                    .as_ref()
                    .map_or("—".into(), |s| format!("{:.3}", s[i])),
            ]
        })
        .collect();
    let mean = |d: &[f64]| d.iter().sum::<f64>() / d.len() as f64;
    let mut de_rows: Vec<Vec<String>> = m
        .geometries
        .iter()
        .enumerate()
        .map(|(k, g)| {
            let lab = |r: &gonio_instrument::multiangle::MultiangleReading| {
                r.at(*g).map_or("—".into(), |x| {
                    format!("{:.1} {:.1} {:.1}", x.lab.l, x.lab.a, x.lab.b)
                })
            };
            let measured = target
                .colours
                .iter()
                .find(|(h, _)| h == g)
                .map_or("—".into(), |(_, l)| {
                    format!("{:.1} {:.1} {:.1}", l.l, l.a, l.b)
                });
            vec![
                g.to_string(),
                measured,
                lab(&m.fitted.multiangle),
                format!("{:.2}", m.start.de00[k]),
                format!("{:.2}", m.fitted.de00[k]),
            ]
        })
        .collect();
    de_rows.push(vec![
        "mean".into(),
        String::new(),
        String::new(),
        format!("{:.2}", mean(&m.start.de00)),
        format!("{:.2}", mean(&m.fitted.de00)),
    ]);
    Ok(vec![
        Block::Text(format!(
            "From a target back to a formulation: the Cornell measurement of the Cayman \
             blue-green metallic, read at the ASTM E2194 geometries, matched by aluminium flakes \
             in a cyan-tinted binder under a clear coat (examples/coatings/cayman_tinted_start.toml) \
             by varying the flakes' coverage and tilt spread and the tinted coat's thickness \
             (Nelder-Mead on the mean ΔE00, every reading with the same random numbers; {} \
             readings of {MATCH_WALKS} walks per geometry in {:.0} s). σ is the Gauss-Newton \
             standard deviation, about half the real scatter (docs/formulation.md). The match \
             gets the lightness travel but not the hue: the cyan's spectrum (a ColorChecker patch, \
             not a measured pigment) is bluer than the Cayman's, and the aim of a mean ΔE00 of 2 \
             is not reached (docs/formulation.md, \"The Cornell Cayman\").",
            m.evaluations, m.seconds
        )),
        Block::Table {
            headers: ["constituent", "bounds", "start", "fitted", "σ"]
                .map(String::from)
                .to_vec(),
            rows: fitted_rows,
        },
        Block::Table {
            headers: [
                "geometry",
                "measured L* a* b*",
                "fitted L* a* b*",
                "ΔE00 start",
                "ΔE00 fitted",
            ]
            .map(String::from)
            .to_vec(),
            rows: de_rows,
        },
        Block::Code(format!(
            "gonio coating match cayman_tinted_start.toml --target cayman.astm \\\n    --vary \
             {MATCH_VARY} --walks {MATCH_WALKS} --starts 1 -o cayman_fitted.toml"
        )),
    ])
}

/// The constituents the demo varies, as `--vary` takes them: the top's roughness (rms slope α),
/// the flakes' tilt spread (°) and their coverage.
const VARY: &str = "roughness=0.01:0.1,tilt=4:20,coverage=0.3:0.8";
/// The readings it analyses, as `--outputs` takes them.
const OUTPUTS: &str = "gu20,gu60,haze,doi,L@45as15,L@45as45,L@45as110,flop,dE00";
/// Morris trajectories: 20 × (3 + 1) = 80 readings (about 35 s on two cores).
const TRAJECTORIES: usize = 20;

pub(super) fn formulation_section(dir: &Path) -> Result<Section> {
    let mut blocks = cayman_match(dir)?;
    let settings = Settings::default();
    let toml = Path::new(EXAMPLES).join("coatings/silver_metallic.toml");
    let silver = description::read(&toml, &settings.wavelengths_nm)?;
    let varied = Varied::parse_list(VARY)?;
    let outputs = Output::parse_list(OUTPUTS)?;
    let method = Method::parse("morris", Some(TRAJECTORIES))?;
    let s = coating_sensitivity::run(&silver, &varied, &outputs, method, &settings)?;
    let sensitivity_dir = dir.join("sensitivity");
    s.write(&sensitivity_dir, 0.1)?;
    let Indices::Morris { effects, .. } = &s.indices else {
        anyhow::bail!("the demo's sensitivity is a Morris screening");
    };
    let names = s.input_names();
    let mut headers = vec!["reading".to_string(), "base formulation".into()];
    headers.extend(names.iter().map(|n| format!("μ* {n}")));
    let rows = s
        .outputs
        .iter()
        .zip(effects)
        .enumerate()
        .map(|(k, (o, e))| {
            let mut row = vec![o.title(), format!("{:.2}", s.base[k])];
            row.extend(
                e.mu_star
                    .iter()
                    .zip(&e.mu_star_conf)
                    .map(|(m, c)| format!("{m:.2} ± {c:.2}")),
            );
            row
        })
        .collect();
    blocks.extend([
            Block::Text(format!(
                "A designer asks which constituents matter for which reading. gonio varies the \
                 silver metallic's top roughness (α 0.01–0.1), flake tilt spread (4–20°) and \
                 flake coverage (0.3–0.8) over a Morris screening design ({} readings, each with \
                 the same random numbers so that differences are the formulation's) and reads \
                 gloss, haze, DOI (ISO 2813, ASTM E430), L* at three E2194 geometries, the flop \
                 index and ΔE00 from the base formulation at every point. μ* is the mean \
                 absolute change of the reading when one constituent moves across a third of its \
                 range (docs/formulation.md); ± is its 95% bootstrap interval. In words:",
                s.points.nrows()
            )),
            Block::Code(s.summary(0.1)),
            Block::Table { headers, rows },
            Block::Image {
                path: sensitivity_dir.join("sensitivity-flop.png"),
                caption: "What drives the flop index: μ* of each constituent".into(),
            },
            Block::Code(format!(
                "gonio coating sensitivity silver_metallic.toml \\\n    --vary {VARY} \\\n    \
                 --outputs {OUTPUTS} \\\n    --method morris --samples {TRAJECTORIES} -o sensitivity"
            )),
    ]);
    Ok(Section {
        title: "Formulation: matching a measured paint, and what drives a metallic's appearance"
            .into(),
        blocks,
        seconds: 0.0,
    })
}
