//! Bruker Vision64 `.opdx` reader (Dektak XT stylus profilometers): line profiles.
//!
//! Layout, as read by SurfaceTopography's `OPDx.py` and Gwyddion's `dektakvca.c`: the magic
//! `VCA DATA\x01\x00\x00\x55`, then a tree of items, all little-endian. An item is its name (u32
//! length, UTF-8 bytes), a type byte and a content that depends on the type: scalars (bool,
//! i16, u16, i32, u32, i64, u64, f32, f64), strings and byte blobs preceded by a variable
//! length (a byte 1, 2 or 4 giving the width of the length that follows), quantities (f64
//! value, unit name, unit symbol), units (unit name, symbol, f64 value, 12 bytes), string
//! lists, double arrays and matrices (a type name, a variable length, the payload), and
//! containers (a variable length, the items they hold, a terminator item of type 0x7F and two
//! bytes); the file ends like a container, with a terminator and two bytes. Item paths join
//! the names: `/MetaData/DataKind` is `Surface Profile` for a profile;
//! `/MetaData/1D_Channels/Height` lists the profile channels, and each channel `C` has
//! `/1D_Data/C/NumPoints`, `Extent` (the distance from the first to the last point, with its
//! unit), `DataScale` (the height of one stored unit, with its unit), `DataKind` and `Array`
//! (5 bytes, then `NumPoints` f64). A height is the stored value times the data scale; the
//! spacing is the extent over `NumPoints − 1`, and the points' positions (`PositionArray`),
//! when stored, must be evenly spaced. Areal maps (`Surface Height`, `/2D_Data`) are
//! recognised but not read.

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::Result;
use crate::heightmap::HeightMap;
use crate::io::binary::{Binary, Le};
use crate::io::common::{metres_per_unit, unit_scale};
use byteorder::ByteOrder;
use std::path::Path;

pub(crate) const NAME: &str = "Bruker OPDx";

const MAGIC: &[u8] = b"VCA DATA\x01\x00\x00\x55";
/// Bytes before the values of a double array.
const DOUBLE_ARRAY_EXTRA: usize = 5;
/// Bytes after the value of a unit.
const UNIT_EXTRA: usize = 12;
/// Deepest nesting of containers read (the files nest four or five deep).
const MAX_DEPTH: usize = 32;

pub(crate) fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The content of an item that the reader uses; everything else is skipped.
#[derive(Debug, Clone)]
enum Value {
    Integer(i64),
    Text(String),
    List(Vec<String>),
    /// A quantity or unit: a value in a unit.
    Quantity(f64, String),
    /// A double array: where its bytes start and how many there are.
    Array(usize, usize),
    /// Anything else (numbers, matrices, time stamps, type ids).
    Other,
}

/// Item paths and their values, in file order.
type Manifest = Vec<(String, Value)>;

/// A cursor over the item tree.
struct Items<'b, 'a> {
    b: &'b Binary<'a>,
    at: usize,
}

impl Items<'_, '_> {
    fn take(&mut self, len: usize, what: &str) -> Result<&[u8]> {
        let s = self.b.slice(self.at, len, what)?;
        self.at += len;
        Ok(s)
    }

    fn u8(&mut self, what: &str) -> Result<u8> {
        Ok(self.take(1, what)?[0])
    }

    fn u32(&mut self, what: &str) -> Result<u32> {
        Ok(Le::read_u32(self.take(4, what)?))
    }

    fn f64(&mut self, what: &str) -> Result<f64> {
        Ok(Le::read_f64(self.take(8, what)?))
    }

    fn name(&mut self, what: &str) -> Result<String> {
        let len = self.u32(what)? as usize;
        Ok(String::from_utf8_lossy(self.take(len, what)?).into_owned())
    }

    /// A length whose width (1, 2 or 4 bytes) its first byte gives.
    fn varlen(&mut self, what: &str) -> Result<usize> {
        Ok(match self.u8(what)? {
            1 => usize::from(self.u8(what)?),
            2 => usize::from(Le::read_u16(self.take(2, what)?)),
            4 => self.u32(what)? as usize,
            other => {
                return Err(self.b.err(format!(
                    "{what}: a length of {other} bytes is not 1, 2 or 4"
                )));
            }
        })
    }

    /// The end of a block of `len` bytes from here, checked against the file.
    fn block_end(&self, len: usize, what: &str) -> Result<usize> {
        self.b.slice(self.at, len, what)?;
        Ok(self.at + len)
    }

