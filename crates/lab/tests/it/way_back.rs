//! The way back from a target (docs/lab.md, "Match and sensitivity"): the constituents a
//! formulation offers, bad match and sensitivity requests refused at once with a 4xx naming what
//! is wrong, and (slow) a match that recovers a known flake tilt, a cancelled one, and a Morris
//! screening that ranks the constituents as the physics says.

use crate::server::{client, example, json, post, start};
use serde_json::{Value, json};

/// Upload `csv` as a target; its id.
fn upload_csv(agent: &ureq::Agent, base: &str, csv: &str) -> String {
    let (status, v) = json(
        agent
            .post(format!("{base}/api/upload/target?name=target.csv"))
            .send(csv.as_bytes()),
    );
    assert_eq!(status, 200, "{v}");
    v["id"].as_str().unwrap().to_string()
}

/// A multi-angle CSV (geometry, L*, a*, b*) of `formulation`'s readings at E2194.
fn reading_csv(agent: &ureq::Agent, base: &str, formulation: &Value) -> String {
    let (status, r) = json(post(
        agent,
        &format!("{base}/api/readings"),
        &json!({ "formulation": formulation }),
    ));
    assert_eq!(status, 200, "{r}");
    std::iter::once("geometry,L,a,b\n".to_string())
        .chain(r["multiangle"].as_array().unwrap().iter().map(|g| {
            format!(
                "{},{},{},{}\n",
                g["geometry"].as_str().unwrap(),
                g["L"],
                g["a"],
                g["b"]
            )
        }))
        .collect()
}

/// Poll the job until it has ended (at most `seconds`); every answer seen.
fn follow(agent: &ureq::Agent, base: &str, id: &str, seconds: f64) -> Vec<Value> {
    let clock = std::time::Instant::now();
    let mut seen = Vec::new();
    loop {
        let (status, v) = json(agent.get(format!("{base}/api/jobs/{id}")).call());
        assert_eq!(status, 200, "{v}");
        let state = v["state"].as_str().unwrap().to_string();
        seen.push(v);
        if state != "running" && state != "cancelling" {
            return seen;
        }
        assert!(clock.elapsed().as_secs_f64() < seconds, "{seen:?}");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// The silver metallic offers its roughness, coat thickness, flake tilt and coverage (no TiO2:
/// aluminium flakes) with `Varied::default_bounds`; with library pigments the base holds them,
/// each offered by its concentration, and `/api/pigments` lists the library.
#[test]
fn constituents_and_library_pigments() {
    let (base, agent) = (start(), client());
    let f = example(&agent, &base, "silver_metallic");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/constituents"),
        &json!({ "formulation": f }),
    ));
    assert_eq!(status, 200, "{v}");
    let names: Vec<&str> = v["constituents"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["roughness", "tilt", "coverage", "thickness"]);
    let tilt = &v["constituents"][1];
    assert_eq!(
        (tilt["lo"].as_f64(), tilt["hi"].as_f64()),
        (Some(2.0), Some(40.0))
    );
    assert_eq!(tilt["value"].as_f64(), Some(12.0));
    // E2194: 5 gloss-meter readings, L*, a*, b* at 5 geometries, flop, ΔE00.
    assert_eq!(v["outputs"].as_array().unwrap().len(), 22, "{v}");

    let red = example(&agent, &base, "red_pigmented");
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/constituents"),
        &json!({ "formulation": red, "pigments": {"from": "library",
                 "names": ["pyrrole_red", "titanium_white"]} }),
    ));
    assert_eq!(status, 200, "{v}");
    assert_eq!(
        v["formulation"]["base"]["pigment"],
        json!([{"library": "pyrrole_red", "concentration": 0.1},
               {"library": "titanium_white", "concentration": 0.1}])
    );
    let c = v["constituents"].as_array().unwrap();
    let red_c = c
        .iter()
        .find(|c| c["name"] == "concentration:pyrrole_red")
        .unwrap();
    // A tenth to four times the start.
    assert!(
        (red_c["lo"].as_f64().unwrap() - 0.01).abs() < 1e-12,
        "{red_c}"
    );
    assert!(
        (red_c["hi"].as_f64().unwrap() - 0.4).abs() < 1e-12,
        "{red_c}"
    );
    let (_, pigments) = json(agent.get(format!("{base}/api/pigments")).call());
    let library: Vec<&str> = pigments
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["library"] == true)
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(library.len(), 19, "{library:?}");
    assert!(library.contains(&"phthalo_blue_green_shade"));
}

