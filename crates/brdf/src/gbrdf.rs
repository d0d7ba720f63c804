//! gonio's own table file, `.gbrdf`: a small binary container with a self-describing JSON header
//! and f32 little-endian values aligned so that the file can be memory-mapped and read without
//! copying. The layout is specified in `docs/formats.md` (section `.gbrdf`):
//!
//! | offset | size | content |
//! |---|---|---|
//! | 0 | 8 | magic `GBRDF\0\r\n` |
//! | 8 | 4 | u32 LE format version (1) |
//! | 12 | 4 | u32 LE byte length `L` of the JSON header |
//! | 16 | L | JSON header, UTF-8 |
//! | 16 + L | pad | zero bytes up to `data_offset`, the next multiple of 64 |
//! | data_offset | 4 N | N = cells × channels f32 LE values, channel fastest |
//!
//! Files are written to a temporary file beside the target and renamed over it, so a reader
//! never sees half a file.

use crate::error::{BrdfError, Result};
use crate::table::{BrdfTable, Channels, Provenance, Resolution, Storage};
use std::io::Write;
use std::path::Path;

/// The 8 magic bytes (the `\r\n` catches text-mode transfers, as PNG's signature does).
pub const MAGIC: &[u8; 8] = b"GBRDF\0\r\n";
/// The format version this code writes and reads.
pub const VERSION: u32 = 1;
/// Alignment of the value block in bytes.
pub const ALIGN: usize = 64;
/// The parameterisation name in the header.
pub const PARAMETERISATION: &str = "rusinkiewicz-sqrt-theta-h";
/// Largest header accepted (a spectral table with thousands of wavelengths fits easily).
const MAX_HEADER: usize = 16 << 20;

/// The JSON header of a `.gbrdf` file.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Header {
    /// Always `gbrdf`.
    pub format: String,
    /// Format version, equal to the binary one.
    pub version: u32,
    /// Always [`PARAMETERISATION`].
    pub parameterisation: String,
    /// Node counts.
    pub resolution: Resolution,
    /// Order of the value array, slowest first.
    pub layout: String,
    /// What the channels hold.
    pub channels: Channels,
    /// Unit of the values.
    pub value_unit: String,
    /// Byte offset of the first value.
    pub data_offset: u64,
    /// Number of f32 values.
    pub value_count: u64,
    /// Where the table came from.
    pub provenance: Provenance,
}

impl Header {
    fn of(table: &BrdfTable, data_offset: u64) -> Header {
        Header {
            format: "gbrdf".into(),
            version: VERSION,
            parameterisation: PARAMETERISATION.into(),
            resolution: table.resolution(),
            layout: "phi_h, theta_h, theta_d, phi_d, channel (last fastest); NaN = no data".into(),
            channels: table.channels().clone(),
            value_unit: "1/sr".into(),
            data_offset,
            value_count: table.values().len() as u64,
            provenance: table.provenance().clone(),
        }
    }
}

fn header_json(table: &BrdfTable) -> Result<(Vec<u8>, usize)> {
    // The offset depends on the header length, which depends (weakly) on the offset's digits:
    // iterate until it is stable.
    let mut offset = 0u64;
    loop {
        let json = serde_json::to_vec(&Header::of(table, offset))
            .map_err(|e| BrdfError::Invalid(format!("cannot encode the header: {e}")))?;
        let want = (16 + json.len()).div_ceil(ALIGN) * ALIGN;
        if want as u64 == offset {
            return Ok((json, want));
        }
        offset = want as u64;
    }
}

