//! Bounds-checked reading of binary instrument files: every field read names the file and what
//! was being read when the file is too short, and every array a header claims is checked (with
//! the size helpers of [`crate::io::common`]) against the bytes present before anything is
//! allocated.

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use crate::io::common::{build_map, data_bytes, grid_points};
use byteorder::{BigEndian, ByteOrder, LittleEndian};
use std::io::Read;
use std::path::Path;

/// Largest ratio of inflated to deflated size zlib can reach (1032:1, zlib technical details,
/// <https://zlib.net/zlib_tech.html>): a header claiming more is lying.
pub(crate) const MAX_ZLIB_RATIO: usize = 1032;

/// The bytes of one file together with its name and format, for error messages.
pub(crate) struct Binary<'a> {
    path: &'a Path,
    format: &'static str,
    bytes: &'a [u8],
}

impl<'a> Binary<'a> {
    pub(crate) fn new(path: &'a Path, format: &'static str, bytes: &'a [u8]) -> Self {
        Binary {
            path,
            format,
            bytes,
        }
    }

    /// The file's name, for messages.
    pub(crate) fn path(&self) -> &'a Path {
        self.path
    }

    /// Length of the file in bytes.
    pub(crate) fn len(&self) -> usize {
        self.bytes.len()
    }

    /// A format error naming this file.
    pub(crate) fn err(&self, message: impl Into<String>) -> SurfaceError {
        SurfaceError::format(self.path, self.format, message)
    }

    /// `len` bytes at `offset`, or an error saying the file is truncated inside `what`.
    pub(crate) fn slice(&self, offset: usize, len: usize, what: &str) -> Result<&'a [u8]> {
        offset
            .checked_add(len)
            .and_then(|end| self.bytes.get(offset..end))
            .ok_or_else(|| {
                self.err(format!(
                    "file truncated: {what} needs {len} bytes at offset {offset}, but the file has \
                     only {} bytes",
                    self.bytes.len()
                ))
            })
    }

    pub(crate) fn u8(&self, offset: usize, what: &str) -> Result<u8> {
        Ok(self.slice(offset, 1, what)?[0])
    }

    pub(crate) fn u16<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<u16> {
        Ok(E::read_u16(self.slice(offset, 2, what)?))
    }

    pub(crate) fn i16<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<i16> {
        Ok(E::read_i16(self.slice(offset, 2, what)?))
    }

    pub(crate) fn u32<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<u32> {
        Ok(E::read_u32(self.slice(offset, 4, what)?))
    }

    pub(crate) fn i32<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<i32> {
        Ok(E::read_i32(self.slice(offset, 4, what)?))
    }

    pub(crate) fn f32<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<f32> {
        Ok(E::read_f32(self.slice(offset, 4, what)?))
    }

    pub(crate) fn f64<E: ByteOrder>(&self, offset: usize, what: &str) -> Result<f64> {
        Ok(E::read_f64(self.slice(offset, 8, what)?))
    }

    /// A fixed-size text field: up to the first NUL, Latin-1 decoded, surrounding blanks removed.
    pub(crate) fn text(&self, offset: usize, len: usize, what: &str) -> Result<String> {
        Ok(header_text(self.slice(offset, len, what)?))
    }

    /// The `points` values of `bytes_per_point` bytes each at `offset`, after checking (before
    /// any allocation) that the file holds them.
    pub(crate) fn array(
        &self,
        offset: usize,
        points: usize,
        bytes_per_point: usize,
        what: &str,
    ) -> Result<&'a [u8]> {
        let available = self.bytes.len().checked_sub(offset).ok_or_else(|| {
            self.err(format!(
                "{what} starts at offset {offset}, beyond the end of the {}-byte file",
                self.bytes.len()
            ))
        })?;
        let needed = data_bytes(self.path, self.format, points, bytes_per_point, available)
            .map_err(|e| self.err(format!("{what}: {}", strip_prefix(&e))))?;
        self.slice(offset, needed, what)
    }

    /// Number of points of an `nx × ny` grid stated by the header (both positive, not absurdly
    /// large).
    pub(crate) fn grid(&self, nx: i64, ny: i64) -> Result<(usize, usize)> {
        if nx <= 0 || ny <= 0 {
            return Err(self.err(format!("the header states a grid of {nx} × {ny} points")));
        }
        grid_points(self.path, self.format, nx as u64, ny as u64)?;
        Ok((nx as usize, ny as usize))
    }

    /// A spacing in metres that must be positive and finite.
    pub(crate) fn spacing(&self, value: f64, what: &str) -> Result<f64> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(self.err(format!(
                "{what} = {value} must be a positive, finite number"
            )))
        }
    }

    /// Inflate the zlib stream `input` (part of this file) onto `out`; it must give exactly
    /// `raw` bytes. A claim beyond zlib's largest expansion is refused before inflating, and
    /// inflation stops one byte past `raw`, so a lying size cannot make it allocate more.
    pub(crate) fn inflate(
        &self,
        input: &[u8],
        raw: usize,
        out: &mut Vec<u8>,
        what: &str,
    ) -> Result<()> {
        if raw > input.len().saturating_mul(MAX_ZLIB_RATIO) {
            return Err(self.err(format!(
                "{what}: {} compressed bytes cannot inflate to the {raw} bytes claimed",
                input.len()
            )));
        }
        let before = out.len();
        flate2::read::ZlibDecoder::new(input)
            .take(raw as u64 + 1)
            .read_to_end(out)
            .map_err(|e| self.err(format!("{what}: {e}")))?;
        if out.len() - before != raw {
            return Err(self.err(format!(
                "{what} inflates to {} bytes, not the {raw} its header states",
                out.len() - before
            )));
        }
        Ok(())
    }

    /// The height map of `ny` rows of `nx` heights in metres (NaN = not measured).
    pub(crate) fn height_map(
        &self,
        heights: Vec<f64>,
        grid: (usize, usize),
        spacing: (f64, f64),
    ) -> Result<HeightMap> {
        build_map(self.path, self.format, heights, grid, spacing)
    }
}