/// Every bad request is refused before a job starts, with a 4xx whose message names what is
/// wrong.
#[test]
fn bad_requests_are_refused_with_their_reason() {
    let (base, agent) = (start(), client());
    let f = example(&agent, &base, "silver_metallic");
    let red = example(&agent, &base, "red_pigmented");
    let target = upload_csv(
        &agent,
        &base,
        "geometry,L,a,b\n45as15,110,0,0\n45as45,40,0,0\n",
    );
    let tilt = json!([{"name": "tilt"}]);
    let cases = [
        (
            "match",
            json!({"formulation": f, "target": target, "vary": [{"name": "gloss"}]}),
            400,
            "vary one of roughness",
        ),
        (
            "match",
            json!({"formulation": f, "target": target,
                         "vary": [{"name": "tilt", "lo": 40, "hi": 2}]}),
            400,
            "lower bound must be below",
        ),
        (
            "match",
            json!({"formulation": f, "target": target,
                         "vary": [{"name": "coverage", "lo": 0.1, "hi": 1.5}]}),
            400,
            "coverage",
        ),
        (
            "match",
            json!({"formulation": f, "vary": tilt}),
            400,
            "missing field `target`",
        ),
        (
            "match",
            json!({"formulation": f, "target": "u999.csv", "vary": tilt}),
            404,
            "no target upload 'u999.csv'",
        ),
        (
            "match",
            json!({"formulation": red, "target": target,
                         "vary": [{"name": "concentration:phthalo_bleu"}],
                         "pigments": {"from": "library", "names": ["phthalo_bleu"]}}),
            400,
            "'phthalo_bleu' is not a pigment of gonio's library",
        ),
        (
            "match",
            json!({"formulation": f, "target": target, "vary": tilt,
                         "pigments": {"from": "library", "names": ["pyrrole_red"]}}),
            400,
            "Kubelka-Munk base",
        ),
        (
            "match",
            json!({"formulation": red, "target": target,
                         "vary": [{"name": "concentration:blue"}]}),
            400,
            "no pigment of that name",
        ),
        (
            "match",
            json!({"formulation": f, "target": target, "vary": []}),
            400,
            "at least one constituent",
        ),
        (
            "match",
            json!({"formulation": f, "target": target,
                         "vary": [{"name": "tilt"}, {"name": "tilt"}]}),
            400,
            "varied twice",
        ),
        (
            "match",
            json!({"formulation": f, "target": target, "vary": tilt, "starts": 0}),
            400,
            "at least one start",
        ),
        (
            "match",
            json!({"formulation": f, "target": target, "vary": tilt,
                         "objective": "spectral"}),
            400,
            "reflectance",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 0}}),
            400,
            "select at least 1 pigment",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 2,
                                      "candidates": ["pyrrole_red", "phthalo_bleu"]}}),
            400,
            "'phthalo_bleu' is not a pigment of gonio's library",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 3,
                                      "candidates": ["pyrrole_red", "bone_black"]}}),
            400,
            "at most 2",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 20}}),
            400,
            "at most 19",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 1, "finalists": 0}}),
            400,
            "at least 1 finalist",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select"}}),
            400,
            "missing field `max`",
        ),
        (
            "match",
            json!({"formulation": f, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 1}}),
            400,
            "selecting pigments needs a base of kind = \"kubelka-munk\"",
        ),
        (
            "match",
            json!({"formulation": red, "target": target, "vary": [],
                         "pigments": {"from": "select", "max": 1}, "objective": "spectral"}),
            400,
            "reflectance",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "samples": 0}),
            400,
            "0 Morris trajectories",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "method": "fast"}),
            400,
            "method 'fast'",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "outputs": ["gu45"]}),
            400,
            "output 'gu45'",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "outputs": []}),
            400,
            "at least one output",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": [{"name": "tio2"}]}),
            400,
            "interference",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "threshold": 2}),
            400,
            "threshold 2",
        ),
        (
            "sensitivity",
            json!({"formulation": f, "vary": tilt, "trajectories": 4}),
            400,
            "unknown field `trajectories`",
        ),
    ];
    for (endpoint, body, want, says) in cases {
        let (status, v) = json(post(&agent, &format!("{base}/api/{endpoint}"), &body));
        let message = v["error"].as_str().unwrap_or_default();
        assert_eq!(status, want, "{endpoint} {body}: {v}");
        assert!(
            message.contains(says),
            "{endpoint}: '{message}' does not say '{says}'"
        );
    }
    for path in ["jobs/j999", "jobs/nothing"] {
        let (status, v) = json(agent.get(format!("{base}/api/{path}")).call());
        assert_eq!(status, 404, "{v}");
        assert!(v["error"].as_str().unwrap().contains("no job"), "{v}");
    }
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/jobs/j999/cancel"),
        &json!({}),
    ));
    assert_eq!(status, 404, "{v}");
}

