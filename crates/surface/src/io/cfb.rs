//! Reading one stream out of a Microsoft Compound File Binary (OLE2 structured storage), the
//! container of MountainsMap `.mnt` documents.
//!
//! Layout, from Microsoft's [MS-CFB] specification: a 512-byte header (signature
//! `D0 CF 11 E0 A1 B1 1A E1`, sector size 2^9 or 2^12, mini sector size 2^6, the number of FAT
//! sectors, the first sectors of the directory, the mini FAT and the DIFAT, and the first 109
//! DIFAT entries); sector `n` starts at byte `(n + 1) · sector size`. The FAT chains sectors
//! (`0xFFFFFFFE` ends a chain); the directory is a chain of 128-byte entries (UTF-16 name, type,
//! first sector, size). Streams smaller than the mini stream cutoff (4096 bytes) live in 64-byte
//! mini sectors inside the root entry's stream, chained by the mini FAT.
//!
//! Every sector number, chain and size is checked against the file before it is used: a chain
//! that leaves the file, loops, or is shorter than its stream is an error.
//!
//! [MS-CFB]: https://learn.microsoft.com/en-us/openspecs/windows_protocols/ms-cfb/

use crate::error::Result;
use crate::io::binary::{Binary, Le};

pub(crate) const SIGNATURE: &[u8] = &[0xd0, 0xcf, 0x11, 0xe0, 0xa1, 0xb1, 0x1a, 0xe1];

const END_OF_CHAIN: u32 = 0xffff_fffe;
const FREE: u32 = 0xffff_ffff;
const HEADER_DIFAT: usize = 109;
const ENTRY_SIZE: usize = 128;
const TYPE_STREAM: u8 = 2;
const TYPE_ROOT: u8 = 5;

/// A compound file's allocation tables, ready to read streams.
pub(crate) struct Compound<'a, 'b> {
    b: &'b Binary<'a>,
    sector: usize,
    mini_sector: usize,
    cutoff: u64,
    /// Version 3 files use only the low 32 bits of a stream size (MS-CFB 2.6.3).
    size_mask: u64,
    fat: Vec<u32>,
    directory: Vec<u8>,
}

impl<'a, 'b> Compound<'a, 'b> {
    /// The allocation tables and directory of the compound file `b`.
    pub(crate) fn open(b: &'b Binary<'a>) -> Result<Self> {
        if b.slice(0, 8, "compound file signature")? != SIGNATURE {
            return Err(b.err("not a compound (OLE2) file: signature missing"));
        }
        let shift = b.u16::<Le>(0x1e, "sector shift")?;
        let mini_shift = b.u16::<Le>(0x20, "mini sector shift")?;
        if !(shift == 9 || shift == 12) || mini_shift != 6 {
            return Err(b.err(format!(
                "sector sizes 2^{shift} and 2^{mini_shift} are not 2^9 or 2^12 and 2^6"
            )));
        }
        let sector = 1usize << shift;
        if !b.len().is_multiple_of(sector) {
            return Err(b.err(format!(
                "{} bytes is not a whole number of {sector}-byte sectors: the file is truncated",
                b.len()
            )));
        }
        let fat_sectors = b.u32::<Le>(0x2c, "number of FAT sectors")? as usize;
        if fat_sectors.saturating_mul(sector) > b.len() {
            return Err(b.err(format!(
                "{fat_sectors} FAT sectors of {sector} bytes do not fit in the file"
            )));
        }
        let mut compound = Compound {
            b,
            sector,
            mini_sector: 1 << mini_shift,
            cutoff: u64::from(b.u32::<Le>(0x38, "mini stream cutoff")?),
            size_mask: if b.u16::<Le>(0x1a, "major version")? == 3 {
                u64::from(u32::MAX)
            } else {
                u64::MAX
            },
            fat: Vec::with_capacity(fat_sectors * sector / 4),
            directory: Vec::new(),
        };
        // The FAT's sectors: 109 listed in the header, the rest in the chained DIFAT sectors.
        let mut fat_ids = Vec::with_capacity(fat_sectors);
        for k in 0..HEADER_DIFAT.min(fat_sectors) {
            fat_ids.push(b.u32::<Le>(0x4c + 4 * k, "DIFAT")?);
        }
        let mut difat = b.u32::<Le>(0x44, "first DIFAT sector")?;
        let per_sector = sector / 4 - 1;
        while fat_ids.len() < fat_sectors {
            let at = compound.offset(difat, "DIFAT sector")?;
            for k in 0..per_sector.min(fat_sectors - fat_ids.len()) {
                fat_ids.push(b.u32::<Le>(at + 4 * k, "DIFAT")?);
            }
            difat = b.u32::<Le>(at + 4 * per_sector, "next DIFAT sector")?;
        }
        for id in fat_ids {
            let at = compound.offset(id, "FAT sector")?;
            let table = b.slice(at, sector, "FAT sector")?;
            compound.fat.extend(
                table
                    .chunks_exact(4)
                    .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
            );
        }
        let first_dir = b.u32::<Le>(0x30, "first directory sector")?;
        compound.directory = compound.chain(first_dir, None, "directory")?;
        Ok(compound)
    }

