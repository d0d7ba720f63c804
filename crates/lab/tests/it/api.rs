//! Every endpoint answers as docs/lab.md says, and refuses bad input with the library's message.

use crate::server::{UPLOAD_LIMIT, client, data, example, json, post, start, text};
use serde_json::json;

/// The page and its assets are served; unknown paths are a JSON 404.
#[test]
fn page_assets_and_unknown_paths() {
    let (base, agent) = (start(), client());
    let (status, page) = text(agent.get(format!("{base}/")).call());
    assert_eq!(status, 200);
    assert!(page.contains("<title>gonio lab</title>") && page.contains("lab.js"));
    for asset in ["lab.js", "lab.css"] {
        let (status, body) = text(agent.get(format!("{base}/{asset}")).call());
        assert_eq!(status, 200, "{asset}");
        assert!(body.len() > 1000, "{asset}: {} bytes", body.len());
    }
    let (status, v) = json(agent.get(format!("{base}/api/nothing")).call());
    assert_eq!(status, 404);
    assert!(v["error"].as_str().unwrap().contains("docs/lab.md"), "{v}");
    let (status, v) = json(agent.get(format!("{base}/api/health")).call());
    assert_eq!((status, v["lab"].as_bool()), (200, Some(true)));
}

/// The examples are listed and each opens as a formulation; an unknown name (or a path) is a
/// 404 listing the examples; the pigments and lightings are offered.
#[test]
fn examples_pigments_and_lightings() {
    let (base, agent) = (start(), client());
    let (status, list) = json(agent.get(format!("{base}/api/examples")).call());
    assert_eq!(status, 200);
    let names: Vec<&str> = list
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"silver_metallic") && names.len() == 16,
        "{names:?}"
    );
    for name in &names {
        let f = example(&agent, &base, name);
        assert!(f["coat"]["thickness_um"].is_number(), "{name}: {f}");
    }
    for bad in ["nothing", "..%2F..%2FCargo.toml", "silver_metallic.toml"] {
        let (status, v) = json(agent.get(format!("{base}/api/examples/{bad}")).call());
        assert_eq!(status, 404, "{bad}: {v}");
        assert!(
            v["error"].as_str().unwrap().contains("silver_metallic"),
            "{v}"
        );
    }
    let (_, pigments) = json(agent.get(format!("{base}/api/pigments")).call());
    let names: Vec<&str> = pigments
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    for name in ["red", "white", "cyan", "light_skin"] {
        assert!(names.contains(&name), "{names:?}");
    }
    let (_, lightings) = json(agent.get(format!("{base}/api/lightings")).call());
    assert!(!lightings.as_array().unwrap().is_empty());
}

/// A formulation's TOML is what `gonio coating` reads: the same coating as the example it came
/// from (its info equal); a description's text becomes a formulation; bad TOML is a 400 with the
/// parser's line.
#[test]
fn formulations_and_toml() {
    let (base, agent) = (start(), client());
    let bands = gonio_coating::system::default_bands();
    for name in ["silver_metallic", "red_pigmented", "pearl_interference"] {
        let f = example(&agent, &base, name);
        let (status, toml) = text(post(
            &agent,
            &format!("{base}/api/formulation/to-toml"),
            &json!({ "formulation": f }),
        ));
        assert_eq!(status, 200, "{toml}");
        let ours = gonio_coating::description::parse(&toml, &bands).unwrap();
        let theirs = gonio_coating::description::read(
            &data(&format!("examples/coatings/{name}.toml")),
            &bands,
        )
        .unwrap();
        let summary = |c| {
            gonio_instrument::coating_summary::summarise(c, &bands, 16)
                .unwrap()
                .to_json()
        };
        assert_eq!(summary(&ours), summary(&theirs), "{name}");
        let (status, back) = json(
            agent
                .post(format!("{base}/api/formulation/from-toml"))
                .send(toml.clone()),
        );
        assert_eq!(status, 200, "{back}");
        assert_eq!(back["formulation"], f, "{name}");
    }
    let (status, v) = json(
        agent
            .post(format!("{base}/api/formulation/from-toml"))
            .send("[coat]\nindex = \n"),
    );
    assert_eq!(status, 400);
    assert!(v["error"].as_str().unwrap().contains("line 2"), "{v}");
    let (status, v) = json(
        agent
            .post(format!("{base}/api/formulation/from-toml"))
            .send("[coat]\nindex = 1.5\n"),
    );
    assert_eq!(status, 400);
    assert!(v["error"].as_str().unwrap().contains("thickness_um"), "{v}");
}

