//! Gwyddion's ASCII matrix export ("Text matrix of data values"): optional `#` comment lines,
//! then one line of whitespace-separated values per row. With "Add informational comment
//! header" Gwyddion writes `# Channel: name`, `# Width: 12.34 µm`, `# Height: 5678.9 nm` (the
//! physical size of the whole field) and `# Value units: m`.
//!
//! Gwyddion translates the keys into the language of its user interface (`# Breite:`,
//! `# Höhe:` in German, `# Largeur:`, `# Hauteur:` in French, ...). The keys of the languages in
//! [`KEYS`] are read by name; any other header is read by position and value, in the order
//! Gwyddion writes it: the first length (`number unit`) is the width, the second the height, a
//! bare length unit is the value unit, and a line before them that is neither is the channel name.
//!
//! The matrix itself carries no spacing, so a file without the `# Width:` and `# Height:` lines
//! is an error that says how to re-export it. Width, height and value units may be m, mm, µm
//! (um), nm, pm or Å; values in any other unit are an error. Numbers may use a decimal comma;
//! `nan` marks a point that was not measured.

use super::common::{build_map, metres_per_unit, parse_number, unit_scale};
use super::text::{looks_like_gwyddion, matrix_rows, numbered_lines, utf8};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use std::path::Path;

pub(crate) const NAME: &str = "Gwyddion ASCII matrix";

/// A text file whose first non-blank line is a `#` comment.
pub(crate) fn sniff(bytes: &[u8]) -> bool {
    looks_like_gwyddion(bytes)
}

/// What a header line of Gwyddion's export states.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Key {
    Channel,
    Width,
    Height,
    ValueUnits,
}

/// Gwyddion's header keys in the languages of its translations that a user is likely to meet
/// (English, German, French, Czech, Spanish, Italian, Portuguese), compared case-insensitively.
const KEYS: &[(&str, Key)] = &[
    ("channel", Key::Channel),
    ("kanal", Key::Channel),
    ("canal", Key::Channel),
    ("kanál", Key::Channel),
    ("canale", Key::Channel),
    ("width", Key::Width),
    ("breite", Key::Width),
    ("largeur", Key::Width),
    ("šířka", Key::Width),
    ("anchura", Key::Width),
    ("ancho", Key::Width),
    ("larghezza", Key::Width),
    ("largura", Key::Width),
    ("height", Key::Height),
    ("höhe", Key::Height),
    ("hauteur", Key::Height),
    ("výška", Key::Height),
    ("altura", Key::Height),
    ("altezza", Key::Height),
    ("value units", Key::ValueUnits),
    ("werteinheiten", Key::ValueUnits),
    ("einheiten der werte", Key::ValueUnits),
    ("unités des valeurs", Key::ValueUnits),
    ("unités de valeur", Key::ValueUnits),
    ("jednotky hodnot", Key::ValueUnits),
    ("unidades de valor", Key::ValueUnits),
    ("unità dei valori", Key::ValueUnits),
];

/// Which header entry a `# key: value` line is: by its key where the key is known, else by its
/// value and by the entries already seen (Gwyddion writes channel, width, height, value units).
fn classify(key: &str, value: &str, seen: &[Key]) -> Option<Key> {
    let lower = key.trim().to_lowercase();
    if let Some(&(_, k)) = KEYS.iter().find(|(name, _)| *name == lower) {
        return Some(k);
    }
    if is_length(value) {
        return [Key::Width, Key::Height]
            .into_iter()
            .find(|k| !seen.contains(k));
    }
    if metres_per_unit(value).is_some() {
        return (!seen.contains(&Key::ValueUnits)).then_some(Key::ValueUnits);
    }
    (seen.is_empty()).then_some(Key::Channel)
}

/// Whether `value` reads as `number unit` with a length unit.
fn is_length(value: &str) -> bool {
    value
        .split_once(char::is_whitespace)
        .is_some_and(|(n, u)| parse_number(n).is_some() && metres_per_unit(u).is_some())
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let text = utf8(path, NAME, bytes)?;
    let (mut width, mut height, mut z_unit, mut channel) = (None, None, "m", None);
    let mut seen = Vec::new();
    let mut lines = numbered_lines(text).peekable();
    while let Some((_, comment)) = lines.next_if(|(_, l)| l.starts_with('#')) {
        let Some((key, value)) = comment[1..].split_once(':') else {
            continue;
        };
        let value = value.trim();
        let Some(entry) = classify(key, value, &seen) else {
            continue;
        };
        seen.push(entry);
        let key = key.trim();
        match entry {
            Key::Width => width = Some(length(path, key, value)?),
            Key::Height => height = Some(length(path, key, value)?),
            Key::ValueUnits => z_unit = value,
            Key::Channel => channel = Some(value),
        }
    }
    let (mut heights, nx) = matrix_rows(path, NAME, lines)?;
    let (Some(width), Some(height)) = (width, height) else {
        return Err(fail(
            "no '# Width:' and '# Height:' lines (or their translations) state the field size, so \
             the spacing is unknown: export from Gwyddion with \"Add informational comment \
             header\" checked"
                .into(),
        ));
    };
    let z_scale = unit_scale(path, NAME, "value", z_unit)?;
    for h in &mut heights {
        *h *= z_scale;
    }
    let ny = heights.len() / nx;
    let mut map = build_map(
        path,
        NAME,
        heights,
        (nx, ny),
        (width / nx as f64, height / ny as f64),
    )?;
    if let Some(channel) = channel {
        map.meta.extra.push(("channel".into(), channel.to_string()));
    }
    Ok(map)
}

/// A length such as `12.34 µm` in metres.
fn length(path: &Path, key: &str, value: &str) -> Result<f64> {
    let fail = || {
        SurfaceError::format(
            path,
            NAME,
            format!("'# {key}: {value}' is not a positive length with a unit"),
        )
    };
    let (number, unit) = value.split_once(char::is_whitespace).ok_or_else(fail)?;
    let number = parse_number(number)
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(fail)?;
    Ok(number * unit_scale(path, NAME, key, unit.trim())?)
}
