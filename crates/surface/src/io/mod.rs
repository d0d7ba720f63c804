//! Reading and writing height-map files. The format is detected from the file's content (magic
//! bytes or header) and, failing that, from its extension. Readers take the whole file as bytes
//! and check every size a header claims against the bytes present before allocating.

mod al3d;
mod binary;
mod cfb;
mod common;
mod frt;
mod gsf;
mod gwyddion_ascii;
mod header_matrix;
mod ibw;
mod mnt;
mod nanoscope;
mod nid;
mod nms;
mod opdx;
mod picoview;
mod plu;
mod sdf;
mod sur;
mod text;
mod tmd;
mod wsxm;
mod wyko;
mod x3p;
mod xyz;
mod zygo;

use crate::channel::{Channel, ChannelSelector, select};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// A height-map file format that gonio reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// ISO 25178-72 XML 3D surface profile (zip container).
    X3p,
    /// ISO 25178-71 surface data file, ASCII or binary.
    Sdf,
    /// Gwyddion simple field file.
    Gsf,
    /// Gwyddion's ASCII matrix export (with or without its `#` header).
    GwyddionAscii,
    /// Zygo MetroPro `.dat`.
    Zygo,
    /// Wyko / Veeco Vision `.opd`.
    Wyko,
    /// Sensofar `.plu`.
    Plu,
    /// Digital Surf `.sur`.
    Sur,
    /// Alicona `.al3d`.
    Al3d,
    /// FRT MicroProf `.frt`.
    Frt,
    /// Digital Surf MountainsMap document `.mnt`.
    Mnt,
    /// NanoFocus µsurf `.nms`.
    Nms,
    /// TrueMap / GelSight `.tmd`.
    Tmd,
    /// Text matrix with an `h= w= pixel size=` header.
    HeaderMatrix,
    /// Text `x y z` point list on a regular grid.
    XyzList,
    /// Bruker / Veeco / Digital Instruments Nanoscope (`.spm`, `.di`, `.000`, ...).
    Nanoscope,
    /// Nanosurf `.nid`.
    Nid,
    /// Agilent / Molecular Imaging PicoView `.mi`.
    PicoView,
    /// Nanotec WSxM (`.top`, `.stp`, ...).
    Wsxm,
    /// Igor binary wave `.ibw` (Asylum Research).
    Ibw,
    /// Bruker Vision64 `.opdx` (Dektak profiles).
    Opdx,
}

/// How a file is to be read.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// The channel to read; by default the file's first height channel.
    pub channel: Option<ChannelSelector>,
}

/// A format's parser.
#[derive(Clone, Copy)]
enum Parse {
    /// A format that stores one height channel.
    Single(fn(&Path, &[u8]) -> Result<HeightMap>),
    /// A format that stores several channels: the parser lists them in the map's metadata and
    /// reads the one selected (by default the first height channel).
    Channels(fn(&Path, &[u8], Option<&ChannelSelector>) -> Result<HeightMap>),
}

/// A format's reader: its name, a content test and the parser.
struct Reader {
    format: Format,
    name: &'static str,
    extensions: &'static [&'static str],
    sniff: fn(&[u8]) -> bool,
    parse: Parse,
}