/// The message of a format error without its "file: format:" prefix, to re-wrap it with context.
fn strip_prefix(e: &SurfaceError) -> String {
    match e {
        SurfaceError::Format { message, .. } => message.clone(),
        other => other.to_string(),
    }
}

/// Big-endian byte order (Zygo).
pub(crate) type Be = BigEndian;
/// Little-endian byte order (Wyko, Sensofar, Digital Surf, Alicona).
pub(crate) type Le = LittleEndian;

/// Text of a fixed-size header field up to the first NUL, with surrounding blanks removed:
/// UTF-8 where the bytes are valid UTF-8 (other software writes `µm` as the two bytes `c2 b5`),
/// else Latin-1 (the instruments' own `b5` for `µ`). A Latin-1 string is valid UTF-8 only when it
/// is ASCII or holds a run like `Âµ`, which no header field means, so the choice is unambiguous.
pub(crate) fn header_text(bytes: &[u8]) -> String {
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    let bytes = &bytes[..end];
    match std::str::from_utf8(bytes) {
        Ok(text) => text.trim().to_string(),
        Err(_) => bytes
            .iter()
            .map(|&b| char::from(b))
            .collect::<String>()
            .trim()
            .to_string(),
    }
}

/// A time as `YYYY-MM-DDThh:mm:ssZ` (UTC, whole seconds; the civil date comes from `jiff`).
pub(crate) fn iso_utc(time: jiff::Timestamp) -> String {
    time.strftime("%Y-%m-%dT%H:%M:%SZ").to_string()
}

/// A Unix time (seconds since 1970-01-01 UTC) as `YYYY-MM-DDThh:mm:ssZ`, or `None` outside the
/// years -9999 to 9999.
pub(crate) fn unix_time_iso(seconds: i64) -> Option<String> {
    jiff::Timestamp::from_second(seconds).ok().map(iso_utc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unix_times_match_known_dates() {
        let iso = |s| unix_time_iso(s).unwrap();
        assert_eq!(iso(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 12:34:56 UTC (leap day), from `date -u -d @951827696`.
        assert_eq!(iso(951_827_696), "2000-02-29T12:34:56Z");
        assert_eq!(iso(-1), "1969-12-31T23:59:59Z");
        // The largest u32 time stamp a Zygo or Sensofar header can hold (`date -u -d @4294967295`).
        assert_eq!(iso(i64::from(u32::MAX)), "2106-02-07T06:28:15Z");
        assert_eq!(unix_time_iso(i64::MAX), None);
    }

    #[test]
    fn reads_are_bounds_checked() {
        let bytes = [1u8, 2, 3];
        let b = Binary::new(Path::new("x.bin"), "test", &bytes);
        assert_eq!(b.u16::<Be>(0, "a").unwrap(), 0x0102);
        assert_eq!(b.u16::<Le>(1, "a").unwrap(), 0x0302);
        let e = b.u32::<Le>(0, "the count").unwrap_err().to_string();
        assert!(e.contains("x.bin") && e.contains("the count"), "{e}");
        assert!(b.slice(usize::MAX, 2, "x").is_err());
        assert_eq!(b.array(1, 2, 1, "data").unwrap(), &[2, 3]);
        assert!(b.array(1, 2, 2, "data").is_err());
        assert!(b.array(5, 1, 1, "data").is_err());
        assert!(b.array(0, usize::MAX, 2, "data").is_err());
        assert!(b.grid(0, 3).is_err());
        assert!(b.grid(-1, 3).is_err());
        assert_eq!(b.grid(2, 3).unwrap(), (2, 3));
    }

    #[test]
    fn header_text_stops_at_nul_and_trims_and_reads_latin1_or_utf8() {
        assert_eq!(header_text(b" 20X  Mirau\0junk"), "20X  Mirau");
        assert_eq!(header_text(&[0xb5, b'm', b' ', b' ']), "µm");
        assert_eq!(header_text(&[0xc2, 0xb5, b'm', 0, 0xb5]), "µm");
        assert_eq!(header_text(&[0xc5, 0]), "Å");
        assert_eq!(header_text("Å".as_bytes()), "Å");
    }
}
