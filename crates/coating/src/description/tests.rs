//! Unit tests of the description reader: the forms of each field, the errors that name the
//! file and the field, and files beside the description.

use super::*;

const WL: [f64; 3] = [400.0, 550.0, 700.0];

/// A description with the coat's `index` field as given.
fn with_index(index: &str, folder: &Path, wl: &[f64]) -> Result<Coating> {
    parse_in(
        &format!(
            "[coat]\nindex = {index}\nthickness_um = 40\n[base]\nkind = \"diffuse\"\n\
             reflectance = 0.3\n"
        ),
        folder,
        wl,
    )
}

/// Sellmeier's formula with Schott's N-BK7 coefficients gives the catalogue's indices at
/// the Fraunhofer lines (nF 1.52238 at 486.13 nm, nd 1.51680 at 587.56 nm, nC 1.51432 at
/// 656.27 nm; the catalogue rounds to 1e-5, so the bound is one unit there); a measured index
/// inline or from a CSV file beside the description interpolates its samples; below a
/// term's resonance the check says why it refuses.
#[test]
fn sellmeier_and_measured_indices() {
    let bk7 = "{ sellmeier_b = [1.03961212, 0.231792344, 1.01046945], \
               sellmeier_c_um2 = [0.00600069867, 0.0200179144, 103.560653] }";
    let c = with_index(bk7, Path::new("."), &WL).unwrap();
    for (nm, n) in [(486.13, 1.52238), (587.56, 1.51680), (656.27, 1.51432)] {
        assert!(
            (c.coat.index.at(nm) - n).abs() < 1e-5,
            "{nm} nm: {}",
            c.coat.index.at(nm)
        );
    }
    let inline = with_index(
        "{ nm = [400, 700], values = [1.52, 1.49] }",
        Path::new("."),
        &WL,
    )
    .unwrap();
    assert!((inline.coat.index.at(550.0) - 1.505).abs() < 1e-12);
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("index.csv"),
        "wavelength_nm,value\n400,1.52\n700,1.49\n",
    )
    .unwrap();
    let file = with_index("{ file = \"index.csv\" }", dir.path(), &WL).unwrap();
    assert_eq!(file.coat.index, inline.coat.index);
    let missing = with_index("{ file = \"none.csv\" }", dir.path(), &WL).unwrap_err();
    assert!(missing.to_string().contains("none.csv"), "{missing}");
    let resonance = "{ sellmeier_b = [1.0, 0.0, 0.0], sellmeier_c_um2 = [0.2, 0.0, 0.0] }";
    let err = with_index(resonance, Path::new("."), &WL).unwrap_err();
    assert!(err.to_string().contains("no real index"), "{err}");
}

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
fn rough_top_and_flakes() {
    let base =
        "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n";
    let s = parse(
        &format!("[top]\nroughness = {{ distribution = \"ggx\", alpha = 0.05 }}\n{base}[flakes]\nkind = \"aluminium\"\ncoverage = 0.5\ntilt_deg = 12\n"),
        &WL,
    )
    .unwrap();
    assert_eq!(s.roughness, Some(Microfacet::ggx(0.05)));
    assert!(matches!(
        s.flakes,
        Some(Flakes {
            pigment: FlakePigment::Metal { .. },
            coverage: 0.5,
            ..
        })
    ));
    assert!(s.clear_coat().is_none());
    // Sq and correlation length: Beckmann of rms slope 2 Sq / T.
    let s = parse(
        &format!("[top]\nroughness = {{ sq_um = 0.1, correlation_um = 4 }}\n{base}[flakes]\nkind = \"interference\"\ncoverage = 0.4\ntilt_deg = 10\ntio2_nm = 120\n"),
        &WL,
    )
    .unwrap();
    assert_eq!(s.roughness, Some(Microfacet::beckmann(0.05)));
    assert!(matches!(
        s.flakes.unwrap().pigment,
        FlakePigment::Interference {
            tio2_nm: 120.0,
            mica_nm: 300.0,
            mica_index: 1.58
        }
    ));
    let bad = |text: String, needle: &str| {
        let e = parse(&text, &WL).unwrap_err().to_string();
        assert!(e.contains(needle), "{needle}: {e}");
    };
    bad(
        format!("[top]\nroughness = {{ alpha = 0.1, sq_um = 0.1 }}\n{base}"),
        "one of",
    );
    bad(
        format!("[top]\nroughness = {{ sq_um = 0.1 }}\n{base}"),
        "correlation_um",
    );
    bad(
        format!("[top]\nroughness = {{ alpha = 3 }}\n{base}"),
        "at most 1",
    );
    bad(
        format!("{base}[flakes]\nkind = \"aluminium\"\ncoverage = 2\ntilt_deg = 10\n"),
        "coverage",
    );
    bad(
        format!("[top]\nroughness = {{ map = \"missing.x3p\" }}\n{base}"),
        "top.roughness.map",
    );
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

/// The files a description names are its top's map and its coat's index table, beside it, as
/// `read` opens them (so that they need not exist to be listed); a description naming none
/// lists none, and an unreadable description is an error naming it.
#[test]
fn referenced_files_are_the_map_and_the_index_table() {
    let dir = tempfile::tempdir().unwrap();
    let both = dir.path().join("both.toml");
    std::fs::write(
        &both,
        "[top]\nroughness = { map = \"maps/peel.x3p\" }\n\
         [coat]\nindex = { file = \"index.csv\" }\nthickness_um = 40\n\
         [base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
    )
    .unwrap();
    assert_eq!(
        referenced_files(&both).unwrap(),
        vec![
            dir.path().join("maps/peel.x3p"),
            dir.path().join("index.csv")
        ]
    );
    let none = dir.path().join("none.toml");
    std::fs::write(
        &none,
        "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
    )
    .unwrap();
    assert!(referenced_files(&none).unwrap().is_empty());
    let err = referenced_files(&dir.path().join("absent.toml")).unwrap_err();
    assert!(err.to_string().contains("absent.toml"), "{err}");
}
