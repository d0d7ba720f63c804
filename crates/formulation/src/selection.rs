//! Colorant selection: which pigments of gonio's library, up to a number given, and at which
//! concentrations, together with the other varied constituents, bring a start formulation
//! closest to a target ([`run`]). As formulation programs do (E. Allen, ch. 7 of Grum &
//! Bartleson, *Optical Radiation Measurements*, vol. 2, 1980; R. S. Berns, *Billmeyer and
//! Saltzman's Principles of Color Technology*, 4th ed., 2019, ch. 9), every combination of the
//! candidates is screened with a cheap model ([`crate::screen`]: the coating's own response to
//! its base's reflectance, the concentrations fitted per combination), and the full match
//! ([`crate::matching`], unchanged) runs on the best few finalists, each started from its
//! screened concentrations; the finalist that ends lowest is the selection.
//!
//! The steps are public so that a front end can spread them ([`screen()`], then
//! [`finalist_start`] and [`matching::search`] per finalist anywhere, then [`conclude`]): the
//! result equals [`run`]'s, every reading being made with seed 0.

use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
use crate::fitted_description::{with_library_pigments, with_values};
use crate::matching::{self, Match, Run, Settings};
use crate::screen::{self, CONCENTRATION_RANGE, Response, Screened};
use crate::target::GlossTarget;
use crate::watch::{Progress, Watch};
use gonio_coating::pigment_library::{self, LibraryPigment};
use gonio_coating::system::Coating;
use gonio_instrument::coating_study::Constituent;
use gonio_instrument::multiangle_target::Target;
use gonio_io::Cancel;
use rayon::prelude::*;
use std::sync::Mutex;
use std::time::Instant;

/// Default number of library pigments chosen at most (a formulation program's usual three
/// colorants besides the white).
pub const MAX_PIGMENTS: usize = 3;

/// Default number of finalists the full match runs on (docs/formulation.md, "Colorant
/// selection": the screen ranked the true combination first on the synthetic solids and third
/// on the metallic, whose coverage it holds at the start's value).
pub const FINALISTS: usize = 3;

/// A finalist's concentration is fitted from its screened value c within
/// `[max(c / SPAN, 0.001), min(SPAN c, 1)]`.
pub const SPAN: f64 = 10.0;

/// The library pigments a selection may choose: those named in `from` (every one of the
/// library when `None`), less those already in `start`'s base. Refused: a base that is not a
/// Kubelka-Munk layer, an unknown name (the error suggests the closest), a name given twice or
/// already in the base, no candidate left.
pub fn candidates(
    start: &Coating,
    from: Option<&[String]>,
) -> Result<Vec<&'static LibraryPigment>> {
    screen::with_pigments(start, &[], &[])?;
    let present = screen::base_pigments(start);
    let list: Vec<&'static LibraryPigment> = match from {
        None => pigment_library::pigments()
            .iter()
            .filter(|p| !present.iter().any(|q| q.name == p.name))
            .collect(),
        Some(names) => {
            let mut list: Vec<&'static LibraryPigment> = Vec::new();
            for name in names.iter().map(|n| n.trim()) {
                let p = pigment_library::find(name)?;
                if list.iter().any(|q| q.name == p.name) {
                    return Err(FormulationError::Invalid(format!(
                        "candidate '{name}' is given twice"
                    )));
                }
                if present.iter().any(|q| q.name == p.name) {
                    return Err(FormulationError::Invalid(format!(
                        "candidate '{name}' is already in the start's base (vary its \
                         concentration instead: concentration:{name})"
                    )));
                }
                list.push(p);
            }
            list
        }
    };
    if list.is_empty() {
        return Err(FormulationError::Invalid(
            "no candidate pigment to select from".into(),
        ));
    }
    Ok(list)
}

/// Every combination of 1 to `max` of `n` candidates, as indices in increasing order, the
/// smaller combinations first.
pub fn combinations(n: usize, max: usize) -> Vec<Vec<usize>> {
    let mut all: Vec<Vec<usize>> = Vec::new();
    let mut layer: Vec<Vec<usize>> = vec![vec![]];
    for _ in 0..max.min(n) {
        layer = layer
            .iter()
            .flat_map(|c| {
                let from = c.last().map_or(0, |&i| i + 1);
                (from..n).map(move |i| {
                    let mut d = c.clone();
                    d.push(i);
                    d
                })
            })
            .collect();
        all.extend(layer.iter().cloned());
    }
    all
}

