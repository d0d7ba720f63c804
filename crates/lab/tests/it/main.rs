//! The lab's HTTP API, tested against a server on an ephemeral port (docs/lab.md): every
//! endpoint, bad requests, limits, concurrent clients and cancellation.

mod api;
mod browser;
mod handlers;
mod report;
mod server;
mod way_back;
