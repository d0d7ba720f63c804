//! ISO 25178-72 X3P (the openGPS "ISO5436_2" container): a zip archive holding `main.xml`,
//! which describes the axes and the grid, the point data (in `bindata/data.bin` or as
//! `<DataList>` inside the XML), an optional bitmask of valid points and MD5 checksums.
//!
//! Read: matrix data (`<MatrixDimension>`, one layer) of int16, int32, float32 or float64 (`I`,
//! `L`, `F`, `D`), incremental or absolute x and y axes (absolute ones must lie on a regular
//! grid), invalid points from `valid.bin` (bit i, least significant first, of byte i / 8), from
//! empty `<Datum/>` elements and from non-finite floats. Every member's zip CRC-32 is verified:
//! a mismatch is an error naming the member. An MD5 checksum that does not match is a warning in
//! [`crate::Metadata::warnings`], not an error (the zip CRC already guards the bytes).
//!
//! Variants other writers produce are read with a warning: every member under one folder
//! (`name/main.xml`, `name/bindata/data.bin`, as the R package x3ptools writes), a root element
//! outside the ISO 5436-2 namespace, and an empty `<Offset/>` (taken as 0).
//!
//! Written: float64 binary data, a `valid.bin` where points are missing, and the checksums.

use super::common::{build_map, data_bytes, grid_points, md5_hex};
use crate::error::{Result, SurfaceError};
use crate::heightmap::{HeightMap, Metadata};
use roxmltree::{Document, Node};
use std::io::{Cursor, Read, Write};
use std::path::Path;
use zip::ZipArchive;

pub(crate) const NAME: &str = "ISO 25178-72 X3P";

const ZIP_MAGIC: &[u8] = b"PK\x03\x04";
/// Largest expansion that DEFLATE achieves (1032:1, zlib's technical notes): an entry that
/// declares more bytes than its compressed size allows is lying.
const MAX_DEFLATE_RATIO: u64 = 1032;
/// What X3P writers put in a required field they know nothing about.
const NOT_AVAILABLE: &str = "not available";
/// Namespace of the ISO 5436-2 schema that X3P files use.
const NAMESPACE: &str = "http://www.opengps.eu/2008/ISO5436_2";

/// Zip magic, and `main.xml` named in the first local header or in the central directory.
pub(crate) fn sniff(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1024)];
    let tail = &bytes[bytes.len().saturating_sub(70_000)..];
    bytes.starts_with(ZIP_MAGIC) && (contains(head, b"main.xml") || contains(tail, b"main.xml"))
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

/// The numeric type of an axis's values (ISO 5436-2 `DataType`).
#[derive(Debug, Clone, Copy, PartialEq)]
enum DataType {
    Int16,
    Int32,
    Float32,
    Float64,
}

