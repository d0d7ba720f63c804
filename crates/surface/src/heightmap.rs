//! The [`HeightMap`] type: a regular grid of surface heights in metres with its spacings, a mask
//! of measured points and the metadata the instrument file carried.

use crate::channel::Channel;
use crate::error::{Result, SurfaceError};
use ndarray::Array2;
use std::path::PathBuf;

/// Where a height map came from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Metadata {
    /// Instrument (manufacturer and model) as the file names it.
    pub instrument: Option<String>,
    /// The file the map was read from.
    pub source: Option<PathBuf>,
    /// Date of the measurement or file, as the file writes it.
    pub date: Option<String>,
    /// Name of the format the map was read from ("X3P", "Zygo MetroPro", ...).
    pub format: Option<String>,
    /// Any other key/value pairs worth showing to a person (comments, operator, ...).
    pub extra: Vec<(String, String)>,
    /// The channels the file holds (one for single-channel formats).
    pub channels: Vec<Channel>,
    /// Index in `channels` of the channel this map was read from.
    pub channel: usize,
}

/// Key under which readers record warnings in [`Metadata::extra`] (e.g. a checksum mismatch).
pub const WARNING_KEY: &str = "warning";

impl Metadata {
    /// The warnings a reader raised about the file (a checksum that does not match, ...), for a
    /// program to show; the map was read all the same.
    pub fn warnings(&self) -> impl Iterator<Item = &str> {
        self.extra
            .iter()
            .filter(|(k, _)| k == WARNING_KEY)
            .map(|(_, v)| v.as_str())
    }

    /// Record a warning about the file in [`Metadata::extra`].
    pub fn warn(&mut self, message: impl Into<String>) {
        self.extra.push((WARNING_KEY.to_string(), message.into()));
    }
}

/// Largest number of points a height map may hold (2^31: a 46 341 × 46 341 map, 16 GiB of f64).
pub const MAX_POINTS: usize = 1 << 31;

/// A height map: `nx × ny` heights in metres on a regular grid of spacing `dx × dy` metres.
///
/// Heights are stored row-major with shape `(ny, nx)`, indexed `[iy, ix]`; point `(ix, iy)` lies
/// at `x = ix·dx`, `y = iy·dy`. Points the instrument did not measure are invalid: their height is
/// NaN and the mask (when present) is false there. Every valid height is finite.
///
/// A line profile (a file holding one measured line) is a map of one row marked as a profile
/// ([`HeightMap::is_profile`]); its `dy` equals `dx` and means nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    heights: Array2<f64>,
    valid: Option<Array2<bool>>,
    dx: f64,
    dy: f64,
    profile: bool,
    /// Where the map came from.
    pub meta: Metadata,
}

impl HeightMap {
    /// A fully measured map. Fails if any height is not finite or a spacing is not a positive,
    /// finite number.
    pub fn new(heights: Array2<f64>, dx: f64, dy: f64) -> Result<Self> {
        if let Some(bad) = heights.iter().find(|h| !h.is_finite()) {
            return Err(SurfaceError::Invalid(format!(
                "height {bad} is not finite (use HeightMap::with_invalid for non-measured points)"
            )));
        }
        Self::with_invalid(heights, dx, dy)
    }

    /// A map whose NaN heights mark non-measured points. Infinite heights are an error.
    pub fn with_invalid(heights: Array2<f64>, dx: f64, dy: f64) -> Result<Self> {
        check_spacing(dx, dy)?;
        let (ny, nx) = heights.dim();
        if nx == 0 || ny == 0 {
            return Err(SurfaceError::Invalid(format!("empty grid {nx} × {ny}")));
        }
        if nx.saturating_mul(ny) > MAX_POINTS {
            return Err(SurfaceError::Invalid(format!(
                "grid {nx} × {ny} exceeds the limit of {MAX_POINTS} points"
            )));
        }
        if heights.iter().any(|h| h.is_infinite()) {
            return Err(SurfaceError::Invalid("infinite height".into()));
        }
        let any_invalid = heights.iter().any(|h| h.is_nan());
        let valid = any_invalid.then(|| heights.mapv(|h| !h.is_nan()));
        Ok(HeightMap {
            heights,
            valid,
            dx,
            dy,
            profile: false,
            meta: Metadata::default(),
        })
    }