/// What the screen found: every combination scored, best first.
#[derive(Clone, Debug)]
pub struct Screen {
    /// The candidates, in the library's order.
    pub candidates: Vec<String>,
    /// Every combination tried with its fitted concentrations and score, best (lowest) first.
    pub tried: Vec<Screened>,
    /// Readings of the real coating made (the stack's response: three; the embedded table: its
    /// nodes).
    pub readings: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Screen every combination of 1 to `max_pigments` of `candidates` added to `start`
/// ([`crate::screen`]), with `settings`' objective, bands and walks; stops with
/// [`FormulationError::Cancelled`] once `cancel` is raised. Refused: no pigment to select, no
/// candidate, more pigments than candidates.
pub fn screen(
    start: &Coating,
    target: &Target,
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    settings: &Settings,
    cancel: &Cancel,
) -> Result<Screen> {
    let watch = Watch {
        cancel: Some(cancel),
        progress: None,
    };
    screen_watched(start, target, candidates, max_pigments, settings, &watch)
}

/// Refuse a selection of `max_pigments` of `candidates` in `finalists`: none to select, no
/// candidate, more pigments than candidates, no finalist.
pub fn check(candidates: usize, max_pigments: usize, finalists: usize) -> Result<()> {
    if max_pigments == 0 {
        return Err(FormulationError::Invalid(
            "select at least 1 pigment (0 given)".into(),
        ));
    }
    if candidates == 0 {
        return Err(FormulationError::Invalid(
            "no candidate pigment to select from".into(),
        ));
    }
    if max_pigments > candidates {
        return Err(FormulationError::Invalid(format!(
            "select up to {max_pigments} pigments of {candidates} candidates: at most \
             {candidates}"
        )));
    }
    if finalists == 0 {
        return Err(FormulationError::Invalid(
            "a selection needs at least 1 finalist (0 given)".into(),
        ));
    }
    Ok(())
}

/// Check a selection before it reads anything, so that a front end refuses a bad request at
/// once: [`check`]'s counts, then the match a finalist runs (`matching::check`: its settings,
/// objective and target, and `varied`, each valid for the start) on `start` with the first
/// candidate added at 0.1 (any concentration of the screen's range serves: the checks do not
/// depend on it).
#[allow(clippy::too_many_arguments)]
pub fn check_run(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    finalists: usize,
    settings: &Settings,
) -> Result<()> {
    check(candidates.len(), max_pigments, finalists)?;
    let first = Screened {
        pigments: vec![candidates[0].name.clone()],
        concentrations: vec![0.1],
        score: 0.0,
    };
    let (coating, all) = finalist_start(start, varied, &first)?;
    matching::check(&coating, target, gloss, &all, settings)
}

/// [`screen()`] under `watch`: told after every combination the combinations screened, of how
/// many, and the lowest screen score so far (`Progress`' readings, total and best), and stopped
/// ([`FormulationError::Cancelled`]) before the next combination once its flag is raised.
pub fn screen_watched(
    start: &Coating,
    target: &Target,
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    settings: &Settings,
    watch: &Watch,
) -> Result<Screen> {
    let clock = Instant::now();
    check(candidates.len(), max_pigments, 1)?;
    screen::with_pigments(start, &[], &[])?;
    let response = Response::measure(
        start,
        &target.geometries(),
        &settings.wavelengths_nm,
        settings.walks,
        candidates,
        max_pigments,
    )?;
    let all = combinations(candidates.len(), max_pigments);
    // Combinations screened and the lowest score, from every thread.
    let so_far = Mutex::new((0usize, f64::INFINITY));
    let mut tried = all
        .par_iter()
        .map(|c| {
            if watch.cancel.is_some_and(|c| c.is_cancelled()) {
                return Err(FormulationError::Cancelled);
            }
            let pigments: Vec<&LibraryPigment> = c.iter().map(|&i| candidates[i]).collect();
            let s = screen::fit(&response, start, target, settings.objective, &pigments)?;
            let mut n = so_far.lock().unwrap_or_else(|p| p.into_inner());
            *n = (n.0 + 1, n.1.min(s.score));
            watch.report(Progress {
                readings: n.0,
                total: Some(all.len()),
                best: Some(n.1),
            });
            Ok(s)
        })
        .collect::<Result<Vec<_>>>()?;
    // A stable sort: ties keep the combinations' order.
    tried.sort_by(|a, b| a.score.total_cmp(&b.score));
    Ok(Screen {
        candidates: candidates.iter().map(|p| p.name.clone()).collect(),
        tried,
        readings: response.readings(),
        seconds: clock.elapsed().as_secs_f64(),
    })
}

/// A finalist's start: `start` with the screened pigments added at their screened
/// concentrations, and what its match varies: `varied`, then each added pigment's
/// concentration within [`SPAN`] of its screened value.
pub fn finalist_start(
    start: &Coating,
    varied: &[Varied],
    screened: &Screened,
) -> Result<(Coating, Vec<Varied>)> {
    let pigments = screened
        .pigments
        .iter()
        .map(|n| pigment_library::find(n))
        .collect::<gonio_coating::Result<Vec<_>>>()?;
    let coating = screen::with_pigments(start, &pigments, &screened.concentrations)?;
    let mut all = varied.to_vec();
    for (name, &c) in screened.pigments.iter().zip(&screened.concentrations) {
        all.push(Varied {
            name: format!("concentration:{name}"),
            constituent: Constituent::Concentration(name.clone()),
            lo: (c / SPAN).max(CONCENTRATION_RANGE.0),
            hi: (c * SPAN).min(CONCENTRATION_RANGE.1),
        });
    }
    Ok((coating, all))
}

/// One finalist: its screened combination, its start and varied constituents
/// ([`finalist_start`]) and its full match.
#[derive(Clone, Debug)]
pub struct Finalist {
    pub screened: Screened,
    pub start: Coating,
    pub varied: Vec<Varied>,
    pub result: Match,
}

/// The finalist of `screened` from its search's `runs` ([`matching::search`] on
/// [`finalist_start`]'s coating and constituents, made here or elsewhere).
pub fn conclude_finalist(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    screened: &Screened,
    settings: &Settings,
    runs: Vec<Run>,
) -> Result<Finalist> {
    let (coating, all) = finalist_start(start, varied, screened)?;
    let result = matching::conclude(&coating, target, gloss, &all, settings, runs)?;
    Ok(Finalist {
        screened: screened.clone(),
        start: coating,
        varied: all,
        result,
    })
}

/// A selection's result.
#[derive(Clone, Debug)]
pub struct Selection {
    pub screen: Screen,
    /// The finalists, in the screen's order.
    pub finalists: Vec<Finalist>,
    /// The finalist whose match ended lowest.
    pub best: usize,
    /// Wall-clock seconds in all.
    pub seconds: f64,
}

/// The selection of `screen`'s `finalists` (in the screen's order): the one whose match ended
/// lowest (the first of equals).
pub fn conclude(screen: Screen, finalists: Vec<Finalist>, seconds: f64) -> Result<Selection> {
    let best = finalists
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| {
            a.result
                .fitted
                .objective
                .total_cmp(&b.result.fitted.objective)
        })
        .map(|(i, _)| i)
        .ok_or_else(|| FormulationError::Invalid("a selection needs one finalist".into()))?;
    Ok(Selection {
        screen,
        finalists,
        best,
        seconds,
    })
}