impl DataType {
    fn from_code(code: &str) -> Option<Self> {
        Some(match code {
            "I" => DataType::Int16,
            "L" => DataType::Int32,
            "F" => DataType::Float32,
            "D" => DataType::Float64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            DataType::Int16 => 2,
            DataType::Int32 | DataType::Float32 => 4,
            DataType::Float64 => 8,
        }
    }

    /// The little-endian value at the start of `b`.
    fn read(self, b: &[u8]) -> f64 {
        match self {
            DataType::Int16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            DataType::Int32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::Float32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::Float64 => f64::from_le_bytes(b[..8].try_into().expect("8 bytes")),
        }
    }
}

/// One axis of `Record1/Axes`: incremental (`I`: coordinate = offset + index × increment) or
/// absolute (`A`: every point stores its coordinate as offset + increment × value).
#[derive(Debug, Clone, Copy)]
struct Axis {
    absolute: bool,
    data_type: DataType,
    increment: f64,
    offset: f64,
}

impl Axis {
    fn value(&self, raw: f64) -> f64 {
        self.offset + self.increment * raw
    }
}

/// Read an X3P file.
pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    if !bytes.starts_with(ZIP_MAGIC) {
        return Err(fail(
            "the file does not start with a zip local header (PK\\3\\4)".into(),
        ));
    }
    let zip = ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| fail(format!("not a readable zip container: {e}")))?;
    let mut meta = Metadata::default();
    let mut zip = Container::open(path, zip, &mut meta)?;
    let xml_bytes = zip.read_entry(path, "main.xml", None)?;
    let xml =
        std::str::from_utf8(&xml_bytes).map_err(|e| fail(format!("main.xml is not UTF-8: {e}")))?;
    let xml = xml.trim_start_matches('\u{feff}');
    let declared;
    let doc = match Document::parse(xml) {
        Ok(doc) => doc,
        Err(roxmltree::Error::UnknownNamespace(prefix, _)) => {
            // A prefixed root (`<p:ISO5436_2>`) whose prefix nobody declared: bind it to the
            // ISO 5436-2 namespace, which is what the writer meant.
            declared = declare_prefix(xml, &prefix)
                .ok_or_else(|| fail(format!("main.xml uses the undeclared prefix '{prefix}'")))?;
            meta.warn(format!(
                "main.xml uses the namespace prefix '{prefix}' without declaring it; read as the \
                 ISO 5436-2 namespace"
            ));
            Document::parse(&declared)
                .map_err(|e| fail(format!("main.xml is not well-formed XML: {e}")))?
        }
        Err(e) => return Err(fail(format!("main.xml is not well-formed XML: {e}"))),
    };
    let root = doc.root_element();
    if root.tag_name().name() != "ISO5436_2" {
        return Err(fail(format!(
            "main.xml has root element <{}>, not <ISO5436_2>",
            root.tag_name().name()
        )));
    }
    if root.tag_name().namespace() != Some(NAMESPACE) {
        meta.warn(format!(
            "the root element <ISO5436_2> is not in the ISO 5436-2 namespace ({NAMESPACE}); \
             read as if it were"
        ));
    }

    let record1 = child(path, root, "Record1")?;
    let feature = text_of(path, record1, "FeatureType")?;
    if feature != "SUR" {
        return Err(fail(format!(
            "feature type '{feature}' is not an areal surface (SUR); profiles and point clouds \
             are not height maps"
        )));
    }
    let axes = child(path, record1, "Axes")?;
    let [cx, cy, cz] = ["CX", "CY", "CZ"].map(|name| axis(path, axes, name, &mut meta));
    let (cx, cy, cz) = (cx?, cy?, cz?);
    if !cz.absolute {
        return Err(fail("the z axis (CZ) must be absolute (AxisType A)".into()));
    }

    if let Some(record2) = element(root, "Record2") {
        read_record2(record2, &mut meta);
    }

    let record3 = child(path, root, "Record3")?;
    let Some(dims) = element(record3, "MatrixDimension") else {
        return Err(fail(
            "Record3 has no <MatrixDimension>: unordered point lists are not supported".into(),
        ));
    };
    let size = |name: &str| -> Result<u64> {
        let text = text_of(path, dims, name)?;
        text.parse::<u64>()
            .map_err(|_| fail(format!("MatrixDimension/{name} '{text}' is not a count")))
    };
    let (nx, ny, nz) = (size("SizeX")?, size("SizeY")?, size("SizeZ")?);
    if nz != 1 {
        return Err(fail(format!(
            "{nz} layers (SizeZ): only single-layer maps are supported"
        )));
    }
    let n = grid_points(path, NAME, nx, ny)?;
    let (nx, ny) = (nx as usize, ny as usize);

    let columns = [cx, cy, cz];
    let points = if let Some(link) = element(record3, "DataLink") {
        read_binary_points(path, &mut zip, link, &columns, n, &mut meta)?
    } else if let Some(list) = element(record3, "DataList") {
        read_xml_points(path, list, &columns, n)?
    } else {
        return Err(fail("Record3 has neither <DataLink> nor <DataList>".into()));
    };

    let checksum_name = element(root, "Record4")
        .and_then(|r| element(r, "ChecksumFile"))
        .and_then(|n| n.text())
        .map_or("md5checksum.hex", str::trim);
    check_main_checksum(&mut zip, checksum_name, &xml_bytes, &mut meta);

    let dx = spacing(
        path,
        "x",
        &cx,
        points.x.as_deref(),
        &points.z,
        (nx, ny),
        true,
    )?;
    let dy = spacing(
        path,
        "y",
        &cy,
        points.y.as_deref(),
        &points.z,
        (nx, ny),
        false,
    )?;
    let mut map = build_map(path, NAME, points.z, (nx, ny), (dx, dy))?;
    for warning in meta.warnings() {
        map.meta.warn(format!("{}: {warning}", path.display()));
    }
    meta.extra
        .retain(|(k, _)| k != crate::heightmap::WARNING_KEY);
    map.meta.instrument = meta.instrument;
    map.meta.date = meta.date;
    map.meta.extra.append(&mut meta.extra);
    Ok(map)
}

