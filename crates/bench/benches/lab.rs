//! The lab's speed as a designer meets it (issue #33), over HTTP against a lab in this process:
//! readings and pictures from request to response for each example (median and 95th
//! percentile: a latency's tail matters, which criterion does not report, hence this harness),
//! a slider dragged through twenty values in two seconds (the CPU idle again after the last),
//! and the memory after a thousand changes. `cargo bench -p gonio-bench --bench lab`; figures in
//! docs/performance.md. A quiet machine: nothing else running.

use serde_json::{Value, json};
use std::time::{Duration, Instant};

fn start() -> String {
    let address = gonio_lab::spawn(
        "127.0.0.1:0".parse().expect("an address"),
        Default::default(),
    );
    format!("http://{}", address.expect("a lab on a free port"))
}

fn post(agent: &ureq::Agent, url: &str, body: &Value) -> (u16, Vec<u8>) {
    let mut r = agent
        .post(url)
        .header("content-type", "application/json")
        .send(body.to_string())
        .expect("a response");
    let status = r.status().as_u16();
    let bytes = r
        .body_mut()
        .with_config()
        .limit(1 << 26)
        .read_to_vec()
        .expect("a body");
    (status, bytes)
}

/// The formulation of example `name`.
fn example(agent: &ureq::Agent, base: &str, name: &str) -> Value {
    let mut r = agent
        .get(format!("{base}/api/examples/{name}"))
        .call()
        .expect("an example");
    let v: Value =
        serde_json::from_str(&r.body_mut().read_to_string().expect("text")).expect("JSON");
    v["formulation"].clone()
}

/// `f` with its coat's thickness set to `um` (a slider every formulation has).
fn with_thickness(f: &Value, um: f64) -> Value {
    let mut g = f.clone();
    g["coat"]["thickness_um"] = json!(um);
    g
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let k = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[k]
}

/// Time `n` requests to `endpoint`, each a formulation moved a little; ms, sorted.
fn latencies(
    agent: &ureq::Agent,
    base: &str,
    f: &Value,
    endpoint: &str,
    extra: &Value,
    n: usize,
) -> Vec<f64> {
    let mut t: Vec<f64> = (0..n)
        .map(|k| {
            let mut body = json!({ "formulation": with_thickness(f, 30.0 + k as f64) });
            for (key, v) in extra.as_object().expect("an object") {
                body[key] = v.clone();
            }
            let t0 = Instant::now();
            let (status, bytes) = post(agent, &format!("{base}/api/{endpoint}"), &body);
            assert_eq!(status, 200, "{}", String::from_utf8_lossy(&bytes));
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t
}

fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes into the struct it is given; RUSAGE_SELF is always valid.
    let usage = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        libc::getrusage(libc::RUSAGE_SELF, &mut usage);
        usage
    };
    let t = |tv: libc::timeval| tv.tv_sec as f64 + tv.tv_usec as f64 * 1e-6;
    t(usage.ru_utime) + t(usage.ru_stime)
}

/// Resident memory of this process, MiB.
fn rss_mib() -> f64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: f64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or(f64::NAN);
    pages * 4096.0 / (1 << 20) as f64
}

fn main() {
    // `cargo bench` passes --bench; `cargo test --benches` would run this too: only on --bench.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let base = start();
    let agent: ureq::Agent = ureq::Agent::config_builder()
        .http_status_as_error(false)
        .build()
        .into();
    let names: Vec<String> = gonio_lab::examples::EXAMPLES
        .iter()
        .map(|(n, _)| n.to_string())
        .collect();
    println!("readings (request to response, 30 each after 3 warm-ups), ms:");
    println!("| example | median | p95 | max |");
    for name in &names {
        let f = example(&agent, &base, name);
        latencies(&agent, &base, &f, "readings", &json!({}), 3);
        let t = latencies(&agent, &base, &f, "readings", &json!({}), 30);
        println!(
            "| {name} | {:.0} | {:.0} | {:.0} |",
            percentile(&t, 0.5),
            percentile(&t, 0.95),
            t[t.len() - 1]
        );
    }
    println!("\npreview picture (request to PNG, 10 each after 1 warm-up), ms:");
    println!("| example | median | p95 |");
    for name in &names {
        let f = example(&agent, &base, name);
        latencies(
            &agent,
            &base,
            &f,
            "picture",
            &json!({ "quality": "preview" }),
            1,
        );
        let t = latencies(
            &agent,
            &base,
            &f,
            "picture",
            &json!({ "quality": "preview" }),
            10,
        );
        println!(
            "| {name} | {:.0} | {:.0} |",
            percentile(&t, 0.5),
            percentile(&t, 0.95)
        );
    }
    println!("\nconverged picture (request to PNG, 2 each), s:");
    for name in ["silver_metallic", "red_solid", "pearl_interference"] {
        let f = example(&agent, &base, name);
        let t = latencies(
            &agent,
            &base,
            &f,
            "picture",
            &json!({ "quality": "converged" }),
            2,
        );
        println!("| {name} | {:.1} | {:.1} |", t[0] / 1e3, t[1] / 1e3);
    }

    // A slider dragged through twenty values in two seconds, as the page sends them.
    let f = example(&agent, &base, "silver_metallic");
    let drag = |changes: usize, spacing: Duration| {
        let handles: Vec<_> = (0..changes)
            .map(|k| {
                let (base, g) = (base.clone(), with_thickness(&f, 20.0 + (k % 100) as f64));
                let h = std::thread::spawn(move || {
                    let agent: ureq::Agent = ureq::Agent::config_builder()
                        .http_status_as_error(false)
                        .build()
                        .into();
                    let a = post(
                        &agent,
                        &format!("{base}/api/readings"),
                        &json!({ "formulation": g, "channel": "readings-B" }),
                    )
                    .0;
                    let b = post(
                        &agent,
                        &format!("{base}/api/picture"),
                        &json!({ "formulation": g, "channel": "picture-B" }),
                    )
                    .0;
                    (a, b)
                });
                std::thread::sleep(spacing);
                h
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a client"))
            .collect::<Vec<_>>()
    };
    let statuses = drag(20, Duration::from_millis(100));
    let answered = Instant::now();
    let c0 = cpu_seconds();
    std::thread::sleep(Duration::from_secs(1));
    let busy = cpu_seconds() - c0;
    let done = statuses.iter().filter(|s| s.0 == 200).count();
    println!(
        "\n20 changes in 2 s: {done} readings answered, {} cancelled; in the second after the last answer the CPU was busy {:.2} core-s ({:?} after)",
        statuses.len() - done,
        busy,
        answered.elapsed()
    );

    // Memory across a thousand changes (sent every 20 ms: most are cancelled by the next), in
    // four rounds, then after the server's idle threads have gone (tokio keeps a blocking thread
    // 10 s): growth that stops is the allocator's arenas and the kept tables filling; growth
    // that goes on would be a leak.
    let mut rss = vec![("before".to_string(), rss_mib())];
    for round in 1..=4 {
        drag(250, Duration::from_millis(20));
        rss.push((format!("after {}", 250 * round), rss_mib()));
    }
    std::thread::sleep(Duration::from_secs(12));
    rss.push(("12 s later".to_string(), rss_mib()));
    println!(
        "resident memory (MiB) over 1000 changes: {}",
        rss.iter()
            .map(|(k, v)| format!("{k} {v:.0}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
}
