//! Export to Radiance's XML BSDF as a tensor tree, the form `bsdf2ttree` writes and Radiance's
//! `BSDF` material and BSDF library (`SDloadFile`) read, written straight from the table: no
//! `pabopto2bsdf` interpolant on the way, whose lobes misread a Lambert table by up to 34% at
//! grazing light (docs/brdf-tables.md, "Grazing light").
//!
//! **Format** (G. Ward, Radiance `src/common/bsdf_t.c`: `SDloadTre`, `load_bsdf_data`,
//! `load_tree_data`, `SDqueryTre`; `src/cv/bsdf2ttree.c`, `eval_isotropic`,
//! `eval_anisotropic`). A WINDOW 6 XML `WindowElement` whose `DataDefinition` says
//! `IncidentDataStructure` `TensorTree3` (isotropic) or `TensorTree4` (any), with one
//! `WavelengthData` per component: `Visible` (CIE Y, 1/sr) and, for colour, `CIE-u` and
//! `CIE-v` (the CIE 1976 chromaticity u′ v′ of each cell; Radiance reads no X or Z). Each holds
//! one `WavelengthDataBlock` with `AngleBasis` `LBNL/Shirley-Chiu` (required) and
//! `WavelengthDataDirection` `Reflection Back`, which Radiance's loader swaps to its front
//! reflection ("front and back are reversed from WINDOW 6 orientations"): both directions on
//! the +z side, the side the surface normal faces. `ScatteringData` is a tree of `{ }`: a node
//! is either 2^n children (n the rank) or a grid of 2^(n k) values, the last coordinate
//! fastest; a child's index has bit i set when it covers the upper half of coordinate i.
//!
//! **Coordinates.** Radiance looks a pair up without interpolation (the cell holding it) in
//! the unit cube of rank n. The first direction Radiance's renderer passes is the one toward
//! the viewer (`src/rt/m_bsdf.c`: `SDevalBSDF(&sv, vjit, vsmp, sd)`, the ray's and the
//! source's directions), and it indexes the tree's incidence coordinates; the direction toward
//! the light indexes the other two. So cell values are gonio's `f(wo = view, wi = light)` and a
//! table that is not reciprocal renders the right way round (tested with `rtrace`). Both
//! directions point away from the surface.
//! - Outgoing (light) `l`: `disk2square(l.x, l.y)`, the Shirley-Chiu map of the projected
//!   direction (P. Shirley, K. Chiu, "A low-distortion map between disk and square", JGT 2(3),
//!   1997; Radiance `src/common/disk2square.c`), area-preserving: every cell covers π/4^k of
//!   projected solid angle.
//! - Incidence (view) `v`, TensorTree4: `disk2square(-v.x, -v.y)` (the mirrored direction, as
//!   WINDOW's incident direction travels toward the surface).
//! - Incidence, TensorTree3: `1/2 - sin θ_v / 2`, only the lower half of the axis used (the
//!   upper half holds zeros), and `l` turned about z by `-atan2(-v.y, -v.x)`, which puts the
//!   view at azimuth 180°: the tree holds the view in the x-z plane at x ≤ 0.
//!
//! **Which rank.** A monochrome isotropic table is written as a `TensorTree3`; a colour table,
//! isotropic or not, as a `TensorTree4`. Radiance (6.0a, as PyPI's pyradiance 1.3.1 ships it)
//! splits off the least colour of a coloured tree as a diffuse part (`subtract_min_RGB`) and
//! rebuilds the u′ and v′ trees voxel by voxel, skipping the unused half of a `TensorTree3`
//! (`adjust_utree`, `adjust_vtree`); the rebuilt trees keep empty branches there, which
//! `SDsimplifyTre` refuses, so the u′ v′ trees are dropped and everything above the diffuse
//! part takes the colour of the first of its sharpened primaries, a red (x, y = 0.69, 0.32;
//! measured: a table of x, y = 0.455, 0.407 came back 0.675, 0.326). This is the red shift of
//! the PAB-Opto route's colour trees (docs/brdf-tables.md). A `TensorTree4` has no unused half
//! and keeps its colour (tested).
//!
//! **Values.** Each cell holds the mean of the table over its sub-cells' centres
//! ([`SUBSAMPLES_RANK3`], [`SUBSAMPLES_RANK4`] per axis of each dimension), uniform
//! in the tree's coordinates: over the light's projected solid angle, which keeps the table's
//! reflectance, and over the view's cell. Colour as the PAB-Opto export writes it
//! ([`super::pabopto::xyz_weights`], relative to Radiance's equal-energy white), each cell's
//! mean X, Y, Z written as Y and u′ = 4X / (X + 15Y + 3Z), v′ = 9Y / (X + 15Y + 3Z) (CIE 15:2004
//! §8.1), which Radiance turns back into x, y (`SDyuv2rgb`); a black cell has the white's u′ v′.
//!
//! **Resolution.** A tree of order k has 2^k cells per side: the light's cells are π/4^k of
//! projected solid angle (k = 6: 1.8° across at the pole, k = 5: 3.6°); a `TensorTree3` has
//! 2^(k-1) view cells, even steps of 2^(1-k) in sin θ_v (k = 6: 0-1.8° at the normal, 3.6°
//! wide at 60°, the last one 75.5-90°), a `TensorTree4` 2^k × 2^k like the light's. A cell's
//! value is its mean, so lobes narrower than a cell are spread over it, and a value differs from
//! the table at a pair by the table's change across the cell (docs/brdf-tables.md).