/// The heights (NaN where invalid) and, for absolute x or y axes, the stored coordinates.
struct Points {
    x: Option<Vec<f64>>,
    y: Option<Vec<f64>>,
    z: Vec<f64>,
}

fn read_binary_points(
    path: &Path,
    zip: &mut Container,
    link: Node,
    columns: &[Axis; 3],
    n: usize,
    meta: &mut Metadata,
) -> Result<Points> {
    let point_size: usize = columns
        .iter()
        .filter(|a| a.absolute)
        .map(|a| a.data_type.size())
        .sum();
    let data_name = text_of(path, link, "PointDataLink")?;
    let data = zip.read_entry(path, data_name, Some((n, point_size)))?;
    let valid_name = element(link, "ValidPointsLink")
        .and_then(|e| e.text())
        .map(str::trim);
    let valid = match valid_name {
        Some(name) => Some(zip.read_entry(path, name, Some((n.div_ceil(8), 1)))?),
        None => None,
    };
    // The checksums take as long as decoding: compute them on another thread.
    let (digests, (x, y, z)) = rayon::join(
        || (md5_hex(&data), valid.as_deref().map(md5_hex)),
        || decode_points(&data, valid.as_deref(), columns, n, point_size),
    );
    if let Some(expected) = element(link, "MD5ChecksumPointData").and_then(|e| e.text()) {
        compare_md5(meta, data_name, &digests.0, expected);
    }
    let expected = element(link, "MD5ChecksumValidPoints").and_then(|e| e.text());
    if let (Some(name), Some(actual), Some(expected)) = (valid_name, &digests.1, expected) {
        compare_md5(meta, name, actual, expected);
    }
    Ok(Points { x, y, z })
}

/// The stored coordinates of the absolute axes of `n` points of `point_size` bytes (x, y when
/// absolute, and z), with NaN heights where `valid` clears a point's bit or a float is not
/// finite.
fn decode_points(
    data: &[u8],
    valid: Option<&[u8]>,
    columns: &[Axis; 3],
    n: usize,
    point_size: usize,
) -> (Option<Vec<f64>>, Option<Vec<f64>>, Vec<f64>) {
    let mut offset = 0;
    let mut column = |axis: &Axis| -> Option<Vec<f64>> {
        if !axis.absolute {
            return None;
        }
        let start = offset;
        offset += axis.data_type.size();
        let values = (0..n)
            .map(|i| axis.value(axis.data_type.read(&data[start + i * point_size..])))
            .collect();
        Some(values)
    };
    let x = column(&columns[0]);
    let y = column(&columns[1]);
    let mut z = column(&columns[2]).expect("CZ is absolute");
    for (i, h) in z.iter_mut().enumerate() {
        let masked = valid.is_some_and(|bits| bits[i / 8] & (1 << (i % 8)) == 0);
        if masked || !h.is_finite() {
            *h = f64::NAN;
        }
    }
    (x, y, z)
}

