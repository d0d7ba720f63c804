//! Integration tests of gonio-brdf: the analytic models, distributions and samplers, tables and
//! their formats through the public API, and tabulated BRDFs against independent references:
//! the Cornell import (held-out error, colour, shape where the data are sparse), the MERL gamut
//! mapping, and the exports read by Mitsuba 3 and Radiance.
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod analysis;
mod astm;
mod bilinear;
mod cayman;
mod cayman_colour;
mod colour;
mod common;
mod coords;
mod csv;
mod discrete;
mod fit_samples;
mod fresnel;
mod import_shape;
mod merl;
mod merl_gamut;
mod microfacet;
mod mitsuba;
mod models;
mod quadrature;
mod radiance;
mod radiance_grazing;
mod radiance_tree;
mod radiance_xml;
mod sampler;
mod sampling;
mod spec;
mod tensor;
mod validate;
