//! The fitted formulation as a coating description: the start file's TOML with the varied
//! constituents' values replaced, everything else (comments, layout, the other fields) kept as
//! written. Edited with `toml_edit`, which keeps each value's surrounding comments (its
//! "decor") when the value is replaced here.

use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
use gonio_instrument::coating_study::Constituent;
use toml_edit::{DocumentMut, InlineTable, Item, TableLike, Value};

/// `text` (a coating description) with each of `varied` set to its value in `values`: the
/// top's roughness α (`[top] roughness = { distribution, alpha }`; a roughness given as Sq and a
/// correlation length or a height map becomes `alpha`, Beckmann's rms slope, as
/// `Constituent::apply` reads it; 0 removes `[top]`, a smooth top), `[flakes]` `tilt_deg`,
/// `coverage`, `tio2_nm`, `[coat] thickness_um`, `[base] thickness_um`, or the `concentration` of the
/// `[[base.pigment]]` of that name. Errors name the field that is missing.
pub fn with_values(text: &str, varied: &[Varied], values: &[f64]) -> Result<String> {
    let mut doc: DocumentMut = text
        .parse()
        .map_err(|e| FormulationError::Invalid(format!("not TOML: {e}")))?;
    for (v, &value) in varied.iter().zip(values) {
        let missing = |field: &str| {
            FormulationError::Invalid(format!(
                "{}: the description has no {field} to replace",
                v.name
            ))
        };
        let root = doc.as_table_mut();
        match &v.constituent {
            Constituent::Roughness => {
                if value == 0.0 {
                    root.remove("top");
                    continue;
                }
                let top = root
                    .entry("top")
                    .or_insert_with(|| Item::Table(toml_edit::Table::new()))
                    .as_table_like_mut()
                    .ok_or_else(|| missing("[top] table"))?;
                let alpha_given = top
                    .get("roughness")
                    .and_then(Item::as_table_like)
                    .is_some_and(|r| r.contains_key("alpha"));
                if alpha_given {
                    let roughness = top
                        .get_mut("roughness")
                        .and_then(Item::as_table_like_mut)
                        .ok_or_else(|| missing("[top] roughness"))?;
                    set(roughness, "alpha", value).ok_or_else(|| missing("roughness.alpha"))?;
                } else {
                    let distribution = top
                        .get("roughness")
                        .and_then(|r| r.get("distribution"))
                        .and_then(Item::as_str)
                        .unwrap_or("beckmann")
                        .to_string();
                    let mut table = InlineTable::new();
                    table.insert("distribution", distribution.into());
                    table.insert("alpha", value.into());
                    replace(top, "roughness", Value::InlineTable(table));
                }
            }
            Constituent::FlakeTilt | Constituent::FlakeCoverage | Constituent::Tio2 => {
                let key = match v.constituent {
                    Constituent::FlakeTilt => "tilt_deg",
                    Constituent::FlakeCoverage => "coverage",
                    _ => "tio2_nm",
                };
                let flakes = root
                    .get_mut("flakes")
                    .and_then(Item::as_table_like_mut)
                    .ok_or_else(|| missing("[flakes] table"))?;
                set(flakes, key, value).ok_or_else(|| missing(&format!("flakes.{key}")))?;
            }
            Constituent::BaseThickness => {
                let base = root
                    .get_mut("base")
                    .and_then(Item::as_table_like_mut)
                    .ok_or_else(|| missing("[base] table"))?;
                set(base, "thickness_um", value).ok_or_else(|| missing("base.thickness_um"))?;
            }
            Constituent::CoatThickness => {
                let coat = root
                    .get_mut("coat")
                    .and_then(Item::as_table_like_mut)
                    .ok_or_else(|| missing("[coat] table"))?;
                set(coat, "thickness_um", value).ok_or_else(|| missing("coat.thickness_um"))?;
            }
            Constituent::Concentration(name) => {
                let pigments = root
                    .get_mut("base")
                    .and_then(|b| b.get_mut("pigment"))
                    .ok_or_else(|| missing("[[base.pigment]]"))?;
                // A pigment is known by its `name`, or a library pigment given without one by
                // its `library` name (as the description names it, `description::read`).
                let is_it = |p: &dyn TableLike| {
                    p.get("name")
                        .or_else(|| p.get("library"))
                        .and_then(Item::as_str)
                        == Some(name.as_str())
                };
                let found = match pigments {
                    Item::ArrayOfTables(tables) => tables
                        .iter_mut()
                        .find(|p| is_it(*p))
                        .map(|p| set(p, "concentration", value)),
                    Item::Value(Value::Array(array)) => array
                        .iter_mut()
                        .filter_map(Value::as_inline_table_mut)
                        .find(|p| is_it(*p))
                        .map(|p| set(p, "concentration", value)),
                    _ => None,
                };
                found.flatten().ok_or_else(|| {
                    missing(&format!("pigment named '{name}' with a concentration"))
                })?;
            }
        }
    }
    Ok(doc.to_string())
}