fn read_xml_points(path: &Path, list: Node, columns: &[Axis; 3], n: usize) -> Result<Points> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let count = list.children().filter(|c| c.is_element()).count();
    if count != n {
        return Err(fail(format!(
            "<DataList> holds {count} <Datum> elements, MatrixDimension states {n} points"
        )));
    }
    let stored: Vec<usize> = (0..3).filter(|&i| columns[i].absolute).collect();
    let mut values: [Vec<f64>; 3] = Default::default();
    for &i in &stored {
        values[i] = Vec::with_capacity(n);
    }
    for (index, datum) in list.children().filter(|c| c.is_element()).enumerate() {
        let text = datum.text().unwrap_or("").trim();
        if text.is_empty() {
            for &i in &stored {
                values[i].push(f64::NAN);
            }
            continue;
        }
        let parts: Vec<&str> = text.split(';').map(str::trim).collect();
        if parts.len() != stored.len() {
            return Err(fail(format!(
                "<Datum> {index} holds {} values, the absolute axes need {}",
                parts.len(),
                stored.len()
            )));
        }
        for (&i, part) in stored.iter().zip(&parts) {
            let raw = if part.is_empty() {
                f64::NAN
            } else {
                part.parse::<f64>()
                    .map_err(|_| fail(format!("<Datum> {index}: '{part}' is not a number")))?
            };
            values[i].push(if raw.is_finite() {
                columns[i].value(raw)
            } else {
                f64::NAN
            });
        }
    }
    let [x, y, z] = values;
    Ok(Points {
        x: columns[0].absolute.then_some(x),
        y: columns[1].absolute.then_some(y),
        z,
    })
}

/// The spacing along one axis: the increment of an incremental axis, or for an absolute axis
/// the slope of the least-squares line through the stored coordinates against the grid index,
/// provided every valid point lies within 1% of a spacing of that line.
fn spacing(
    path: &Path,
    name: &str,
    axis: &Axis,
    coords: Option<&[f64]>,
    z: &[f64],
    (nx, ny): (usize, usize),
    along_x: bool,
) -> Result<f64> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let Some(coords) = coords else {
        return Ok(axis.increment);
    };
    let index = |i: usize| if along_x { i % nx } else { i / nx } as f64;
    let (mut s, mut si, mut sc, mut sii, mut sic) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, (&c, &h)) in coords.iter().zip(z).enumerate() {
        if h.is_nan() || !c.is_finite() {
            continue;
        }
        let k = index(i);
        (s, si, sc, sii, sic) = (s + 1.0, si + k, sc + c, sii + k * k, sic + k * c);
    }
    let denominator = s * sii - si * si;
    if (if along_x { nx } else { ny }) < 2 || denominator <= 0.0 {
        return Err(fail(format!(
            "the absolute {name} axis has too few valid points to give a spacing"
        )));
    }
    let step = (s * sic - si * sc) / denominator;
    let origin = (sc - step * si) / s;
    let worst = coords
        .iter()
        .zip(z)
        .enumerate()
        .filter(|(_, (c, h))| !h.is_nan() && c.is_finite())
        .map(|(i, (c, _))| (c - origin - step * index(i)).abs())
        .fold(0.0, f64::max);
    if !(step > 0.0 && worst <= 0.01 * step) {
        return Err(fail(format!(
            "the absolute {name} coordinates do not lie on an increasing regular grid \
             (fitted spacing {step:e} m, worst deviation {worst:e} m)"
        )));
    }
    Ok(step)
}