    /// A line profile: heights in metres at spacing `dx` along the line, NaN where not measured.
    pub fn profile(heights: Vec<f64>, dx: f64) -> Result<Self> {
        let n = heights.len();
        let row = Array2::from_shape_vec((1, n), heights)
            .map_err(|e| SurfaceError::Invalid(format!("profile of {n} points: {e}")))?;
        HeightMap::with_invalid(row, dx, dx)?.into_profile()
    }

    /// This one-row map marked as a line profile; an error when it has more than one row.
    pub fn into_profile(mut self) -> Result<Self> {
        if self.ny() != 1 {
            return Err(SurfaceError::Invalid(format!(
                "a line profile has one row, not {}",
                self.ny()
            )));
        }
        self.profile = true;
        Ok(self)
    }

    /// Whether this map is a line profile (one measured line) rather than an areal map.
    pub fn is_profile(&self) -> bool {
        self.profile
    }

    /// Number of points along x (columns).
    pub fn nx(&self) -> usize {
        self.heights.ncols()
    }

    /// Number of points along y (rows).
    pub fn ny(&self) -> usize {
        self.heights.nrows()
    }

    /// Spacing along x in metres.
    pub fn dx(&self) -> f64 {
        self.dx
    }

    /// Spacing along y in metres.
    pub fn dy(&self) -> f64 {
        self.dy
    }

    /// Heights in metres, shape `(ny, nx)`; NaN at invalid points.
    pub fn heights(&self) -> &Array2<f64> {
        &self.heights
    }

    /// Height at `(ix, iy)` in metres, or `None` where the point was not measured.
    pub fn get(&self, ix: usize, iy: usize) -> Option<f64> {
        let h = self.heights[[iy, ix]];
        (!h.is_nan()).then_some(h)
    }

    /// The validity mask (`true` = measured), or `None` when every point is valid.
    pub fn mask(&self) -> Option<&Array2<bool>> {
        self.valid.as_ref()
    }

    /// Whether point `(ix, iy)` was measured.
    pub fn is_valid(&self, ix: usize, iy: usize) -> bool {
        self.valid.as_ref().is_none_or(|m| m[[iy, ix]])
    }

    /// Number of measured points.
    pub fn valid_count(&self) -> usize {
        match &self.valid {
            None => self.heights.len(),
            Some(m) => m.iter().filter(|&&v| v).count(),
        }
    }

    /// Fraction of measured points, in [0, 1].
    pub fn valid_fraction(&self) -> f64 {
        self.valid_count() as f64 / self.heights.len() as f64
    }

    /// Replace the heights (same shape), keeping spacing and metadata; NaN marks invalid points.
    pub fn with_heights(&self, heights: Array2<f64>) -> Result<Self> {
        let mut map = HeightMap::with_invalid(heights, self.dx, self.dy)?;
        map.profile = self.profile && map.ny() == 1;
        map.meta = self.meta.clone();
        Ok(map)
    }

    /// Same heights on a new spacing (metres), e.g. after a file's units were corrected.
    pub fn with_spacing(mut self, dx: f64, dy: f64) -> Result<Self> {
        check_spacing(dx, dy)?;
        self.dx = dx;
        self.dy = dy;
        Ok(self)
    }

    /// Take the heights out of the map.
    pub fn into_heights(self) -> Array2<f64> {
        self.heights
    }
}

fn check_spacing(dx: f64, dy: f64) -> Result<()> {
    for (name, d) in [("dx", dx), ("dy", dy)] {
        if !(d.is_finite() && d > 0.0) {
            return Err(SurfaceError::Invalid(format!(
                "spacing {name} = {d} m must be a positive, finite number"
            )));
        }
    }
    Ok(())
}
