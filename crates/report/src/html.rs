//! The HTML report: one self-contained page (images embedded as base64 PNG) that a person reads
//! top to bottom, with what was computed, figures, tables and timings. The demo writes one
//! ([`crate::demo`]); any front end can compose its own from [`Section`]s of [`Block`]s.

use crate::output::{create_dir, io_error, write_bytes};
use crate::{ReportError, Result};
use base64::Engine;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One piece of a section.
pub enum Block {
    /// A paragraph of plain text.
    Text(String),
    /// A table with a header row.
    Table {
        headers: Vec<String>,
        rows: Vec<Vec<String>>,
    },
    /// A PNG image from a file, embedded in the page, with a caption.
    Image { path: PathBuf, caption: String },
    /// Preformatted text (command lines, small listings).
    Code(String),
    /// Links to files beside the report: a lead-in, then each link's text and its path relative
    /// to the report's folder (`"near-specular.exr"`, `"standard/silver/manifest.json"`).
    Links {
        lead: String,
        links: Vec<(String, String)>,
    },
}

/// A section of the report with the time its computation took.
pub struct Section {
    pub title: String,
    pub blocks: Vec<Block>,
    pub seconds: f64,
}

/// The whole report.
pub struct Report {
    pub title: String,
    pub intro: String,
    /// Paragraphs under "Summary", before the contents: what the run found, with its numbers.
    pub summary: Vec<String>,
    pub sections: Vec<Section>,
}

/// Escape text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl Report {
    /// Render the page; images are read and embedded.
    pub fn to_html(&self) -> Result<String> {
        let mut h = String::new();
        let total: f64 = self.sections.iter().map(|s| s.seconds).sum();
        write!(
            h,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <title>{t}</title><style>{css}</style></head><body>\n<h1>{t}</h1>\n<p>{intro}</p>\n",
            t = esc(&self.title),
            css = CSS,
            intro = esc(&self.intro)
        )?;
        if !self.summary.is_empty() {
            h.push_str("<h2>Summary</h2>\n");
            for p in &self.summary {
                writeln!(h, "<p>{}</p>", esc(p))?;
            }
        }
        h.push_str("<h2>Contents</h2>\n<table><tr><th>section</th><th>time (s)</th></tr>\n");
        for (i, s) in self.sections.iter().enumerate() {
            writeln!(
                h,
                "<tr><td><a href=\"#s{i}\">{}</a></td><td class=\"num\">{:.1}</td></tr>",
                esc(&s.title),
                s.seconds
            )?;
        }
        writeln!(
            h,
            "<tr><td><b>total</b></td><td class=\"num\"><b>{total:.1}</b></td></tr></table>"
        )?;
        for (i, s) in self.sections.iter().enumerate() {
            writeln!(h, "<section id=\"s{i}\"><h2>{}</h2>", esc(&s.title))?;
            for b in &s.blocks {
                match b {
                    Block::Text(t) => writeln!(h, "<p>{}</p>", esc(t))?,
                    Block::Code(t) => writeln!(h, "<pre>{}</pre>", esc(t))?,
                    Block::Table { headers, rows } => {
                        if let Some((i, r)) = rows
                            .iter()
                            .enumerate()
                            .find(|(_, r)| r.len() != headers.len())
                        {
                            return Err(ReportError::Invalid(format!(
                                "section '{}': a table row {} has {} cells for {} headers ({})",
                                s.title,
                                i + 1,
                                r.len(),
                                headers.len(),
                                headers.join(", ")
                            )));
                        }
                        h.push_str("<table><tr>");
                        for c in headers {
                            write!(h, "<th>{}</th>", esc(c))?;
                        }
                        h.push_str("</tr>\n");
                        for r in rows {
                            h.push_str("<tr>");
                            for c in r {
                                write!(h, "<td>{}</td>", esc(c))?;
                            }
                            h.push_str("</tr>\n");
                        }
                        h.push_str("</table>\n");
                    }
                    Block::Links { lead, links } => {
                        write!(h, "<p>{}", esc(lead))?;
                        for (i, (text, href)) in links.iter().enumerate() {
                            let sep = if i == 0 { " " } else { ", " };
                            write!(h, "{sep}<a href=\"{}\">{}</a>", esc(href), esc(text))?;
                        }
                        h.push_str("</p>\n");
                    }
                    Block::Image { path, caption } => {
                        let bytes = std::fs::read(path).map_err(|e| io_error(path, e))?;
                        let data = base64::engine::general_purpose::STANDARD.encode(bytes);
                        writeln!(
                            h,
                            "<figure><img src=\"data:image/png;base64,{data}\" alt=\"{c}\"><figcaption>{c}</figcaption></figure>",
                            c = esc(caption)
                        )?;
                    }
                }
            }
            writeln!(
                h,
                "<p class=\"time\">computed in {:.1} s</p></section>",
                s.seconds
            )?;
        }
        h.push_str("</body></html>\n");
        Ok(h)
    }

    /// Write the page to `path` atomically.
    pub fn write(&self, path: &Path) -> Result<()> {
        let html = self.to_html()?;
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        create_dir(dir)?;
        write_bytes(path, html.as_bytes())
    }
}

const CSS: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}\
h1{border-bottom:2px solid #345}h2{margin-top:2em;color:#234}\
table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:left}\
th{background:#eef}td.num{text-align:right}figure{margin:1em 0}img{max-width:100%;border:1px solid #ccc}\
figcaption{font-size:90%;color:#555}pre{background:#f4f4f4;padding:.6em;overflow-x:auto}.time{color:#777;font-size:85%}";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn html_escapes_and_embeds() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("a.png");
        image::RgbImage::from_pixel(2, 2, image::Rgb([10, 20, 30]))
            .save(&png)
            .unwrap();
        let report = Report {
            title: "T <1>".into(),
            intro: "a & b".into(),
            summary: vec!["found <3>".into()],
            sections: vec![Section {
                title: "S".into(),
                blocks: vec![
                    Block::Text("x < y".into()),
                    Block::Image {
                        path: png,
                        caption: "cap".into(),
                    },
                    Block::Table {
                        headers: vec!["h".into()],
                        rows: vec![vec!["1".into()]],
                    },
                ],
                seconds: 1.5,
            }],
        };
        let html = report.to_html().unwrap();
        assert!(
            html.contains("T &lt;1&gt;") && html.contains("a &amp; b") && html.contains("x &lt; y")
        );
        assert!(html.contains("<h2>Summary</h2>\n<p>found &lt;3&gt;</p>"));
        assert!(html.contains("data:image/png;base64,iVBOR"));
        let out = dir.path().join("r/report.html");
        report.write(&out).unwrap();
        assert!(out.exists());
    }

    #[test]
    fn a_row_of_the_wrong_width_is_refused() {
        let report = Report {
            title: "T".into(),
            intro: String::new(),
            summary: Vec::new(),
            sections: vec![Section {
                title: "gloss".into(),
                blocks: vec![Block::Table {
                    headers: vec!["sample".into(), "GU 60°".into()],
                    rows: vec![
                        vec!["a".into(), "1".into()],
                        vec!["b".into(), "ray".into(), "2".into()],
                    ],
                }],
                seconds: 0.0,
            }],
        };
        let err = report.to_html().unwrap_err().to_string();
        assert!(
            err.contains("'gloss'") && err.contains("row 2 has 3 cells for 2"),
            "{err}"
        );
    }
}
