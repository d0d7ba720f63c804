//! The reports in the lab (docs/lab.md, "The demo's report", "The conformance report"): a
//! request with a field the endpoint does not know, an unknown renderer or samples out of
//! range is refused at once; report names the lab never gave are 404s; and (slow) the quick
//! demo's job and the conformance suite's on gonio end with their pages, served.

use crate::server::{client, json, post, start, text};
use serde_json::json;

#[test]
fn bad_requests_and_unknown_reports_are_refused() {
    let (base, agent) = (start(), client());
    let (status, v) = json(post(
        &agent,
        &format!("{base}/api/report/demo"),
        &json!({ "quik": true }),
    ));
    assert_eq!(status, 400, "{v}");
    assert!(v["error"].as_str().unwrap().contains("quik"), "{v}");
    for (body, says) in [
        (json!({ "renderer": ["gonio"] }), "renderer"),
        (
            json!({ "renderers": ["povray"] }),
            "unknown renderer 'povray'",
        ),
        (json!({ "spp": 0 }), "not between 1 and 65536"),
    ] {
        let (status, v) = json(post(
            &agent,
            &format!("{base}/api/report/conformance"),
            &body,
        ));
        assert_eq!(status, 400, "{body}: {v}");
        assert!(v["error"].as_str().unwrap().contains(says), "{v}");
    }
    for name in ["r999", "x1", "r", "..%2Fetc"] {
        let (status, body) = text(agent.get(format!("{base}/api/reports/{name}")).call());
        assert_eq!(status, 404, "{name}: {body}");
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// The job `id`'s final state, polled.
    fn finished(base: &str, agent: &ureq::Agent, id: &str) -> serde_json::Value {
        let clock = std::time::Instant::now();
        loop {
            let (status, v) = json(agent.get(format!("{base}/api/jobs/{id}")).call());
            assert_eq!(status, 200, "{v}");
            if v["state"] != "running" {
                return v;
            }
            assert!(clock.elapsed().as_secs() < 600, "{v}");
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
    }

    #[test]
    fn the_conformance_suite_on_gonio_is_served_as_a_page() {
        let (base, agent) = (start(), client());
        let (status, v) = json(post(
            &agent,
            &format!("{base}/api/report/conformance"),
            &json!({ "renderers": ["gonio"], "spp": 16 }),
        ));
        assert_eq!(status, 202, "{v}");
        let done = finished(&base, &agent, v["id"].as_str().unwrap());
        assert_eq!(done["state"], "done", "{done}");
        assert_eq!(done["kind"], "report");
        assert_eq!(done["result"]["passed"], true, "{done}");
        let scenes = done["result"]["scenes"].as_array().unwrap();
        assert_eq!(scenes.len(), 7, "{done}");
        let page = done["result"]["report"].as_str().unwrap();
        let (status, html) = text(agent.get(format!("{base}{page}")).call());
        assert_eq!(status, 200);
        for s in scenes {
            assert_eq!(s["runs"][0]["verdict"], "pass", "{s}");
            let name = s["scene"].as_str().unwrap();
            assert!(html.contains(&format!("<h2>{name}</h2>")), "{name}");
        }
    }

    #[test]
    fn the_quick_demo_is_served_as_a_page() {
        let (base, agent) = (start(), client());
        let (status, v) = json(post(&agent, &format!("{base}/api/report/demo"), &json!({})));
        assert_eq!(status, 202, "{v}");
        let done = finished(&base, &agent, v["id"].as_str().unwrap());
        assert_eq!(done["state"], "done", "{done}");
        assert_eq!(done["kind"], "report");
        assert!(
            done["line"].as_str().unwrap().starts_with("step 8 of 8"),
            "{done}"
        );
        let sections = done["result"]["sections"].as_array().unwrap();
        assert_eq!(sections.len(), 8, "{done}");
        let page = done["result"]["report"].as_str().unwrap();
        let (status, html) = text(agent.get(format!("{base}{page}")).call());
        assert_eq!(status, 200);
        for s in sections {
            let title = s["title"].as_str().unwrap();
            assert!(html.contains(&format!("<h2>{title}</h2>")), "{title}");
        }
    }
}
