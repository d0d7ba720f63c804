//! Integration tests of gonio-coating against independent implementations: the thin-film
//! stacks against the transfer-matrix method of the `tmm` package (PyPI, S. J. Byrnes), metal
//! flakes under a smooth coat against NIST's SCATMECH (PyPI `pySCATMECH`), the layered walk
//! against a brute-force photon simulation of its model written in the test; and the clear
//! coat, flakes, Kubelka-Munk layers, thin films and the coating system through the public API.
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod basecoat;
mod clear_coat;
mod flakes;
mod glint;
mod kubelka_munk;
mod oracle;
mod pigment_library;
mod scatmech_oracle;
mod system;
mod thin_film;
mod tmm_oracle;
mod walk_brute_force;
mod walk_brute_force_basecoat;