/// Write `table` to `path` (temporary file + rename).
pub fn write(table: &BrdfTable, path: &Path) -> Result<()> {
    let (json, offset) = header_json(table)?;
    write_atomic(path, |w| {
        w.write_all(MAGIC)?;
        w.write_all(&VERSION.to_le_bytes())?;
        w.write_all(&(json.len() as u32).to_le_bytes())?;
        w.write_all(&json)?;
        w.write_all(&vec![0u8; offset - 16 - json.len()])?;
        let mut buf = Vec::with_capacity(1 << 16);
        for chunk in table.values().chunks(1 << 14) {
            buf.clear();
            chunk
                .iter()
                .for_each(|v| buf.extend_from_slice(&v.to_le_bytes()));
            w.write_all(&buf)?;
        }
        Ok(())
    })
}

/// Write a file atomically ([`gonio_io::write_atomic`]: the old file or the complete new one,
/// never half a file); errors name the file.
pub fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut std::io::BufWriter<&mut std::fs::File>) -> std::io::Result<()>,
) -> Result<()> {
    let io = |e| BrdfError::io(path, e);
    gonio_io::write_atomic(path, |w| body(w).map_err(io), io)
}

/// Parse and check the header of a file's bytes; returns the header.
pub fn parse_header(bytes: &[u8], path: &Path) -> Result<Header> {
    let bad = |p: String| BrdfError::format(path, p);
    if bytes.len() < 16 {
        return Err(bad(format!(
            "{} bytes is too short for a .gbrdf file (truncated?)",
            bytes.len()
        )));
    }
    if &bytes[..8] != MAGIC {
        return Err(bad("not a .gbrdf file (wrong magic bytes)".into()));
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if version != VERSION {
        return Err(bad(format!(
            "format version {version}; this gonio reads version {VERSION} (upgrade gonio)"
        )));
    }
    let len = u32::from_le_bytes(bytes[12..16].try_into().expect("4 bytes")) as usize;
    if len > MAX_HEADER || 16 + len > bytes.len() {
        return Err(bad(format!(
            "header of {len} bytes does not fit in the {}-byte file (truncated?)",
            bytes.len()
        )));
    }
    let header: Header = serde_json::from_slice(&bytes[16..16 + len])
        .map_err(|e| bad(format!("header is not valid JSON for a .gbrdf table: {e}")))?;
    if header.format != "gbrdf" || header.version != version {
        return Err(bad(
            "header names another format or version than the file".into()
        ));
    }
    if header.parameterisation != PARAMETERISATION {
        return Err(bad(format!(
            "unknown parameterisation '{}'",
            header.parameterisation
        )));
    }
    header.resolution.validate().map_err(bad)?;
    header.channels.validate().map_err(bad)?;
    let count = header.resolution.cell_count() as u64 * header.channels.count() as u64;
    if header.value_count != count {
        return Err(bad(format!(
            "header says {} values but a {} table of {} channels has {count}",
            header.value_count,
            header.resolution.describe(),
            header.channels.count()
        )));
    }
    let offset = header.data_offset;
    if offset < (16 + len) as u64 || !offset.is_multiple_of(ALIGN as u64) {
        return Err(bad(format!(
            "data offset {offset} is not an aligned offset after the header"
        )));
    }
    let want = offset + 4 * count;
    if bytes.len() as u64 != want {
        return Err(bad(format!(
            "file has {} bytes, the header describes {want} (truncated or padded)",
            bytes.len()
        )));
    }
    Ok(header)
}

/// Read a `.gbrdf` file into memory.
pub fn read(path: &Path) -> Result<BrdfTable> {
    let bytes = std::fs::read(path).map_err(|e| BrdfError::io(path, e))?;
    let header = parse_header(&bytes, path)?;
    let values = bytes[header.data_offset as usize..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
        .collect();
    into_table(header, Storage::Owned(values), path)
}

/// Open a `.gbrdf` file memory-mapped: the values are read from the page cache without a copy
/// (on a big-endian machine they are converted into memory instead). The file must not be
/// changed while the table is alive.
pub fn open_mapped(path: &Path) -> Result<BrdfTable> {
    let file = std::fs::File::open(path).map_err(|e| BrdfError::io(path, e))?;
    // SAFETY: the map is read-only and the documentation asks that the file stay unchanged
    // while mapped; every byte is validated before use.
    let map = unsafe { memmap2::Mmap::map(&file) }.map_err(|e| BrdfError::io(path, e))?;
    let header = parse_header(&map, path)?;
    let offset = header.data_offset as usize;
    let len = header.value_count as usize;
    let aligned = (map.as_ptr() as usize + offset).is_multiple_of(std::mem::align_of::<f32>());
    if cfg!(target_endian = "little") && aligned {
        into_table(header, Storage::Mapped { map, offset, len }, path)
    } else {
        let values = map[offset..]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().expect("4")))
            .collect();
        into_table(header, Storage::Owned(values), path)
    }
}

