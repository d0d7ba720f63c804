//! The coating study: a smooth coat's gloss is Fresnel's ratio, constituents are checked, roughness
//! lowers gloss.

use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_coating::description;
use gonio_coating::system::Coating;
use gonio_instrument::coating_study::*;
use gonio_instrument::gloss::{self};
use gonio_instrument::multiangle::{self};

fn red(index: &str, top: &str) -> Coating {
    let text = format!(
        "{top}\n[coat]\nindex = {index}\nthickness_um = 40\n[base]\nkind = \"diffuse\"\n\
         reflectance = {{ nm = [400, 550, 600, 700], values = [0.05, 0.05, 0.3, 0.7] }}\n"
    );
    description::parse(&text, &[400.0, 555.0, 700.0]).unwrap()
}

/// A smooth coat's gloss is the ratio of its Fresnel reflectance to the black-glass
/// standard's (ISO 2813) plus the body light inside the receptor (a body BRDF of a few
/// hundredths per steradian over a receptor of 2e-3 sr at 20°: under 0.5 GU).
#[test]
fn smooth_coat_gloss_is_fresnels_ratio() {
    let g = gloss::measure(&CoatingSpecimen::new(&red("1.5", ""), 555.0, 16).unwrap()).unwrap();
    for (gu, deg) in [(g.gu20, 20f64), (g.gu60, 60.0), (g.gu85, 85.0)] {
        let c = deg.to_radians().cos();
        let want = 100.0 * dielectric(c, 1.5) / dielectric(c, gloss::STANDARD_INDEX);
        assert!((gu - want).abs() < 0.5, "{deg}°: {gu} vs {want}");
    }
    assert!(g.doi > 99.0, "{}", g.doi);
}

#[test]
fn constituents_are_checked() {
    let coating = red("1.5", "");
    assert!(Constituent::parse("gloss").is_err());
    assert!(Constituent::FlakeTilt.apply(&coating, 10.0).is_err());
    assert!(Constituent::Tio2.apply(&coating, 100.0).is_err());
    let c = Constituent::parse("concentration:red").unwrap();
    assert!(c.apply(&coating, 0.5).is_err());
    let rough = Constituent::Roughness.apply(&coating, 0.1).unwrap();
    assert_eq!(rough.roughness, Some(Microfacet::beckmann(0.1)));
    assert_eq!(
        Constituent::Roughness.apply(&rough, 0.0).unwrap().roughness,
        None
    );
    assert_eq!(Constituent::epoxy_series().len(), 6);
}

/// `run` reads each variant as `read_coating` does with seed 0, bit for bit; the same seed
/// repeats a reading made of walks exactly (common random numbers) and another seed gives an
/// independent one (here 1 000 walks per geometry over a rough top: the readings differ).
#[test]
fn read_coating_is_the_studys_reading_and_seeded() {
    let coating = red("1.5", "[top]\nroughness = { alpha = 0.1 }");
    let wl = [400.0, 550.0, 700.0];
    let g = &multiangle::E2194;
    let rows = run(&coating, &Constituent::Roughness, &[0.1], g, &wl, 1000, 4).unwrap();
    let zero = read_coating(&coating, g, &wl, 1000, 4, 0).unwrap();
    assert_eq!(rows[0].multiangle, zero.multiangle);
    assert_eq!(rows[0].gloss, zero.gloss);
    let one = read_coating(&coating, g, &wl, 1000, 4, 1).unwrap();
    assert_eq!(
        one.multiangle,
        read_coating(&coating, g, &wl, 1000, 4, 1)
            .unwrap()
            .multiangle
    );
    for (a, b) in one
        .multiangle
        .geometries
        .iter()
        .zip(&zero.multiangle.geometries)
    {
        assert_ne!(a.lab, b.lab, "{}", a.geometry);
    }
    assert_ne!(one.gloss.gu60, zero.gloss.gu60);
}

mod slow {
    use super::*;

    /// Roughening the coat lowers its gloss at every angle and raises the lightness near the
    /// specular direction (45as15), leaving the far geometries (45as110) alone.
    #[test]
    fn roughness_lowers_gloss() {
        let coating = red("1.5", "[top]\nroughness = { alpha = 0.02 }");
        let rows = run(
            &coating,
            &Constituent::Roughness,
            &[0.02, 0.06, 0.15],
            &multiangle::E2194,
            &[400.0, 500.0, 600.0, 700.0],
            2048,
            32,
        )
        .unwrap();
        for pair in rows.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            assert!(b.gloss.gu60 < a.gloss.gu60 && b.gloss.gu20 < a.gloss.gu20);
            assert!(b.multiangle.geometries[0].lab.l > a.multiangle.geometries[0].lab.l);
        }
        let far: Vec<f64> = rows
            .iter()
            .map(|r| r.multiangle.geometries[4].lab.l)
            .collect();
        assert!((far[0] - far[2]).abs() < 1.0, "{far:?}");
    }
}

/// `base_thickness` reads and sets the Kubelka-Munk basecoat's thickness, and is refused on a
/// diffuse base. Fails before the constituent existed (`parse` refused the name).
#[test]
fn base_thickness_is_the_basecoats() {
    let text = "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"kubelka-munk\"\n\
                thickness_um = 15\nsubstrate = 0.3\n[[base.pigment]]\n\
                library = \"phthalo_blue_green_shade\"\nconcentration = 0.2\n";
    let coating = gonio_coating::description::parse(text, &[450.0, 550.0]).unwrap();
    let c = Constituent::parse("base_thickness").unwrap();
    assert_eq!(c.value(&coating).unwrap(), 15.0);
    let thicker = c.apply(&coating, 25.0).unwrap();
    assert_eq!(c.value(&thicker).unwrap(), 25.0);
    assert_eq!(thicker.coat, coating.coat);
    assert!(c.apply(&red("1.5", ""), 10.0).is_err());
}