mod slow {
    use super::*;

    /// A match from the silver metallic (tilt 12°) to the reading of the same coating with its
    /// flakes at 20° recovers the tilt: the job reports its readings and best ΔE00 while it
    /// runs, and its result is the fitted formulation (tilt as fitted) with the ΔE00 per
    /// geometry before and after. The target is read with the readings' walks and the match
    /// with 256: the two differ by their noise (σ of L* about 0.1–0.3 at 256 walks,
    /// docs/formulation.md), which moves the optimum by a fraction of a degree where L* changes
    /// by several units per degree of tilt at 45as15; 2° is a margin of several times that.
    #[test]
    fn a_match_recovers_the_tilt_and_another_is_cancelled() {
        let (base, agent) = (start(), client());
        let f = example(&agent, &base, "silver_metallic");
        let mut at20 = f.clone();
        at20["flakes"]["tilt_deg"] = json!(20.0);
        let target = upload_csv(&agent, &base, &reading_csv(&agent, &base, &at20));
        let request = json!({"formulation": f, "target": target, "vary": [{"name": "tilt"}],
                             "walks": 256, "starts": 1, "iterations": 25});
        let (status, started) = json(post(&agent, &format!("{base}/api/match"), &request));
        assert_eq!(status, 202, "{started}");
        let id = started["id"].as_str().unwrap();
        let seen = follow(&agent, &base, id, 300.0);
        let done = seen.last().unwrap();
        assert_eq!(done["state"], "done", "{done}");
        assert!(done["readings"].as_u64().unwrap() >= 10, "{done}");
        let r = &done["result"];
        let fitted = r["constituents"][0]["fitted"].as_f64().unwrap();
        assert!((fitted - 20.0).abs() < 2.0, "tilt {fitted}: {r}");
        assert_eq!(
            r["formulation"]["flakes"]["tilt_deg"].as_f64(),
            Some(fitted)
        );
        assert!(r["constituents"][0]["sigma"].as_f64().unwrap() > 0.0, "{r}");
        let (start_de, fitted_de) = (
            r["mean_de00_start"].as_f64().unwrap(),
            r["mean_de00_fitted"].as_f64().unwrap(),
        );
        assert!(fitted_de < 0.25 * start_de, "{start_de} → {fitted_de}");
        assert_eq!(r["geometries"].as_array().unwrap().len(), 5);
        // The best so far never rises, and ends at least as low as the fitted objective's
        // search value.
        let best: Vec<f64> = seen.iter().filter_map(|v| v["best"].as_f64()).collect();
        assert!(best.windows(2).all(|w| w[1] <= w[0]), "{best:?}");

        // A long match, cancelled: it ends as cancelled (409) soon after.
        let long = json!({"formulation": f, "target": target, "vary": [{"name": "tilt"},
                          {"name": "coverage"}], "walks": 256, "starts": 8, "iterations": 400});
        let (status, started) = json(post(&agent, &format!("{base}/api/match"), &long));
        assert_eq!(status, 202, "{started}");
        let id = started["id"].as_str().unwrap();
        std::thread::sleep(std::time::Duration::from_millis(500));
        let (status, _) = json(post(
            &agent,
            &format!("{base}/api/jobs/{id}/cancel"),
            &json!({}),
        ));
        assert_eq!(status, 200);
        let clock = std::time::Instant::now();
        let seen = follow(&agent, &base, id, 60.0);
        let end = seen.last().unwrap();
        assert_eq!(end["state"], "cancelled", "{end}");
        assert_eq!(end["status"], 409, "{end}");
        assert!(
            clock.elapsed().as_secs_f64() < 10.0,
            "{:?}",
            clock.elapsed()
        );
    }

