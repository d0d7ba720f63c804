//! The error type of the `surface` crate: every failure names the file (when there is one) and
//! what was wrong with it.

use std::path::PathBuf;

/// Everything that can go wrong while reading, writing or processing a height map.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// The file could not be opened, read or written.
    #[error("{path}: {error}")]
    Io {
        path: PathBuf,
        /// What went wrong; printed in the message, so not also returned as `source()`.
        error: std::io::Error,
    },
    /// The file was read but its content is not a valid height map of the detected format.
    #[error("{path}: {format}: {message}")]
    Format {
        path: PathBuf,
        format: &'static str,
        message: String,
    },
    /// No reader recognised the file's content or extension.
    #[error(
        "{path}: unknown height-map format (supported: X3P, SDF, GSF, Gwyddion ASCII, Zygo .dat, Wyko .opd, Sensofar .plu, Digital Surf .sur, Alicona .al3d, FRT .frt, MountainsMap .mnt, NanoFocus .nms, TrueMap .tmd, Nanoscope .spm/.di, Nanosurf .nid, Igor .ibw, PicoView .mi, WSxM .top/.stp, Bruker .opdx, h= w= text matrix, x y z text list)"
    )]
    UnknownFormat { path: PathBuf },
    /// A height map that breaks the invariants of [`crate::HeightMap`] (bad spacing, NaN, size).
    #[error("invalid height map: {0}")]
    Invalid(String),
    /// A request that cannot be met (e.g. synthesis parameters that contradict each other or
    /// the grid); the message says which and why.
    #[error("{0}")]
    Request(String),
}

impl SurfaceError {
    /// A format error for `path` in the given format.
    pub fn format(
        path: impl Into<PathBuf>,
        format: &'static str,
        message: impl Into<String>,
    ) -> Self {
        SurfaceError::Format {
            path: path.into(),
            format,
            message: message.into(),
        }
    }

    /// An I/O error for `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        SurfaceError::Io {
            path: path.into(),
            error: source,
        }
    }
}

/// Result with [`SurfaceError`].
pub type Result<T, E = SurfaceError> = std::result::Result<T, E>;
