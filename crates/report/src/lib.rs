//! gonio-report: the reports gonio composes, in one library that every front end calls (the
//! `gonio` command, the Python package, the lab): the HTML page of sections, text, tables and
//! figures ([`html`]), the booth's closure against the multi-angle instrument ([`closure`]),
//! the demo that runs the whole pipeline on embedded data and writes it up
//! ([`demo`]: `gonio demo`, `gonio.report.demo`), the conformance suite's report
//! ([`conformance`]: `gonio conformance`, `gonio.report.conformance`), and the files and plots
//! the demo shares with
//! the commands that write the same ones ([`study`], [`plots`], [`isotropy_files`],
//! [`texture_pictures`], [`orange_peel`], [`units`], [`output`]). Above `formulation`,
//! `render` and `conformance`, below `cli`, `python` and `lab`. It computes nothing itself: the
//! physics is the libraries' below; it reports progress through [`gonio_io::Progress`] and never writes to the
//! terminal.

pub mod closure;
pub mod conformance;
pub mod demo;
pub mod error;
pub mod html;
pub mod isotropy_files;
pub mod orange_peel;
pub mod output;
pub mod plots;
pub mod study;
pub mod texture_pictures;
pub mod units;

pub use error::{ReportError, Result};