    /// "Let gonio select": a white basecoat matched to the reading of the same white with two
    /// library pigments added (a green: phthalo blue green shade 0.04, hansa yellow opaque
    /// 0.15), selecting up to 2 of 4 candidates. The job says its steps (the screen of the 4 + 6
    /// combinations, counted as they are screened, then each finalist's match), and its result
    /// is the best finalist's match as a plain match's (the ΔE00 per geometry, the fitted
    /// formulation with the chosen pigments as library entries) with the `selection`: the true
    /// pigments chosen, 10 combinations screened, 2 finalists with their mean ΔE00, the chosen
    /// one the lowest. A selection that is cancelled ends as cancelled.
    #[test]
    fn a_selection_finds_the_true_pigments() {
        let (base, agent) = (start(), client());
        let white = "[coat]\nindex = 1.5\nthickness_um = 40\n\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 30\nsubstrate = 0.6\n\n[[base.pigment]]\nlibrary = \"titanium_white\"\nconcentration = 1.0\n";
        let green = format!(
            "{white}\n[[base.pigment]]\nlibrary = \"phthalo_blue_green_shade\"\nconcentration = 0.04\n\n[[base.pigment]]\nlibrary = \"hansa_yellow_opaque\"\nconcentration = 0.15\n"
        );
        let formulation = |text: &str| {
            let (status, v) = json(
                agent
                    .post(format!("{base}/api/formulation/from-toml"))
                    .send(text.as_bytes()),
            );
            assert_eq!(status, 200, "{v}");
            v["formulation"].clone()
        };
        let (white, green) = (formulation(white), formulation(&green));
        let target = upload_csv(&agent, &base, &reading_csv(&agent, &base, &green));
        let candidates = [
            "pyrrole_red",
            "hansa_yellow_opaque",
            "phthalo_blue_green_shade",
            "bone_black",
        ];
        let request = json!({"formulation": white, "target": target, "vary": [],
            "pigments": {"from": "select", "max": 2, "candidates": candidates, "finalists": 2},
            "walks": 64, "starts": 1, "iterations": 60});
        let (status, started) = json(post(&agent, &format!("{base}/api/match"), &request));
        assert_eq!(status, 202, "{started}");
        let clock = std::time::Instant::now();
        let seen = follow(&agent, &base, started["id"].as_str().unwrap(), 300.0);
        let done = seen.last().unwrap();
        eprintln!(
            "selection in {:.1} s: finalists {}, mean ΔE00 {} → {}",
            clock.elapsed().as_secs_f64(),
            done["result"]["selection"]["finalists"],
            done["result"]["mean_de00_start"],
            done["result"]["mean_de00_fitted"]
        );
        assert_eq!(done["state"], "done", "{done}");
        let steps: Vec<&str> = seen
            .iter()
            .filter_map(|v| v["stage"]["step"].as_str())
            .collect();
        assert!(steps.contains(&"finalist"), "{steps:?}");
        for v in &seen {
            if v["stage"]["step"] == "screen" {
                assert_eq!(v["stage"]["combinations"], 10, "{v}");
                assert!(v["readings"].as_u64().unwrap() <= 10, "{v}");
            }
        }
        let r = &done["result"];
        let sel = &r["selection"];
        let mut chosen: Vec<&str> = sel["pigments"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p.as_str().unwrap())
            .collect();
        chosen.sort();
        assert_eq!(
            chosen,
            ["hansa_yellow_opaque", "phthalo_blue_green_shade"],
            "{sel}"
        );
        assert_eq!(sel["combinations"], 10, "{sel}");
        let finalists = sel["finalists"].as_array().unwrap();
        assert_eq!(finalists.len(), 2, "{sel}");
        let mean = |k: usize| finalists[k]["mean_de00"].as_f64().unwrap();
        let best = sel["chosen"].as_u64().unwrap() as usize;
        assert!(mean(best) <= mean(1 - best), "{sel}");
        // The plain match's fields, of the chosen finalist.
        assert_eq!(r["geometries"].as_array().unwrap().len(), 5, "{r}");
        let fitted = r["mean_de00_fitted"].as_f64().unwrap();
        assert!((fitted - mean(best)).abs() < 1e-9, "{fitted} against {sel}");
        // The target is the reading of a solid (a smooth coat over a Kubelka-Munk base: no
        // walk noise), so the true pigments fit it exactly but for the search's tolerance.
        assert!(fitted < 0.05, "{r}");
        let concentrations = &finalists[best]["concentrations"];
        for (k, want) in sel["finalists"][best]["pigments"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                if p == "hansa_yellow_opaque" {
                    0.15
                } else {
                    0.04
                }
            })
            .enumerate()
        {
            let got = concentrations[k].as_f64().unwrap();
            assert!((got - want).abs() < 0.002, "{got} against {want}: {sel}");
        }
        let library: Vec<&str> = r["formulation"]["base"]["pigment"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|p| p["library"].as_str())
            .collect();
        assert_eq!(library.len(), 3, "{r}");
        assert!(r["toml"].as_str().unwrap().contains("hansa_yellow_opaque"));

