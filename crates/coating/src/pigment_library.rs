//! gonio's built-in library of measured pigments: the two-constant Kubelka-Munk K(λ) and S(λ)
//! of 19 real pigments (Golden Heavy Body artist acrylics, 380–750 nm every 10 nm; provenance in
//! `data/pigments/README.md`: the Artist Paint Spectral Database of the Rochester Institute of
//! Technology, Okumura 2005 and Berns' group, as repackaged in waacton/Unicolour), embedded in
//! the library. A coating description names a pigment (`[[base.pigment]] library = "NAME"`,
//! [`crate::description`]); `gonio pigments` shows them.
//!
//! The data's units are relative (titanium white's S is 1 at every wavelength). A layer's K and
//! S per micrometre are `SCALE_PER_UM · c · K_rel` and `SCALE_PER_UM · c · S_rel`, with c the
//! concentration: the fraction of the pigment's paint in the layer, 1 for the paint as it comes
//! (the masstone). Opaque colours (R∞ of Duncan's mixture) depend on K/S only, not on the scale.

use crate::clear_coat::Pigment;
use crate::error::{CoatingError, Result};
use crate::kubelka_munk::{Coefficients, saunderson_specular_excluded};
use gonio_color::Spectrum;
use std::sync::LazyLock;

/// The absolute scale of the library, 1/µm per relative unit: titanium white's paint scatters
/// S = 0.5/µm. No absolute value is published for these paints (the database's K and S come
/// from masstones and tints, which fix K/S and the ratios between paints only), so the scale is
/// chosen from hiding: with it, a film of the white paint over black comes within 1 ΔE00
/// (D65, 10°) of its opaque colour at 40 µm and reaches the contrast ratio 0.98 (ASTM D2805's
/// "complete hiding", over a white of reflectance 0.80) at 24 µm — the few tens of micrometres
/// of dry film at which white paints hide. docs/coatings.md ("The pigment library") gives the
/// thicknesses every pigment needs with it; to model a weaker or stronger paint, scale its
/// concentrations (Duncan's mixing is linear in them).
pub const SCALE_PER_UM: f64 = 0.5;

/// Saunderson's external reflectance k1 of the database's measuring geometry (Unicolour pairs
/// the data with it): the reflectance read through the paint's surface, specular excluded, is
/// [`saunderson_specular_excluded`]`(R, k1, k2)` of the internal Kubelka-Munk reflectance R.
pub const SAUNDERSON_K1: f64 = 0.03;

/// Saunderson's internal reflectance k2 for diffuse light of the database's measuring geometry.
pub const SAUNDERSON_K2: f64 = 0.65;

/// The library's white, the one the tints are made with.
pub const WHITE: &str = "titanium_white";

/// Parts of white to one part of the pigment's paint in the tint `gonio pigments` shows (1:10).
pub const TINT_PARTS_WHITE: f64 = 10.0;

/// The embedded data (`data/pigments/golden_heavy_body_ks.csv`).
const CSV: &str = include_str!("../data/pigments/golden_heavy_body_ks.csv");

/// The file the data came from, for messages.
const SOURCE: &str = "golden_heavy_body_ks.csv";

/// One pigment of the library: relative K and S at the library's wavelengths.
#[derive(Clone, Debug, PartialEq)]
pub struct LibraryPigment {
    /// Its name in descriptions (`phthalo_blue_green_shade`).
    pub name: String,
    /// The Colour Index generic name (`PB15`).
    pub colour_index: String,
    /// Absorption K, relative units (titanium white's S = 1).
    pub k: Spectrum,
    /// Scattering S, relative units.
    pub s: Spectrum,
}

impl LibraryPigment {
    /// The pigment at `concentration` as a layer constituent: K and S per micrometre, the relative
    /// values times [`SCALE_PER_UM`], at the library's wavelengths.
    pub fn pigment(&self, concentration: f64) -> Result<Pigment> {
        let scaled = |q: &Spectrum| {
            let values = q.values().iter().map(|v| v * SCALE_PER_UM).collect();
            Spectrum::new(q.wavelengths_nm().to_vec(), values)
                .map_err(|e| CoatingError::Invalid(format!("{}: {e}", self.name)))
        };
        Ok(Pigment {
            name: self.name.clone(),
            concentration,
            k_per_um: scaled(&self.k)?,
            s_per_um: scaled(&self.s)?,
        })
    }

    /// Its masstone: the opaque layer of its paint alone, R∞ inside the surface.
    pub fn masstone(&self) -> Result<Spectrum> {
        opaque_reflectance(&[(1.0, self)])
    }

    /// Its tint with the library's white, 1 part of the paint to [`TINT_PARTS_WHITE`] parts of
    /// white: R∞ inside the surface.
    pub fn tint(&self) -> Result<Spectrum> {
        opaque_reflectance(&[(1.0, self), (TINT_PARTS_WHITE, find(WHITE)?)])
    }
}

/// The library, parsed once.
static LIBRARY: LazyLock<Vec<LibraryPigment>> = LazyLock::new(|| {
    parse(CSV).unwrap_or_else(|e| panic!("the embedded {SOURCE} does not parse: {e}"))
});

/// Every pigment of the library, in the file's order.
pub fn pigments() -> &'static [LibraryPigment] {
    &LIBRARY
}

/// The wavelengths (nm) at which the library holds K and S: 380–750 every 10 nm.
pub fn wavelengths_nm() -> &'static [f64] {
    LIBRARY[0].k.wavelengths_nm()
}