/// Binary formats with magic bytes come first; the text formats, whose tests are looser, last.
/// Each text layout has its own content test (see `text`); a `.txt` file that passes none is
/// read as a Gwyddion matrix, the first reader listing that extension.
const READERS: &[Reader] = &[
    Reader {
        format: Format::X3p,
        name: x3p::NAME,
        extensions: &["x3p"],
        sniff: x3p::sniff,
        parse: Parse::Single(x3p::parse),
    },
    Reader {
        format: Format::Zygo,
        name: zygo::NAME,
        extensions: &["dat"],
        sniff: zygo::sniff,
        parse: Parse::Single(zygo::parse),
    },
    Reader {
        format: Format::Wyko,
        name: wyko::NAME,
        extensions: &["opd"],
        sniff: wyko::sniff,
        parse: Parse::Single(wyko::parse),
    },
    Reader {
        format: Format::Plu,
        name: plu::NAME,
        extensions: &["plu", "apx"],
        sniff: plu::sniff,
        parse: Parse::Single(plu::parse),
    },
    Reader {
        format: Format::Sur,
        name: sur::NAME,
        extensions: &["sur"],
        sniff: sur::sniff,
        parse: Parse::Single(sur::parse),
    },
    Reader {
        format: Format::Al3d,
        name: al3d::NAME,
        extensions: &["al3d"],
        sniff: al3d::sniff,
        parse: Parse::Single(al3d::parse),
    },
    Reader {
        format: Format::Nanoscope,
        name: nanoscope::NAME,
        extensions: &[
            "spm", "di", "000", "001", "002", "003", "004", "005", "006", "007", "008", "009",
        ],
        sniff: nanoscope::sniff,
        parse: Parse::Channels(nanoscope::parse),
    },
    Reader {
        format: Format::Nid,
        name: nid::NAME,
        extensions: &["nid"],
        sniff: nid::sniff,
        parse: Parse::Channels(nid::parse),
    },
    Reader {
        format: Format::PicoView,
        name: picoview::NAME,
        extensions: &["mi"],
        sniff: picoview::sniff,
        parse: Parse::Channels(picoview::parse),
    },
    Reader {
        format: Format::Wsxm,
        name: wsxm::NAME,
        extensions: &["top", "stp"],
        sniff: wsxm::sniff,
        parse: Parse::Channels(wsxm::parse),
    },
    Reader {
        format: Format::Ibw,
        name: ibw::NAME,
        extensions: &["ibw"],
        sniff: ibw::sniff,
        parse: Parse::Channels(ibw::parse),
    },
    Reader {
        format: Format::Opdx,
        name: opdx::NAME,
        extensions: &["opdx"],
        sniff: opdx::sniff,
        parse: Parse::Channels(opdx::parse),
    },
    Reader {
        format: Format::Frt,
        name: frt::NAME,
        extensions: &["frt"],
        sniff: frt::sniff,
        parse: Parse::Single(frt::parse),
    },
    Reader {
        format: Format::Mnt,
        name: mnt::NAME,
        extensions: &["mnt"],
        sniff: mnt::sniff,
        parse: Parse::Single(mnt::parse),
    },
    Reader {
        format: Format::Nms,
        name: nms::NAME,
        extensions: &["nms"],
        sniff: nms::sniff,
        parse: Parse::Single(nms::parse),
    },
    Reader {
        format: Format::Tmd,
        name: tmd::NAME,
        extensions: &["tmd"],
        sniff: tmd::sniff,
        parse: Parse::Single(tmd::parse),
    },
    Reader {
        format: Format::Gsf,
        name: gsf::NAME,
        extensions: &["gsf"],
        sniff: gsf::sniff,
        parse: Parse::Single(gsf::parse),
    },
    Reader {
        format: Format::Sdf,
        name: sdf::NAME,
        extensions: &["sdf"],
        sniff: sdf::sniff,
        parse: Parse::Single(sdf::parse),
    },
    Reader {
        format: Format::GwyddionAscii,
        name: gwyddion_ascii::NAME,
        extensions: &["txt", "asc", "csv"],
        sniff: gwyddion_ascii::sniff,
        parse: Parse::Single(gwyddion_ascii::parse),
    },
    Reader {
        format: Format::HeaderMatrix,
        name: header_matrix::NAME,
        extensions: &[],
        sniff: header_matrix::sniff,
        parse: Parse::Single(header_matrix::parse),
    },
    Reader {
        format: Format::XyzList,
        name: xyz::NAME,
        extensions: &["xyz"],
        sniff: xyz::sniff,
        parse: Parse::Single(xyz::parse),
    },
];

/// Detect the format of a file from its content, or else from its extension.
pub fn detect(path: &Path, bytes: &[u8]) -> Option<Format> {
    pick(path, bytes).map(|r| r.format)
}

fn pick(path: &Path, bytes: &[u8]) -> Option<&'static Reader> {
    READERS.iter().find(|r| (r.sniff)(bytes)).or_else(|| {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        READERS
            .iter()
            .find(|r| r.extensions.contains(&ext.as_str()))
    })
}

