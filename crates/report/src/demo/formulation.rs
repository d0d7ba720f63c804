//! The demo report's formulation section: the three Cornell paints against their matches from
//! the pigment library ([`super::matched`]), and which constituents of the silver metallic drive
//! its gloss, haze, DOI, colour and flop (Morris screening, `gonio coating sensitivity`: the
//! summary in words, the table of μ* and a bar chart), both computed by the library's calls.

use super::pictures::EXAMPLES;
use crate::html::{Block, Section};
use crate::{ReportError, Result};
use gonio_coating::description;
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{self, Indices, Method, Settings, Varied};
use gonio_io::Progress;
use std::path::Path;

/// The constituents the demo varies, as `--vary` takes them: the top's roughness (rms slope α),
/// the flakes' tilt spread (°) and their coverage.
const VARY: &str = "roughness=0.01:0.1,tilt=4:20,coverage=0.3:0.8";
/// The readings it analyses, as `--outputs` takes them.
const OUTPUTS: &str = "gu20,gu60,haze,doi,L@45as15,L@45as45,L@45as110,flop,dE00";
/// Morris trajectories: 20 × (3 + 1) = 80 readings (about 35 s on two cores).
const TRAJECTORIES: usize = 20;

/// The section; `quick` (the quick demo) reads the paints with few walks, without their picture
/// and without the screening.
pub(super) fn formulation_section(dir: &Path, quick: bool, work: &Progress) -> Result<Section> {
    let mut blocks = super::matched::blocks(dir, quick, work)?;
    if !quick {
        blocks.extend(sensitivity_blocks(dir)?);
    }
    Ok(Section {
        title: if quick {
            "Formulation: a measured paint matched from the pigment library".into()
        } else {
            "Formulation: three measured paints matched from the pigment library, and what drives \
             a metallic's appearance"
                .into()
        },
        blocks,
        seconds: 0.0,
    })
}

/// The Morris screening of the silver metallic: the summary in words, the table of μ*, the bar
/// chart of the flop index and the command.
fn sensitivity_blocks(dir: &Path) -> Result<Vec<Block>> {
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
        return Err(ReportError::Invalid(
            "the demo's sensitivity is a Morris screening".into(),
        ));
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
    Ok(vec![
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
    ])
}
