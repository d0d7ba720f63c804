//! The samples of a scattered fit sorted into cells of their regression coordinates, so that a
//! query visits only the samples within the kernel's reach.

use super::{Bandwidths, DIM};

/// The samples sorted into a grid of cells over the first two coordinates `(u, t)`, and within
/// each cell by the third, `s cos p`, so that a query visits only the samples of the cells
/// within the kernel's reach, and of those only the ones within its reach in `s cos p`, instead
/// of all of them (the kernel is cut at 3.5 bandwidths: a sample farther than that in any
/// coordinate weighs 0). The third coordinate matters: its bandwidths are ten times narrower
/// than a cell, so most samples of the cells near a query lie outside the kernel in it, and
/// testing them was most of an import's time. The samples a query visits are taken in their own
/// order, as a scan of all of them would, so the sums, and so every fitted value, are the same
/// to the bit.
pub(super) struct Cells {
    /// The grid's lower corner in `u` and `t`.
    origin: [f64; 2],
    /// Cells along `u` and `t`.
    count: [usize; 2],
    /// `samples[start[c]..start[c + 1]]`: the samples in cell `c` (`u` index slowest), in
    /// increasing `s cos p`.
    start: Vec<usize>,
    samples: Vec<usize>,
    /// `keys[i]`: the `s cos p` of `samples[i]`.
    keys: Vec<f64>,
}

impl Cells {
    /// The size of a cell in `u` and `t`: half the smallest reach of the cross-validated
    /// bandwidths (3.5 × 0.02 in `u`, 3.5 × 0.05 in `t`), so that a query with the narrowest
    /// kernel visits about three cells per coordinate.
    pub(super) const SIZE: [f64; 2] = [0.035, 0.0875];

    pub(super) fn new(points: &[[f64; DIM]]) -> Cells {
        let origin = [0, 1].map(|k| points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
        let count = [0, 1].map(|k| {
            let hi = points.iter().map(|p| p[k]).fold(origin[k], f64::max);
            ((hi - origin[k]) / Self::SIZE[k]).floor() as usize + 1
        });
        let mut cells = Cells {
            origin,
            count,
            start: Vec::new(),
            samples: Vec::new(),
            keys: Vec::new(),
        };
        let cell_of: Vec<usize> = points
            .iter()
            .map(|p| cells.index(0, p[0]) * count[1] + cells.index(1, p[1]))
            .collect();
        cells.start = vec![0; count[0] * count[1] + 1];
        for &c in &cell_of {
            cells.start[c + 1] += 1;
        }
        for c in 1..cells.start.len() {
            cells.start[c] += cells.start[c - 1];
        }
        let mut next = cells.start.clone();
        cells.samples = vec![0; points.len()];
        for (j, &c) in cell_of.iter().enumerate() {
            cells.samples[next[c]] = j;
            next[c] += 1;
        }
        for c in 0..count[0] * count[1] {
            cells.samples[cells.start[c]..cells.start[c + 1]]
                .sort_by(|&i, &j| points[i][2].total_cmp(&points[j][2]));
        }
        cells.keys = cells.samples.iter().map(|&j| points[j][2]).collect();
        cells
    }

    /// The cell index along coordinate `k` of the value `v`, clamped to the grid.
    pub(super) fn index(&self, k: usize, v: f64) -> usize {
        (((v - self.origin[k]) / Self::SIZE[k]).floor().max(0.0) as usize).min(self.count[k] - 1)
    }

    /// The runs of `samples` (ranges of indices into it) that hold every sample which may lie
    /// within the kernel of bandwidths `bw` about `x`: one run per cell within reach in `u` and
    /// `t`, cut to the samples within reach in `s cos p`.
    pub(super) fn runs(
        &self,
        x: &[f64; DIM],
        bw: &Bandwidths,
    ) -> impl Iterator<Item = (usize, usize)> {
        // 3.5 bandwidths, widened by a part in a million against rounding at the boundary.
        let reach = [0, 1, 2].map(|k| 3.5 * bw[k] * (1.0 + 1e-6));
        let [u0, u1] = [x[0] - reach[0], x[0] + reach[0]].map(|v| self.index(0, v));
        let [t0, t1] = [x[1] - reach[1], x[1] + reach[1]].map(|v| self.index(1, v));
        let (lo, hi) = (x[2] - reach[2], x[2] + reach[2]);
        (u0..=u1)
            .flat_map(move |iu| (iu * self.count[1] + t0)..=(iu * self.count[1] + t1))
            .map(move |c| {
                let (a, b) = (self.start[c], self.start[c + 1]);
                let keys = &self.keys[a..b];
                (
                    a + keys.partition_point(|&k| k < lo),
                    a + keys.partition_point(|&k| k <= hi),
                )
            })
    }

    /// Calls `visit` with every sample that may lie within the kernel of bandwidths `bw` about
    /// `x`, in increasing order (a superset of those with nonzero weight).
    pub(super) fn near(&self, x: &[f64; DIM], bw: &Bandwidths, mut visit: impl FnMut(usize)) {
        let n = self.samples.len();
        let mut marked = vec![0u64; n.div_ceil(64)];
        for (first, last) in self.runs(x, bw) {
            for &j in &self.samples[first..last] {
                marked[j / 64] |= 1 << (j % 64);
            }
        }
        for (w, mut bits) in marked.into_iter().enumerate() {
            while bits != 0 {
                visit(w * 64 + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
    }

    /// Calls `visit` with the samples that may lie within the kernel of bandwidths `bw` about
    /// `x`, in no particular order, until it returns true.
    pub(super) fn any_near(
        &self,
        x: &[f64; DIM],
        bw: &Bandwidths,
        mut visit: impl FnMut(usize) -> bool,
    ) {
        for (first, last) in self.runs(x, bw) {
            for &j in &self.samples[first..last] {
                if visit(j) {
                    return;
                }
            }
        }
    }
}
