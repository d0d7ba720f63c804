//! Stale work stops (issue #33): a newer request on the same channel, or the client leaving,
//! cancels a computation, and the server's CPU is idle again soon after. A test binary of its
//! own, so that the process's CPU time is the lab's alone.

#[path = "it/server.rs"]
#[allow(dead_code)] // the helpers the API tests use beside the ones used here
mod server;

use serde_json::json;
use server::{client, example, post, start};
use std::time::{Duration, Instant};

/// CPU time of this process so far (user + system), s.
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

/// The CPU this process uses over `window` from now, in cores (1 = one core busy throughout).
fn cores_busy(window: Duration) -> f64 {
    let c0 = cpu_seconds();
    std::thread::sleep(window);
    (cpu_seconds() - c0) / window.as_secs_f64()
}

#[test]
fn stale_work_is_cancelled() {
    let (base, agent) = (start(), client());
    let f = example(&agent, &base, "silver_metallic");
    let picture = |quality: &str, channel: &str| json!({ "formulation": f, "quality": quality, "channel": channel });
    // 1. A newer request on the channel stops the older: the converged picture (seconds of work)
    //    answers 409 soon after a preview is asked for on its channel.
    let first = std::thread::spawn({
        let (base, body) = (base.clone(), picture("converged", "B"));
        move || {
            let r = post(&client(), &format!("{base}/api/picture"), &body).unwrap();
            (r.status().as_u16(), Instant::now())
        }
    });
    std::thread::sleep(Duration::from_millis(1500));
    let asked = Instant::now();
    let r = post(
        &agent,
        &format!("{base}/api/picture"),
        &picture("preview", "B"),
    )
    .unwrap();
    assert_eq!(r.status().as_u16(), 200);
    let (status, stopped) = first.join().unwrap();
    assert_eq!(status, 409, "the older picture was not cancelled");
    let late = stopped.saturating_duration_since(asked);
    eprintln!(
        "the older picture stopped {:.0} ms after the newer request",
        late.as_secs_f64() * 1e3
    );
    assert!(late < Duration::from_secs(2), "{late:?}");

    // 2. A client that leaves (times out) stops its computation: the server's CPU falls idle.
    let impatient: ureq::Agent = ureq::Agent::config_builder()
        .timeout_global(Some(Duration::from_millis(1000)))
        .build()
        .into();
    assert!(
        post(
            &impatient,
            &format!("{base}/api/picture"),
            &picture("converged", "")
        )
        .is_err()
    );
    std::thread::sleep(Duration::from_millis(500));
    let busy = cores_busy(Duration::from_secs(1));
    eprintln!("after the client left: {busy:.2} cores busy");
    assert!(
        busy < 0.2,
        "{busy:.2} cores still busy after the client left"
    );

    // 3. Twenty slider changes within two seconds, each superseding the last, on the readings
    //    and picture channels as the page sends them: the CPU is idle again within a second of
    //    the last answer.
    let mut handles = Vec::new();
    for k in 0..20 {
        let mut g = f.clone();
        g["flakes"]["tilt_deg"] = json!(8.0 + 0.5 * k as f64);
        let base = base.clone();
        handles.push(std::thread::spawn(move || {
            let agent = client();
            let a = post(
                &agent,
                &format!("{base}/api/readings"),
                &json!({ "formulation": g, "channel": "readings-B" }),
            )
            .unwrap();
            let b = post(
                &agent,
                &format!("{base}/api/picture"),
                &json!({ "formulation": g, "channel": "picture-B" }),
            )
            .unwrap();
            (a.status().as_u16(), b.status().as_u16())
        }));
        std::thread::sleep(Duration::from_millis(100));
    }
    let statuses: Vec<(u16, u16)> = handles.into_iter().map(|h| h.join().unwrap()).collect();
    assert_eq!(statuses.last(), Some(&(200, 200)), "{statuses:?}");
    assert!(
        statuses
            .iter()
            .all(|&(a, b)| (a == 200 || a == 409) && (b == 200 || b == 409)),
        "{statuses:?}"
    );
    let last = Instant::now();
    let busy = cores_busy(Duration::from_secs(1));
    eprintln!(
        "statuses {statuses:?}; in the second after the last answer: {busy:.2} cores busy ({:?})",
        last.elapsed()
    );
    assert!(busy < 0.2, "{busy:.2} cores busy after the last change");
}
