//! Scattering from surface topography: the geometric ray method and the scalar Kirchhoff
//! approximation turn a height map into BRDF curves and tables; analytic models for Gaussian
//! random surfaces serve as references.

pub mod analytic;
pub mod error;
pub mod geometry;
pub mod inplane;
pub mod kirchhoff;
pub mod ray;
pub mod table;

pub use error::{Result, ScatterError};
pub use geometry::{CurvePoint, Detector, Goniometer, InplaneCurve};
pub use inplane::InplaneMethod;
