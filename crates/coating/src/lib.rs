//! gonio-coating: the optics of a coating's constituents, the layer above the surface's
//! topography. Thin films (the TiO2 layers of interference pigments; [`thin_film`]) and
//! pigmented layers by Kubelka-Munk two-constant theory ([`kubelka_munk`]). The layered stack
//! that joins them with the rough top interface and a clear coat into one BRDF is future work
//! (`docs/coatings.md` says what exists and what does not).

pub mod error;
pub mod kubelka_munk;
pub mod thin_film;

pub use error::{CoatingError, Result};