fn into_table(header: Header, data: Storage, path: &Path) -> Result<BrdfTable> {
    BrdfTable::from_storage(header.resolution, header.channels, header.provenance, data)
        .map_err(|e| BrdfError::format(path, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::TableBuilder;

    fn sample_table() -> BrdfTable {
        let channels = Channels::Spectral {
            wavelengths_nm: vec![450.0, 550.0, 650.0],
        };
        let mut b = TableBuilder::new(Resolution::anisotropic(6, 5, 8, 4), channels)
            .unwrap()
            .with_provenance(Provenance::new("test surface", "model"));
        b.fill(|c, out| {
            for (k, o) in out.iter_mut().enumerate() {
                *o = (1.0 + k as f64) * c.wi.z / (0.1 + c.wo.z) + 1.0 / 3.0;
            }
        });
        b.build().unwrap()
    }

    fn bits(t: &BrdfTable) -> Vec<u32> {
        t.values().iter().map(|v| v.to_bits()).collect()
    }

    #[test]
    fn round_trip_is_bit_exact_read_and_mapped() {
        let t = sample_table();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gbrdf");
        write(&t, &path).unwrap();
        for back in [read(&path).unwrap(), open_mapped(&path).unwrap()] {
            assert_eq!(bits(&back), bits(&t));
            assert_eq!(back.resolution(), t.resolution());
            assert_eq!(back.channels(), t.channels());
            assert_eq!(back.provenance(), t.provenance());
        }
        assert!(open_mapped(&path).unwrap().is_mapped() || cfg!(target_endian = "big"));
        let bytes = std::fs::read(&path).unwrap();
        let h = parse_header(&bytes, &path).unwrap();
        assert_eq!(h.data_offset % ALIGN as u64, 0);
    }

    #[test]
    fn corrupt_and_truncated_files_give_clean_errors() {
        let t = sample_table();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.gbrdf");
        write(&t, &path).unwrap();
        let good = std::fs::read(&path).unwrap();
        let bad_path = dir.path().join("bad.gbrdf");
        let check = |bytes: &[u8], needle: &str| {
            std::fs::write(&bad_path, bytes).unwrap();
            for e in [
                read(&bad_path).unwrap_err(),
                open_mapped(&bad_path).unwrap_err(),
            ] {
                let msg = e.to_string();
                assert!(msg.contains("bad.gbrdf") && msg.contains(needle), "{msg}");
            }
        };
        check(&good[..good.len() - 4], "truncated");
        check(&good[..100], "truncated");
        check(&good[..10], "too short");
        let mut magic = good.clone();
        magic[0] = b'X';
        check(&magic, "magic");
        let mut version = good.clone();
        version[8] = 9;
        check(&version, "version 9");
        let mut json = good.clone();
        json[17] = b'#';
        check(&json, "JSON");
        let mut huge = good.clone();
        huge[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        check(&huge, "does not fit");
        let mut padded = good.clone();
        padded.extend_from_slice(&[0; 4]);
        check(&padded, "padded");
        assert!(
            read(&dir.path().join("missing.gbrdf"))
                .unwrap_err()
                .to_string()
                .contains("missing.gbrdf")
        );
    }
}
