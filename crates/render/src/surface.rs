//! Materials computed from topography: a height map (a file, or a synthetic epoxy surface of
//! the `surface` crate) turned into a tabulated BRDF by the ray method
//! ([`gonio_scatter::table::ray_table`]) when the scene is loaded. The table is cached in
//! `.gonio-cache/` beside the scene file ([`gonio_scatter::table::cache`]: keyed by gonio's
//! version and table revision, the surface — the height-map file's path, size and modification
//! time, or the synthetic surface's parameters — and the options' values), so that later loads
//! read it instead of recomputing it.

use crate::error::{RenderError, Result};
use gonio_brdf::Ior;
use gonio_brdf::table::{BrdfTable, Provenance};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::table::cache::TableCache;
use gonio_scatter::table::{TableOptions, isotropic_turns, ray_table, texture_aspect_ratio};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// `surface = { ... }` in a material: the height map and the scattering method.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SurfaceDesc {
    /// A height-map file (any format `gonio surface` reads).
    #[serde(default)]
    pub file: Option<PathBuf>,
    /// The file's channel to read, a name or a 0-based index (multi-channel AFM files;
    /// default: the first height channel; `gonio surface info FILE` lists them).
    #[serde(default)]
    pub channel: Option<String>,
    /// Or a synthetic epoxy sample of this rms height, nm
    /// (`gonio_surface::synth::epoxy_surface`).
    #[serde(default)]
    pub epoxy_sq_nm: Option<f64>,
    /// Seed of the synthetic surface (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Points along each side of the synthetic surface (default 512: 256 µm at the epoxy
    /// series' 0.5 µm spacing, about 40 correlation lengths).
    #[serde(default)]
    pub points: Option<usize>,
    /// The scattering method: `ray` (geometric optics, the default).
    #[serde(default)]
    pub method: Option<String>,
    /// Refractive index of the coating (default 1.55).
    #[serde(default)]
    pub index: Option<f64>,
    /// Azimuths of incidence the table averages the surface over (default as `gonio brdf
    /// compute`, from the map's texture aspect ratio Str: 1 from 0.5 up, 8 from 0.3 to 0.5, 24
    /// below 0.3).
    #[serde(default)]
    pub azimuths: Option<usize>,
}

/// The BRDF table of material `name` described by `desc`; `dir` is the scene file's directory
/// (for relative paths and the cache) and `scene` names the file in errors.
pub fn table(desc: &SurfaceDesc, dir: &Path, scene: &Path, name: &str) -> Result<BrdfTable> {
    let bad = |p: String| RenderError::scene(scene, format!("material `{name}`: {p}"));
    let method = desc.method.as_deref().unwrap_or("ray");
    if method != "ray" {
        return Err(bad(format!(
            "surface method `{method}` is not available here; use `ray`"
        )));
    }
    let index = desc.index.unwrap_or(1.55);
    if index.is_nan() || index <= 1.0 {
        return Err(bad(format!("surface `index` must exceed 1, got {index}")));
    }
    if let Some(azimuths) = desc.azimuths
        && (azimuths == 0 || azimuths > 64)
    {
        return Err(bad(format!(
            "surface `azimuths` must be 1 to 64, got {azimuths}"
        )));
    }
    let seed = desc.seed.unwrap_or(1);
    let points = desc.points.unwrap_or(512);
    if !(16..=8192).contains(&points) {
        return Err(bad(format!(
            "surface `points` must be 16 to 8192, got {points}"
        )));
    }
    let (source, stamp) = match (&desc.file, desc.epoxy_sq_nm) {
        (Some(file), None) => {
            let path = if file.is_absolute() {
                file.clone()
            } else {
                dir.join(file)
            };
            let meta = std::fs::metadata(&path).map_err(|e| RenderError::Io {
                path: path.clone(),
                error: e,
            })?;
            let modified = meta
                .modified()
                .ok()
                .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                .map_or(0, |d| d.as_nanos());
            let stamp = format!(
                "file={}|len={}|mtime={modified}|channel={:?}",
                path.display(),
                meta.len(),
                desc.channel
            );
            (Source::File(path), stamp)
        }
        (None, Some(sq_nm)) => {
            if sq_nm.is_nan() || sq_nm <= 0.0 {
                return Err(bad(format!("`epoxy_sq_nm` must be positive, got {sq_nm}")));
            }
            (
                Source::Epoxy(sq_nm),
                format!("epoxy_sq_nm={sq_nm}|seed={seed}|points={points}"),
            )
        }
        _ => {
            return Err(bad(
                "a surface needs exactly one of `file` (a height map) or `epoxy_sq_nm`".into(),
            ));
        }
    };
    let ray_options = RayOptions {
        ior: Ior::Dielectric(index),
        ..RayOptions::default()
    };
    // The default turns depend on the map (its Str), which the stamp identifies; an explicit
    // count is part of the surface's identity too.
    let cache = TableCache::new(dir.join(".gonio-cache"));
    let surface = format!("{stamp}|azimuths={:?}", desc.azimuths);
    cache.get_or_compute(&surface, &ray_options, &TableOptions::isotropic(), || {
        let map = match &source {
            Source::File(path) => {
                let channel = desc
                    .channel
                    .as_deref()
                    .map(str::parse::<gonio_surface::ChannelSelector>)
                    .transpose()
                    .map_err(|e| bad(format!("surface `channel`: {e}")))?;
                let options = gonio_surface::io::ReadOptions { channel };
                let map = gonio_surface::io::read_with(path, &options).map_err(|e| {
                    RenderError::scene(path, format!("cannot read the height map: {e}"))
                })?;
                if map.is_profile() {
                    return Err(bad(format!(
                        "{} holds a line profile; a surface's table needs an areal height map",
                        path.display()
                    )));
                }
                map
            }
            Source::Epoxy(sq_nm) => gonio_surface::synth::GaussianSurface {
                nx: points,
                ny: points,
                ..gonio_surface::synth::epoxy_surface(sq_nm * 1e-9, seed)
            }
            .generate()
            .map_err(|e| bad(format!("cannot synthesise the surface: {e}")))?,
        };
        let options = TableOptions {
            incidence_azimuths: desc
                .azimuths
                .unwrap_or_else(|| isotropic_turns(texture_aspect_ratio(&map))),
            ..TableOptions::isotropic()
        };
        let engine =
            RayEngine::new(&map, ray_options).map_err(|e| bad(format!("ray method: {e}")))?;
        let provenance = Provenance::new(stamp, "ray");
        ray_table(&engine, &options, provenance, &gonio_io::Progress::silent())
            .map_err(|e| bad(format!("ray method: {e}")))
    })
}

enum Source {
    File(PathBuf),
    Epoxy(f64),
}
