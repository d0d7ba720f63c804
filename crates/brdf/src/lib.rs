//! BRDFs for gonio: Fresnel reflectance, microfacet distributions, analytic models, tabulated
//! BRDFs and their file formats.

pub mod bxdf;
pub mod error;
pub mod fit;
pub mod formats;
pub mod fresnel;
pub mod gbrdf;
pub mod microfacet;
pub mod models;
pub mod quadrature;
pub mod sampling;
pub mod table;
pub mod trig;
pub mod validate;

pub use bxdf::{Brdf, BrdfSample, Rgb, SpectralBrdf};
pub use error::{BrdfError, Result};
pub use fresnel::Ior;
