//! The booth's display renderings: sRGB and Display P3 through Little CMS against
//! colour-science, the ICC profile embedded in the PNG, and the mask of out-of-gamut and
//! over-range pixels.

use crate::oracle;
use gonio_color::Observer;
use gonio_render::picture::{
    DisplayPicture, DisplaySpace, MASK_BOTH, MASK_OUT_OF_GAMUT, MASK_OVER_RANGE, XyzPicture,
};
use image::ImageDecoder;
use lcms2::{Profile, Tag, TagSignature};
use rand::{RngExt, SeedableRng};

/// XYZ of chromaticity (x, y) at luminance `y_lum`.
fn from_xy(x: f64, y: f64, y_lum: f64) -> [f64; 3] {
    [x / y * y_lum, y_lum, (1.0 - x - y) / y * y_lum]
}

/// The perfect diffuser in a booth of 2000 lx under D65 (E/π = 636.6 cd/m²) and under
/// illuminant A (CIE 15:2004 table T.3 chromaticities, 2°).
fn whites() -> [[f64; 3]; 2] {
    let lum = 2000.0 / std::f64::consts::PI;
    [from_xy(0.3127, 0.3290, lum), from_xy(0.44757, 0.40745, lum)]
}

fn to_f32(v: &[[f64; 3]]) -> Vec<[f32; 3]> {
    v.iter().map(|p| p.map(|c| c as f32)).collect()
}

/// colour-science's `XYZ_to_RGB` (the booth's white adapted to the display's by Bradford),
/// linear and encoded, against gonio's Little CMS rendering of the same XYZ: 300 colours, from
/// dark to above the white, many outside either gamut, under a D65 and an A booth.
///
/// The bound is one 8-bit step (1/255): gonio's value is rounded to the nearest step (half a
/// step), and the rest is the two implementations' arithmetic — the ICC profile's colorants in
/// s15Fixed16 (2⁻¹⁷ each, up to about 7e-5 in a linear value, which the curve's slope of 12.92
/// near black makes 0.2 of a step) and Little CMS's rounding through 16 bits on its way to 8.
/// Measured: at most 0.64 of a step. Where colour-science's linear value is clearly (by 1e-3)
/// inside or outside [0, 1], the flags must agree with it.
#[test]
fn display_values_agree_with_colour_science() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(44);
    // One run of the oracle for both booths (colour-science takes seconds to import).
    let cases: Vec<([f64; 3], Vec<[f32; 3]>)> = whites()
        .into_iter()
        .map(|white| {
            let xyz: Vec<[f64; 3]> = (0..300)
                .map(|_| {
                    let (x, y): (f64, f64) =
                        (rng.random_range(0.1..0.6), rng.random_range(0.1..0.6));
                    let x = x.min(0.95 - y);
                    from_xy(x, y, white[1] * rng.random_range(0.0..1.2))
                })
                .collect();
            (white, to_f32(&xyz))
        })
        .collect();
    let script = r#"
import json, sys, numpy as np, colour
results = []
for case in json.load(sys.stdin):
    w = np.array(case["white"]); xyz = np.array(case["xyz"]) / w[1]
    xy = colour.XYZ_to_xy(w)
    out = {}
    for name in ["sRGB", "Display P3"]:
        lin = colour.XYZ_to_RGB(xyz, name, illuminant=xy, chromatic_adaptation_transform="Bradford")
        enc = colour.RGB_COLOURSPACES[name].cctf_encoding(np.clip(lin, 0, 1))
        out[name] = {"linear": lin.tolist(), "encoded": enc.tolist()}
    results.append(out)