/// `text` (a coating description) with a `[[base.pigment]]` of gonio's library added for each
/// of `names` (`library = "NAME"`, `concentration = 0`, to be set by [`with_values`]), after
/// the base's own pigments, in the same form they are written in (tables or an inline array).
/// Errors: no `[base]` table.
pub fn with_library_pigments(text: &str, names: &[String]) -> Result<String> {
    let mut doc: DocumentMut = text
        .parse()
        .map_err(|e| FormulationError::Invalid(format!("not TOML: {e}")))?;
    let base = doc
        .get_mut("base")
        .and_then(Item::as_table_like_mut)
        .ok_or_else(|| {
            FormulationError::Invalid(
                "the description has no [base] table to add pigments to".into(),
            )
        })?;
    let pigments = base
        .entry("pigment")
        .or_insert_with(|| Item::ArrayOfTables(toml_edit::ArrayOfTables::new()));
    for name in names {
        match pigments {
            Item::ArrayOfTables(tables) => {
                let mut t = toml_edit::Table::new();
                t.insert("library", toml_edit::value(name.as_str()));
                t.insert("concentration", toml_edit::value(0.0));
                tables.push(t);
            }
            Item::Value(Value::Array(array)) => {
                let mut t = InlineTable::new();
                t.insert("library", name.as_str().into());
                t.insert("concentration", 0.0.into());
                array.push(t);
            }
            _ => {
                return Err(FormulationError::Invalid(
                    "base.pigment is neither [[base.pigment]] tables nor an array of them".into(),
                ));
            }
        }
    }
    Ok(doc.to_string())
}

/// Set the number `key` of `table` to `value`, keeping the comments around the old value;
/// `None` when the key is missing.
fn set(table: &mut dyn TableLike, key: &str, value: f64) -> Option<()> {
    table.get(key)?;
    replace(table, key, Value::from(value));
    Some(())
}

/// Put `new` at `key`, with the old value's comments and spacing if there was one.
fn replace(table: &mut dyn TableLike, key: &str, mut new: Value) {
    if let Some(old) = table.get(key).and_then(Item::as_value) {
        *new.decor_mut() = old.decor().clone();
    }
    table.insert(key, Item::Value(new));
}

#[cfg(test)]
mod tests {
    use super::*;

    const SILVER: &str = "# A silver metallic\n\n[top]\nroughness = { distribution = \"ggx\", alpha = 0.03 }   # a glossy clear coat\n\n[coat]\nindex = 1.5\nthickness_um = 40   # µm\n\n[flakes]\nkind = \"aluminium\"\ncoverage = 0.6   # of the base\ntilt_deg = 12\n\n[base]\nkind = \"diffuse\"\nreflectance = 0.25\n";

    fn varied(s: &str) -> Vec<Varied> {
        Varied::parse_list(s).unwrap()
    }