use super::pabopto::xyz_weights;
use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use crate::sampling::concentric_disk;
use crate::table::{BrdfTable, Channels};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_4, PI};
use std::io::Write;
use std::path::Path;

/// Tree order (2^order cells per side) of a `TensorTree3` by default: 32 view cells, 64 × 64
/// light cells, 131 072 values (about 1.5 MB of text).
pub const DEFAULT_ORDER_RANK3: u32 = 6;

/// Tree order of a `TensorTree4` by default: 32^4 cells, about 1 million values per component
/// (12 MB of text each); order 6 would write 16 million.
pub const DEFAULT_ORDER_RANK4: u32 = 5;

/// Largest order of a `TensorTree3` (2^23 values) and of a `TensorTree4` (2^24 per component).
pub const MAX_ORDER_RANK3: u32 = 8;
/// See [`MAX_ORDER_RANK3`].
pub const MAX_ORDER_RANK4: u32 = 6;

/// Sub-cells per axis of each of the three dimensions of a `TensorTree3`'s cell (27 table
/// evaluations per cell).
pub const SUBSAMPLES_RANK3: usize = 3;

/// Sub-cells per axis of each of the four dimensions of a `TensorTree4`'s cell (16).
pub const SUBSAMPLES_RANK4: usize = 2;

/// CIE 1976 u′, v′ of the equal-energy white (x = y = 1/3): 4/19, 9/19.
const WHITE_UV: [f64; 2] = [4.0 / 19.0, 9.0 / 19.0];

/// The rank of `table`'s tree: 3 for a monochrome isotropic table, else 4 (see "Which rank").
pub fn rank(table: &BrdfTable) -> usize {
    if table.resolution().is_isotropic() && matches!(table.channels(), Channels::Mono) {
        3
    } else {
        4
    }
}

/// The default order for `table`: [`DEFAULT_ORDER_RANK3`] or [`DEFAULT_ORDER_RANK4`].
pub fn default_order(table: &BrdfTable) -> u32 {
    if rank(table) == 3 {
        DEFAULT_ORDER_RANK3
    } else {
        DEFAULT_ORDER_RANK4
    }
}

/// A table as the tensor tree Radiance reads: per cell, Y and, for a colour table, u′ v′.
#[derive(Debug, Clone)]
pub struct TensorTree {
    order: u32,
    /// 3 (`TensorTree3`) or 4.
    rank: usize,
    /// Y (1/sr) of the cells in use: a `TensorTree3`'s lower half of the view axis, a
    /// `TensorTree4`'s every cell; row-major, the last coordinate fastest.
    y: Vec<f32>,
    /// u′, v′ of the same cells (colour tables).
    uv: Option<Vec<[f32; 2]>>,
}

