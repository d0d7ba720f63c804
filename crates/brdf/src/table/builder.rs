//! Filling a table: from any [`Brdf`] (tabulating an analytic model), from a closure, or cell by
//! cell from another engine (the scattering methods), which reads each cell's pair of directions
//! from [`TableBuilder::cells`] and writes values with [`TableBuilder::set`].

use super::{BrdfTable, Channels, HalfDiff, MIN_COS, Provenance, Resolution, Storage};
use crate::bxdf::Brdf;
use crate::error::{BrdfError, Result};
use glam::DVec3;
use rayon::prelude::*;

/// One cell (grid node) of a table: its index and the pair of directions it stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// Linear index, see [`Resolution::cell_index`].
    pub index: usize,
    /// Direction toward the light, unit length, local frame.
    pub wi: DVec3,
    /// Direction toward the viewer.
    pub wo: DVec3,
    /// The half/difference angles of the pair.
    pub angles: HalfDiff,
}

impl Cell {
    /// The cell of a linear index, the sines and cosines of its angles looked up in `trig`.
    fn of_with(res: &Resolution, index: usize, trig: &NodeTrig) -> Cell {
        let angles = res.cell_angles(index);
        let [ph, th, td, pd] = res.cell_indices(index);
        let (wi, wo) = angles.to_dirs_with([
            trig.theta_h[th],
            trig.phi_h[ph],
            trig.theta_d[td],
            trig.phi_d[pd],
        ]);
        Cell {
            index,
            wi,
            wo,
            angles,
        }
    }

    /// Whether both directions are above the horizon (by more than 0.06°), i.e. the cell holds
    /// data; other cells stay NaN.
    pub fn is_above_horizon(&self) -> bool {
        self.wi.z > MIN_COS && self.wo.z > MIN_COS
    }
}

/// The `(sine, cosine)` of each node angle along each axis of a grid, found once: a cell's
/// directions are then products of these (six `sin_cos` per cell were a tenth of a ray table's
/// time).
struct NodeTrig {
    theta_h: Vec<(f64, f64)>,
    phi_h: Vec<(f64, f64)>,
    theta_d: Vec<(f64, f64)>,
    phi_d: Vec<(f64, f64)>,
}

impl NodeTrig {
    fn new(res: &Resolution) -> NodeTrig {
        let along = |n: usize, angle: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
            (0..n).map(|k| angle(k).sin_cos()).collect()
        };
        let at = |ph, th, td, pd| res.cell_angles(res.cell_index(ph, th, td, pd));
        NodeTrig {
            theta_h: along(res.theta_h, &|k| at(0, k, 0, 0).theta_h),
            phi_h: along(res.phi_h, &|k| at(k, 0, 0, 0).phi_h),
            theta_d: along(res.theta_d, &|k| at(0, 0, k, 0).theta_d),
            phi_d: along(res.phi_d, &|k| at(0, 0, 0, k).phi_d),
        }
    }
}

/// A table under construction. Cells above the horizon start at zero, the others are NaN.
pub struct TableBuilder {
    res: Resolution,
    channels: Channels,
    provenance: Provenance,
    values: Vec<f32>,
    trig: NodeTrig,
}

impl TableBuilder {
    /// An empty table of this grid and these channels.
    pub fn new(res: Resolution, channels: Channels) -> Result<TableBuilder> {
        res.validate().map_err(BrdfError::Invalid)?;
        channels.validate().map_err(BrdfError::Invalid)?;
        let nc = channels.count();
        let trig = NodeTrig::new(&res);
        let mut values = vec![0.0f32; res.cell_count() * nc];
        values.par_chunks_mut(nc).enumerate().for_each(|(i, v)| {
            if !Cell::of_with(&res, i, &trig).is_above_horizon() {
                v.fill(f32::NAN);
            }
        });
        Ok(TableBuilder {
            res,
            channels,
            provenance: Provenance::default(),
            values,
            trig,
        })
    }

    /// Set where the table comes from.
    pub fn with_provenance(mut self, provenance: Provenance) -> TableBuilder {
        self.provenance = provenance;
        self
    }

    /// The grid.
    pub fn resolution(&self) -> Resolution {
        self.res
    }

    /// The channels.
    pub fn channels(&self) -> &Channels {
        &self.channels
    }

