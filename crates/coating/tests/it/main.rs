//! Integration tests of gonio-coating against independent implementations: the thin-film
//! stacks against the transfer-matrix method of the `tmm` package (PyPI, S. J. Byrnes).

mod tmm_oracle;
