//! gonio-coating: coatings from their constituents. Thin films (the TiO2 layers of
//! interference pigments; [`thin_film`]), pigmented layers by Kubelka-Munk two-constant theory
//! ([`kubelka_munk`]), and a smooth clear coat over a diffuse base with every internal
//! reflection counted ([`clear_coat`]), described in TOML ([`description`]). A rough top
//! interface and effect flakes are future work (`docs/coatings.md` says what exists and what
//! does not).

pub mod clear_coat;
pub mod description;
pub mod error;
pub mod kubelka_munk;
pub mod thin_film;

pub use error::{CoatingError, Result};
