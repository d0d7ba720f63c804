//! A cache of ray-method tables on disk: computing the table of a 512² map takes tens of
//! seconds, so a program that loads the same surface again (the renderer, for every scene that
//! names it) reads the `.gbrdf` it wrote the first time.
//!
//! A cached table is named by a key of everything its values depend on: gonio's version and
//! [`TABLE_REVISION`] (so a change of the algorithm never serves a table the old code made),
//! the caller's identity of the surface (a file's path, size and modification time, or a
//! synthetic surface's parameters), and the values of the [`RayOptions`] and [`TableOptions`].
//! A cache that cannot be read or written costs only time: a missing or unreadable file is
//! recomputed, a failed write is ignored.

use super::TableOptions;
use crate::ray::RayOptions;
use gonio_brdf::gbrdf;
use gonio_brdf::table::BrdfTable;
use std::path::PathBuf;

/// Revision of the tables [`super::ray_table`] makes from the same inputs. Raise it with every
/// change that alters a table's values, so that caches written before are not read. Revision 2:
/// the ray method levels the map (angles from its mean plane). Revision 3: maps of fewer than
/// 2¹⁸ facets are folded in smaller chunks (the partial sums, and so the last bits, change).
pub const TABLE_REVISION: u32 = 3;

/// Tables cached as `.gbrdf` files in one directory.
#[derive(Debug, Clone)]
pub struct TableCache {
    dir: PathBuf,
}

impl TableCache {
    /// A cache in `dir` (created when the first table is written).
    pub fn new(dir: impl Into<PathBuf>) -> TableCache {
        TableCache { dir: dir.into() }
    }

    /// The file that holds the table of `surface` (the caller's identity of the height map and
    /// of any choice it makes from it) under these options.
    pub fn path(&self, surface: &str, ray: &RayOptions, table: &TableOptions) -> PathBuf {
        let inputs = format!(
            "gonio {} table revision {TABLE_REVISION}|{surface}|{ray:?}|{table:?}",
            env!("CARGO_PKG_VERSION")
        );
        self.dir.join(format!("{:016x}.gbrdf", fnv1a(&inputs)))
    }

    /// The cached table of these inputs (as for [`TableCache::path`]), or the one `compute`
    /// makes, which is then written there.
    pub fn get_or_compute<E>(
        &self,
        surface: &str,
        ray: &RayOptions,
        table: &TableOptions,
        compute: impl FnOnce() -> Result<BrdfTable, E>,
    ) -> Result<BrdfTable, E> {
        let path = self.path(surface, ray, table);
        if let Ok(table) = gbrdf::read(&path) {
            return Ok(table);
        }
        let table = compute()?;
        if std::fs::create_dir_all(&self.dir).is_ok() {
            // A cache that cannot be written only costs time on the next load.
            let _ = gbrdf::write(&table, &path);
        }
        Ok(table)
    }
}

/// FNV-1a, 64 bits (Fowler, Noll & Vo): a stable hash of the key text, the same on every
/// platform and release (std's hasher promises neither).
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