/// Values the coating library refuses are a 400 with its own message, from every endpoint that
/// takes a formulation; so are bad JSON, unknown fields and wrong types.
#[test]
fn invalid_formulations_and_requests_are_refused_with_the_librarys_message() {
    let (base, agent) = (start(), client());
    let mut f = example(&agent, &base, "silver_metallic");
    f["flakes"]["coverage"] = json!(1.5);
    let mut g = f.clone();
    g["flakes"]["coverage"] = json!(0.5);
    g["coat"]["index"] = json!(-1.0);
    let mut h = g.clone();
    h["coat"]["index"] = json!(1.5);
    h["coat"]["thickness_um"] = json!(-3.0);
    let bands = gonio_coating::system::default_bands();
    for (formulation, words) in [(&f, "coverage"), (&g, "index"), (&h, "thickness")] {
        let toml = toml::to_string(formulation).unwrap();
        let library = match gonio_coating::description::parse(&toml, &bands) {
            Err(e) => e.to_string(),
            Ok(c) => c.check(&bands).unwrap_err().to_string(),
        };
        assert!(library.contains(words), "{library}");
        for endpoint in ["readings", "picture", "formulation/to-toml", "export/gbrdf"] {
            let (status, v) = json(post(
                &agent,
                &format!("{base}/api/{endpoint}"),
                &json!({ "formulation": formulation }),
            ));
            assert_eq!(status, 400, "{endpoint}: {v}");
            assert_eq!(v["error"].as_str().unwrap(), library, "{endpoint}");
        }
    }
    for (body, words) in [
        ("{", "JSON"),
        ("[]", "JSON"),
        ("{\"formulation\": {}, \"colour\": 1}", "unknown field"),
        ("{\"formulation\": 3}", "JSON object"),
        (
            "{\"formulation\": {\"coat\": {\"index\": \"glass\"}}}",
            "index",
        ),
    ] {
        let (status, v) = json(
            agent
                .post(format!("{base}/api/readings"))
                .header("content-type", "application/json")
                .send(body),
        );
        assert_eq!(status, 400, "{body}: {v}");
        assert!(v["error"].as_str().unwrap().contains(words), "{body}: {v}");
    }
    let good = example(&agent, &base, "red_solid");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": good, "standard": "E9999" }),
    ));
    assert_eq!(status, 400, "{v}");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/picture"),
        &json!({ "formulation": good, "quality": "best" }),
    ));
    assert_eq!(status, 400, "{v}");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/export/obj"),
        &json!({ "formulation": good }),
    ));
    assert_eq!(status, 404, "{v}");
}

/// A topography upload is read by gonio's reader (its statistics are the library's), kept under
/// an id, and a formulation may name that id, and nothing else: not a path on the server, not an
/// id the lab did not give. A damaged file gets the reader's message naming the client's file; a
/// file past the limit a 413 saying the limit.
#[test]
fn topography_uploads() {
    let (base, agent) = (start(), client());
    let path = data("crates/surface/tests/data/matrix-3.txt");
    let bytes = std::fs::read(&path).unwrap();
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/topography?name=matrix-3.txt"))
            .send(&bytes[..]),
    );
    assert_eq!(status, 200, "{v}");
    let map = gonio_surface::io::read(&path).unwrap();
    let stats = gonio_surface::stats::statistics(&map).unwrap();
    assert_eq!(v["read"]["nx"], 256);
    assert!((v["read"]["sq_um"].as_f64().unwrap() - stats.sq * 1e6).abs() < 1e-12);
    assert!((v["read"]["sdq"].as_f64().unwrap() - stats.sdq).abs() < 1e-15);
    // SurfaceTopography reads Sq 35.22 nm (../shared/data/README.md).
    assert!(
        (v["read"]["sq_um"].as_f64().unwrap() - 0.03522).abs() < 0.00001,
        "{v}"
    );
    let id = v["id"].as_str().unwrap().to_string();
    let mut f = example(&agent, &base, "red_rough");
    f["top"] = json!({ "roughness": { "map": id } });
    let (status, r) = json(post(
        &agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": f }),
    ));
    assert_eq!(status, 200, "{r}");
    for name in ["../../etc/passwd", "/etc/passwd", "u999.txt", "Cargo.toml"] {
        f["top"] = json!({ "roughness": { "map": name } });
        let (status, v) = json(post(
            &agent,
            &format!("{base}/api/readings"),
            &json!({ "formulation": f }),
        ));
        assert_eq!(status, 404, "{name}: {v}");
        assert!(v["error"].as_str().unwrap().contains("upload"), "{v}");
    }
    let mut damaged = bytes.clone();
    damaged.truncate(bytes.len() / 2);
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/topography?name=mine.txt"))
            .send(&damaged[..]),
    );
    assert_eq!(status, 400, "{v}");
    let message = v["error"].as_str().unwrap();
    assert!(
        message.contains("mine.txt") && !message.contains("gonio-lab-"),
        "{message}"
    );
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/topography?name=noextension"))
            .send(&bytes[..]),
    );
    assert_eq!(status, 400, "{v}");
    let big = vec![0u8; UPLOAD_LIMIT + 1];
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/topography?name=big.sur"))
            .send(&big[..]),
    );
    assert_eq!(status, 413, "{v}");
    assert!(v["error"].as_str().unwrap().contains("1 MiB"), "{v}");
}

