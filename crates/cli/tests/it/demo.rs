//! The demo end to end through the `gonio` binary: `gonio demo --quick` writes a report with
//! every section, and every command the report shows runs as written beside it, printing the
//! numbers the report quotes. The report's own checks (tables, summary, the page in Chromium)
//! are gonio-report's (crates/report/tests/it/demo.rs).

use std::path::Path;

use crate::common::quick_demo;

/// Every command the report shows names only files that exist in the output folder (inputs
/// and the outputs the demo wrote), so that it runs as written there.
fn commands_name_files_beside_the_report(html: &str, out: &Path) {
    let unescape = |s: &str| {
        s.replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&amp;", "&")
    };
    let mut commands = 0;
    for block in html.split("<pre>").skip(1) {
        let block = unescape(&block[..block.find("</pre>").unwrap()]);
        for line in block.lines().filter(|l| l.starts_with("gonio ")) {
            commands += 1;
            let words: Vec<&str> = line.split_whitespace().collect();
            for (i, word) in words.iter().enumerate().skip(2) {
                let after_output = matches!(words[i - 1], "-o" | "--output" | "--csv" | "--plot");
                let has_extension = !word.starts_with('-')
                    && word.parse::<f64>().is_err()
                    && Path::new(word).extension().is_some_and(|e| {
                        e.to_string_lossy()
                            .chars()
                            .all(|c| c.is_ascii_alphanumeric())
                    });
                if after_output || has_extension {
                    assert!(
                        out.join(word).exists() || expanded(out, word),
                        "'{line}' names {word}, which is not in {}",
                        out.display()
                    );
                }
            }
        }
    }
    assert!(commands >= 5, "only {commands} commands shown");
}

/// Whether the folder `out` holds files that a command writing several plots makes of the
/// output name `word` (`gonio isotropy -o isotropy.png` with two angles writes
/// `isotropy_rot90.png` and `isotropy_rot45.png`).
fn expanded(out: &Path, word: &str) -> bool {
    let path = Path::new(word);
    let (Some(stem), Some(ext)) = (path.file_stem(), path.extension()) else {
        return false;
    };
    let prefix = format!("{}_", stem.to_string_lossy());
    std::fs::read_dir(out.join(path.parent().unwrap_or(Path::new(""))))
        .unwrap()
        .filter_map(|e| e.ok())
        .any(|e| {
            let p = e.path();
            p.extension() == Some(ext)
                && p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with(&prefix))
        })
}

/// The title of the demo's texture section.
const TEXTURE: &str = "Texture: sparkle, graininess and orange peel";