    /// The values are replaced, the comments kept, and the text reads back to the coating the
    /// constituents give.
    #[test]
    fn values_are_replaced_and_comments_kept() {
        let v = varied("tilt=4:20,coverage=0.1:0.9,roughness=0.01:0.1,thickness=10:60");
        let text = with_values(SILVER, &v, &[8.25, 0.4125, 0.045, 35.5]).unwrap();
        for comment in [
            "# A silver metallic",
            "# a glossy clear coat",
            "# µm",
            "# of the base",
        ] {
            assert!(text.contains(comment), "{comment} lost:\n{text}");
        }
        assert!(text.contains("coverage = 0.4125   # of the base"), "{text}");
        let wl = [450.0, 550.0, 650.0];
        let got = gonio_coating::description::parse(&text, &wl).unwrap();
        let mut want = gonio_coating::description::parse(SILVER, &wl).unwrap();
        for (v, x) in v.iter().zip([8.25, 0.4125, 0.045, 35.5]) {
            want = v.constituent.apply(&want, x).unwrap();
        }
        assert_eq!(got, want);
    }

    /// A roughness given as Sq and correlation length becomes α; 0 removes the top; a smooth
    /// coating gains a Beckmann top; a pigment's concentration is found by its name.
    #[test]
    fn roughness_and_concentration_forms() {
        let wl = [450.0, 550.0, 650.0];
        let rough = "[top]\nroughness = { sq_um = 0.1, correlation_um = 4 }\n[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 20\nsubstrate = 0.6\n\n[[base.pigment]]\nname = \"red\"\nconcentration = 1.0 # full\nk_per_um = 1\ns_per_um = 0.5\n\n[[base.pigment]]\nname = \"white\"\nconcentration = 0.05\nk_per_um = 0.0005\ns_per_um = 2.0\n";
        for (s, x) in [
            ("roughness=0:0.1", 0.07),
            ("roughness=0:0.1", 0.0),
            ("concentration:white=0:1", 0.25),
            ("base_thickness=5:60", 12.5),
        ] {
            let v = varied(s);
            let text = with_values(rough, &v, &[x]).unwrap();
            let got = gonio_coating::description::parse(&text, &wl).unwrap();
            let start = gonio_coating::description::parse(rough, &wl).unwrap();
            assert_eq!(
                got,
                v[0].constituent.apply(&start, x).unwrap(),
                "{s} {x}:\n{text}"
            );
            assert!(text.contains("# full"));
        }
        let smooth = "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n";
        let v = varied("roughness=0:0.1");
        let text = with_values(smooth, &v, &[0.05]).unwrap();
        let start = gonio_coating::description::parse(smooth, &wl).unwrap();
        assert_eq!(
            gonio_coating::description::parse(&text, &wl).unwrap(),
            v[0].constituent.apply(&start, 0.05).unwrap()
        );
        let e = with_values(smooth, &varied("tilt=1:2"), &[1.5]).unwrap_err();
        assert!(e.to_string().contains("no [flakes] table"), "{e}");
        let e = with_values(rough, &varied("concentration:blue=0:1"), &[0.5]).unwrap_err();
        assert!(e.to_string().contains("'blue'"), "{e}");
        // A library pigment without a name is known by its library name.
        let library = "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 30\nsubstrate = 0.6\n\n[[base.pigment]]\nlibrary = \"titanium_white\"\nconcentration = 1.0\n\n[[base.pigment]]\nlibrary = \"phthalo_blue_green_shade\"\nconcentration = 0.1 # toner\n";
        let v = varied("concentration:phthalo_blue_green_shade=0.01:0.5");
        let text = with_values(library, &v, &[0.2]).unwrap();
        let start = gonio_coating::description::parse(library, &wl).unwrap();
        assert_eq!(
            gonio_coating::description::parse(&text, &wl).unwrap(),
            v[0].constituent.apply(&start, 0.2).unwrap(),
            "{text}"
        );
        assert!(text.contains("# toner"));
    }
}