/// Readings of a formulation: the same for the same formulation (common random numbers), and
/// eight clients at once get what each would get alone.
#[test]
fn readings_are_deterministic_and_eight_clients_are_served_at_once() {
    let (base, agent) = (start(), client());
    let names = [
        "silver_metallic",
        "pearl_interference",
        "red_solid",
        "red_rough",
        "red_pigmented",
        "solid_three_pigments",
        "cayman_start",
        "cayman_tinted_start",
    ];
    let reading = |agent: &ureq::Agent, name: &str| {
        let f = example(agent, &base, name);
        let (status, mut v) = json(post(
            agent,
            &format!("{base}/api/readings"),
            &json!({ "formulation": f }),
        ));
        assert_eq!(status, 200, "{name}: {v}");
        v.as_object_mut().unwrap().remove("seconds");
        v
    };
    let alone: Vec<_> = names.iter().map(|n| reading(&agent, n)).collect();
    let together: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = names
            .iter()
            .map(|n| s.spawn(|| reading(&client(), n)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(alone, together);
    let gu60 = |v: &serde_json::Value| v["gloss"]["gloss_60_gu"].as_f64().unwrap();
    // A smooth coat of n = 1.5 (red_solid): 60° gloss is the Fresnel reflectance over the
    // standard's (n = 1.567) times 100: 100 × 0.0893 / 0.1003 ≈ 89 GU; the rough red is below.
    assert!((gu60(&alone[2]) - 89.0).abs() < 1.5, "{}", alone[2]);
    assert!(gu60(&alone[3]) < gu60(&alone[2]));
}

/// A measured BRDF uploaded as a target: its readings at the standard's geometries, and the
/// formulation's ΔE00 against it at each; a damaged target gets the reader's message.
#[test]
fn targets_give_colour_differences() {
    let (base, agent) = (start(), client());
    let bytes = std::fs::read(data("crates/brdf/tests/data/cayman.astm")).unwrap();
    let (status, t) = json(
        agent
            .post(format!(
                "{base}/api/upload/target?name=cayman.astm&standard=E2194"
            ))
            .send(&bytes[..]),
    );
    assert_eq!(status, 200, "{t}");
    let id = t["id"].as_str().unwrap();
    let f = example(&agent, &base, "cayman_start");
    let (status, r) = json(post(
        &agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": f, "target": id }),
    ));
    assert_eq!(status, 200, "{r}");
    let de: Vec<f64> = r["target"]["de00"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["de00"].as_f64().unwrap())
        .collect();
    assert_eq!(de.len(), 5);
    // The target's own readings come along (its swatches, its in-plane BRDF at the incidence).
    assert_eq!(
        r["target"]["read"]["multiangle"].as_array().unwrap().len(),
        5
    );
    assert_eq!(t["read"]["multiangle"], r["target"]["read"]["multiangle"]);
    // The formulation against a target made of its own reading (a CSV of its CIELAB): 0.
    let csv: String = std::iter::once("geometry,L,a,b\n".to_string())
        .chain(r["multiangle"].as_array().unwrap().iter().map(|g| {
            format!(
                "{},{},{},{}\n",
                g["geometry"].as_str().unwrap(),
                g["L"],
                g["a"],
                g["b"]
            )
        }))
        .collect();
    let (status, own) = json(
        agent
            .post(format!("{base}/api/upload/target?name=own.csv"))
            .send(csv.as_bytes()),
    );
    assert_eq!(status, 200, "{own}");
    let (_, r2) = json(post(
        &agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": f, "target": own["id"] }),
    ));
    assert!(
        r2["target"]["max_de00"].as_f64().unwrap() < 1e-6,
        "{}",
        r2["target"]
    );
    assert!(
        de.iter().all(|d| d.is_finite() && *d > 0.0 && *d < 60.0),
        "{de:?}"
    );
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/target?name=bad.astm"))
            .send(&bytes[..bytes.len() / 3]),
    );
    assert_eq!(status, 400, "{v}");
    assert!(v["error"].as_str().unwrap().contains("bad.astm"), "{v}");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": f, "target": "u12345.astm" }),
    ));
    assert_eq!(status, 404, "{v}");
}

