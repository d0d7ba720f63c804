//! `gonio render --spectral` end to end: the flag selects the spectral colour mode (reported in
//! the JSON), a grey furnace renders white in both modes, and both modes write the picture.

use crate::common::ok;

/// The white furnace of `examples/furnace.toml` (shared with the renderer's tests): a white
/// Lambertian sphere in a uniform sky of radiance 1, every pixel 1 in either mode.
const FURNACE: &str = include_str!("../../../../examples/furnace.toml");

#[test]
fn spectral_flag_selects_the_spectral_mode() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("furnace.toml");
    std::fs::write(&scene, FURNACE).unwrap();
    for (flag, mode) in [(None, "tristimulus"), (Some("--spectral"), "spectral")] {
        let out = dir.path().join(format!("{mode}.hdr"));
        let mut args = vec![
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--spp",
            "16",
            "--json",
        ];
        args.extend(flag);
        let stdout = ok(&args).stdout;
        let json: serde_json::Value = serde_json::from_slice(&stdout).unwrap();
        assert_eq!(json["colour_mode"], mode);
        let img = gonio_render::Image::read(&out).unwrap();
        let mean = img.luminance_mean();
        // RGBE rounds to 8 bits of mantissa; the spectral mode adds wavelength noise.
        assert!((mean - 1.0).abs() < 0.02, "{mode}: mean {mean}");
    }
}

/// `--denoise` and `--no-denoise` override the scene's `[render] denoise`, and the JSON says
/// which was done; a denoised furnace stays the furnace (the filter averages, with normalised
/// weights, pixels that all estimate 1).
#[test]
fn denoise_flags_override_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("furnace.toml");
    std::fs::write(&scene, format!("{FURNACE}\n[render]\ndenoise = true\n")).unwrap();
    for (flag, denoised) in [
        (None, true),
        (Some("--no-denoise"), false),
        (Some("--denoise"), true),
    ] {
        let out = dir.path().join("furnace.exr");
        let mut args = vec![
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--spp",
            "4",
            "--json",
        ];
        args.extend(flag);
        let json: serde_json::Value = serde_json::from_slice(&ok(&args).stdout).unwrap();
        assert_eq!(json["denoised"], denoised, "{flag:?}");
        let mean = gonio_render::Image::read(&out).unwrap().luminance_mean();
        // Each pixel's four samples estimate 1 with MIS noise of a few percent; the mean of
        // 1 600 pixels is within 0.2% of 1 and the filter only averages them.
        assert!((mean - 1.0).abs() < 0.01, "{flag:?}: mean {mean}");
    }
}
