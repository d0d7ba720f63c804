//! gonio-coating: coatings from their constituents. Thin films (the TiO2 layers of
//! interference pigments; [`thin_film`]), pigmented layers by Kubelka-Munk two-constant theory
//! ([`kubelka_munk`]) with a built-in library of measured pigments ([`pigment_library`]), a smooth clear coat over a diffuse base with every internal reflection
//! counted exactly ([`clear_coat`]), and the general system ([`system`]): a smooth or rough top
//! interface ([`interface`]), an absorbing clear coat, aluminium or interference flakes over
//! the base ([`flakes`]) or inside a pigmented basecoat ([`basecoat`]), coupled by position-free Monte Carlo layered transport ([`layered`]);
//! described in TOML ([`description`]). `docs/coatings.md` says what is modelled and how it is
//! validated.

pub mod basecoat;
pub mod cell;
pub mod clear_coat;
mod compensation;
pub mod description;
pub mod error;
pub mod flakes;
pub mod glint;
pub mod interface;
pub mod kubelka_munk;
pub mod layered;
pub mod pigment_library;
pub mod system;
pub mod thin_film;

pub use error::{CoatingError, Result};
