//! Turning a height map about its centre: exact quarter turns (no interpolation), and the pair
//! of an original and a turned map over the same area that the isotropy check compares.

use super::{crop, rotate};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use ndarray::Array2;

/// The map turned by `turns` quarter turns counter-clockwise (from +x toward +y) about its
/// centre, exactly: the point at `(x, y)` of the result is the point at `(y, -x)` of `map`
/// (about the centre), as [`rotate`] by 90° would give, but without interpolation; the grid and
/// spacings are swapped for odd turns.
pub fn quarter_turns(map: &HeightMap, turns: i64) -> Result<HeightMap> {
    let mut out = map.clone();
    for _ in 0..turns.rem_euclid(4) {
        let h = out.heights();
        let ny = h.nrows();
        let turned = Array2::from_shape_fn((h.ncols(), ny), |(iy, ix)| h[[ny - 1 - ix, iy]]);
        let meta = out.meta.clone();
        out = HeightMap::with_invalid(turned, out.dy(), out.dx())?;
        out.meta = meta;
    }
    Ok(out)
}

/// The number of quarter turns `angle_deg` is, when it is a whole number of them.
fn as_quarter_turns(angle_deg: f64) -> Option<i64> {
    let q = angle_deg / 90.0;
    ((q - q.round()).abs() < 1e-9).then(|| q.round() as i64)
}

/// The original map and the map turned by `angle_deg`, over the same area: for a quarter turn
/// the whole map and its exact turn; otherwise both cropped to the largest centred square that
/// lies inside the turned map. Returns `(original, turned, exact)`.
pub fn turned_pair(map: &HeightMap, angle_deg: f64) -> Result<(HeightMap, HeightMap, bool)> {
    if !angle_deg.is_finite() {
        return Err(SurfaceError::Invalid(format!(
            "rotation angle {angle_deg}° is not finite"
        )));
    }
    if let Some(turns) = as_quarter_turns(angle_deg) {
        return Ok((map.clone(), quarter_turns(map, turns)?, true));
    }
    // A centred square of half-side h turned by theta stays inside the half-extents (a, b) when
    // h (|cos| + |sin|) <= min(a, b); one point of margin keeps its corners off the edge.
    let theta = angle_deg.to_radians();
    let a = 0.5 * (map.nx() - 1) as f64 * map.dx();
    let b = 0.5 * (map.ny() - 1) as f64 * map.dy();
    let half = a.min(b) / (theta.cos().abs() + theta.sin().abs());
    // Points along an axis of `n` with spacing `d`: the same parity as `n`, so the crop is
    // centred exactly, and within 2·half less one point of margin.
    let side = |n: usize, d: f64| -> usize {
        let fit = ((2.0 * half / d).floor() as usize).saturating_sub(1);
        let mut m = fit.min(n);
        if (n - m) % 2 == 1 {
            m = m.saturating_sub(1);
        }
        m
    };
    let (cx, cy) = (side(map.nx(), map.dx()), side(map.ny(), map.dy()));
    if cx < 8 || cy < 8 {
        return Err(SurfaceError::Invalid(format!(
            "the {} × {} map leaves only {cx} × {cy} points inside its turn by {angle_deg}°; \
             use a larger map",
            map.nx(),
            map.ny()
        )));
    }
    let (x0, y0) = ((map.nx() - cx) / 2, (map.ny() - cy) / 2);
    let turned = rotate(map, theta)?;
    Ok((
        crop(map, x0, y0, cx, cy)?,
        crop(&turned, x0, y0, cx, cy)?,
        false,
    ))
}
