//! Text `x y z` point lists on a regular grid: one point per line, three whitespace-separated
//! numbers, in any order (SurfaceTopography's `xyz-1.txt` lists x slowest, y fastest).
//!
//! The distinct x and y values must be evenly spaced (each within 1% of a spacing of its place
//! on the grid), and every grid point must be listed exactly once; `nan` as z marks a point that
//! was not measured. Point (ix, iy) of the map is the point at the ix-th smallest x and the
//! iy-th smallest y.
//!
//! Units: such a list states none. The reader takes the numbers as metres, gonio's unit, rather
//! than guessing a scale (µm or nm would be as plausible for a profilometer export and the file
//! cannot tell them apart), and says so in a warning in the metadata, so that a program can ask
//! for the real unit and rescale with `HeightMap::with_spacing` and `with_heights`.

use super::common::grid_points;
use super::text::{looks_like_xyz, numbered_lines, numbers, utf8};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use ndarray::Array2;
use std::path::Path;

pub(crate) const NAME: &str = "x y z point list";

/// The warning every map read from a point list carries.
pub(crate) const UNIT_WARNING: &str =
    "the x y z list states no units: x, y and z were read as metres";

/// How far (as a fraction of the spacing) a coordinate may lie from its grid line.
const GRID_TOLERANCE: f64 = 0.01;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    looks_like_xyz(bytes)
}

pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let text = utf8(path, NAME, bytes)?;
    let mut points = Vec::new();
    for (number, line) in numbered_lines(text) {
        let values = numbers(line).filter(|v| v.len() == 3).ok_or_else(|| {
            fail(format!(
                "line {number}: '{line}' is not three numbers x y z"
            ))
        })?;
        let (x, y, z) = (values[0], values[1], values[2]);
        if !(x.is_finite() && y.is_finite()) || z.is_infinite() {
            return Err(fail(format!(
                "line {number}: x and y must be finite and z finite or nan"
            )));
        }
        points.push((x, y, z));
    }
    if points.is_empty() {
        return Err(fail("the file lists no points".into()));
    }
    let xs = Axis::of(path, "x", points.iter().map(|p| p.0))?;
    let ys = Axis::of(path, "y", points.iter().map(|p| p.1))?;
    let (nx, ny) = (xs.count, ys.count);
    let expected = grid_points(path, NAME, nx as u64, ny as u64)?;
    if points.len() != expected {
        return Err(fail(format!(
            "{} points do not fill the grid of {nx} distinct x × {ny} distinct y = {expected} \
             points: the list is not a complete regular grid",
            points.len()
        )));
    }
    let mut grid = Array2::from_elem((ny, nx), None);
    for (k, &(x, y, z)) in points.iter().enumerate() {
        let (ix, iy) = (xs.index(x), ys.index(y));
        if grid[[iy, ix]].replace(z).is_some() {
            return Err(fail(format!(
                "point {} (x = {x}, y = {y}) lies on a grid point already listed",
                k + 1
            )));
        }
    }
    // Every cell is filled: as many points as cells, and none listed twice.
    let heights = grid.mapv(|z| z.unwrap_or(f64::NAN));
    let mut map = HeightMap::with_invalid(heights, xs.step, ys.step).map_err(|e| match e {
        SurfaceError::Invalid(m) => fail(m),
        other => other,
    })?;
    map.meta.warn(UNIT_WARNING);
    Ok(map)
}

/// The grid lines of one coordinate: first value, spacing and count.
struct Axis {
    first: f64,
    step: f64,
    count: usize,
}

impl Axis {
    /// The evenly spaced distinct values of `values`, or an error naming the coordinate.
    fn of(path: &Path, name: &str, values: impl Iterator<Item = f64>) -> Result<Axis> {
        let fail = |m: String| SurfaceError::format(path, NAME, m);
        let mut sorted: Vec<f64> = values.collect();
        sorted.sort_by(f64::total_cmp);
        let (first, last) = (sorted[0], sorted[sorted.len() - 1]);
        let span = last - first;
        // Distinct values: gaps larger than a millionth of the span.
        let mut distinct = vec![first];
        for &v in &sorted[1..] {
            if v - distinct[distinct.len() - 1] > 1e-6 * span {
                distinct.push(v);
            }
        }
        let count = distinct.len();
        if count < 2 {
            return Err(fail(format!(
                "every point has {name} = {first}: a profile, not a map"
            )));
        }
        let step = span / (count - 1) as f64;
        if let Some((k, v)) = distinct
            .iter()
            .enumerate()
            .find(|&(k, &v)| (v - (first + k as f64 * step)).abs() > GRID_TOLERANCE * step)
        {
            return Err(fail(format!(
                "the {count} distinct {name} values are not evenly spaced: {name} = {v} is not \
                 within 1% of a spacing of {}",
                first + k as f64 * step
            )));
        }
        Ok(Axis { first, step, count })
    }

    /// Index of the grid line nearest to `v`.
    fn index(&self, v: f64) -> usize {
        (((v - self.first) / self.step).round() as usize).min(self.count - 1)
    }
}
