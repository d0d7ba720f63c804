//! The TOML description of a coating (`examples/coatings/*.toml`, `docs/coatings.md`):
//! a clear coat and a base, read into [`ClearCoatOverBase`] with errors that name the file and
//! the field.
//!
//! ```toml
//! [coat]
//! index = 1.5                     # or { cauchy_a = 1.48, cauchy_b_um2 = 0.0045 }
//! thickness_um = 40
//! absorption_per_um = 0           # σ(λ), 1/µm: a number or { nm = [...], values = [...] }
//!
//! [base]
//! kind = "diffuse"                # or "kubelka-munk"
//! reflectance = { nm = [400, 500, 600, 700], values = [0.05, 0.05, 0.3, 0.7] }
//!
//! # kind = "kubelka-munk": thickness_um, substrate (a spectrum) and one or more
//! # [[base.pigment]] with name, concentration, k_per_um and s_per_um (spectra).
//! ```

use crate::clear_coat::{Base, ClearCoatOverBase, Coat, Dispersion, Pigment};
use crate::error::{CoatingError, Result};
use gonio_color::Spectrum;
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    coat: CoatFields,
    base: BaseFields,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CoatFields {
    index: IndexField,
    thickness_um: f64,
    #[serde(default)]
    absorption_per_um: Option<SpectrumField>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum IndexField {
    Constant(f64),
    Cauchy { cauchy_a: f64, cauchy_b_um2: f64 },
}

#[derive(Deserialize)]
#[serde(untagged)]
enum SpectrumField {
    Constant(f64),
    Sampled { nm: Vec<f64>, values: Vec<f64> },
}

#[derive(Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
enum BaseFields {
    Diffuse {
        reflectance: SpectrumField,
    },
    KubelkaMunk {
        thickness_um: f64,
        substrate: SpectrumField,
        pigment: Vec<PigmentFields>,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PigmentFields {
    name: String,
    concentration: f64,
    k_per_um: SpectrumField,
    s_per_um: SpectrumField,
}

impl SpectrumField {
    fn spectrum(self, field: &str) -> Result<Spectrum> {
        let made = match self {
            SpectrumField::Constant(v) => Spectrum::constant(vec![380.0, 780.0], v),
            SpectrumField::Sampled { nm, values } => Spectrum::new(nm, values),
        };
        made.map_err(|e| CoatingError::Invalid(format!("{field}: {e}")))
    }
}

/// Read a coating description. Checks the values at `wavelengths_nm` (those the table will
/// hold).
pub fn read(path: &Path, wavelengths_nm: &[f64]) -> Result<ClearCoatOverBase> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))?;
    parse(&text, wavelengths_nm)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))
}

/// Parse the text of a coating description (see [`read`]).
pub fn parse(text: &str, wavelengths_nm: &[f64]) -> Result<ClearCoatOverBase> {
    let file: File = toml::from_str(text).map_err(|e| CoatingError::Invalid(e.to_string()))?;
    let index = match file.coat.index {
        IndexField::Constant(n) => Dispersion::Constant(n),
        IndexField::Cauchy {
            cauchy_a,
            cauchy_b_um2,
        } => Dispersion::Cauchy {
            a: cauchy_a,
            b_um2: cauchy_b_um2,
        },
    };
    let coat = Coat {
        index,
        thickness_um: file.coat.thickness_um,
        absorption_per_um: file
            .coat
            .absorption_per_um
            .unwrap_or(SpectrumField::Constant(0.0))
            .spectrum("coat.absorption_per_um")?,
    };
    let base = match file.base {
        BaseFields::Diffuse { reflectance } => Base::Diffuse {
            reflectance: reflectance.spectrum("base.reflectance")?,
        },
        BaseFields::KubelkaMunk {
            thickness_um,
            substrate,
            pigment,
        } => {
            if !(thickness_um.is_finite() && thickness_um >= 0.0) {
                return Err(CoatingError::Invalid(format!(
                    "base.thickness_um {thickness_um}: must be finite and non-negative"
                )));
            }
            if pigment.is_empty() {
                return Err(CoatingError::Invalid(
                    "base: a kubelka-munk base needs at least one [[base.pigment]]".into(),
                ));
            }
            Base::KubelkaMunk {
                thickness_um,
                substrate: substrate.spectrum("base.substrate")?,
                pigments: pigment
                    .into_iter()
                    .map(|p| {
                        let field = |f: &str| format!("base.pigment '{}'.{f}", p.name);
                        Ok(Pigment {
                            concentration: p.concentration,
                            k_per_um: p.k_per_um.spectrum(&field("k_per_um"))?,
                            s_per_um: p.s_per_um.spectrum(&field("s_per_um"))?,
                            name: p.name,
                        })
                    })
                    .collect::<Result<Vec<_>>>()?,
            }
        }
    };
    let stack = ClearCoatOverBase { coat, base };
    stack.check(wavelengths_nm)?;
    Ok(stack)
}

#[cfg(test)]
mod tests {
    use super::*;

    const WL: [f64; 3] = [400.0, 550.0, 700.0];

    #[test]
    fn diffuse_and_kubelka_munk_bases() {
        let s = parse(
            r#"
            [coat]
            index = { cauchy_a = 1.48, cauchy_b_um2 = 0.0045 }
            thickness_um = 40
            [base]
            kind = "diffuse"
            reflectance = { nm = [400, 700], values = [0.1, 0.7] }
            "#,
            &WL,
        )
        .unwrap();
        assert!((s.coat.index.at(500.0) - (1.48 + 0.0045 / 0.25)).abs() < 1e-15);
        assert!((s.base.reflectance(550.0).unwrap() - 0.4).abs() < 1e-15);
        assert_eq!(s.coat.absorption_per_um.value_at(550.0), 0.0);
        let s = parse(
            r#"
            [coat]
            index = 1.5
            thickness_um = 40
            absorption_per_um = 0.001
            [base]
            kind = "kubelka-munk"
            thickness_um = 25
            substrate = 0.85
            [[base.pigment]]
            name = "white"
            concentration = 0.8
            k_per_um = 0.001
            s_per_um = 1.0
            "#,
            &WL,
        )
        .unwrap();
        assert!(matches!(s.base, Base::KubelkaMunk { ref pigments, .. } if pigments.len() == 1));
    }

    #[test]
    fn errors_name_the_field() {
        let bad = |text: &str, needle: &str| {
            let e = parse(text, &WL).unwrap_err().to_string();
            assert!(e.contains(needle), "{needle}: {e}");
        };
        bad(
            "[coat]\nindex = 1.5\nthickness_um = 4\n[base]\nkind = \"glass\"\n",
            "glass",
        );
        bad(
            "[coat]\nindex = 1.5\nthickness_um = 4\ncolour = 1\n[base]\nkind = \"diffuse\"\nreflectance = 0.5\n",
            "colour",
        );
        bad(
            "[coat]\nindex = 1.5\nthickness_um = 4\n[base]\nkind = \"diffuse\"\nreflectance = 1.5\n",
            "base reflectance",
        );
        bad(
            "[coat]\nindex = 1.5\nthickness_um = 4\n[base]\nkind = \"diffuse\"\nreflectance = { nm = [400], values = [0.2, 0.3] }\n",
            "base.reflectance",
        );
        bad(
            "[coat]\nindex = 1.5\nthickness_um = 4\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 5\nsubstrate = 0.5\npigment = []\n",
            "at least one",
        );
    }
}