    /// The cells that hold data (both directions above the horizon), in index order.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        (0..self.res.cell_count())
            .map(|i| Cell::of_with(&self.res, i, &self.trig))
            .filter(Cell::is_above_horizon)
    }

    /// The cell of a linear index.
    pub fn cell(&self, index: usize) -> Cell {
        Cell::of_with(&self.res, index, &self.trig)
    }

    /// Set one channel of one cell (f in 1/sr). Cells below the horizon and out-of-range indices
    /// are errors.
    pub fn set(&mut self, cell: usize, channel: usize, value: f64) -> Result<()> {
        let nc = self.channels.count();
        if cell >= self.res.cell_count() || channel >= nc {
            return Err(BrdfError::Invalid(format!(
                "cell {cell} channel {channel} is outside a {} table of {nc} channels",
                self.res.describe()
            )));
        }
        let slot = &mut self.values[cell * nc + channel];
        if slot.is_nan() {
            return Err(BrdfError::Invalid(format!(
                "cell {cell} lies below the horizon"
            )));
        }
        *slot = value as f32;
        Ok(())
    }

    /// Fill every cell above the horizon from a function of the cell, in parallel; the function
    /// writes the channel values into its slice. Deterministic whatever the thread count.
    pub fn fill(&mut self, f: impl Fn(&Cell, &mut [f64]) + Sync) {
        self.visit(false, None, f);
    }

    /// [`TableBuilder::fill`] for a reciprocal BRDF: `f` runs only in each class's
    /// [`Resolution::representative_cell`] (with `mirror`, a BRDF also symmetric about the plane
    /// of incidence) and the class's other cells take its values.
    pub fn fill_symmetric(&mut self, mirror: bool, f: impl Fn(&Cell, &mut [f64]) + Sync) {
        self.visit(false, Some(mirror), f);
    }

    /// [`TableBuilder::fill`] with the slice holding the cell's values so far (an earlier
    /// fill's): a second pass that refines them.
    pub fn refine(&mut self, f: impl Fn(&Cell, &mut [f64]) + Sync) {
        self.visit(true, None, f);
    }

    /// [`TableBuilder::refine`] on the representatives of [`TableBuilder::fill_symmetric`].
    pub fn refine_symmetric(&mut self, mirror: bool, f: impl Fn(&Cell, &mut [f64]) + Sync) {
        self.visit(true, Some(mirror), f);
    }

    /// Every cell above the horizon through `f`, its slice zeroed or, with `current`, holding
    /// the cell's values; with `symmetric` (whether the mirror counts), only the
    /// representatives, whose values are then copied to the rest of their class (a class's
    /// cells are all above the horizon or all below: the symmetries keep both cosines).
    fn visit(
        &mut self,
        current: bool,
        symmetric: Option<bool>,
        f: impl Fn(&Cell, &mut [f64]) + Sync,
    ) {
        let res = self.res;
        let nc = self.channels.count();
        let trig = &self.trig;
        let computed = |i: usize| symmetric.is_none_or(|m| res.representative_cell(i, m) == i);
        self.values.par_chunks_mut(nc).enumerate().for_each_init(
            || vec![0.0f64; nc],
            |buf, (i, out)| {
                let cell = Cell::of_with(&res, i, trig);
                if cell.is_above_horizon() && computed(i) {
                    if current {
                        buf.iter_mut()
                            .zip(out.iter())
                            .for_each(|(b, o)| *b = f64::from(*o));
                    } else {
                        buf.fill(0.0);
                    }
                    f(&cell, buf);
                    for (o, v) in out.iter_mut().zip(buf.iter()) {
                        *o = *v as f32;
                    }
                }
            },
        );
        if let Some(mirror) = symmetric {
            // The representative is the class's lowest index, so it is set before its copies.
            for i in 0..res.cell_count() {
                let r = res.representative_cell(i, mirror);
                if r != i {
                    self.values.copy_within(r * nc..(r + 1) * nc, i * nc);
                }
            }
        }
    }

    /// The finished table.
    pub fn build(self) -> Result<BrdfTable> {
        BrdfTable::from_storage(
            self.res,
            self.channels,
            self.provenance,
            Storage::Owned(self.values),
        )
    }
}

