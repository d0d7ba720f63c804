//! Multi-channel instrument files and line profiles at the command line: `surface info` lists a
//! file's channels and reads the one `--channel` names (by name or index, after the subcommand
//! or before it), an unknown channel is an error listing the channels, a line profile gets its
//! ISO 21920-2 statistics, and commands that need an areal map refuse a profile (exit 2).

use crate::common::{gonio, ok};
use serde_json::Value;
use std::path::PathBuf;

fn fixture(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../surface/tests/data")
        .join(name)
        .display()
        .to_string()
}

fn info_json(args: &[&str]) -> Value {
    let out = ok(args);
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// di-3.di holds ZSensor, AmplitudeError, Phase and Height (SurfaceTopography reads ZSensor,
/// Sq 35.22 nm after levelling; tests/data/README.md).
#[test]
fn surface_info_lists_channels_and_reads_the_one_chosen() {
    let file = fixture("di-3.di");
    let default = info_json(&["surface", "info", &file, "--json"]);
    let names: Vec<&str> = default["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), 4, "{names:?}");
    assert_eq!(default["channel"], 0);
    let sq = default["sq_m"].as_f64().unwrap();
    assert!((sq / 35.22e-9 - 1.0).abs() < 0.001, "Sq {sq}");

    let by_index = info_json(&["surface", "info", &file, "--channel", "3", "--json"]);
    assert_eq!(by_index["channel"], 3);
    let by_name = info_json(&["--channel", "height", "surface", "info", &file, "--json"]);
    assert_eq!(by_name["channel"], 3);
    assert_eq!(by_index["sq_m"], by_name["sq_m"]);
    assert_ne!(by_index["sq_m"], default["sq_m"]);

    let text = String::from_utf8(ok(&["surface", "info", &file]).stdout).unwrap();
    assert!(
        text.contains("channels") && text.contains("ZSensor"),
        "{text}"
    );
}

#[test]
fn an_unknown_or_non_height_channel_is_an_error_listing_the_channels() {
    let file = fixture("di-3.di");
    for channel in ["Nope", "Phase", "9"] {
        let out = gonio(&["surface", "info", &file, "--channel", channel]);
        assert_eq!(out.status.code(), Some(2), "--channel {channel}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("ZSensor") && err.contains("di-3.di"), "{err}");
    }
}

/// opdx-3.opdx is a 3001-point stylus profile; SurfaceTopography gives Rq 2.826 nm after
/// removing the line (tests/data/README.md).
#[test]
fn a_profile_gets_profile_statistics_and_areal_commands_refuse_it() {
    let file = fixture("opdx-3.opdx");
    let info = info_json(&["surface", "info", &file, "--json"]);
    assert_eq!(info["profile"], true);
    assert_eq!(info["n"], 3001);
    let rq = info["rq_m"].as_f64().unwrap();
    assert!((rq / 2.8257e-9 - 1.0).abs() < 0.001, "Rq {rq}");
    let text = String::from_utf8(ok(&["surface", "info", &file]).stdout).unwrap();
    assert!(
        text.contains("Rq") && text.contains("ISO 21920-2"),
        "{text}"
    );
    for args in [
        vec!["gloss", file.as_str()],
        vec!["inplane", file.as_str(), "--json"],
        vec![
            "surface",
            "level",
            file.as_str(),
            "-o",
            "/tmp/never-written.x3p",
        ],
    ] {
        let out = gonio(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("line profile"), "{args:?}: {err}");
    }
}

/// `gonio render` reads the height maps its scene names: `--channel` is refused there (exit 2)
/// with the way to give a surface's channel in the scene.
#[test]
fn render_takes_channels_from_the_scene() {
    let out = gonio(&["--channel", "Height", "render", "scene.toml", "-o", "x.png"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("channel = "), "{err}");
}