/// Record2's metadata; empty fields and the placeholder "not available" (which MountainsMap
/// and gonio write) are skipped.
fn read_record2(record2: Node, meta: &mut Metadata) {
    fn text<'a>(node: Node<'a, '_>, name: &str) -> Option<&'a str> {
        element(node, name)
            .and_then(|e| e.text())
            .map(str::trim)
            .filter(|t| !t.is_empty() && *t != NOT_AVAILABLE)
    }
    meta.date = text(record2, "Date").map(str::to_string);
    if let Some(instrument) = element(record2, "Instrument") {
        let name: Vec<&str> = ["Manufacturer", "Model"]
            .iter()
            .filter_map(|k| text(instrument, k))
            .collect();
        if !name.is_empty() {
            meta.instrument = Some(name.join(" "));
        }
        for (key, field) in [
            ("instrument serial", "Serial"),
            ("instrument version", "Version"),
        ] {
            if let Some(v) = text(instrument, field) {
                meta.extra.push((key.into(), v.into()));
            }
        }
    }
    for (key, field) in [
        ("creator", "Creator"),
        ("calibration date", "CalibrationDate"),
        ("comment", "Comment"),
    ] {
        if let Some(v) = text(record2, field) {
            meta.extra.push((key.into(), v.into()));
        }
    }
    if let Some(probe) = element(record2, "ProbingSystem").and_then(|p| text(p, "Type")) {
        meta.extra.push(("probing system".into(), probe.into()));
    }
}

/// Compare the MD5 of an entry with the one `main.xml` states; a mismatch is a warning.
fn compare_md5(meta: &mut Metadata, name: &str, actual: &str, expected: &str) {
    if !actual.eq_ignore_ascii_case(expected.trim()) {
        meta.warn(format!(
            "MD5 checksum of {name} is {actual}, main.xml states {}: the data may be corrupt",
            expected.trim()
        ));
    }
}

/// Compare main.xml with the checksum file (`<hex digest> *main.xml`); a mismatch or a missing
/// checksum file is a warning.
fn check_main_checksum(zip: &mut Container, name: &str, xml: &[u8], meta: &mut Metadata) {
    let mut text = String::new();
    let read = zip
        .archive
        .by_name(&zip.member(name))
        .map(|f| f.take(1024).read_to_string(&mut text));
    match read {
        Ok(Ok(_)) => {
            let expected = text.split_whitespace().next().unwrap_or("");
            compare_md5(meta, "main.xml", &md5_hex(xml), expected);
        }
        _ => meta.warn(format!("checksum file {name} is missing or unreadable")),
    }
}

/// The zip archive and the folder its members live in: `""` for the standard layout, `"name/"`
/// when every member sits under one folder (x3ptools).
struct Container<'a> {
    archive: ZipArchive<Cursor<&'a [u8]>>,
    folder: String,
}

impl<'a> Container<'a> {
    /// Find `main.xml`: at the root, or else in exactly one folder of the archive (a warning).
    fn open(
        path: &Path,
        archive: ZipArchive<Cursor<&'a [u8]>>,
        meta: &mut Metadata,
    ) -> Result<Self> {
        if archive.index_for_name("main.xml").is_some() {
            return Ok(Container {
                archive,
                folder: String::new(),
            });
        }
        let mut folders: Vec<String> = archive
            .file_names()
            .filter_map(|n| n.ok()?.strip_suffix("main.xml").map(str::to_string))
            .filter(|f| f.ends_with('/'))
            .collect();
        folders
            .sort_unstable_by(|a, b| (a.matches('/').count(), a).cmp(&(b.matches('/').count(), b)));
        let folder = match folders.as_slice() {
            [] => {
                return Err(SurfaceError::format(
                    path,
                    NAME,
                    "the archive holds no main.xml: not an X3P file",
                ));
            }
            [one] => one.clone(),
            [first, second, ..] => {
                return Err(SurfaceError::format(
                    path,
                    NAME,
                    format!(
                        "the archive holds several main.xml ({first}main.xml, \
                         {second}main.xml, ...): which surface to read is ambiguous"
                    ),
                ));
            }
        };
        meta.warn(format!(
            "every member lies under the folder '{folder}' (as x3ptools writes), not at the \
             archive's root as ISO 25178-72 places them"
        ));
        Ok(Container { archive, folder })
    }

    /// The archive name of a member that `main.xml` names relative to itself.
    fn member(&self, name: &str) -> String {
        format!("{}{}", self.folder, name.trim())
    }

