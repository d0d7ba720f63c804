//! Running the suite: every scene through every renderer asked for, each picture compared with
//! the scene's reference, a verdict per scene and renderer, and the pictures and results written
//! (the report composed from them is `gonio_report::conformance`'s).
//!
//! The verdicts. A scene of luminance (the furnaces, the plate, the coat, the mirror) passes
//! when every region's mean luminance is within `4 SE + 1e-4 Y_ref + loss Y_ref` of the
//! reference: 4 standard errors of the Monte Carlo mean (a normal deviate beyond 4 σ has
//! probability 6e-5), 1e-4 for the pictures' f32 pixels (24-bit mantissas summed over a region
//! of a few thousand pixels: below 1e-5, rounded up), and the relative size of the renderer's
//! bounded loss where one applies (an export's table, gonio's own table of the coat's body:
//! [`crate::loss`]). A metameric scene passes when each patch's
//! CIELAB is within `ΔE_noise + 0.2` of the reference and the pair's ΔE00 within the sum of the
//! patches' tolerances of the reference pair's: ΔE_noise is the CIEDE2000 that 4 standard
//! errors of the patch's mean make ([`crate::compare::delta_e_noise`]), 0.2 the difference
//! between the reference's integration (ASTM E308 weights at 10 nm) and the renderers'
//! (the spectra interpolated linearly between bands, integrated against finely sampled CIE
//! functions), checked against colour-science's 1 nm integration in the tests.
//! A failing scene whose export cannot represent it ([`crate::loss::Loss::cannot`]) is reported
//! as that known loss, not as a failure; its tolerance is not loosened.

use crate::compare::{self, RegionStats, luminance};
use crate::error::{Error, Result};
use crate::loss::{Loss, loss};
use crate::scene::{SIZE, Scene, SceneId};
use crate::{gonio, mitsuba, radiance};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// A renderer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Renderer {
    Gonio,
    Mitsuba,
    Radiance,
}

impl Renderer {
    /// Every renderer.
    pub const ALL: [Renderer; 3] = [Renderer::Gonio, Renderer::Mitsuba, Renderer::Radiance];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Renderer::Gonio => "gonio",
            Renderer::Mitsuba => "mitsuba",
            Renderer::Radiance => "radiance",
        }
    }

    /// The renderer named `name`.
    pub fn from_name(name: &str) -> Option<Renderer> {
        Renderer::ALL.into_iter().find(|r| r.name() == name)
    }
}

/// How a renderer got the scene's materials.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Route {
    /// gonio's renderer on gonio's own scene.
    Own,
    /// A peer through gonio's exports of the materials (tables: Mitsuba's tensor `.bsdf`,
    /// Radiance's XML BSDF; [`crate::export`]).
    Export,
    /// A peer on its native plugins for the same models, where it has them: beside the export,
    /// it shows what the export loses.
    Native,
}

impl Route {
    /// Its name in file names and the report.
    pub fn name(self) -> &'static str {
        match self {
            Route::Own => "own",
            Route::Export => "export",
            Route::Native => "native",
        }
    }
}

impl Renderer {
    /// The routes by which `self` renders `scene`: gonio its own; a peer gonio's export and,
    /// where it has one, its native version.
    pub fn routes(self, scene: &Scene) -> Vec<Route> {
        match self {
            Renderer::Gonio => vec![Route::Own],
            Renderer::Mitsuba => vec![Route::Export, Route::Native],
            Renderer::Radiance if radiance::has_native(scene) => {
                vec![Route::Export, Route::Native]
            }
            Renderer::Radiance => vec![Route::Export],
        }
    }
}

/// What to run.
#[derive(Debug, Clone)]
pub struct Options {
    /// The renderers.
    pub renderers: Vec<Renderer>,
    /// Samples per pixel of the Monte Carlo renderers (gonio, Mitsuba).
    pub spp: u32,
    /// Where the scenes' files, the pictures and the report go.
    pub dir: PathBuf,
}

/// The verdict of one scene by one renderer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Every check holds.
    Pass,
    /// A check fails, and the export's known loss explains it.
    KnownLoss,
    /// A check fails unexplained.
    Fail,
    /// The renderer is not installed.
    Unavailable,
}

/// One check: a measured quantity against its reference and tolerance.
#[derive(Debug, Clone, Serialize)]
pub struct Check {
    pub what: String,
    pub value: f64,
    pub reference: f64,
    pub tolerance: f64,
    pub pass: bool,
}

