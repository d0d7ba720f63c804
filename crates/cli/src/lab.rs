//! `gonio lab`: start the formulation lab's web server (crate `gonio-lab`, docs/lab.md) and say
//! where to open it.

use clap::Args;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};

#[derive(Args, Debug)]
pub struct LabArgs {
    /// TCP port to listen on (0: any free port, printed).
    #[arg(long, default_value_t = 8765)]
    port: u16,
    /// Address to listen on. The default, 127.0.0.1, serves this machine only; another address
    /// (0.0.0.0: every interface) lets other machines use the lab and its uploads, with no
    /// authentication.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    host: IpAddr,
}

pub fn run(args: LabArgs) -> anyhow::Result<()> {
    if !args.host.is_loopback() {
        eprintln!(
            "gonio lab: warning: listening on {}: anyone who can reach this machine can use the \
             lab (no authentication)",
            args.host
        );
    }
    gonio_lab::run(SocketAddr::new(args.host, args.port), |address| {
        let shown = if address.ip().is_unspecified() {
            SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), address.port())
        } else {
            address
        };
        eprintln!("gonio lab: open http://{shown}/ in a browser (Ctrl-C stops the lab)");
    })?;
    eprintln!("gonio lab: stopped");
    Ok(())
}