/// The cells of each row of each table in `html` (header rows left out), unescaped.
fn table_rows(html: &str) -> Vec<Vec<Vec<String>>> {
    html.split("<table>")
        .skip(1)
        .map(|t| {
            t[..t.find("</table>").unwrap()]
                .split("<tr>")
                .skip(2)
                .map(|row| {
                    row.split("<td>")
                        .skip(1)
                        .map(|c| c[..c.find("</td>").unwrap()].replace("&amp;", "&"))
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// The lines of the `<pre>` blocks in `html` that start with `gonio `.
fn commands(html: &str) -> Vec<String> {
    html.split("<pre>")
        .skip(1)
        .flat_map(|b| b[..b.find("</pre>").unwrap()].lines())
        .filter(|l| l.starts_with("gonio "))
        .map(String::from)
        .collect()
}

/// Run the command `line` shown by the report (with `extra` arguments) in `out`, its JSON.
fn run_shown(line: &str, extra: &[&str], out: &Path) -> serde_json::Value {
    let mut args: Vec<&str> = line.split_whitespace().skip(1).collect();
    args.extend(extra);
    let output = crate::common::ok_in(&args, out);
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("{line}: not JSON: {e}"))
}

/// The texture section: the two sparkle close-ups and the orange-peel panel as pictures, and
/// its numbers those that the commands it shows print when run as written beside the report:
/// `gonio texture` (each lamp's spots, density, area, intensity and grade, and the graininess,
/// to the digits shown), `gonio surface waviness` and `gonio gloss` (each band's rms slope
/// and the DOI of each orange-peel map).
fn texture_section_quotes_its_commands(html: &str, out: &Path) {
    let start = html
        .find(&format!("<h2>{TEXTURE}</h2>"))
        .expect("a texture section");
    let section = &html[start..start + html[start..].find("</section>").unwrap()];
    let images = section.matches("<img src=\"data:image/png;base64,").count();
    assert_eq!(images, 3, "two sparkle close-ups and the orange peel");
    let tables = table_rows(section);
    let shown = commands(section);
    let texture: Vec<&String> = shown
        .iter()
        .filter(|l| l.starts_with("gonio texture"))
        .collect();
    assert_eq!(texture.len(), 2, "{shown:?}");
    let (sparkle, grain) = (&tables[0], &tables[1]);
    assert_eq!(sparkle.len(), 6, "two diameters at three lamp angles");
    for (k, line) in texture.iter().enumerate() {
        let json = run_shown(line, &["--json"], out);
        let diameter = &grain[k][0];
        assert!(
            line.contains(&format!("silver_{diameter}um.toml")),
            "{line}"
        );
        assert_eq!(
            grain[k][1],
            format!("{:.2}", json["graininess_percent"].as_f64().unwrap()),
            "{line}: graininess"
        );
        let lamps = json["sparkle"].as_array().unwrap();
        for (row, lamp) in sparkle[3 * k..3 * k + 3].iter().zip(lamps) {
            let f = |key: &str| lamp[key].as_f64().unwrap();
            let spots = lamp["spots"].as_u64().unwrap();
            let intensity = if spots > 0 {
                format!("{:.0}", f("intensity"))
            } else {
                "—".into()
            };
            let want = vec![
                diameter.clone(),
                format!("{}", f("lamp_deg")),
                spots.to_string(),
                format!("{:.1}", f("density_per_mm2")),
                format!("{:.3}", f("area_percent")),
                intensity,
                format!("{:.1}", f("grade")),
            ];
            assert_eq!(row, &want, "{line}");
        }
        let folder = out.join(line.rsplit(' ').next().unwrap());
        for png in [
            "sparkle_15.png",
            "sparkle_45.png",
            "sparkle_75.png",
            "diffuse.png",
        ] {
            assert!(
                folder.join(png).is_file(),
                "{} has no {png}",
                folder.display()
            );
        }
    }
    let bands = &tables[2];
    let maps: Vec<&str> = shown
        .iter()
        .filter_map(|l| l.strip_prefix("gonio surface waviness "))
        .collect();
    assert_eq!(maps.len(), 2, "{shown:?}");
    let header = &section[section.find("<th>band</th>").unwrap()..];
    for (k, map) in maps.iter().enumerate() {
        let json = run_shown(&format!("gonio surface waviness {map}"), &["--json"], out);
        for (row, band) in bands.iter().zip(json["bands"].as_array().unwrap()) {
            assert_eq!(row[0], band["name"].as_str().unwrap());
            let want = match band["rms_slope_rad"].as_f64() {
                Some(s) => format!("{:.3}", s * 1e3),
                None => band["unresolved"]
                    .as_str()
                    .unwrap()
                    .split(':')
                    .next()
                    .unwrap()
                    .into(),
            };
            assert_eq!(row[2 + k], want, "{map}, band {}", row[0]);
        }
        let gloss = run_shown(&format!("gonio gloss {map} --index 1.5"), &["--json"], out);
        let doi = format!(
            "DOI {:.1} ± {:.1}",
            gloss["doi"].as_f64().unwrap(),
            gloss["doi_uncertainty"].as_f64().unwrap()
        );
        assert!(
            header.contains(&doi),
            "{map}: {doi} not in the bands' header"
        );
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn quick_demo_writes_every_section_with_commands_that_run() {
        let out = quick_demo();
        let html = std::fs::read_to_string(out.join("report.html")).unwrap();
        for title in [
            "Surfaces: the epoxy roughness series",
            "A real instrument file: x3p-2.x3p",
            "Isotropy of x3p-2.x3p",
            "The roughness study",
            "Coatings and multi-angle colour",
            "Formulation: a measured paint matched from the pigment library",
            TEXTURE,
        ] {
            assert!(html.contains(title), "section '{title}' missing");
        }
        commands_name_files_beside_the_report(&html, out);
    }

    #[test]
    fn quick_demo_texture_section_quotes_its_commands() {
        let out = quick_demo();
        let html = std::fs::read_to_string(out.join("report.html")).unwrap();
        texture_section_quotes_its_commands(&html, out);
    }
}