/// One scene by one renderer.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    pub renderer: Renderer,
    pub route: Route,
    pub verdict: Verdict,
    pub loss: Option<Loss>,
    pub regions: Vec<RegionStats>,
    pub checks: Vec<Check>,
    /// FLIP's mean error over the picture (0 identical, 1 most different).
    pub flip_mean: f64,
    /// Seconds the renderer took (its files' writing included).
    pub seconds: f64,
}

/// One scene's results.
#[derive(Debug, Clone, Serialize)]
pub struct SceneResult {
    pub scene: Scene,
    pub runs: Vec<Run>,
}

/// The whole suite's results.
#[derive(Debug, Clone, Serialize)]
pub struct Results {
    pub spp: u32,
    pub size: usize,
    pub scenes: Vec<SceneResult>,
}

/// A run's name in the report and the pictures' file names: `gonio`, `mitsuba_export`,
/// `radiance_native`.
pub fn label(renderer: Renderer, route: Route) -> String {
    match route {
        Route::Own => renderer.name().to_string(),
        r => format!("{}_{}", renderer.name(), r.name()),
    }
}

impl Run {
    /// Its name ([`label`]).
    pub fn label(&self) -> String {
        label(self.renderer, self.route)
    }
}

impl Results {
    /// Whether every available renderer passed every scene it can represent.
    pub fn passed(&self) -> bool {
        self.scenes
            .iter()
            .flat_map(|s| &s.runs)
            .all(|r| r.verdict != Verdict::Fail)
    }
}

fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    gonio_io::write_atomic(
        path,
        |w| {
            std::io::Write::write_all(w, bytes)
                .map_err(|e| Error::io(&path.display().to_string(), e))
        },
        |e| Error::io(&path.display().to_string(), e),
    )
}

/// Enlargement of the pictures in a run's strip (`NAME_RENDERER_strip.png`: reference, picture,
/// difference, FLIP map), so that a 64-pixel picture shows its pixels in the report.
const STRIP_SCALE: usize = 3;

/// Run the suite: the pictures (PNG) and `results.json` are written into `options.dir`, the
/// scenes' files for each renderer into its `files/`; the report is composed above this crate
/// (`gonio_report::conformance`).
pub fn run(options: &Options) -> Result<Results> {
    if !(1..=65536).contains(&options.spp) {
        return Err(Error::Invalid(format!(
            "spp: {} samples per pixel is not between 1 and 65536",
            options.spp
        )));
    }
    let dir = &options.dir;
    let files = dir.join("files");
    std::fs::create_dir_all(&files).map_err(|e| Error::io(&files.display().to_string(), e))?;
    let mut scenes = vec![];
    for id in SceneId::ALL {
        let scene = Scene::new(id)?;
        let reference = scene.reference()?;
        let name = id.name();
        let reference8 = compare::srgb8(&reference.rgb, scene.white);
        write(
            &dir.join(format!("{name}_reference.png")),
            &compare::png(reference8.clone())?,
        )?;
        let mut runs = vec![];
        for (renderer, route) in options
            .renderers
            .iter()
            .flat_map(|&r| r.routes(&scene).into_iter().map(move |route| (r, route)))
        {
            let start = std::time::Instant::now();
            let spp = samples(&scene, options.spp);
            let picture = match renderer {
                Renderer::Gonio => Some(gonio::render(&scene, &files, spp)?),
                Renderer::Mitsuba => mitsuba::render(&scene, &files, spp, route)?,
                Renderer::Radiance => radiance::render(&scene, &files, route)?,
            };
            let seconds = start.elapsed().as_secs_f64();
            let Some(mut picture) = picture else {
                runs.push(Run {
                    renderer,
                    route,
                    verdict: Verdict::Unavailable,
                    loss: None,
                    regions: vec![],
                    checks: vec![],
                    flip_mean: f64::NAN,
                    seconds,
                });
                continue;
            };
            if scene.is_spectral() {
                normalise_to_white(&scene, &reference, &mut picture);
            }
            let loss = loss(renderer, route, &scene, &reference, &files)?;
            let regions = compare::regions(&scene, &reference, &picture);
            let checks = checks(&scene, &regions, loss.as_ref());
            let (flip_map, flip_mean) = compare::flip(&reference.rgb, &picture, scene.white);
            let tag = format!("{name}_{}", label(renderer, route));
            let picture8 = compare::srgb8(&picture, scene.white);
            let diff8 = compare::difference(&reference.rgb, &picture, 0.1 * scene.white);
            let (strip, w, h) =
                compare::strip(&[&reference8, &picture8, &diff8, &flip_map], STRIP_SCALE);
            write(
                &dir.join(format!("{tag}_strip.png")),
                &compare::png_sized(strip, w, h)?,
            )?;
            write(&dir.join(format!("{tag}.png")), &compare::png(picture8)?)?;
            write(
                &dir.join(format!("{tag}_flip.png")),
                &compare::png(flip_map)?,
            )?;
            write(&dir.join(format!("{tag}_diff.png")), &compare::png(diff8)?)?;
            let pass = checks.iter().all(|c| c.pass);
            let verdict = match (&loss, pass) {
                (_, true) => Verdict::Pass,
                (Some(l), false) if l.cannot => Verdict::KnownLoss,
                _ => Verdict::Fail,
            };
            runs.push(Run {
                renderer,
                route,
                verdict,
                loss,
                regions,
                checks,
                flip_mean,
                seconds,
            });
        }
        scenes.push(SceneResult { scene, runs });
    }
    let results = Results {
        spp: options.spp,
        size: SIZE,
        scenes,
    };
    write(
        &dir.join("results.json"),
        serde_json::to_string_pretty(&results)?.as_bytes(),
    )?;
    Ok(results)
}