/// Where a selection is, told to [`run_watched`]'s caller as each step begins.
#[derive(Clone, Debug, PartialEq)]
pub enum Stage {
    /// The screen of this many combinations.
    Screen { combinations: usize },
    /// The full match of finalist `index` (from 0) of `count`, of these pigments.
    Finalist {
        index: usize,
        count: usize,
        pigments: Vec<String>,
    },
}

/// Select up to `max_pigments` of `candidates` ([`candidates`]) for `start` and fit them,
/// with the constituents of `varied`, to `target` (and the `gloss` readings): the screen, then
/// the full match of the best `finalists` combinations, serially (each match in parallel
/// inside). `progress` gets the screen's summary and the matches' lines; `cancel` stops the
/// selection before its next combination or reading (cancelled). The entry point of every
/// front end's "let gonio select" ([`run_watched`] for one that follows it).
#[allow(clippy::too_many_arguments)]
pub fn run(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    finalists: usize,
    settings: &Settings,
    progress: &mut dyn FnMut(&str),
    cancel: &Cancel,
) -> Result<Selection> {
    let watch = Watch {
        cancel: Some(cancel),
        progress: None,
    };
    run_watched(
        start,
        target,
        gloss,
        varied,
        candidates,
        max_pigments,
        finalists,
        settings,
        watch,
        &mut |_| {},
        progress,
    )
}