    /// Read the next item into `manifest`; `false` at a terminator.
    fn item(&mut self, manifest: &mut Manifest, prefix: &str, depth: usize) -> Result<bool> {
        let name = self.name("item name")?;
        let path = format!("{prefix}/{name}");
        let kind = self.u8("item type")?;
        let value = match kind {
            0x7F => return Ok(false),
            0x7D | 0x46 | 0x47 => {
                if depth >= MAX_DEPTH {
                    return Err(self.b.err(format!("{path}: containers nest too deep")));
                }
                let len = self.varlen(&path)?;
                let end = self.block_end(len, &path)?;
                while self.item(manifest, &path, depth + 1)? {
                    if self.at > end {
                        break;
                    }
                }
                self.take(2, "container end")?;
                if self.at != end {
                    return Err(self.b.err(format!(
                        "{path}: the container's items end at byte {}, not at {end} as its \
                         length says",
                        self.at
                    )));
                }
                return Ok(true);
            }
            0x01 => self.take(1, &path).map(|_| Value::Other)?,
            0x04 | 0x05 => self.take(2, &path).map(|_| Value::Other)?,
            0x06 => Value::Integer(i64::from(Le::read_i32(self.take(4, &path)?))),
            0x07 => Value::Integer(i64::from(self.u32(&path)?)),
            0x0A => Value::Integer(Le::read_i64(self.take(8, &path)?)),
            0x0B => Value::Integer(i64::try_from(Le::read_u64(self.take(8, &path)?)).unwrap_or(-1)),
            0x0C | 0x0D => {
                let width = if kind == 0x0C { 4 } else { 8 };
                self.take(width, &path).map(|_| Value::Other)?
            }
            0x12 => {
                let len = self.varlen(&path)?;
                Value::Text(String::from_utf8_lossy(self.take(len, &path)?).into_owned())
            }
            0x13 => {
                let len = self.varlen(&path)?;
                let end = self.block_end(len, &path)?;
                let value = self.f64(&path)?;
                self.name(&path)?;
                let symbol = self.name(&path)?;
                if self.at > end {
                    return Err(self
                        .b
                        .err(format!("{path}: the quantity overruns its length")));
                }
                self.at = end;
                Value::Quantity(value, symbol)
            }
            0x15 => self.take(9, &path).map(|_| Value::Other)?,
            0x18 => {
                let len = self.varlen(&path)?;
                let end = self.block_end(len, &path)?;
                self.name(&path)?;
                let symbol = self.name(&path)?;
                let value = self.f64(&path)?;
                self.take(UNIT_EXTRA, &path)?;
                if self.at != end {
                    return Err(self
                        .b
                        .err(format!("{path}: the unit does not fill its length")));
                }
                Value::Quantity(value, symbol)
            }
            0x40 => {
                self.name(&path)?;
                let len = self.varlen(&path)?;
                let start = self.at;
                self.at = self.block_end(len, &path)?;
                Value::Array(start, len)
            }
            0x42 => {
                self.name(&path)?;
                let len = self.varlen(&path)?;
                let end = self.block_end(len, &path)?;
                let mut list = Vec::new();
                while self.at < end {
                    list.push(self.name(&path)?);
                }
                if self.at != end {
                    return Err(self.b.err(format!("{path}: the list overruns its length")));
                }
                Value::List(list)
            }
            0x0E | 0x45 | 0x00 | 0x7C => {
                // Type ids, matrices and position data: a type name, (for a named matrix a
                // u32 and a name), a length and that many bytes.
                self.name(&path)?;
                if kind == 0x00 {
                    self.u32(&path)?;
                    self.name(&path)?;
                }
                let len = self.varlen(&path)?;
                self.at = self.block_end(len, &path)?;
                Value::Other
            }
            other => {
                return Err(self.b.err(format!(
                    "{path}: unknown item type {other:#04x} at byte {}",
                    self.at - 1
                )));
            }
        };
        manifest.push((path, value));
        Ok(true)
    }
}