        // The same selection, cancelled in its screen or its first finalist.
        let (status, started) = json(post(&agent, &format!("{base}/api/match"), &request));
        assert_eq!(status, 202, "{started}");
        let id = started["id"].as_str().unwrap();
        std::thread::sleep(std::time::Duration::from_millis(300));
        let (status, _) = json(post(
            &agent,
            &format!("{base}/api/jobs/{id}/cancel"),
            &json!({}),
        ));
        assert_eq!(status, 200);
        let end = follow(&agent, &base, id, 60.0);
        assert_eq!(end.last().unwrap()["state"], "cancelled", "{end:?}");
    }

    /// Morris screening of the silver metallic's roughness and flake tilt: 60° gloss is driven
    /// most by the roughness (the top's specular peak, from about 90 GU at α 0.01 to a few at
    /// 0.2; the flakes' own near-specular light adds less), L* at 45as15 most by the tilt (the
    /// flakes' lobe widening away from the specular); the job counts its readings to the total
    /// r (d + 1) + 1 + noise repeats, and the chart's figures are the library's JSON.
    #[test]
    fn a_morris_screening_ranks_the_constituents() {
        let (base, agent) = (start(), client());
        let f = example(&agent, &base, "silver_metallic");
        let request = json!({"formulation": f,
            "vary": [{"name": "roughness", "lo": 0.01, "hi": 0.2}, {"name": "tilt"}],
            "outputs": ["gu60", "L@45as15"], "samples": 4, "walks": 128, "noise_repeats": 0});
        let (status, started) = json(post(&agent, &format!("{base}/api/sensitivity"), &request));
        assert_eq!(status, 202, "{started}");
        let seen = follow(&agent, &base, started["id"].as_str().unwrap(), 300.0);
        let done = seen.last().unwrap();
        assert_eq!(done["state"], "done", "{done}");
        assert_eq!(
            (done["readings"].as_u64(), done["total"].as_u64()),
            (Some(13), Some(13))
        );
        let r = &done["result"];
        assert_eq!(r["method"], "morris");
        let mu = |k: usize, input: &str| {
            r["outputs"][k]["indices"]["mu_star"][input]
                .as_f64()
                .unwrap()
        };
        assert!(mu(0, "roughness") > 2.0 * mu(0, "tilt"), "{r}");
        assert!(mu(1, "tilt") > mu(1, "roughness"), "{r}");
        let summary = r["summary"].as_str().unwrap();
        assert!(
            summary.contains("60° gloss is driven by roughness"),
            "{summary}"
        );
    }
}