print(json.dumps(results))
"#;
    let input: Vec<serde_json::Value> = cases
        .iter()
        .map(|(white, xyz)| {
            serde_json::json!({
                "white": white,
                "xyz": xyz.iter().map(|p| p.map(f64::from)).collect::<Vec<_>>(),
            })
        })
        .collect();
    let Some(results) = oracle::run::<Vec<serde_json::Value>>(
        script,
        "colour",
        "colour-science",
        &serde_json::Value::Array(input),
    ) else {
        return;
    };
    for ((white, xyz32), out) in cases.iter().zip(&results) {
        let white = *white;
        let xyz: Vec<[f64; 3]> = xyz32.iter().map(|p| p.map(f64::from)).collect();
        let picture = XyzPicture::new(30, 10, xyz32, Observer::Cie1931TwoDegree).unwrap();
        for (space, name) in [
            (DisplaySpace::Srgb, "sRGB"),
            (DisplaySpace::DisplayP3, "Display P3"),
        ] {
            let shown = DisplayPicture::new(&picture, white, space).unwrap();
            let enc: Vec<[f64; 3]> = serde_json::from_value(out[name]["encoded"].clone()).unwrap();
            let lin: Vec<[f64; 3]> = serde_json::from_value(out[name]["linear"].clone()).unwrap();
            let mut worst = 0.0f64;
            let mut checked_flags = 0;
            for i in 0..xyz.len() {
                for k in 0..3 {
                    let d = (f64::from(shown.rgb()[i][k]) / 255.0 - enc[i][k]).abs();
                    worst = worst.max(d);
                    assert!(
                        d <= 1.0 / 255.0,
                        "{name}, white {white:?}, XYZ {:?}: gonio {:?}, colour-science {:?}",
                        xyz[i],
                        shown.rgb()[i],
                        enc[i].map(|v| v * 255.0)
                    );
                }
                let y = xyz[i][1] / white[1];
                let clear = (y - 1.0).abs() > 1e-3
                    && lin[i]
                        .iter()
                        .all(|c| c.abs() > 1e-3 && (c - 1.0).abs() > 1e-3);
                if clear {
                    checked_flags += 1;
                    let over = y > 1.0;
                    let out_of_gamut = lin[i].iter().any(|&c| c < 0.0)
                        || (!over && lin[i].iter().any(|&c| c > 1.0));
                    assert_eq!(
                        shown.flagged(i),
                        (out_of_gamut, over),
                        "{name}, XYZ {:?}, colour-science's linear RGB {:?}",
                        xyz[i],
                        lin[i]
                    );
                }
            }
            assert!(checked_flags > 250, "{checked_flags}");
            eprintln!(
                "{name}, white {white:?}: largest difference from colour-science {:.3} of an 8-bit step",
                worst * 255.0
            );
        }
    }
}