pub(crate) fn parse(
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let b = Binary::new(path, NAME, bytes);
    if !bytes.starts_with(MAGIC) {
        return Err(b.err("not an OPDx file: the magic 'VCA DATA' is missing"));
    }
    let mut items = Items {
        b: &b,
        at: MAGIC.len(),
    };
    let mut manifest = Manifest::new();
    while items.item(&mut manifest, "", 0)? {}
    items.take(2, "end of the item tree")?;
    let get = |key: &str| {
        manifest
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.clone())
    };
    let missing = |key: &str| b.err(format!("the file lacks the item {key}"));
    match get("/MetaData/DataKind") {
        Some(Value::Text(kind)) if kind == "Surface Profile" => {}
        Some(Value::Text(kind)) => {
            return Err(b.err(format!(
                "the file holds a '{kind}'; only profiles ('Surface Profile') are read"
            )));
        }
        _ => return Err(missing("/MetaData/DataKind")),
    }
    let Some(Value::List(names)) = get("/MetaData/1D_Channels/Height") else {
        return Err(missing("/MetaData/1D_Channels/Height"));
    };
    if names.is_empty() {
        return Err(b.err("the file lists no profile channel"));
    }
    let quantity = |key: &str| match get(key) {
        Some(Value::Quantity(value, unit)) if value.is_finite() => Ok((value, unit)),
        _ => Err(missing(key)),
    };
    let channels = names
        .iter()
        .enumerate()
        .map(|(index, name)| {
            let (_, unit) = quantity(&format!("/1D_Data/{name}/DataScale"))?;
            let kind = match get(&format!("/1D_Data/{name}/DataKind")) {
                Some(Value::Text(kind)) => kind,
                _ => name.clone(),
            };
            Ok(Channel {
                index,
                name: kind,
                is_height: metres_per_unit(&unit).is_some(),
                problem: None,
                unit: Some(unit),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let index = select(path, NAME, &channels, selector)?;
    let prefix = format!("/1D_Data/{}", names[index]);
    let n = match get(&format!("{prefix}/NumPoints")) {
        Some(Value::Integer(n)) => b.grid(n, 1)?.0,
        _ => return Err(missing(&format!("{prefix}/NumPoints"))),
    };
    if n < 2 {
        return Err(b.err("a profile of one point has no spacing"));
    }
    let Some(Value::Array(start, len)) = get(&format!("{prefix}/Array")) else {
        return Err(missing(&format!("{prefix}/Array")));
    };
    let values = b.array(start + DOUBLE_ARRAY_EXTRA, n, 8, "profile")?;
    if DOUBLE_ARRAY_EXTRA + values.len() != len {
        return Err(b.err(format!(
            "the profile array holds {len} bytes, not the {} of {n} points",
            DOUBLE_ARRAY_EXTRA + values.len()
        )));
    }
    check_even_spacing(&b, get(&format!("{prefix}/PositionArray")), n)?;
    let (scale, unit) = quantity(&format!("{prefix}/DataScale"))?;
    let scale = scale * unit_scale(path, NAME, "height", &unit)?;
    let heights = values
        .chunks_exact(8)
        .map(|c| {
            let v = Le::read_f64(c) * scale;
            if v.is_finite() { v } else { f64::NAN }
        })
        .collect();
    let (extent, unit) = quantity(&format!("{prefix}/Extent"))?;
    let extent = extent * unit_scale(path, NAME, "extent", &unit)?;
    let dx = b.spacing(extent / (n - 1) as f64, "spacing (m)")?;
    let mut map = HeightMap::profile(heights, dx).map_err(|e| b.err(e.to_string()))?;
    map.meta.channel = index;
    map.meta.channels = channels;
    map.meta.instrument = match get("/MetaData/MeasurementSettings/InstrumentName") {
        Some(Value::Text(name)) => Some(format!("Bruker {name}")),
        _ => Some("Bruker Dektak".into()),
    };
    if let (Some(Value::Text(date)), Some(Value::Text(time))) =
        (get("/MetaData/Date"), get("/MetaData/Time"))
    {
        map.meta.date = Some(format!("{date} {time}"));
    }
    Ok(map)
}

/// The profile is read on an even grid; when the file also stores each point's position (a
/// `PositionArray` of f64), those positions must be evenly spaced (to 1 part in 10^6 of the
/// step), or the profile is refused rather than misplaced.
fn check_even_spacing(b: &Binary, positions: Option<Value>, n: usize) -> Result<()> {
    let Some(Value::Array(start, len)) = positions else {
        return Ok(());
    };
    let bytes = b.array(start + DOUBLE_ARRAY_EXTRA, n, 8, "profile positions")?;
    if DOUBLE_ARRAY_EXTRA + bytes.len() != len {
        return Err(b.err(format!(
            "the position array holds {len} bytes, not the {} of {n} points",
            DOUBLE_ARRAY_EXTRA + bytes.len()
        )));
    }
    let x: Vec<f64> = bytes.chunks_exact(8).map(Le::read_f64).collect();
    let step = (x[n - 1] - x[0]) / (n - 1) as f64;
    let uneven = x
        .windows(2)
        .map(|w| w[1] - w[0])
        .find(|d| !((d - step).abs() <= 1e-6 * step.abs() && step > 0.0));
    match uneven {
        Some(d) => Err(b.err(format!(
            "the profile's points are not evenly spaced (a step of {d} where the mean step is \
             {step}): uneven profiles are not read"
        ))),
        None => Ok(()),
    }
}