    /// Byte offset of sector `id`, which must lie inside the file.
    fn offset(&self, id: u32, what: &str) -> Result<usize> {
        (id as usize)
            .checked_add(1)
            .and_then(|n| n.checked_mul(self.sector))
            .filter(|&at| at.saturating_add(self.sector) <= self.b.len())
            .ok_or_else(|| {
                self.b
                    .err(format!("{what}: sector {id} lies outside the file"))
            })
    }

    /// The bytes of the sector chain starting at `start`, cut to `size` when given.
    fn chain(&self, start: u32, size: Option<u64>, what: &str) -> Result<Vec<u8>> {
        let limit = size.map_or(self.b.len(), |s| s.min(self.b.len() as u64) as usize);
        let mut out = Vec::with_capacity(limit);
        let mut id = start;
        while id != END_OF_CHAIN && out.len() < size.map_or(usize::MAX, |s| s as usize) {
            if out.len() >= self.b.len() {
                return Err(self.b.err(format!("{what}: the sector chain loops")));
            }
            let at = self.offset(id, what)?;
            out.extend_from_slice(self.b.slice(at, self.sector, what)?);
            id = *self
                .fat
                .get(id as usize)
                .ok_or_else(|| self.b.err(format!("{what}: sector {id} has no FAT entry")))?;
        }
        if let Some(size) = size {
            if (out.len() as u64) < size {
                return Err(self.b.err(format!(
                    "{what}: its chain holds {} bytes, fewer than its size {size}",
                    out.len()
                )));
            }
            out.truncate(size as usize);
        }
        Ok(out)
    }

