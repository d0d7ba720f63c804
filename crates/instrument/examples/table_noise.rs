//! How far a coating table's multi-angle reading strays from the coating read directly: the
//! cells a reading at the E2539 geometries (E2194's five among them) interpolates, at the
//! default resolution of `gonio coating compute` (90 × 90 × 48, 31 bands), re-estimated with
//! independent walks (stream offsets 1, 2, ...), each set read through the table's
//! interpolation as `gonio multiangle` reads a table; against the direct reading (16 384 walks
//! per geometry). Prints per geometry the direct L*, the mean and the standard deviation of the
//! table's deviation in L*, the largest deviation and how often it exceeds 1 L*; and the walks
//! the cells took.
//!
//! ```text
//! cargo run --release -p gonio-instrument --features studies --example table_noise -- \
//!     examples/coatings/silver_metallic.toml [--tables 100] [--samples 32] [--target-dl 0.333] \
//!     [--cells]
//! ```
//!
//! `--target-dl 0` gives every cell `--samples` walks. `--cells` studies the cells instead:
//! for each cell the readings interpolate it prints its noise at `--samples` walks (the
//! standard deviation of its L* over the `--tables` estimates), how the standard error each
//! estimate finds from its own walks and from its neighbourhood's compares with it (median
//! ratio and 5% quantile), the cell's final noise and walks, and the bias of a rule that would
//! add walks by the cell's own standard error instead (its mean L* less the final mean): what
//! the adaptive walks decide on.

use gonio_brdf::formats::astm::default_resolution;
use gonio_brdf::table::{HalfDiff, Provenance, TableBuilder};
use gonio_coating::cell::{
    CellWalks, NEIGHBOURHOOD, luminance_weights, neighbourhood_se, neighbours, walks_needed,
};
use gonio_coating::description;
use gonio_coating::layered::Scratch;
use gonio_coating::system::{TABLE_WALKS, TARGET_DL};
use gonio_color::Xyz;
use gonio_instrument::multiangle::{self, E2539, Settings};
use std::collections::BTreeSet;
use std::f64::consts::PI;
use std::path::PathBuf;

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn number<T: std::str::FromStr>(
    args: &mut impl Iterator<Item = String>,
    flag: &str,
) -> Result<T, String> {
    let v = args.next().ok_or(format!("{flag} needs a value"))?;
    v.parse().map_err(|_| format!("{flag} {v}: not a number"))
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let (mut path, mut tables, mut samples, mut target, mut cells_mode) =
        (None::<PathBuf>, 100usize, TABLE_WALKS, TARGET_DL, false);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--tables" => tables = number(&mut args, "--tables")?,
            "--samples" => samples = number(&mut args, "--samples")?,
            "--target-dl" => target = number(&mut args, "--target-dl")?,
            "--cells" => cells_mode = true,
            _ if path.is_none() => path = Some(a.into()),
            _ => return Err(format!("unexpected argument {a}")),
        }
    }
    let path = path.ok_or(
        "usage: table_noise COATING.toml [--tables N] [--samples N] [--target-dl L] [--cells]",
    )?;
    let wl: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
    let res = default_resolution();
    let coating = description::read(&path, &wl).map_err(|e| e.to_string())?;
    let mut stencil = BTreeSet::new();
    for g in &E2539 {
        let (wi, wo) = g.directions();
        let a = HalfDiff::from_dirs(wi, wo).ok_or("a geometry below the horizon")?;
        stencil.extend(res.corners(&a).iter().filter(|c| c.1 > 0.0).map(|c| c.0));
    }
    let walks = CellWalks::adaptive(samples, target);
    if cells_mode {
        return cells(&coating, &wl, &stencil, tables, walks);
    }
    let settings = Settings::default();
    let evaluator = coating.evaluator(&wl).map_err(|e| e.to_string())?;
    let brdf = |wo, wi, out: &mut [f64]| {
        evaluator.eval(wo, wi, 16_384, 1, &mut Scratch::default(), out);
    };
    let direct = multiangle::read(&brdf, &wl, &E2539, &settings).map_err(|e| e.to_string())?;
    let mut deviations = vec![Vec::new(); E2539.len()];
    let (mut walks_sum, mut walks_cells, mut walks_max) = (0u64, 0usize, 0usize);
    for t in 0..tables {
        let (table, spent) = coating
            .table_cells(
                res,
                &wl,
                walks.with_stream(t as u64 + 1),
                Provenance::default(),
                |i| stencil.contains(&i),
            )
            .map_err(|e| e.to_string())?;
        walks_sum += spent.walks;
        walks_cells += spent.cells;
        walks_max = walks_max.max(spent.max);
        let read = multiangle::read_table(&table, &E2539, &settings).map_err(|e| e.to_string())?;
        for (k, (r, d)) in read.geometries.iter().zip(&direct.geometries).enumerate() {
            deviations[k].push(r.lab.l - d.lab.l);
        }
    }
    println!(
        "{}: {tables} tables' cells ({} cells), {samples} walks per cell{}; walks per cell {:.1} on \
         average, {walks_max} at most",
        path.display(),
        stencil.len(),
        walks.target_dl.map_or(String::new(), |t| format!(
            ", more in batches of {} up to {} where a cell's L* is expected noisier than {t:.3}",
            walks.first(),
            walks.most()
        )),
        walks_sum as f64 / walks_cells as f64,
    );
    println!("geometry   direct L*   mean ΔL*   sd ΔL*   max |ΔL*|   > 1 L*");
    for (g, (d, devs)) in direct.geometries.iter().zip(&deviations).enumerate() {
        let n = devs.len() as f64;
        let mean = devs.iter().sum::<f64>() / n;
        let sd = (devs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let max = devs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let over = devs.iter().filter(|x| x.abs() > 1.0).count();
        println!(
            "{:<10} {:>8.2} {:>10.3} {:>8.3} {:>10.2} {:>8}",
            E2539[g].to_string(),
            d.lab.l,
            mean,
            sd,
            max,
            over
        );
    }
    Ok(())
}

