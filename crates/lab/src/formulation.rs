//! A formulation as the page holds it: the coating description's TOML tables as a JSON object
//! (`{"top": {"roughness": {...}}, "coat": {...}, "flakes": {...}, "base": {...}}`, the fields
//! of docs/coatings.md), so that the page, a script and `gonio coating` share one model and every
//! check is the coating library's own. A formulation becomes TOML text (what the page downloads,
//! and `gonio coating` reads unchanged) and the TOML text a [`Coating`].
//!
//! The only file a formulation may name is a topography uploaded to this lab
//! (`top.roughness.map`), by the id the upload returned: never a path on the server.

use crate::error::ApiError;
use gonio_coating::system::{Coating, default_bands};
use serde_json::Value;
use std::path::Path;

/// The TOML text of `formulation` (a JSON object of the description's tables). Nulls are
/// dropped (a field left empty in the form is a field left out).
pub fn to_toml(formulation: &Value) -> Result<String, ApiError> {
    let Value::Object(_) = formulation else {
        return Err(ApiError::BadRequest(
            "the formulation must be a JSON object of the description's tables (top, coat, \
             flakes, base)"
                .into(),
        ));
    };
    toml::to_string(&without_nulls(formulation)).map_err(|e| {
        ApiError::BadRequest(format!("the formulation cannot be written as TOML: {e}"))
    })
}

/// The formulation (JSON) of a description's TOML text.
pub fn from_toml(text: &str) -> Result<Value, ApiError> {
    toml::from_str::<Value>(text).map_err(|e| ApiError::BadRequest(format!("TOML: {e}")))
}

/// `value` with every null (in objects and arrays) removed.
fn without_nulls(value: &Value) -> Value {
    match value {
        Value::Object(map) => Value::Object(
            map.iter()
                .filter(|(_, v)| !v.is_null())
                .map(|(k, v)| (k.clone(), without_nulls(v)))
                .collect(),
        ),
        Value::Array(items) => Value::Array(
            items
                .iter()
                .filter(|v| !v.is_null())
                .map(without_nulls)
                .collect(),
        ),
        other => other.clone(),
    }
}

/// The topography a formulation names (`top.roughness.map`), if any.
pub fn map_name(formulation: &Value) -> Option<&str> {
    formulation.pointer("/top/roughness/map")?.as_str()
}

/// The coating of `formulation`, checked by the coating library at gonio's bands; a named
/// topography is read from `uploads` (the caller has checked that the name is an upload's id).
pub fn coating(formulation: &Value, uploads: &Path) -> Result<(Coating, String), ApiError> {
    let text = to_toml(formulation)?;
    let coating = gonio_coating::description::parse_in(&text, uploads, &default_bands())
        .map_err(|e| ApiError::BadRequest(e.to_string()))?;
    coating
        .check(&default_bands())
        .map_err(|e| ApiError::BadRequest(e.to_string()))?;
    Ok((coating, text))
}

/// The concentration a library pigment new to a formulation starts at: a tenth of the paint as
/// it comes (the masstone is 1), so that `Varied::default_bounds` (a tenth to four times the
/// value) span 0.01–0.4, from a faint tint to a strong one.
pub const LIBRARY_START_CONCENTRATION: f64 = 0.1;

/// `formulation` with its base's pigments replaced by the library pigments `names`, each
/// `{"library": NAME, "concentration": c}` as a description names one (docs/coatings.md): a
/// pigment the formulation already has under that name (or library name) keeps its
/// concentration, another starts at [`LIBRARY_START_CONCENTRATION`]. The base must be a
/// Kubelka-Munk layer; an unknown name is refused with the library's message (the closest name).
pub fn with_library_pigments(formulation: &Value, names: &[String]) -> Result<Value, ApiError> {
    let bad = |m: String| ApiError::BadRequest(m);
    if names.is_empty() {
        return Err(bad("pigments from the library: name at least one".into()));
    }
    if formulation.pointer("/base/kind").and_then(Value::as_str) != Some("kubelka-munk") {
        return Err(bad(
            "library pigments go in a Kubelka-Munk base: set the base to pigments \
             (base.kind = \"kubelka-munk\") first"
                .into(),
        ));
    }
    let own = formulation
        .pointer("/base/pigment")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let mut pigments = Vec::new();
    for (i, name) in names.iter().enumerate() {
        if names[..i].contains(name) {
            return Err(bad(format!("pigment '{name}': named twice")));
        }
        gonio_coating::pigment_library::find(name).map_err(|e| bad(e.to_string()))?;
        let is_it = |p: &&Value| {
            [p.get("name"), p.get("library")]
                .iter()
                .any(|v| v.and_then(Value::as_str) == Some(name.as_str()))
        };
        let concentration = own
            .iter()
            .find(is_it)
            .and_then(|p| p.get("concentration"))
            .and_then(Value::as_f64)
            .unwrap_or(LIBRARY_START_CONCENTRATION);
        pigments.push(serde_json::json!({ "library": name, "concentration": concentration }));
    }
    let mut f = formulation.clone();
    f["base"]["pigment"] = Value::Array(pigments);
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every example's description survives TOML → JSON → TOML as the same coating (its JSON
    /// form equal after the round trip), and nulls are fields left out.
    #[test]
    fn examples_round_trip_through_json() {
        for (name, text) in crate::examples::EXAMPLES {
            let json = from_toml(text).unwrap();
            let back = to_toml(&json).unwrap();
            assert_eq!(from_toml(&back).unwrap(), json, "{name}");
        }
        let with_null = serde_json::json!({"coat": {"index": 1.5, "thickness_um": 40,
            "absorption_per_um": null}, "base": {"kind": "diffuse", "reflectance": 0.3}});
        assert!(!to_toml(&with_null).unwrap().contains("absorption"));
        assert!(to_toml(&serde_json::json!([1, 2])).is_err());
    }
}
