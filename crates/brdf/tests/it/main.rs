//! Integration tests of gonio-brdf: tabulated BRDFs against independent references: the Cornell import (held-out error, colour, shape where the data are sparse), the MERL gamut mapping, and the exports read by Mitsuba 3 and Radiance. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod cayman;
mod cayman_colour;
mod common;
mod import_shape;
mod merl_gamut;
mod mitsuba;
mod radiance;