    /// The directory entry at `index`: name, type, first sector, size.
    fn entry(&self, index: usize) -> (String, u8, u32, u64) {
        let e = &self.directory[index * ENTRY_SIZE..(index + 1) * ENTRY_SIZE];
        let name_bytes = usize::from(u16::from_le_bytes([e[64], e[65]])).min(64);
        let units: Vec<u16> = e[..name_bytes]
            .chunks_exact(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .take_while(|&u| u != 0)
            .collect();
        let start = u32::from_le_bytes([e[116], e[117], e[118], e[119]]);
        let mut size = [0u8; 8];
        size.copy_from_slice(&e[120..128]);
        (
            String::from_utf16_lossy(&units),
            e[66],
            start,
            u64::from_le_bytes(size) & self.size_mask,
        )
    }

    /// The content of the stream called `name` (the first stream entry of that name).
    pub(crate) fn stream(&self, name: &str) -> Result<Vec<u8>> {
        let entries = self.directory.len() / ENTRY_SIZE;
        let found = (0..entries)
            .map(|i| self.entry(i))
            .find(|(n, kind, ..)| *kind == TYPE_STREAM && n == name);
        let Some((_, _, start, size)) = found else {
            return Err(self
                .b
                .err(format!("the compound file has no stream '{name}'")));
        };
        if size > self.b.len() as u64 {
            return Err(self.b.err(format!(
                "stream '{name}' claims {size} bytes, more than the file holds"
            )));
        }
        if size >= self.cutoff {
            return self.chain(start, Some(size), name);
        }
        // A small stream: mini sectors inside the root entry's stream.
        let root = (entries > 0).then(|| self.entry(0));
        let Some((_, TYPE_ROOT, root_start, root_size)) = root else {
            return Err(self
                .b
                .err("the compound file's first directory entry is not the root"));
        };
        let mini = self.chain(root_start, Some(root_size), "mini stream")?;
        let mini_fat_start = self.b.u32::<Le>(0x3c, "first mini FAT sector")?;
        let mini_fat: Vec<u32> = if mini_fat_start == END_OF_CHAIN || mini_fat_start == FREE {
            Vec::new()
        } else {
            self.chain(mini_fat_start, None, "mini FAT")?
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect()
        };
        let mut out = Vec::with_capacity(size as usize);
        let mut id = start;
        while (out.len() as u64) < size {
            let at = (id as usize)
                .checked_mul(self.mini_sector)
                .filter(|&at| at + self.mini_sector <= mini.len())
                .ok_or_else(|| {
                    self.b
                        .err(format!("stream '{name}': mini sector {id} lies outside"))
                })?;
            out.extend_from_slice(&mini[at..at + self.mini_sector]);
            id = *mini_fat.get(id as usize).ok_or_else(|| {
                self.b.err(format!(
                    "stream '{name}': mini sector {id} has no mini FAT entry"
                ))
            })?;
            if id == END_OF_CHAIN && (out.len() as u64) < size {
                return Err(self
                    .b
                    .err(format!("stream '{name}': its mini chain ends early")));
            }
        }
        out.truncate(size as usize);
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn put_u32(v: &mut [u8], at: usize, x: u32) {
        v[at..at + 4].copy_from_slice(&x.to_le_bytes());
    }

    /// A version-3 compound file after MS-CFB: sector 0 the FAT, 1 the directory (root entry
    /// and the 100-byte stream "Small"), 2 the mini FAT, 3 the mini stream holding "Small" in
    /// mini sectors 0 and 1.
    fn small_file() -> Vec<u8> {
        let mut f = vec![0u8; 512 * 5];
        f[..8].copy_from_slice(SIGNATURE);
        f[0x18..0x1a].copy_from_slice(&0x3eu16.to_le_bytes());
        f[0x1a..0x1c].copy_from_slice(&3u16.to_le_bytes());
        f[0x1c..0x1e].copy_from_slice(&0xfffeu16.to_le_bytes());
        f[0x1e..0x20].copy_from_slice(&9u16.to_le_bytes());
        f[0x20..0x22].copy_from_slice(&6u16.to_le_bytes());
        put_u32(&mut f, 0x2c, 1);
        put_u32(&mut f, 0x30, 1);
        put_u32(&mut f, 0x38, 4096);
        put_u32(&mut f, 0x3c, 2);
        put_u32(&mut f, 0x40, 1);
        put_u32(&mut f, 0x44, END_OF_CHAIN);
        put_u32(&mut f, 0x4c, 0);
        for k in 1..HEADER_DIFAT {
            put_u32(&mut f, 0x4c + 4 * k, FREE);
        }
        let sector = |n: usize| 512 * (n + 1);
        for (k, next) in [0xffff_fffd, END_OF_CHAIN, END_OF_CHAIN, END_OF_CHAIN]
            .into_iter()
            .enumerate()
        {
            put_u32(&mut f, sector(0) + 4 * k, next);
        }
        for k in 4..128 {
            put_u32(&mut f, sector(0) + 4 * k, FREE);
        }
        for (i, (name, kind, start, size)) in [
            ("Root Entry", TYPE_ROOT, 3, 128),
            ("Small", TYPE_STREAM, 0, 100),
        ]
        .into_iter()
        .enumerate()
        {
            let e = sector(1) + ENTRY_SIZE * i;
            let units: Vec<u8> = name.encode_utf16().flat_map(u16::to_le_bytes).collect();
            f[e..e + units.len()].copy_from_slice(&units);
            f[e + 64..e + 66].copy_from_slice(&(units.len() as u16 + 2).to_le_bytes());
            f[e + 66] = kind;
            put_u32(&mut f, e + 116, start);
            put_u32(&mut f, e + 120, size);
        }
        put_u32(&mut f, sector(2), 1);
        put_u32(&mut f, sector(2) + 4, END_OF_CHAIN);
        for (k, byte) in f[sector(3)..sector(3) + 100].iter_mut().enumerate() {
            *byte = k as u8;
        }
        f
    }

    #[test]
    fn small_streams_come_from_the_mini_stream() {
        let f = small_file();
        let b = Binary::new(Path::new("c.bin"), "test", &f);
        let c = Compound::open(&b).unwrap();
        let small = c.stream("Small").unwrap();
        assert_eq!(small, (0..100u8).collect::<Vec<_>>());
        let err = c.stream("Missing").err().unwrap().to_string();
        assert!(err.contains("c.bin") && err.contains("Missing"), "{err}");
    }

    #[test]
    fn broken_chains_are_errors() {
        // The mini chain ends after one of the two mini sectors "Small" needs.
        let mut f = small_file();
        put_u32(&mut f, 512 * 3, END_OF_CHAIN);
        let b = Binary::new(Path::new("short.bin"), "test", &f);
        let err = Compound::open(&b).unwrap().stream("Small").err().unwrap();
        assert!(err.to_string().contains("ends early"), "{err}");
        // The directory chain points at itself.
        let mut f = small_file();
        put_u32(&mut f, 512 + 4, 1);
        let b = Binary::new(Path::new("loop.bin"), "test", &f);
        let err = Compound::open(&b).err().unwrap().to_string();
        assert!(err.contains("loop.bin") && err.contains("loops"), "{err}");
        // A file cut inside a sector.
        let f = small_file();
        let b = Binary::new(Path::new("cut.bin"), "test", &f[..f.len() - 1]);
        let err = Compound::open(&b).err().unwrap().to_string();
        assert!(err.contains("truncated"), "{err}");
    }
}
