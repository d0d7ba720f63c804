//! The "tensor file" container that Mitsuba 3 and pbrt-v4 read for their `measured` material
//! (format of Dupuy & Jakob, "An adaptive parameterization for efficient material acquisition
//! and rendering", SIGGRAPH Asia 2018), as laid out by the readers in Mitsuba's
//! `src/core/tensor.cpp` and pbrt-v4's `src/pbrt/bxdfs.cpp`:
//!
//! - 12 bytes `tensor_file\0`, two version bytes (1, 0), u32 field count;
//! - per field: u16 name length, the name, u16 rank, u8 type code, u64 byte offset of the data,
//!   then `rank` u64 extents (row-major, last fastest);
//! - the data blocks at their offsets (this writer aligns them to 8 bytes).
//!
//! All little-endian. Type codes: 1 = u8, 10 = f32 (the `Struct::Type` enumeration: Invalid,
//! UInt8, Int8, UInt16, Int16, UInt32, Int32, UInt64, Int64, Float16, Float32, Float64).

use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

const MAGIC: &[u8; 12] = b"tensor_file\0";
/// Type code of u8 data.
pub const U8: u8 = 1;
/// Type code of f32 data.
pub const F32: u8 = 10;

/// One named array of a tensor file.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Type code ([`U8`] or [`F32`] are the ones this module converts).
    pub dtype: u8,
    /// Extents, slowest first.
    pub shape: Vec<u64>,
    /// Raw little-endian bytes.
    pub data: Vec<u8>,
}

impl Field {
    /// An f32 field.
    pub fn f32(shape: &[usize], values: &[f32]) -> Field {
        let data = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        Field {
            dtype: F32,
            shape: shape.iter().map(|&s| s as u64).collect(),
            data,
        }
    }

    /// A u8 field.
    pub fn u8(values: &[u8]) -> Field {
        Field {
            dtype: U8,
            shape: vec![values.len() as u64],
            data: values.to_vec(),
        }
    }

    /// The values of an f32 field.
    pub fn as_f32(&self) -> Option<Vec<f32>> {
        (self.dtype == F32).then(|| {
            self.data
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes(b.try_into().expect("4")))
                .collect()
        })
    }

    /// Number of elements.
    pub fn len(&self) -> u64 {
        self.shape.iter().product()
    }

    /// Whether the field has no element.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

fn type_size(dtype: u8) -> Option<u64> {
    match dtype {
        1 | 2 => Some(1),
        3 | 4 | 9 => Some(2),
        5 | 6 | 10 => Some(4),
        7 | 8 | 11 => Some(8),
        _ => None,
    }
}

/// Write fields (in name order) to `path` atomically.
pub fn write(path: &Path, fields: &BTreeMap<String, Field>) -> Result<()> {
    let header_len: usize = 12
        + 2
        + 4
        + fields
            .iter()
            .map(|(n, f)| 2 + n.len() + 2 + 1 + 8 + 8 * f.shape.len())
            .sum::<usize>();
    let mut offsets = Vec::with_capacity(fields.len());
    let mut at = header_len.div_ceil(8) * 8;
    for f in fields.values() {
        offsets.push(at as u64);
        at = (at + f.data.len()).div_ceil(8) * 8;
    }
    write_atomic(path, |w| {
        w.write_all(MAGIC)?;
        w.write_all(&[1, 0])?;
        w.write_all(&(fields.len() as u32).to_le_bytes())?;
        for ((name, f), off) in fields.iter().zip(&offsets) {
            w.write_all(&(name.len() as u16).to_le_bytes())?;
            w.write_all(name.as_bytes())?;
            w.write_all(&(f.shape.len() as u16).to_le_bytes())?;
            w.write_all(&[f.dtype])?;
            w.write_all(&off.to_le_bytes())?;
            for s in &f.shape {
                w.write_all(&s.to_le_bytes())?;
            }
        }
        let mut pos = header_len;
        for (f, off) in fields.values().zip(&offsets) {
            w.write_all(&vec![0u8; *off as usize - pos])?;
            w.write_all(&f.data)?;
            pos = *off as usize + f.data.len();
        }
        Ok(())
    })
}

/// Read every field of a tensor file, checking each against the file's size.
pub fn read(path: &Path) -> Result<BTreeMap<String, Field>> {
    let bytes = std::fs::read(path).map_err(|e| BrdfError::io(path, e))?;
    let bad = |p: String| BrdfError::format(path, p);
    if bytes.len() < 18 || &bytes[..12] != MAGIC {
        return Err(bad("not a tensor file (no 'tensor_file' signature)".into()));
    }
    if bytes[12] != 1 || bytes[13] != 0 {
        return Err(bad(format!(
            "tensor file version {}.{}; only 1.0 is known",
            bytes[12], bytes[13]
        )));
    }
    let mut pos = 14usize;
    let mut take = |n: usize| -> Result<&[u8]> {
        let s = bytes
            .get(pos..pos + n)
            .ok_or_else(|| bad("header runs past the end (truncated?)".into()))?;
        pos += n;
        Ok(s)
    };
    let n_fields = u32::from_le_bytes(take(4)?.try_into().expect("4"));
    let mut fields = BTreeMap::new();
    for _ in 0..n_fields {
        let name_len = u16::from_le_bytes(take(2)?.try_into().expect("2")) as usize;
        let name = String::from_utf8(take(name_len)?.to_vec())
            .map_err(|_| bad("a field name is not UTF-8".into()))?;
        let rank = u16::from_le_bytes(take(2)?.try_into().expect("2")) as usize;
        let dtype = take(1)?[0];
        let offset = u64::from_le_bytes(take(8)?.try_into().expect("8"));
        let mut shape = Vec::with_capacity(rank);
        for _ in 0..rank {
            shape.push(u64::from_le_bytes(take(8)?.try_into().expect("8")));
        }
        let size =
            type_size(dtype).ok_or_else(|| bad(format!("field '{name}': unknown type {dtype}")))?;
        let len = shape
            .iter()
            .try_fold(size, |a, &s| a.checked_mul(s))
            .filter(|&l| {
                offset
                    .checked_add(l)
                    .is_some_and(|end| end <= bytes.len() as u64)
            })
            .ok_or_else(|| {
                bad(format!(
                    "field '{name}' of shape {shape:?} runs past the end"
                ))
            })?;
        let data = bytes[offset as usize..(offset + len) as usize].to_vec();
        fields.insert(name, Field { dtype, shape, data });
    }
    Ok(fields)
}