impl TensorTree {
    /// The tree of `table` at `order` (2^order cells per side; from 2 to [`MAX_ORDER_RANK3`]
    /// for a `TensorTree3`, [`MAX_ORDER_RANK4`] for a `TensorTree4`; [`rank`] says which).
    pub fn from_table(table: &BrdfTable, order: u32) -> Result<TensorTree> {
        let rank = rank(table);
        let (max, n) = if rank == 3 {
            (MAX_ORDER_RANK3, SUBSAMPLES_RANK3)
        } else {
            (MAX_ORDER_RANK4, SUBSAMPLES_RANK4)
        };
        if !(2..=max).contains(&order) {
            return Err(BrdfError::Invalid(format!(
                "tensor tree order {order} outside 2 to {max} for this table (a TensorTree{rank})"
            )));
        }
        let xyz = xyz_table(table)?;
        let res = 1usize << order;
        let lights = light_samples(res, n);
        let views: Vec<Vec<DVec3>> = if rank == 3 {
            (0..res / 2).map(|i| iso_view_samples(i, res, n)).collect()
        } else {
            (0..res * res)
                .map(|i| aniso_view_samples(i / res, i % res, res, n))
                .collect()
        };
        let channels = xyz.as_ref().map_or(1, |t| t.channel_count());
        let source = xyz.as_ref().unwrap_or(table);
        let cells: Vec<[f64; 3]> = views
            .par_iter()
            .flat_map_iter(|vs| {
                let mut buf = vec![0.0; channels];
                lights
                    .iter()
                    .map(|ls| {
                        let mut sum = [0.0; 3];
                        for &v in vs {
                            for &l in ls {
                                source.eval_channels(v, l, &mut buf);
                                for (s, b) in sum.iter_mut().zip(&buf) {
                                    *s += b;
                                }
                            }
                        }
                        let count = (vs.len() * ls.len()) as f64;
                        sum.map(|s| clean(s / count))
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let colour = xyz.is_some();
        let y = cells
            .iter()
            .map(|c| if colour { c[1] } else { c[0] } as f32)
            .collect();
        let uv = colour.then(|| cells.iter().map(|&c| uv_of(c).map(|v| v as f32)).collect());
        Ok(TensorTree { order, rank, y, uv })
    }

    /// 2^order cells per side.
    pub fn order(&self) -> u32 {
        self.order
    }

    /// 3 for a `TensorTree3`, 4 for a `TensorTree4`.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// With `CIE-u` and `CIE-v` components.
    pub fn has_colour(&self) -> bool {
        self.uv.is_some()
    }

    /// The CIE XYZ (1/sr, relative to the equal-energy white; X = Y = Z for a monochrome tree)
    /// that the tree holds for the viewer at `view` and the light at `light` (unit vectors on
    /// the +z side), found as Radiance's `SDqueryTre` finds it: the cell holding the pair,
    /// without interpolation. Zero below the horizon.
    pub fn eval_xyz(&self, view: DVec3, light: DVec3) -> [f64; 3] {
        if view.z <= 0.0 || light.z <= 0.0 {
            return [0.0; 3];
        }
        let res = 1usize << self.order;
        let cell = |t: f64| ((t * res as f64) as usize).min(res - 1);
        let index = if self.rank == 3 {
            let sin_v = view.x.hypot(view.y);
            let i0 = cell(0.5 - 0.5 * sin_v).min(res / 2 - 1);
            let turn = -(-view.y).atan2(-view.x);
            let (s, c) = turn.sin_cos();
            let l = DVec2::new(c * light.x - s * light.y, s * light.x + c * light.y);
            let q = disk_to_square(l);
            (i0 * res + cell(q.x)) * res + cell(q.y)
        } else {
            let a = disk_to_square(DVec2::new(-view.x, -view.y));
            let b = disk_to_square(DVec2::new(light.x, light.y));
            ((cell(a.x) * res + cell(a.y)) * res + cell(b.x)) * res + cell(b.y)
        };
        let y = f64::from(self.y[index]);
        match &self.uv {
            None => [y; 3],
            Some(uv) => {
                let [u, v] = uv[index].map(f64::from);
                // x = 9u′ / (6u′ - 16v′ + 12), y = 4v′ / (…), so X / Y = 9u′ / 4v′ and
                // Z / Y = (12 - 3u′ - 20v′) / 4v′.
                [
                    y * 9.0 * u / (4.0 * v),
                    y,
                    y * (12.0 - 3.0 * u - 20.0 * v) / (4.0 * v),
                ]
            }
        }
    }

    /// Write the XML to `path` (atomically), `name` as the material's name.
    pub fn write(&self, path: &Path, name: &str) -> Result<()> {
        let rank = self.rank;
        write_atomic(path, |w| {
            writeln!(w, r#"<?xml version="1.0" encoding="UTF-8"?>"#)?;
            writeln!(
                w,
                "<!-- Written by gonio {} (crates/brdf/src/formats/radiance_xml.rs): tensor tree of \
                 order {}, the cell means of the table. -->",
                env!("CARGO_PKG_VERSION"),
                self.order
            )?;
            writeln!(
                w,
                concat!(
                    r#"<WindowElement xmlns="http://windows.lbl.gov" "#,
                    r#"xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" "#,
                    r#"xsi:schemaLocation="http://windows.lbl.gov/BSDF-v1.4.xsd">"#
                )
            )?;
            writeln!(w, "<WindowElementType>System</WindowElementType>")?;
            writeln!(w, "<FileType>BSDF</FileType>")?;
            writeln!(w, "<Optical>\n<Layer>\n\t<Material>")?;
            writeln!(w, "\t\t<Name>{}</Name>", escape(name))?;
            writeln!(w, "\t\t<Manufacturer>gonio</Manufacturer>")?;
            writeln!(w, "\t\t<DeviceType>Other</DeviceType>\n\t</Material>")?;
            writeln!(w, "\t<DataDefinition>")?;
            writeln!(
                w,
                "\t\t<IncidentDataStructure>TensorTree{rank}</IncidentDataStructure>"
            )?;
            writeln!(w, "\t</DataDefinition>")?;
            self.write_component(w, "Visible", |k| self.y[k])?;
            if let Some(uv) = &self.uv {
                self.write_component(w, "CIE-u", |k| uv[k][0])?;
                self.write_component(w, "CIE-v", |k| uv[k][1])?;
            }
            writeln!(w, "</Layer>\n</Optical>\n</WindowElement>")
        })
    }

    /// One `WavelengthData` element: the component `name` with the value `value(k)` of live
    /// cell `k`.
    fn write_component(
        &self,
        w: &mut impl Write,
        name: &str,
        value: impl Fn(usize) -> f32,
    ) -> std::io::Result<()> {
        writeln!(w, "\t<WavelengthData>")?;
        writeln!(w, "\t\t<LayerNumber>System</LayerNumber>")?;
        writeln!(w, "\t\t<Wavelength unit=\"Integral\">{name}</Wavelength>")?;
        writeln!(
            w,
            "\t\t<SourceSpectrum>CIE Illuminant E</SourceSpectrum>\n\t\t\
             <DetectorSpectrum>{}</DetectorSpectrum>",
            if name == "Visible" {
                "ASTM E308 1931 Y.dsp"
            } else {
                name
            }
        )?;
        writeln!(w, "\t\t<WavelengthDataBlock>")?;
        writeln!(
            w,
            "\t\t\t<WavelengthDataDirection>Reflection Back</WavelengthDataDirection>"
        )?;
        writeln!(w, "\t\t\t<AngleBasis>LBNL/Shirley-Chiu</AngleBasis>")?;
        writeln!(w, "\t\t\t<ScatteringDataType>BRDF</ScatteringDataType>")?;
        writeln!(w, "\t\t\t<ScatteringData>")?;
        let res = 1usize << self.order;
        if self.rank == 3 {
            // Eight children, each a grid of half the resolution; those covering the upper half
            // of the view axis (bit 0) are unused and hold one zero.
            let h = res / 2;
            writeln!(w, "{{")?;
            for child in 0..8usize {
                if child & 1 == 1 {
                    writeln!(w, "{{ 0 }}")?;
                    continue;
                }
                let (o1, o2) = ((child >> 1 & 1) * h, (child >> 2 & 1) * h);
                writeln!(w, "{{")?;
                for j0 in 0..h {
                    for j1 in 0..h {
                        let row = (j0 * res + o1 + j1) * res + o2;
                        write_row(w, (row..row + h).map(&value))?;
                    }
                }
                writeln!(w, "}}")?;
            }
            writeln!(w, "}}")?;
        } else {
            writeln!(w, "{{")?;
            for row in (0..self.y.len()).step_by(res) {
                write_row(w, (row..row + res).map(&value))?;
            }
            writeln!(w, "}}")?;
        }
        writeln!(w, "\t\t\t</ScatteringData>")?;
        writeln!(w, "\t\t</WavelengthDataBlock>")?;
        writeln!(w, "\t</WavelengthData>")
    }
}

/// Build the tree of `table` at `order` (default [`default_order`]) and write it to `path`;
/// the tree is returned (its [`TensorTree::eval_xyz`] is what Radiance will read).
pub fn write(table: &BrdfTable, path: &Path, name: &str, order: Option<u32>) -> Result<TensorTree> {
    let tree = TensorTree::from_table(table, order.unwrap_or_else(|| default_order(table)))?;
    tree.write(path, name)?;
    Ok(tree)
}

/// One line of values, zeros written as `0`, the others with six significant digits.
fn write_row(w: &mut impl Write, values: impl Iterator<Item = f32>) -> std::io::Result<()> {
    let mut first = true;
    for v in values {
        if !first {
            w.write_all(b" ")?;
        }
        first = false;
        if v == 0.0 {
            w.write_all(b"0")?;
        } else {
            write!(w, "{v:.5e}")?;
        }
    }
    writeln!(w)
}

/// The table converted to X, Y, Z channels (relative to the equal-energy white, the weights of
/// the PAB-Opto export) when it has colour, so that each evaluation interpolates three
/// channels; `None` for a monochrome table. The conversion is linear, as is the table's
/// interpolation, so the two commute: only the f32 storage rounds.
fn xyz_table(table: &BrdfTable) -> Result<Option<BrdfTable>> {
    let Some(weights) = xyz_weights(table.channels())? else {
        return Ok(None);
    };
    let values: Vec<f32> = table
        .values()
        .chunks_exact(weights.len())
        .flat_map(|cell| {
            let mut xyz = [0.0f64; 3];
            for (w, &v) in weights.iter().zip(cell) {
                for k in 0..3 {
                    xyz[k] += w[k] * f64::from(v);
                }
            }
            xyz.map(|v| v as f32)
        })
        .collect();
    BrdfTable::from_values(
        table.resolution(),
        Channels::Xyz,
        table.provenance().clone(),
        values,
    )
    .map(Some)
}

/// Negative values (an out-of-gamut colour's X or Z) and values without data become 0, as in
/// the PAB-Opto export (Radiance also reads negative values as 0).
fn clean(v: f64) -> f64 {
    if v.is_finite() { v.max(0.0) } else { 0.0 }
}

/// CIE 1976 u′, v′ of X, Y, Z (CIE 15:2004 §8.1); the equal-energy white's for black.
fn uv_of([x, y, z]: [f64; 3]) -> [f64; 2] {
    let d = x + 15.0 * y + 3.0 * z;
    if y > 0.0 && d > 0.0 {
        [4.0 * x / d, 9.0 * y / d]
    } else {
        WHITE_UV
    }
}

/// The centres of `n` × `n` sub-cells of every light cell of a `res` × `res` Shirley-Chiu
/// square, as directions (row-major cells, the second coordinate fastest).
fn light_samples(res: usize, n: usize) -> Vec<Vec<DVec3>> {
    (0..res * res)
        .map(|c| {
            let (i, j) = (c / res, c % res);
            sub_cells(n)
                .flat_map(|a| sub_cells(n).map(move |b| (a, b)))
                .map(|(a, b)| {
                    let q = DVec2::new((i as f64 + a) / res as f64, (j as f64 + b) / res as f64);
                    hemisphere(concentric_disk(q))
                })
                .collect()
        })
        .collect()
}

/// The views of `n` sub-cells of view cell `i` of a `TensorTree3` of `res` cells per side:
/// `sin θ = 1 - 2 t` for `t` the sub-cells' centres in the tree coordinate, at azimuth 180°.
fn iso_view_samples(i: usize, res: usize, n: usize) -> Vec<DVec3> {
    sub_cells(n)
        .map(|a| {
            let sin = 1.0 - 2.0 * (i as f64 + a) / res as f64;
            hemisphere(DVec2::new(-sin, 0.0))
        })
        .collect()
}

/// The views of `n` × `n` sub-cells of view cell (`i`, `j`) of a `TensorTree4`: the
/// mirror image through the normal of the square's directions (`disk2square(-v.x, -v.y)`).
fn aniso_view_samples(i: usize, j: usize, res: usize, n: usize) -> Vec<DVec3> {
    sub_cells(n)
        .flat_map(|a| sub_cells(n).map(move |b| (a, b)))
        .map(|(a, b)| {
            let q = DVec2::new((i as f64 + a) / res as f64, (j as f64 + b) / res as f64);
            hemisphere(-concentric_disk(q))
        })
        .collect()
}

/// The centres of `n` equal sub-intervals of [0, 1).
fn sub_cells(n: usize) -> impl Iterator<Item = f64> + Clone {
    (0..n).map(move |k| (k as f64 + 0.5) / n as f64)
}

/// The unit vector on the +z side above the point `d` of the unit disk.
fn hemisphere(d: DVec2) -> DVec3 {
    DVec3::new(d.x, d.y, (1.0 - d.length_squared()).max(0.0).sqrt())
}

/// The inverse of [`concentric_disk`]: a point of the unit disk to [0, 1]² (Shirley & Chiu
/// 1997; Radiance `src/common/disk2square.c`, `SDdisk2square`).
fn disk_to_square(d: DVec2) -> DVec2 {
    let r = d.length();
    let mut phi = d.y.atan2(d.x);
    if phi < -FRAC_PI_4 {
        phi += 2.0 * PI;
    }
    let (a, b) = if phi < FRAC_PI_4 {
        (r, phi * r / FRAC_PI_4)
    } else if phi < 3.0 * FRAC_PI_4 {
        (-(phi - 2.0 * FRAC_PI_4) * r / FRAC_PI_4, r)
    } else if phi < 5.0 * FRAC_PI_4 {
        (-r, (phi - PI) * -r / FRAC_PI_4)
    } else {
        ((phi - 6.0 * FRAC_PI_4) * r / FRAC_PI_4, -r)
    };
    DVec2::new((a + 1.0) * 0.5, (b + 1.0) * 0.5)
}

/// `text` with the characters XML reserves escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_to_square_inverts_the_concentric_map() {
        for i in 0..40 {
            for j in 0..40 {
                let q = DVec2::new((i as f64 + 0.3) / 40.0, (j as f64 + 0.7) / 40.0);
                let back = disk_to_square(concentric_disk(q));
                assert!((back - q).length() < 1e-12, "{q} -> {back}");
            }
        }
    }

    #[test]
    fn black_and_grey_have_the_equal_energy_whites_chromaticity() {
        assert_eq!(uv_of([0.0; 3]), WHITE_UV);
        let [u, v] = uv_of([1.0, 1.0, 1.0]);
        assert!((u - WHITE_UV[0]).abs() < 1e-12 && (v - WHITE_UV[1]).abs() < 1e-12);
    }
}
