//! The HTML report of a run (`report.html` beside the pictures): for each scene its reference
//! and, for each renderer, its values against the references, ΔE00 per region, FLIP, the
//! pictures and difference images, the verdict, and what its export loses, in words.

use crate::suite::{Results, Verdict};

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn verdict(v: Verdict) -> &'static str {
    match v {
        Verdict::Pass => "<b style='color:#070'>pass</b>",
        Verdict::KnownLoss => "<b style='color:#a60'>fails: known loss</b>",
        Verdict::Fail => "<b style='color:#b00'>FAIL</b>",
        Verdict::Unavailable => "<i>unavailable</i>",
    }
}

/// The report's HTML.
pub fn html(results: &Results) -> String {
    let mut h = String::from(
        "<!doctype html><html><head><meta charset='utf-8'><title>gonio conformance</title>\
         <style>body{font-family:sans-serif;max-width:72em;margin:auto}table{border-collapse:\
         collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\
         td.l,th.l{text-align:left}img{width:128px;height:128px;image-rendering:pixelated}\
         </style></head><body><h1>gonio conformance</h1>",
    );
    h += &format!(
        "<p>Appearance test scenes with analytic references, rendered by gonio and, through \
         gonio's exports, by Mitsuba 3 and Radiance: {0} × {0} pixels, {1} samples per pixel \
         (gonio, Mitsuba). Values are mean luminances (linear sRGB) over each region; the \
         tolerance is 4 standard errors of the Monte Carlo mean plus the export's bounded \
         loss. Difference images: red where the picture is brighter than the reference, blue \
         where darker, full at 10% of the scene's white. FLIP: LDR, 67 pixels per degree.</p>",
        results.size, results.spp
    );
    h += "<h2>Summary</h2><table><tr><th class=l>scene</th>";
    let renderers: Vec<_> = results
        .scenes
        .first()
        .map(|s| s.runs.iter().map(|r| r.renderer).collect())
        .unwrap_or_default();
    for r in &renderers {
        h += &format!("<th>{}</th>", r.name());
    }
    h += "</tr>";
    for s in &results.scenes {
        h += &format!("<tr><td class=l>{}</td>", s.scene.id.name());
        for r in &s.runs {
            h += &format!("<td>{}</td>", verdict(r.verdict));
        }
        h += "</tr>";
    }
    h += "</table>";
    for s in &results.scenes {
        let name = s.scene.id.name();
        h += &format!(
            "<h2 id='{name}'>{name}</h2><p>{}</p><p><img src='{name}_reference.png' \
             alt='reference'> the analytic reference</p>",
            esc(&s.scene.title)
        );
        for r in &s.runs {
            let rn = r.renderer.name();
            h += &format!("<h3>{rn}: {}</h3>", verdict(r.verdict));
            if let Some(l) = &r.loss {
                h += &format!("<p>What the export loses: {}</p>", esc(&l.text));
            }
            if r.verdict == Verdict::Unavailable {
                continue;
            }
            h += &format!(
                "<p><img src='{name}_{rn}.png' alt='picture'> <img src='{name}_{rn}_diff.png' \
                 alt='difference'> <img src='{name}_{rn}_flip.png' alt='FLIP'><br>picture, \
                 difference, FLIP map (mean {:.4}); {:.1} s</p>",
                r.flip_mean, r.seconds
            );
            h += "<table><tr><th class=l>region</th><th>pixels</th><th>value</th>\
                  <th>reference</th><th>SE</th><th>L*a*b*</th><th>reference L*a*b*</th>\
                  <th>ΔE00</th></tr>";
            for g in &r.regions {
                h += &format!(
                    "<tr><td class=l>{}</td><td>{}</td><td>{:.5}</td><td>{:.5}</td>\
                     <td>{:.1e}</td><td>{:.2} {:.2} {:.2}</td><td>{:.2} {:.2} {:.2}</td>\
                     <td>{:.3}</td></tr>",
                    esc(&g.name),
                    g.pixels,
                    g.value,
                    g.reference,
                    g.standard_error,
                    g.lab[0],
                    g.lab[1],
                    g.lab[2],
                    g.reference_lab[0],
                    g.reference_lab[1],
                    g.reference_lab[2],
                    g.delta_e00
                );
            }
            h += "</table><table><tr><th class=l>check</th><th>value</th><th>reference</th>\
                  <th>tolerance</th><th>holds</th></tr>";
            for c in &r.checks {
                h += &format!(
                    "<tr><td class=l>{}</td><td>{:.5}</td><td>{:.5}</td><td>{:.5}</td>\
                     <td>{}</td></tr>",
                    esc(&c.what),
                    c.value,
                    c.reference,
                    c.tolerance,
                    if c.pass { "yes" } else { "no" }
                );
            }
            h += "</table>";
        }
    }
    h += "</body></html>\n";
    h
}