    /// The bytes of a member, its zip CRC-32 verified. With `expected = Some((count, size))` the
    /// member must hold exactly `count` values of `size` bytes; that size, and any size the member
    /// declares, is checked against what its compressed bytes can hold before anything is
    /// allocated.
    fn read_entry(
        &mut self,
        path: &Path,
        name: &str,
        expected: Option<(usize, usize)>,
    ) -> Result<Vec<u8>> {
        let fail = |m: String| SurfaceError::format(path, NAME, m);
        let name = self.member(name);
        let entry = self
            .archive
            .by_name(&name)
            .map_err(|e| fail(format!("member {name}: {e}")))?;
        let declared = entry.size();
        let compressed = entry.compressed_size();
        let crc = entry.crc32();
        let bound = compressed
            .saturating_mul(MAX_DEFLATE_RATIO)
            .saturating_add(64);
        if declared > bound {
            return Err(fail(format!(
                "member {name} declares {declared} bytes but holds only {compressed} compressed \
                 bytes"
            )));
        }
        let declared =
            usize::try_from(declared).map_err(|_| fail(format!("member {name} too big")))?;
        if let Some((count, size)) = expected {
            let needed = data_bytes(path, NAME, count, size, declared)?;
            if needed != declared {
                return Err(fail(format!(
                    "member {name} holds {declared} bytes, main.xml describes {needed}"
                )));
            }
        }
        let mut out = Vec::with_capacity(declared);
        entry
            .take(declared as u64)
            .read_to_end(&mut out)
            .map_err(|e| fail(format!("member {name}: {e}")))?;
        if out.len() != declared {
            return Err(fail(format!(
                "member {name} holds {} bytes, its header declares {declared}",
                out.len()
            )));
        }
        let actual = crc32fast::hash(&out);
        if actual != crc {
            return Err(fail(format!(
                "member {name} is damaged: its CRC-32 is {actual:08x}, the archive records \
                 {crc:08x}"
            )));
        }
        Ok(out)
    }
}

/// `xml` with `xmlns:{prefix}` bound to the ISO 5436-2 namespace on its root element.
fn declare_prefix(xml: &str, prefix: &str) -> Option<String> {
    let open = format!("<{prefix}:ISO5436_2");
    let at = xml.find(&open)? + open.len();
    let mut out = String::with_capacity(xml.len() + 64);
    out.push_str(&xml[..at]);
    out.push_str(&format!(" xmlns:{prefix}=\"{NAMESPACE}\""));
    out.push_str(&xml[at..]);
    Some(out)
}

fn element<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

fn child<'a, 'input>(path: &Path, node: Node<'a, 'input>, name: &str) -> Result<Node<'a, 'input>> {
    element(node, name).ok_or_else(|| {
        SurfaceError::format(
            path,
            NAME,
            format!("main.xml: <{}> has no <{name}>", node.tag_name().name()),
        )
    })
}

fn text_of<'a>(path: &Path, node: Node<'a, '_>, name: &str) -> Result<&'a str> {
    Ok(child(path, node, name)?.text().unwrap_or("").trim())
}

fn axis(path: &Path, axes: Node, name: &str, meta: &mut Metadata) -> Result<Axis> {
    let fail = |m: String| SurfaceError::format(path, NAME, m);
    let node = child(path, axes, name)?;
    let absolute = match text_of(path, node, "AxisType")? {
        "A" => true,
        "I" => false,
        other => {
            return Err(fail(format!(
                "{name}/AxisType '{other}' is neither I nor A"
            )));
        }
    };
    let number = |field: &str| -> Result<Option<f64>> {
        element(node, field)
            .map(|e| {
                let t = e.text().unwrap_or("").trim();
                t.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| fail(format!("{name}/{field} '{t}' is not a finite number")))
            })
            .transpose()
    };
    let increment = number("Increment")?;
    let offset = match element(node, "Offset") {
        Some(e) if e.text().is_none_or(|t| t.trim().is_empty()) => {
            meta.warn(format!("{name}/Offset is empty; taken as 0"));
            0.0
        }
        _ => number("Offset")?.unwrap_or(0.0),
    };
    let data_type = match element(node, "DataType")
        .and_then(|e| e.text())
        .map(str::trim)
    {
        Some(code) => DataType::from_code(code)
            .ok_or_else(|| fail(format!("{name}/DataType '{code}' is not one of I, L, F, D")))?,
        None if absolute => return Err(fail(format!("the absolute axis {name} has no DataType"))),
        None => DataType::Float64,
    };
    let increment = match increment {
        Some(v) => v,
        None if absolute => 1.0,
        None => {
            return Err(fail(format!(
                "the incremental axis {name} has no Increment"
            )));
        }
    };
    Ok(Axis {
        absolute,
        data_type,
        increment,
        offset,
    })
}