impl BrdfTable {
    /// Tabulate any BRDF on a grid: RGB channels, or one channel (the mean of the three) when
    /// `mono` is set.
    pub fn from_brdf(
        brdf: &dyn Brdf,
        res: Resolution,
        mono: bool,
        provenance: Provenance,
    ) -> Result<BrdfTable> {
        let channels = if mono { Channels::Mono } else { Channels::Rgb };
        let mut b = TableBuilder::new(res, channels)?.with_provenance(provenance);
        b.fill(|cell, out| {
            let f = brdf.eval(cell.wo, cell.wi);
            if mono {
                out[0] = (f.x + f.y + f.z) / 3.0;
            } else {
                out.copy_from_slice(&f.to_array());
            }
        });
        b.build()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::coords::dir;
    use std::f64::consts::PI;

    /// A smooth, isotropic, non-reciprocal test function of the two directions.
    fn smooth(wi: DVec3, wo: DVec3) -> f64 {
        0.3 + 0.2 * wi.z + 0.1 * wo.z * wo.z + 0.05 * wi.dot(wo)
    }

    /// A cell's directions from the looked-up sines and cosines are those of its angles to the
    /// bit, along all four axes of an anisotropic grid.
    #[test]
    fn looked_up_trig_gives_each_cells_directions() {
        let res = Resolution::anisotropic(7, 5, 8, 6);
        let trig = NodeTrig::new(&res);
        for i in 0..res.cell_count() {
            let c = Cell::of_with(&res, i, &trig);
            assert_eq!(c.angles, res.cell_angles(i));
            assert_eq!((c.wi, c.wo), c.angles.to_dirs(), "{:?}", c.angles);
        }
    }

    #[test]
    fn cells_reproduce_their_function_and_interpolation_converges() {
        let mut errs = vec![];
        for n in [8usize, 16, 32] {
            let mut b =
                TableBuilder::new(Resolution::isotropic(n, n, 2 * n), Channels::Mono).unwrap();
            b.fill(|c, out| out[0] = smooth(c.wi, c.wo));
            let t = b.build().unwrap();
            // At the cells themselves the table is exact (to f32).
            let trig = NodeTrig::new(&t.resolution());
            for c in (0..t.resolution().cell_count())
                .step_by(7)
                .map(|i| Cell::of_with(&t.resolution(), i, &trig))
            {
                if c.is_above_horizon() {
                    let mut v = [0.0];
                    t.eval_angles(&c.angles, &mut v);
                    assert!((v[0] - smooth(c.wi, c.wo)).abs() < 1e-6);
                }
            }
            // Between cells the interpolation error falls with the spacing.
            let mut max = 0.0f64;
            for k in 0..400 {
                let wi = dir(
                    0.05 + 1.3 * ((k * 37 % 400) as f64 / 400.0),
                    2.0 * PI * (k as f64 / 400.0),
                );
                let wo = dir(
                    0.05 + 1.3 * ((k * 91 % 400) as f64 / 400.0),
                    0.3 + 5.0 * (k as f64 / 400.0),
                );
                let mut v = [0.0];
                t.eval_channels(wo, wi, &mut v);
                max = max.max((v[0] - smooth(wi, wo)).abs());
            }
            errs.push(max);
        }
        assert!(
            errs[2] < errs[0] / 2.5,
            "interpolation does not converge: {errs:?}"
        );
        assert!(errs[2] < 0.02, "{errs:?}");
    }

    /// A table of a reciprocal function symmetric about the plane of incidence (of the two
    /// cosines and the angle between the directions, symmetric in them) filled on the
    /// representatives alone equals the one filled everywhere to f32 rounding, with the
    /// function called only on representatives (a quarter of the phi_d nodes and one more per
    /// row); refining does the same.
    #[test]
    fn symmetric_fill_equals_the_full_fill() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let f = |c: &Cell| {
            0.3 + 0.2 * (c.wi.z + c.wo.z) + 0.1 * c.wi.z * c.wo.z + 0.05 * c.wi.dot(c.wo)
        };
        let res = Resolution::isotropic(9, 8, 24);
        let mut full = TableBuilder::new(res, Channels::Mono).unwrap();
        full.fill(|c, out| out[0] = f(c));
        let calls = AtomicUsize::new(0);
        let mut sym = TableBuilder::new(res, Channels::Mono).unwrap();
        sym.fill_symmetric(true, |c, out| {
            calls.fetch_add(1, Ordering::Relaxed);
            out[0] = f(c);
        });
        sym.refine_symmetric(true, |_, out| out[0] *= 2.0);
        full.refine(|_, out| out[0] *= 2.0);
        let representatives = full
            .cells()
            .filter(|c| res.representative_cell(c.index, true) == c.index)
            .count();
        assert_eq!(calls.into_inner(), representatives);
        assert!(representatives * 3 < full.cells().count());
        for (a, b) in full.values.iter().zip(&sym.values) {
            assert!(a.is_nan() == b.is_nan());
            if !a.is_nan() {
                assert!((a - b).abs() <= 2e-6 * a.abs(), "{a} against {b}");
            }
        }
    }

    #[test]
    fn set_checks_its_arguments() {
        let mut b = TableBuilder::new(Resolution::isotropic(4, 4, 4), Channels::Rgb).unwrap();
        let first = b.cells().next().unwrap();
        assert!(b.set(first.index, 2, 0.5).is_ok());
        assert!(b.set(first.index, 3, 0.5).is_err());
        assert!(b.set(usize::MAX / 8, 0, 0.5).is_err());
        let below = (0..64)
            .map(|i| b.cell(i))
            .find(|c| !c.is_above_horizon())
            .unwrap();
        assert!(b.set(below.index, 0, 1.0).is_err());
        let t = b.build().unwrap();
        assert_eq!(t.cell_values(first.index)[2], 0.5);
    }
}
