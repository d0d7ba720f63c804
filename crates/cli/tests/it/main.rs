//! Integration tests of gonio-cli: the `gonio` binary as a user runs it: every command, its outputs, errors and exit codes. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod brdf_cli;
mod brdf_colour_cli;
mod brdf_compute_cli;
mod channels_cli;
mod coating_cli;
mod color_cli;
mod common;
mod compare_cli;
mod conformance_cli;
mod demo;
mod first_hour;
mod gloss_cli;
mod inplane_cli;
mod isotropy_cli;
mod kirchhoff_cli;
mod multiangle_cli;
mod orange_peel;
mod outputs;
mod pigments_cli;
mod radiance_picture;
mod render_cli;
mod surface_cli;