/// The pigment called `name`; an unknown name is an error that suggests the closest name and
/// lists the library.
pub fn find(name: &str) -> Result<&'static LibraryPigment> {
    if let Some(p) = LIBRARY.iter().find(|p| p.name == name) {
        return Ok(p);
    }
    let names: Vec<&str> = LIBRARY.iter().map(|p| p.name.as_str()).collect();
    // A name that contains what was typed (a shortened name) first, else the fewest edits.
    let closest = names
        .iter()
        .min_by_key(|n| (!n.contains(name), edit_distance(name, n)))
        .expect("the library is not empty");
    Err(CoatingError::Invalid(format!(
        "'{name}' is not a pigment of gonio's library ({SOURCE}); did you mean '{closest}'? \
         The library: {}",
        names.join(", ")
    )))
}

/// The opaque reflectance R∞ (inside the surface) of a mixture of library pigments, each with
/// its concentration (any common unit: R∞ depends on K/S only), at the library's wavelengths:
/// Duncan's mixing ([`Coefficients::mixture`]) then Kubelka's `R∞ = 1 + K/S − √((K/S)² + 2K/S)`
/// ([`Coefficients::r_infinity`]) at each wavelength.
pub fn opaque_reflectance(parts: &[(f64, &LibraryPigment)]) -> Result<Spectrum> {
    let wl = wavelengths_nm();
    let values = (0..wl.len())
        .map(|i| {
            let constituents = parts
                .iter()
                .map(|&(c, p)| {
                    Coefficients::new(p.k.values()[i], p.s.values()[i]).map(|co| (c, co))
                })
                .collect::<Result<Vec<_>>>()?;
            Ok(Coefficients::mixture(&constituents)?.r_infinity())
        })
        .collect::<Result<Vec<_>>>()?;
    Spectrum::new(wl.to_vec(), values).map_err(|e| CoatingError::Invalid(e.to_string()))
}

/// A reflectance inside the paint's surface as the database's instrument reads it through the
/// surface, specular excluded: [`saunderson_specular_excluded`] with [`SAUNDERSON_K1`] and
/// [`SAUNDERSON_K2`] at each sample (Unicolour's correction of these data; the colour of the
/// paint seen away from its mirror reflection).
pub fn as_measured(internal: &Spectrum) -> Spectrum {
    let values = internal
        .values()
        .iter()
        .map(|&r| saunderson_specular_excluded(r, SAUNDERSON_K1, SAUNDERSON_K2))
        .collect();
    Spectrum::new(internal.wavelengths_nm().to_vec(), values)
        .expect("same wavelengths as a valid spectrum")
}

/// Parse the library's CSV: `#` comments, the header `pigment,colour_index,quantity,<nm>...`,
/// then for each pigment a `K` row and an `S` row.
fn parse(text: &str) -> std::result::Result<Vec<LibraryPigment>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.starts_with('#') && !l.trim().is_empty());
    let (_, header) = lines.next().ok_or("no header line")?;
    let wavelengths: Vec<f64> = header
        .split(',')
        .skip(3)
        .map(|w| {
            w.trim()
                .parse::<f64>()
                .map_err(|e| format!("header {w}: {e}"))
        })
        .collect::<std::result::Result<_, _>>()?;
    let mut out: Vec<LibraryPigment> = Vec::new();
    let mut pending: Option<(String, String, Vec<f64>)> = None;
    for (n, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let at = |what: &str| format!("line {}: {what}", n + 1);
        if fields.len() != 3 + wavelengths.len() {
            return Err(at(&format!(
                "{} fields, expected {}",
                fields.len(),
                3 + wavelengths.len()
            )));
        }
        let values: Vec<f64> = fields[3..]
            .iter()
            .map(|v| v.parse::<f64>().map_err(|e| at(&format!("{v}: {e}"))))
            .collect::<std::result::Result<_, _>>()?;
        let spectrum =
            |v: Vec<f64>| Spectrum::new(wavelengths.clone(), v).map_err(|e| at(&e.to_string()));
        match (fields[2], pending.take()) {
            ("K", None) => pending = Some((fields[0].into(), fields[1].into(), values)),
            ("S", Some((name, colour_index, k))) if name == fields[0] => out.push(LibraryPigment {
                name,
                colour_index,
                k: spectrum(k)?,
                s: spectrum(values)?,
            }),
            _ => return Err(at("expected a K row followed by the same pigment's S row")),
        }
    }
    if pending.is_some() || out.is_empty() {
        return Err("a pigment without its S row, or no pigment".into());
    }
    Ok(out)
}

/// Levenshtein's edit distance between two names (insertions, deletions and substitutions of one
/// character each count 1), for the suggestion of [`find`].
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Levenshtein distances worked by hand: kitten → sitting is 3 (two substitutions, one
    /// insertion); a name is 0 from itself and its length from the empty name.
    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("bone_black", "bone_black"), 0);
        assert_eq!(edit_distance("", "cobalt"), 6);
        assert_eq!(edit_distance("phthalo_blu", "phthalo_blue_red_shade"), 11);
    }

    /// A malformed table names the line and what is wrong.
    #[test]
    fn malformed_tables_are_refused() {
        let head = "pigment,colour_index,quantity,400,500\n";
        let e = parse(&format!("{head}a,P1,S,1,2\n")).unwrap_err();
        assert!(e.contains("line 2"), "{e}");
        let e = parse(&format!("{head}a,P1,K,1\n")).unwrap_err();
        assert!(e.contains("fields"), "{e}");
        let e = parse(&format!("{head}a,P1,K,1,2\n")).unwrap_err();
        assert!(e.contains("without its S row"), "{e}");
        let ok = parse(&format!("# note\n{head}a,P1,K,1,2\na,P1,S,3,4\n")).unwrap();
        assert_eq!(ok[0].s.values(), &[3.0, 4.0]);
    }
}
