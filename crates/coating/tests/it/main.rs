//! Integration tests of gonio-coating against independent implementations: the thin-film
//! stacks against the transfer-matrix method of the `tmm` package (PyPI, S. J. Byrnes), metal
//! flakes under a smooth coat against NIST's SCATMECH (PyPI `pySCATMECH`).

mod oracle;
mod scatmech_oracle;
mod tmm_oracle;