/// Write a map as X3P: float64 heights in `bindata/data.bin` (NaN where invalid), a
/// `bindata/valid.bin` bitmask when points are missing, and the MD5 checksums of all three.
pub(crate) fn to_bytes(map: &HeightMap) -> std::result::Result<Vec<u8>, String> {
    let mut data = Vec::with_capacity(map.heights().len() * 8);
    for h in map.heights() {
        data.extend_from_slice(&h.to_le_bytes());
    }
    let valid = map.mask().map(|mask| {
        let mut bits = vec![0u8; mask.len().div_ceil(8)];
        for (i, _) in mask.iter().enumerate().filter(|(_, v)| **v) {
            bits[i / 8] |= 1 << (i % 8);
        }
        bits
    });
    let xml = main_xml(
        map,
        &md5_hex(&data),
        valid.as_deref().map(md5_hex).as_deref(),
    );
    let checksum = format!("{} *main.xml\n", md5_hex(xml.as_bytes()));

    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let mut add = |name: &str, bytes: &[u8]| -> std::result::Result<(), String> {
        // DEFLATE shrinks float64 heights by a few per cent at most (6% on a 4096² map) and is
        // some 30 times slower than storing them: the binary entries are stored.
        let method = if name.starts_with("bindata/") {
            zip::CompressionMethod::Stored
        } else {
            zip::CompressionMethod::Deflated
        };
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(method)
            .last_modified_time(zip::DateTime::default())
            .large_file(bytes.len() as u64 >= u64::from(u32::MAX));
        zip.start_file(name, options).map_err(|e| e.to_string())?;
        zip.write_all(bytes).map_err(|e| e.to_string())
    };
    add("main.xml", xml.as_bytes())?;
    add("bindata/data.bin", &data)?;
    if let Some(bits) = &valid {
        add("bindata/valid.bin", bits)?;
    }
    add("md5checksum.hex", checksum.as_bytes())?;
    Ok(zip.finish().map_err(|e| e.to_string())?.into_inner())
}

