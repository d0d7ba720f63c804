//! Integration tests of gonio-scatter: the scattering methods against analytic models and each other, and the BRDF tables they make. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod kirchhoff_vs_models;
mod ray_model;
mod ray_transmission;
mod table;
