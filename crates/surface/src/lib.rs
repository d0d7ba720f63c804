//! Surface topography for gonio: height maps read from instrument files or synthesised, their
//! levelling, cropping and rotation, ISO 25178-2 statistics, ISO 21920-2 statistics of line
//! profiles, ISO 16610-21 Gaussian profile filters and the wave-scan bands of a coating's
//! long-wave slope, and facet normals.
//!
//! ```no_run
//! let map = gonio_surface::io::read(std::path::Path::new("sample.x3p"))?;
//! println!("{} × {} points, dx = {} m", map.nx(), map.ny(), map.dx());
//! # Ok::<(), gonio_surface::SurfaceError>(())
//! ```

pub mod channel;
pub mod error;
pub mod gaussian_filter;
pub mod heightmap;
pub mod io;
pub mod normals;
pub mod ops;
pub mod profile_stats;
pub mod spline;
pub mod stats;
pub mod synth;
pub mod synth_psd;
pub mod waviness;

pub use channel::{Channel, ChannelSelector};
pub use error::{Result, SurfaceError};
pub use heightmap::{HeightMap, Metadata};