/// [`run`] under `watch` (the lab's jobs): `stage` is told as the screen and each finalist's
/// match begin; `watch` is told the screen's progress ([`screen_watched`]), then each
/// finalist's match's readings and lowest objective (`matching::run_watched`: its readings
/// counted from 0), and stops the selection before its next combination or reading once its
/// flag is raised.
#[allow(clippy::too_many_arguments)]
pub fn run_watched(
    start: &Coating,
    target: &Target,
    gloss: &[GlossTarget],
    varied: &[Varied],
    candidates: &[&LibraryPigment],
    max_pigments: usize,
    finalists: usize,
    settings: &Settings,
    watch: Watch,
    stage: &mut dyn FnMut(Stage),
    progress: &mut dyn FnMut(&str),
) -> Result<Selection> {
    let clock = Instant::now();
    check(candidates.len(), max_pigments, finalists)?;
    stage(Stage::Screen {
        combinations: combinations(candidates.len(), max_pigments).len(),
    });
    let s = screen_watched(start, target, candidates, max_pigments, settings, &watch)?;
    progress(&format!(
        "screen: {} combinations of up to {max_pigments} of {} candidates in {:.1} s; best {}",
        s.tried.len(),
        s.candidates.len(),
        s.seconds,
        describe(&s.tried[0])
    ));
    let count = finalists.min(s.tried.len());
    let mut done = Vec::with_capacity(count);
    for (k, screened) in s.tried[..count].iter().enumerate() {
        if watch.cancel.is_some_and(|c| c.is_cancelled()) {
            return Err(FormulationError::Cancelled);
        }
        stage(Stage::Finalist {
            index: k,
            count,
            pigments: screened.pigments.clone(),
        });
        progress(&format!(
            "finalist {} of {count}: {}",
            k + 1,
            describe(screened)
        ));
        let (coating, all) = finalist_start(start, varied, screened)?;
        let runs = matching::search_watched(
            &coating,
            target,
            gloss,
            &all,
            settings,
            &watch,
            &mut |line| progress(&format!("  {line}")),
        )?;
        done.push(conclude_finalist(
            start, target, gloss, varied, screened, settings, runs,
        )?);
    }
    conclude(s, done, clock.elapsed().as_secs_f64())
}

/// `a 0.0123 + b 0.456 (screen 0.789)`.
pub fn describe(s: &Screened) -> String {
    let parts: Vec<String> = s
        .pigments
        .iter()
        .zip(&s.concentrations)
        .map(|(n, c)| format!("{n} {c:.4}"))
        .collect();
    format!("{} (screen {:.4})", parts.join(" + "), s.score)
}

impl Selection {
    /// The chosen finalist.
    pub fn chosen(&self) -> &Finalist {
        &self.finalists[self.best]
    }

    /// The fitted description: `start_text` (the start's TOML) with the chosen pigments added
    /// as `[[base.pigment]] library = "NAME"` entries and every varied value replaced by its
    /// fitted one (comments kept).
    pub fn fitted_description(&self, start_text: &str) -> Result<String> {
        let f = self.chosen();
        let text = with_library_pigments(start_text, &f.screened.pigments)?;
        with_values(&text, &f.varied, &f.result.fitted.values)
    }

    /// The selection against `target` as JSON: the chosen finalist's match
    /// ([`Match::to_json`]'s fields) and `selection` {`candidates` \[names\], `combinations`
    /// (how many were screened), `tried` [{pigments, concentrations, score}] (the best
    /// `shown`, best first), `finalists` [{pigments, screen_concentrations, screen_score,
    /// objective, mean_de00, de00 [per geometry, the target's order], concentrations, sigma,
    /// evaluations}], `chosen` (its index in finalists), `pigments` (the chosen ones),
    /// `screen_seconds`, `seconds`}.
    pub fn to_json(&self, target: &Target, shown: usize) -> serde_json::Value {
        let tried: Vec<_> = self
            .screen
            .tried
            .iter()
            .take(shown)
            .map(|s| {
                serde_json::json!({"pigments": s.pigments, "concentrations": s.concentrations,
                                   "score": s.score})
            })
            .collect();
        let finalists: Vec<_> = self
            .finalists
            .iter()
            .map(|f| {
                let m = &f.result;
                let added = f.varied.len() - f.screened.pigments.len();
                let de = &m.fitted.de00;
                serde_json::json!({
                    "pigments": f.screened.pigments,
                    "screen_concentrations": f.screened.concentrations,
                    "screen_score": f.screened.score,
                    "objective": m.fitted.objective,
                    "mean_de00": de.iter().sum::<f64>() / de.len() as f64,
                    "de00": de,
                    "concentrations": m.fitted.values[added..],
                    "sigma": m.sigma.as_ref().map(|s| s[added..].to_vec()),
                    "evaluations": m.evaluations,
                })
            })
            .collect();
        let mut json = self.chosen().result.to_json(target);
        if let Some(out) = json.as_object_mut() {
            out.insert(
                "selection".into(),
                serde_json::json!({
                    "candidates": self.screen.candidates,
                    "combinations": self.screen.tried.len(),
                    "tried": tried,
                    "finalists": finalists,
                    "chosen": self.best,
                    "pigments": self.chosen().screened.pigments,
                    "screen_seconds": self.screen.seconds,
                    "seconds": self.seconds,
                }),
            );
        }
        json
    }
}