/// Read a height map from a file of any supported format (its first height channel).
pub fn read(path: &Path) -> Result<HeightMap> {
    read_with(path, &ReadOptions::default())
}

/// Read a height map from a file of any supported format, as `options` say.
pub fn read_with(path: &Path, options: &ReadOptions) -> Result<HeightMap> {
    let bytes = std::fs::read(path).map_err(|e| SurfaceError::io(path, e))?;
    read_bytes_with(path, &bytes, options)
}

/// Read the bytes of a file as `format`, without detection (one reader alone, as the fuzz
/// targets drive them); `path` names the file in messages.
pub fn read_bytes_as(format: Format, path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    let reader = READERS
        .iter()
        .find(|r| r.format == format)
        .expect("every Format has a reader");
    finish_read(reader, path, bytes, None)
}

/// Read a height map from the bytes of a file; `path` names it in messages and picks the format
/// by extension when the content does not.
pub fn read_bytes(path: &Path, bytes: &[u8]) -> Result<HeightMap> {
    read_bytes_with(path, bytes, &ReadOptions::default())
}

/// [`read_bytes`] as `options` say.
pub fn read_bytes_with(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<HeightMap> {
    let reader =
        pick(path, bytes).ok_or_else(|| SurfaceError::UnknownFormat { path: path.into() })?;
    finish_read(reader, path, bytes, options.channel.as_ref())
}

fn finish_read(
    reader: &Reader,
    path: &Path,
    bytes: &[u8],
    selector: Option<&ChannelSelector>,
) -> Result<HeightMap> {
    let mut map = match reader.parse {
        Parse::Single(parse) => {
            // The one channel of the format, checked like any other before the file is read.
            let only = [Channel {
                index: 0,
                name: "Height".into(),
                unit: None,
                is_height: true,
                problem: None,
            }];
            select(path, reader.name, &only, selector)?;
            let mut map = parse(path, bytes)?;
            map.meta.channels = only.to_vec();
            map
        }
        Parse::Channels(parse) => parse(path, bytes, selector)?,
    };
    map.meta.source = Some(path.to_path_buf());
    map.meta.format = Some(reader.name.to_string());
    let aspect = map.dx().max(map.dy()) / map.dx().min(map.dy());
    if !map.is_profile() && aspect > MAX_PLAUSIBLE_ASPECT {
        map.meta.warn(format!(
            "the spacings differ by a factor of {aspect:.3e} (x {:.4e} m, y {:.4e} m): the \
             header may be damaged; statistics that compare directions (Sal, Str) mean little",
            map.dx(),
            map.dy()
        ));
    }
    Ok(map)
}

/// Largest ratio of the two spacings a map is read without a warning. Instruments write square
/// pixels or nearly so (the shared X3P export: 2.5); a stylus instrument's areal scan may space
/// its lines a few hundred times its points. Far beyond that the header is likelier damaged (one
/// changed byte of a TrueMap header made 3 × 10³⁸).
const MAX_PLAUSIBLE_ASPECT: f64 = 1e3;

/// Write a height map; the extension picks the format (`.x3p` or `.gsf`). The file is written to
/// a temporary file beside the target and renamed, so a failure never leaves half a file.
pub fn write(map: &HeightMap, path: &Path) -> Result<()> {
    let ext = gonio_io::extension(path);
    let bytes = match ext.as_str() {
        "x3p" => x3p::to_bytes(map).map_err(|m| SurfaceError::format(path, x3p::NAME, m))?,
        "gsf" => gsf::to_bytes(map),
        _ => {
            return Err(SurfaceError::format(
                path,
                "output",
                format!("cannot write '.{ext}' files: use the extension .x3p or .gsf"),
            ));
        }
    };
    write_atomic(path, |w| w.write_all(&bytes))
}

/// Write a file atomically ([`gonio_io::write_atomic`]: the old file or the complete new one,
/// never half a file); errors name the file.
pub fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<&mut File>) -> std::io::Result<()>,
) -> Result<()> {
    let io = |e| SurfaceError::io(path, e);
    gonio_io::write_atomic(path, |w| body(w).map_err(io), io)
}
