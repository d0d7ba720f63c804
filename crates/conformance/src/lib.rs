//! gonio-conformance: appearance test scenes with analytic references, in the spirit of CIE
//! 171:2006 (test cases for lighting software) but for appearance, run on gonio's renderer and,
//! through gonio's exports, on Mitsuba 3 and Radiance (`gonio conformance`, `docs/conformance.md`).
//!
//! The scenes ([`scene`]): white and grey furnaces, a Lambertian plate under a uniform sky, a
//! smooth coat over a Kubelka-Munk base, a mirror reflecting a known emitter, and a metameric
//! pair under D65 and under illuminant A. Their closed forms are in [`optics`] and
//! [`metamer`]; each renderer's version of a scene is written by [`gonio`], [`mitsuba`] and
//! [`radiance`], the materials' tables that the peers render through gonio's exports by
//! [`export`]; [`compare`] measures a picture against the reference, [`loss`] says what each
//! export loses, and [`suite`] runs everything, gives the verdicts and writes the pictures and
//! `results.json`. The HTML report is composed above, by `gonio_report::conformance`.
//!
//! ```no_run
//! use gonio_conformance::{Options, Renderer, run};
//! let results = run(&Options { renderers: vec![Renderer::Gonio], spp: 64, dir: "out".into() })?;
//! assert!(results.passed());
//! # Ok::<(), gonio_conformance::Error>(())
//! ```

pub mod compare;
pub mod error;
pub mod export;
pub mod geometry;
pub mod gonio;
pub mod loss;
pub mod metamer;
pub mod mitsuba;
pub mod optics;
mod python;
pub mod radiance;
pub mod reference;
pub mod scene;
pub mod suite;

pub use error::{Error, Result};
pub use python::oracles_required;
pub use suite::{Options, Renderer, Results, Route, Verdict, run};