/// The PNG carries the display's ICC profile: Little CMS parses it back, its creation date is
/// the fixed one, its primaries are the display's, gonio's sRGB is Little CMS's built-in sRGB, and the pixels are the rendering's.
#[test]
fn png_embeds_the_display_profile() {
    let dir = tempfile::tempdir().unwrap();
    let white = whites()[0];
    let xyz = to_f32(&[
        white,
        [0.0; 3],
        from_xy(0.3, 0.5, 200.0),
        from_xy(0.5, 0.3, 100.0),
    ]);
    let picture = XyzPicture::new(2, 2, &xyz, Observer::Cie1931TwoDegree).unwrap();
    for space in DisplaySpace::ALL {
        let shown = DisplayPicture::new(&picture, white, space).unwrap();
        let path = dir.path().join(format!("{}.png", space.file_stem()));
        shown.write_png(&path).unwrap();
        let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
        let mut decoder = image::codecs::png::PngDecoder::new(file).unwrap();
        let icc = decoder.icc_profile().unwrap().expect("no iCCP chunk");
        // The header's creation date is the fixed one, not the clock's, so that the PNG's
        // bytes do not depend on when it was written.
        let created: Vec<u16> = icc[24..36]
            .chunks(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect();
        assert_eq!(created, gonio_render::picture::ICC_CREATED, "{space:?}");
        let profile = Profile::new_icc(&icc).unwrap();
        let Tag::CIExyYTRIPLE(chrm) = profile.read_tag(TagSignature::ChromaticityTag) else {
            panic!("{space:?}: no chromaticity tag")
        };
        // u16Fixed16 numbers: within 2⁻¹⁷ of the written primaries.
        for (got, want) in [chrm.Red, chrm.Green, chrm.Blue]
            .iter()
            .zip(space.primaries())
        {
            assert!(
                (got.x - want[0]).abs() < 1e-5 && (got.y - want[1]).abs() < 1e-5,
                "{space:?}: {got:?} against {want:?}"
            );
        }
        assert_eq!(
            profile
                .info(lcms2::InfoType::Description, lcms2::Locale::none())
                .as_deref(),
            Some(space.description())
        );
        if space == DisplaySpace::Srgb {
            let builtin = Profile::new_srgb();
            for tag in [
                TagSignature::RedColorantTag,
                TagSignature::GreenColorantTag,
                TagSignature::BlueColorantTag,
            ] {
                let (Tag::CIEXYZ(a), Tag::CIEXYZ(b)) =
                    (profile.read_tag(tag), builtin.read_tag(tag))
                else {
                    panic!("{tag:?} missing")
                };
                // Ours is read back from its s15Fixed16 numbers (within 2⁻¹⁷ of the exact).
                let tol = 2f64.powi(-17);
                assert!(
                    (a.X - b.X).abs() < tol && (a.Y - b.Y).abs() < tol && (a.Z - b.Z).abs() < tol,
                    "{tag:?}: {a:?} against Little CMS's sRGB {b:?}"
                );
            }
        }
        let mut pixels = vec![0u8; decoder.total_bytes() as usize];
        decoder.read_image(&mut pixels).unwrap();
        assert_eq!(pixels, shown.rgb().as_flattened());
        // The booth's white is the display's white, black its black.
        assert_eq!((shown.rgb()[0], shown.rgb()[1]), ([255; 3], [0; 3]));
    }
}

/// A pixel's flags: (out of gamut, over range).
type Flags = (bool, bool);

/// Spectral colours lie outside every display's gamut and are flagged; the white, greys and
/// the display's own primaries are not; the P3 green is outside sRGB only; light above the
/// white is over range, in its own mask colour.
#[test]
fn mask_flags_spectral_colours_and_highlights() {
    let dir = tempfile::tempdir().unwrap();
    let white = whites()[0];
    let yw = white[1];
    let cmfs = Observer::Cie1931TwoDegree.cmfs();
    let spectral = |nm: f64, y_rel: f64| {
        let [x, y, z] = cmfs.at(nm);
        [x, y, z].map(|c| c / y * y_rel * yw)
    };
    // Luminance weights of the primaries: Y of R = G = B = 1 split by primary (sRGB: IEC
    // 61966-2-1; Display P3: from its primaries and D65).
    let cases: [([f64; 3], [Flags; 2]); 11] = [
        (white, [(false, false); 2]),
        (white.map(|c| 0.18 * c), [(false, false); 2]),
        ([0.0; 3], [(false, false); 2]),
        (from_xy(0.64, 0.33, 0.5 * 0.2126 * yw), [(false, false); 2]),
        (from_xy(0.15, 0.06, 0.5 * 0.0722 * yw), [(false, false); 2]),
        (
            from_xy(0.265, 0.690, 0.5 * 0.6917 * yw),
            [(true, false), (false, false)],
        ),
        (spectral(450.0, 0.05), [(true, false); 2]),
        (spectral(520.0, 0.3), [(true, false); 2]),
        (spectral(600.0, 0.3), [(true, false); 2]),
        (white.map(|c| 1.5 * c), [(false, true); 2]),
        (spectral(520.0, 1.5), [(true, true); 2]),
    ];
    let xyz = to_f32(&cases.map(|c| c.0));
    let picture = XyzPicture::new(11, 1, &xyz, Observer::Cie1931TwoDegree).unwrap();
    for (s, space) in DisplaySpace::ALL.into_iter().enumerate() {
        let shown = DisplayPicture::new(&picture, white, space).unwrap();
        for (i, (v, expected)) in cases.iter().enumerate() {
            assert_eq!(
                shown.flagged(i),
                expected[s],
                "{space:?}, case {i}: XYZ {v:?}"
            );
        }
        let n = cases.len() as f64;
        let oog = cases.iter().filter(|c| c.1[s].0).count() as f64;
        assert_eq!(shown.out_of_gamut_fraction(), oog / n);
        assert_eq!(shown.over_range_fraction(), 2.0 / n);
        let path = dir.path().join("mask.png");
        shown.write_mask(&path).unwrap();
        let mask = image::open(&path).unwrap().to_rgb8();
        for (i, (_, expected)) in cases.iter().enumerate() {
            let got = mask.get_pixel(i as u32, 0).0;
            match expected[s] {
                (true, false) => assert_eq!(got, MASK_OUT_OF_GAMUT, "{space:?}, case {i}"),
                (false, true) => assert_eq!(got, MASK_OVER_RANGE, "{space:?}, case {i}"),
                (true, true) => assert_eq!(got, MASK_BOTH, "{space:?}, case {i}"),
                (false, false) => assert!(got[0] == got[1] && got[1] == got[2] && got[0] < 64),
            }
        }
    }
}

#[test]
fn a_white_that_is_not_a_colour_is_refused() {
    let xyz = [[1.0f32; 3]];
    let picture = XyzPicture::new(1, 1, &xyz, Observer::Cie1931TwoDegree).unwrap();
    for white in [[0.0, 0.0, 0.0], [1.0, f64::NAN, 1.0], [-1.0, 1.0, 1.0]] {
        let err = DisplayPicture::new(&picture, white, DisplaySpace::Srgb).unwrap_err();
        assert!(err.to_string().contains("booth's white"), "{err}");
    }
}