fn main_xml(map: &HeightMap, data_md5: &str, valid_md5: Option<&str>) -> String {
    let version = env!("CARGO_PKG_VERSION");
    // The source's Record2 is kept (what the reader put in `meta`); gonio's step is added to its
    // comment. Fields the source lacks are gonio's own: the instrument "gonio" and the time now.
    let meta = &map.meta;
    let extra = |key: &str| {
        meta.extra
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| escape(v))
    };
    let xsd_date = meta.date.as_deref().filter(|d| is_xsd_datetime(d));
    let date = xsd_date.map_or_else(now_utc, str::to_string);
    let calibration_date = extra("calibration date")
        .filter(|d| is_xsd_datetime(d))
        .unwrap_or_else(|| date.clone());
    let instrument = escape(meta.instrument.as_deref().unwrap_or("gonio"));
    let or_not_available = |v: Option<String>| v.unwrap_or_else(|| NOT_AVAILABLE.to_string());
    let serial = or_not_available(extra("instrument serial"));
    let instrument_version = match &meta.instrument {
        Some(_) => or_not_available(extra("instrument version")),
        None => version.to_string(),
    };
    let (probe, probe_id) = match extra("probing system") {
        Some(probe) => (probe, NOT_AVAILABLE.to_string()),
        None => ("Software".into(), format!("gonio {version}")),
    };
    let mut comment: Vec<String> = meta
        .extra
        .iter()
        .filter(|(k, _)| k == "comment")
        .map(|(_, v)| v.clone())
        .collect();
    if let (Some(d), None) = (&meta.date, xsd_date) {
        comment.push(format!("measured {d}"));
    }
    comment.push(match &meta.source {
        Some(source) => format!("written by gonio {version} from {}", source.display()),
        None => format!("written by gonio {version}"),
    });
    let comment = comment.join("; ");
    let valid_link = valid_md5.map_or(String::new(), |md5| {
        format!(
            "      <ValidPointsLink>bindata/valid.bin</ValidPointsLink>\n      \
             <MD5ChecksumValidPoints>{md5}</MD5ChecksumValidPoints>\n"
        )
    });
    format!(
        r#"<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<p:ISO5436_2 xmlns:p="{NAMESPACE}"
    xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
    xsi:schemaLocation="{NAMESPACE} {NAMESPACE}/ISO5436_2.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX>
        <AxisType>I</AxisType>
        <DataType>D</DataType>
        <Increment>{dx:e}</Increment>
        <Offset>0</Offset>
      </CX>
      <CY>
        <AxisType>I</AxisType>
        <DataType>D</DataType>
        <Increment>{dy:e}</Increment>
        <Offset>0</Offset>
      </CY>
      <CZ>
        <AxisType>A</AxisType>
        <DataType>D</DataType>
      </CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>{date}</Date>
    <Instrument>
      <Manufacturer>{instrument}</Manufacturer>
      <Model>{NOT_AVAILABLE}</Model>
      <Serial>{serial}</Serial>
      <Version>{instrument_version}</Version>
    </Instrument>
    <CalibrationDate>{calibration_date}</CalibrationDate>
    <ProbingSystem>
      <Type>{probe}</Type>
      <Identification>{probe_id}</Identification>
    </ProbingSystem>
    <Comment>{comment}</Comment>
  </Record2>
  <Record3>
    <MatrixDimension>
      <SizeX>{nx}</SizeX>
      <SizeY>{ny}</SizeY>
      <SizeZ>1</SizeZ>
    </MatrixDimension>
    <DataLink>
      <PointDataLink>bindata/data.bin</PointDataLink>
      <MD5ChecksumPointData>{data_md5}</MD5ChecksumPointData>
{valid_link}    </DataLink>
  </Record3>
  <Record4>
    <ChecksumFile>md5checksum.hex</ChecksumFile>
  </Record4>
</p:ISO5436_2>
"#,
        dx = map.dx(),
        dy = map.dy(),
        nx = map.nx(),
        ny = map.ny(),
        comment = escape(&comment),
    )
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Whether `d` starts like an XML Schema dateTime, `YYYY-MM-DDThh:mm:ss`.
fn is_xsd_datetime(d: &str) -> bool {
    let b = d.as_bytes();
    let digits = |r: std::ops::Range<usize>| r.into_iter().all(|i| b[i].is_ascii_digit());
    b.len() >= 19
        && digits(0..4)
        && b[4] == b'-'
        && digits(5..7)
        && b[7] == b'-'
        && digits(8..10)
        && b[10] == b'T'
        && digits(11..13)
        && b[13] == b':'
        && digits(14..16)
        && b[16] == b':'
        && digits(17..19)
}

/// The current time as an XML Schema dateTime in UTC.
fn now_utc() -> String {
    super::binary::iso_utc(jiff::Timestamp::now())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn datetime_check() {
        assert!(is_xsd_datetime("2007-04-30T13:58:02.6+02:00"));
        assert!(!is_xsd_datetime("30/04/2007"));
        assert!(is_xsd_datetime(&now_utc()));
    }

    #[test]
    fn escapes_markup() {
        assert_eq!(escape("a<b>&c"), "a&lt;b&gt;&amp;c");
    }
}
