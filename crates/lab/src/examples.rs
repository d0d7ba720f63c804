//! The coating descriptions a designer starts from: the repository's `examples/coatings/*.toml`,
//! embedded in the program (the lab opens them by name from this fixed list, never from a path a
//! request gives), and the Kubelka-Munk pigments they hold, offered for any formulation.

use serde_json::{Value, json};

/// Each example's name (its file's stem) and text.
pub const EXAMPLES: [(&str, &str); 16] = [
    (
        "silver_metallic",
        include_str!("../../../examples/coatings/silver_metallic.toml"),
    ),
    (
        "silver_coarse",
        include_str!("../../../examples/coatings/silver_coarse.toml"),
    ),
    (
        "pearl_interference",
        include_str!("../../../examples/coatings/pearl_interference.toml"),
    ),
    (
        "red_solid",
        include_str!("../../../examples/coatings/red_solid.toml"),
    ),
    (
        "red_rough",
        include_str!("../../../examples/coatings/red_rough.toml"),
    ),
    (
        "red_pigmented",
        include_str!("../../../examples/coatings/red_pigmented.toml"),
    ),
    (
        "solid_three_pigments",
        include_str!("../../../examples/coatings/solid_three_pigments.toml"),
    ),
    (
        "cayman_start",
        include_str!("../../../examples/coatings/cayman_start.toml"),
    ),
    (
        "blue_metallic_embedded",
        include_str!("../../../examples/coatings/blue_metallic_embedded.toml"),
    ),
    (
        "cayman_tinted_start",
        include_str!("../../../examples/coatings/cayman_tinted_start.toml"),
    ),
    (
        "krylon_blue_start",
        include_str!("../../../examples/coatings/krylon_blue_start.toml"),
    ),
    (
        "krylon_blue_fitted",
        include_str!("../../../examples/coatings/krylon_blue_fitted.toml"),
    ),
    (
        "cayman_library_start",
        include_str!("../../../examples/coatings/cayman_library_start.toml"),
    ),
    (
        "cayman_library_fitted",
        include_str!("../../../examples/coatings/cayman_library_fitted.toml"),
    ),
    (
        "garnet_red_start",
        include_str!("../../../examples/coatings/garnet_red_start.toml"),
    ),
    (
        "garnet_red_fitted",
        include_str!("../../../examples/coatings/garnet_red_fitted.toml"),
    ),
];

/// The text of the example `name`.
pub fn text(name: &str) -> Option<&'static str> {
    EXAMPLES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The example's title: the first line of its opening comment.
fn title(text: &str) -> String {
    text.lines()
        .next()
        .and_then(|l| l.strip_prefix('#'))
        .map(|l| l.trim().trim_end_matches(':').to_string())
        .unwrap_or_default()
}

/// The list the page offers: `[{name, title}]`.
pub fn list() -> Value {
    Value::Array(
        EXAMPLES
            .iter()
            .map(|(name, text)| json!({ "name": name, "title": title(text) }))
            .collect(),
    )
}

/// Every Kubelka-Munk pigment of the examples (`[[base.pigment]]`), once per name:
/// `[{name, example, pigment}]`, then every pigment of gonio's library
/// (`gonio_coating::pigment_library`): `[{name, library: true, colour_index, pigment}]`;
/// `pigment` is the table as a formulation holds it (a library pigment's
/// `{"library": NAME, "concentration": LIBRARY_START_CONCENTRATION}`).
pub fn pigments() -> Value {
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for (name, text) in EXAMPLES {
        let Ok(description) = toml::from_str::<Value>(text) else {
            continue;
        };
        let Some(list) = description
            .pointer("/base/pigment")
            .and_then(Value::as_array)
        else {
            continue;
        };
        for p in list {
            let Some(pigment) = p.get("name").and_then(Value::as_str) else {
                continue;
            };
            if seen.insert(pigment.to_string()) {
                out.push(json!({ "name": pigment, "example": name, "pigment": p }));
            }
        }
    }
    for p in gonio_coating::pigment_library::pigments() {
        out.push(json!({
            "name": p.name, "library": true, "colour_index": p.colour_index,
            "pigment": {
                "library": p.name,
                "concentration": crate::formulation::LIBRARY_START_CONCENTRATION,
            },
        }));
    }
    Value::Array(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every example file in the repository is in the list, and every listed one reads as a
    /// coating; their pigments are offered.
    #[test]
    fn every_example_is_listed_and_reads() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/coatings");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| {
                let p = e.unwrap().path();
                (p.extension()? == "toml").then(|| p.file_stem().unwrap().to_string_lossy().into())
            })
            .collect();
        on_disk.sort();
        let mut listed: Vec<String> = EXAMPLES.iter().map(|(n, _)| n.to_string()).collect();
        listed.sort();
        assert_eq!(on_disk, listed);
        for (name, text) in EXAMPLES {
            gonio_coating::description::parse(text, &gonio_coating::system::default_bands())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!title(text).is_empty(), "{name}");
        }
        let names: Vec<String> = pigments()
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["name"].as_str().unwrap().to_string())
            .collect();
        assert!(names.len() >= 3, "{names:?}");
    }
}