/// A preview picture is a PNG of the panel at the preview's size, the same bytes for the same
/// formulation and light, another under another light; its figures come as headers. Unknown
/// lights and qualities are refused naming the ones there are.
#[test]
fn pictures() {
    let (base, agent) = (start(), client());
    let f = example(&agent, &base, "red_solid");
    let shot = |lighting: &str| {
        let mut r = post(
            &agent,
            &format!("{base}/api/picture"),
            &json!({ "formulation": f, "lighting": lighting, "quality": "preview" }),
        )
        .unwrap();
        assert_eq!(r.status().as_u16(), 200);
        assert_eq!(r.headers()["content-type"], "image/png");
        assert_eq!(r.headers()["x-gonio-size"], "192x128");
        r.body_mut().read_to_vec().unwrap()
    };
    let studio = shot("studio");
    let picture = image::load_from_memory(&studio).unwrap();
    assert_eq!((picture.width(), picture.height()), (192, 128));
    assert_eq!(shot("studio"), studio);
    assert_ne!(shot("booth"), studio);
    let (_, lightings) = json(agent.get(format!("{base}/api/lightings")).call());
    let names: Vec<&str> = lightings
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["studio", "booth"]);
    for (field, value) in [("lighting", "sunset"), ("quality", "best")] {
        let (status, v) = json(post(
            &agent,
            &format!("{base}/api/picture"),
            &json!({ "formulation": f, field: value }),
        ));
        assert_eq!(status, 400, "{v}");
        assert!(v["error"].as_str().unwrap().contains(value), "{v}");
    }
}

/// The table exports are files the readers take: a `.gbrdf` with the coating's bands, a Mitsuba
/// tensor that gonio's port of Mitsuba's `measured` reader opens (Mitsuba itself reads the same
/// writer's files in crates/brdf's oracle tests).
#[test]
fn table_exports() {
    let (base, agent) = (start(), client());
    let f = example(&agent, &base, "red_solid");
    let dir = tempfile::tempdir().unwrap();
    for (format, name) in [
        ("gbrdf", "coating.gbrdf"),
        ("mitsuba", "coating_mitsuba.bsdf"),
    ] {
        let mut r = post(
            &agent,
            &format!("{base}/api/export/{format}"),
            &json!({ "formulation": f }),
        )
        .unwrap();
        assert_eq!(r.status().as_u16(), 200);
        let disposition = r.headers()["content-disposition"]
            .to_str()
            .unwrap()
            .to_string();
        assert!(disposition.contains(name), "{disposition}");
        let path = dir.path().join(name);
        std::fs::write(
            &path,
            r.body_mut()
                .with_config()
                .limit(1 << 28)
                .read_to_vec()
                .unwrap(),
        )
        .unwrap();
    }
    let table = gonio_brdf::gbrdf::read(&dir.path().join("coating.gbrdf")).unwrap();
    assert_eq!(table.channels().count(), 31);
    gonio_brdf::formats::mitsuba::TensorBrdf::read(&dir.path().join("coating_mitsuba.bsdf"))
        .unwrap();
}