/// One estimate of a cell in the study of `--cells`.
#[derive(Clone)]
struct Estimate {
    /// The L* of the cell's first walks.
    first_l: f64,
    /// The standard error in L* they show.
    own_se: f64,
    /// The standard error in L* its neighbourhood's first walks show.
    neighbourhood_se: f64,
    /// The L* of all its walks.
    final_l: f64,
    /// The L* it would have with the walks its own standard error asks for.
    own_rule_l: f64,
    /// Its walks.
    walks: usize,
}

/// The study of `--cells` (the module's documentation).
fn cells(
    coating: &gonio_coating::system::Coating,
    wl: &[f64],
    stencil: &BTreeSet<usize>,
    tables: usize,
    walks: CellWalks,
) -> Result<(), String> {
    let res = default_resolution();
    let evaluator = coating.evaluator(wl).map_err(|e| e.to_string())?;
    let luminance = luminance_weights(wl).map_err(|e| e.to_string())?;
    let builder = TableBuilder::new(
        res,
        gonio_brdf::table::Channels::Spectral {
            wavelengths_nm: wl.to_vec(),
        },
    )
    .map_err(|e| e.to_string())?;
    let white = Xyz::new(0.0, 100.0, 0.0);
    let lightness = |f: &[f64]| {
        let y = PI * f.iter().zip(&luminance).map(|(f, w)| f * w).sum::<f64>();
        Xyz::new(0.0, 100.0 * y, 0.0).to_lab(white).l
    };
    let mut around: BTreeSet<usize> = stencil.clone();
    for &i in stencil {
        around.extend(neighbours(&res, i, NEIGHBOURHOOD));
    }
    let around: Vec<usize> = around
        .into_iter()
        .filter(|&i| builder.cell(i).is_above_horizon())
        .collect();
    let mut rows: Vec<Vec<Estimate>> = vec![Vec::new(); stencil.len()];
    let mut out = vec![0.0; wl.len()];
    for t in 0..tables {
        let w = walks.with_stream(t as u64 + 1);
        let mut first = std::collections::HashMap::new();
        for &i in &around {
            let c = builder.cell(i);
            let se = evaluator.eval_cell(
                c.wo,
                c.wi,
                &w,
                &luminance,
                &mut Scratch::default(),
                &mut out,
            );
            first.insert(i, (se, out.clone()));
        }
        for (row, &i) in rows.iter_mut().zip(stencil) {
            let c = builder.cell(i);
            let (own, values) = first[&i].clone();
            let pooled = neighbourhood_se(&res, i, |j| first.get(&j).map(|f| f.0)).unwrap_or(own);
            let count = walks_needed(&w, w.target_at(c.wo, c.wi), pooled);
            let mut f = values.clone();
            evaluator.refine_cell(c.wo, c.wi, &w, count, &mut Scratch::default(), &mut f);
            let mut by_own = values.clone();
            let own_count = walks_needed(&w, w.target_at(c.wo, c.wi), own);
            evaluator.refine_cell(
                c.wo,
                c.wi,
                &w,
                own_count,
                &mut Scratch::default(),
                &mut by_own,
            );
            row.push(Estimate {
                first_l: lightness(&values),
                own_se: own,
                neighbourhood_se: pooled,
                final_l: lightness(&f),
                own_rule_l: lightness(&by_own),
                walks: count,
            });
        }
    }
    let stats = |x: &[f64]| {
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        (
            mean,
            (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt(),
        )
    };
    let quantile = |mut x: Vec<f64>, q: f64| {
        x.sort_by(f64::total_cmp);
        x[((x.len() - 1) as f64 * q).round() as usize]
    };
    println!(
        "{} cells, {} first walks, {tables} estimates each; per cell: the first walks' L* (mean, \
         sd over the estimates), their own standard error and the neighbourhood's over that sd \
         (median, 5%), the final L* (mean, sd), the walks (mean), and the mean L* the walks its own \
         standard error asks for would give, less the final mean",
        stencil.len(),
        walks.first()
    );
    println!(
        "θi    θo    cos    L*first  sd      own 50%  5%     nbhd 50%  5%     L*final  sd     walks  own rule ΔL*"
    );
    for (row, &i) in rows.iter().zip(stencil) {
        let c = builder.cell(i);
        let (m0, s0) = stats(&row.iter().map(|r| r.first_l).collect::<Vec<_>>());
        let (m1, s1) = stats(&row.iter().map(|r| r.final_l).collect::<Vec<_>>());
        let own: Vec<f64> = row.iter().map(|r| r.own_se / s0).collect();
        let nbhd: Vec<f64> = row.iter().map(|r| r.neighbourhood_se / s0).collect();
        let spent = row.iter().map(|r| r.walks as f64).sum::<f64>() / row.len() as f64;
        let (m2, _) = stats(&row.iter().map(|r| r.own_rule_l).collect::<Vec<_>>());
        println!(
            "{:>5.1} {:>5.1} {:>6.3} {:>8.2} {:>6.3} {:>7.2} {:>5.2} {:>8.2} {:>5.2} {:>9.2} {:>6.3} {:>6.0} {:>+9.3}",
            c.wi.z.acos().to_degrees(),
            c.wo.z.acos().to_degrees(),
            c.wi.dot(c.wo),
            m0,
            s0,
            quantile(own.clone(), 0.5),
            quantile(own, 0.05),
            quantile(nbhd.clone(), 0.5),
            quantile(nbhd, 0.05),
            m1,
            s1,
            spent,
            m2 - m1
        );
    }
    Ok(())
}
