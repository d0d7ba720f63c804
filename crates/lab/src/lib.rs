//! gonio lab: a coating designer's workbench in the browser. `gonio lab` serves one page on
//! this machine where a formulation (the coating description of docs/coatings.md, as a form)
//! is changed with sliders and its readings (gloss, haze, DOI, multi-angle colour), its picture
//! on a curved panel and its difference from a measured target follow within a second.
//!
//! This crate holds the HTTP server ([`api`]), the state between requests ([`state`]) and the
//! page (HTML, CSS and JavaScript written in this repository and embedded in the program: no
//! network, no build step). Every computation is a call into the libraries ([`compute`]) that
//! the command line and the Python package make too. The JSON API is documented in docs/lab.md.

pub mod api;
mod assets;
pub mod compute;
pub mod error;
pub mod examples;
pub mod formulation;
pub mod jobs;
pub mod matching;
pub mod report;
pub mod sensitivity;
pub mod state;

pub use state::{Lab, Limits};

use std::net::SocketAddr;
use std::sync::Arc;

/// Serve the lab on `listener` until `shutdown` completes (requests in flight are finished).
pub async fn serve(
    listener: tokio::net::TcpListener,
    lab: Arc<Lab>,
    shutdown: impl std::future::Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    axum::serve(listener, api::router(lab))
        .with_graceful_shutdown(shutdown)
        .await
}

/// Start a lab with `limits` on `address` (port 0: any free one) in a thread and runtime of its
/// own, serving until the process ends; returns the address it listens on. For tests and
/// benchmarks that talk to a lab over HTTP from the same process.
pub fn spawn(address: SocketAddr, limits: Limits) -> std::io::Result<SocketAddr> {
    let listener = std::net::TcpListener::bind(address)?;
    listener.set_nonblocking(true)?;
    let bound = listener.local_addr()?;
    let lab = Arc::new(Lab::new(limits)?);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    std::thread::spawn(move || {
        runtime.block_on(async move {
            match tokio::net::TcpListener::from_std(listener) {
                Ok(listener) => {
                    if let Err(e) = serve(listener, lab, std::future::pending()).await {
                        eprintln!("gonio lab: {e}");
                    }
                }
                Err(e) => eprintln!("gonio lab: {e}"),
            }
        })
    });
    Ok(bound)
}

/// Run the lab on `address` until Ctrl-C: binds, calls `ready` with the address it listens on
/// (port 0 picks a free one), serves. Errors: the address cannot be bound (in use: the message
/// says how to choose another port), or the runtime cannot start.
pub fn run(address: SocketAddr, ready: impl FnOnce(SocketAddr)) -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    runtime.block_on(async move {
        let listener = tokio::net::TcpListener::bind(address).await.map_err(|e| {
            std::io::Error::new(
                e.kind(),
                format!(
                    "cannot listen on {address}: {e} (another program uses the port? give --port)"
                ),
            )
        })?;
        ready(listener.local_addr()?);
        let lab = Arc::new(Lab::new(Limits::default())?);
        serve(listener, lab, async {
            let _ = tokio::signal::ctrl_c().await;
        })
        .await
    })
}