/// The samples per pixel of `scene` for the Monte Carlo renderers: `spp`, four times that in
/// the metameric scenes, where each path carries a few wavelengths and the colour noise per
/// sample is larger (twice the samples' precision for the colours' tolerance).
pub fn samples(scene: &Scene, spp: u32) -> u32 {
    if scene.is_spectral() {
        spp.saturating_mul(4)
    } else {
        spp
    }
}

/// Scale a spectral scene's picture so that its white patch has the reference's luminance: the
/// renderers' films differ in absolute scale (Mitsuba's spectral film normalises by the CIE
/// Y integral, gonio's by D65), which this scene does not test; colours are relative to the
/// white patch anyway.
fn normalise_to_white(
    scene: &Scene,
    reference: &crate::scene::Reference,
    picture: &mut [[f64; 3]],
) {
    let Some(w) = scene.regions.iter().position(|r| r.name == "white") else {
        return;
    };
    let (mut own, mut refl, mut n) = (0.0, 0.0, 0.0);
    for ((p, r), g) in picture.iter().zip(&reference.rgb).zip(&reference.region) {
        if *g == Some(w) {
            own += luminance(*p);
            refl += luminance(*r);
            n += 1.0;
        }
    }
    if n > 0.0 && own > 0.0 {
        let k = refl / own;
        for c in picture.iter_mut() {
            *c = c.map(|v| v * k);
        }
    }
}

/// The checks of a scene's regions ([`crate::suite`]'s doc gives the tolerances).
fn checks(scene: &Scene, regions: &[RegionStats], loss: Option<&Loss>) -> Vec<Check> {
    let extra = loss.map_or(0.0, |l| l.tolerance);
    if !scene.is_spectral() {
        return regions
            .iter()
            .map(|r| {
                let tolerance = 4.0 * r.standard_error + (1e-4 + extra) * r.reference.abs();
                Check {
                    what: format!("{}: mean luminance", r.name),
                    value: r.value,
                    reference: r.reference,
                    tolerance,
                    pass: (r.value - r.reference).abs() <= tolerance,
                }
            })
            .collect();
    }
    let white = regions
        .iter()
        .find(|r| r.name == "white")
        .map_or([scene.white; 3], |r| r.rgb);
    let mut out = vec![];
    let mut tol = vec![];
    for r in regions.iter().filter(|r| r.name != "white") {
        let tolerance = compare::delta_e_noise(r, white) + SPECTRAL_INTEGRATION_DE;
        tol.push(tolerance);
        out.push(Check {
            what: format!("{}: ΔE00 from the reference colour", r.name),
            value: r.delta_e00,
            reference: 0.0,
            tolerance,
            pass: r.delta_e00 <= tolerance,
        });
    }
    let patches: Vec<&RegionStats> = regions.iter().filter(|r| r.name != "white").collect();
    if let [a, b] = patches[..] {
        let value = compare::delta_e(a.lab, b.lab);
        let reference = compare::delta_e(a.reference_lab, b.reference_lab);
        let tolerance = tol.iter().sum::<f64>();
        out.push(Check {
            what: "ΔE00 between the two patches".into(),
            value,
            reference,
            tolerance,
            pass: (value - reference).abs() <= tolerance,
        });
    }
    out
}

/// The ΔE00 allowed for the difference between the reference's spectral integration and the
/// renderers' ([`crate::suite`]'s doc).
pub const SPECTRAL_INTEGRATION_DE: f64 = 0.2;
