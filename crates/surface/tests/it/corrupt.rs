//! Robustness of every reader on damaged copies of every fixture in tests/data: truncated at
//! several lengths, with bytes of the header flipped, and with a header that claims far more
//! data than the file holds. Each read runs under `catch_unwind`, so a panic is reported with the
//! fixture and the mutation instead of aborting the run, and a counting allocator checks that no
//! single allocation exceeds what the file's size justifies.
//!
//! What is asserted:
//! - truncations (to 0 and 3 bytes, half the header, the header alone, half the data, one byte
//!   short) give an error that names the file. Text fixtures are cut relative to their content
//!   without trailing whitespace, since a lost final newline is not damage; PLU files relative to
//!   the end of their heights, since what follows them has no stated size. Gwyddion's ASCII
//!   matrix and x y z lists state no point count, so a cut that leaves whole rows of whole
//!   numbers cannot be told from a smaller file: there a read may succeed, but never with more
//!   points; the same holds for a text file cut between two digits of a number;
//! - flipping the first bytes (the magic or first header field) gives an error naming the file;
//!   flipping any other header byte gives an error naming the file or a valid map (a byte of a
//!   date or a comment may change harmlessly), never a panic;
//! - a header whose grid fields are patched to 40000 × 40000 points (under the crate's point
//!   limit, so only the check against the file's size can stop it), or a profile's length to
//!   40000 points, gives an error;
//! - no mutation leads to a single allocation larger than 16 × the file size + 1 MiB.

use crate::fixture_tools::{fixture, rezip};
use gonio_surface::io;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

/// Records the largest single allocation made by the current thread.
struct CountingAllocator;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

fn note(size: usize) {
    let _ = LARGEST.try_with(|l| l.set(l.get().max(size)));
}

// SAFETY: every method hands its arguments unchanged to the system allocator, which upholds
// the `GlobalAlloc` contract; recording a size allocates nothing (a thread-local `Cell`).
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        // SAFETY: the caller's `layout` obligations pass through unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        // SAFETY: as for `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        // SAFETY: `ptr` came from this allocator, i.e. from `System`, with `layout`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as for `realloc`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

// The allocator of the whole test binary (every module of tests/it): it only records, per
// thread, so tests running beside these do not disturb their figures.
#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// How to make a fixture's header lie about the size of its grid.
enum Lie {
    /// The format states no grid size (Gwyddion's ASCII matrix, x y z lists).
    NoSizeField,
    /// Big-endian u16 fields at these offsets.
    U16Be(&'static [usize]),
    /// Little-endian u16 fields at these offsets.
    U16Le(&'static [usize]),
    /// Little-endian u32 fields at these offsets.
    U32Le(&'static [usize]),
    /// NUL-padded decimal text fields starting at these offsets.
    PaddedDecimal(&'static [usize]),
    /// Replace these texts of the header.
    Text(&'static [(&'static str, &'static str)]),
    /// Replace these texts of an X3P's main.xml.
    X3pXml(&'static [(&'static str, &'static str)]),
}

struct Case {
    name: &'static str,
    /// Length of the header (for X3P: the first zip local file header), or of a leading part of
    /// it where the format's header is long.
    header: usize,
    /// A text format: cuts are made relative to the content without trailing whitespace.
    text: bool,
    /// The file starts with a signature (all but PLU, which starts with a date).
    signature: bool,
    /// Where the data the reader needs ends, when the file carries more after it whose size the
    /// header does not state (PLU); cuts are then made before this point.
    data_end: Option<usize>,
    lie: Lie,
}

const HUGE: u32 = 40_000;

fn damaged_copies(case: &Case, bytes: &[u8]) -> Vec<(String, Vec<u8>, Expect)> {
    let content = match case.data_end {
        Some(end) => end,
        None if case.text => bytes.trim_ascii_end().len(),
        None => bytes.len(),
    };
    let header = case.header.min(content);
    let truncate_expect = match case.lie {
        Lie::NoSizeField => Expect::ErrOrNoLarger,
        _ => Expect::Err,
    };
    let mut out = Vec::new();
    for cut in [
        0,
        3,
        header / 2,
        header,
        header + (content - header) / 2,
        content - 1,
    ] {
        // A text file cut between two digits of its last number still ends in a number, which
        // no reader can tell from an intact one; the header still fixes the grid size.
        let inside_number = case.text
            && cut > 0
            && bytes[cut - 1].is_ascii_digit()
            && bytes.get(cut).is_some_and(u8::is_ascii_digit);
        out.push((
            format!("truncated to {cut} bytes"),
            bytes[..cut].to_vec(),
            if inside_number {
                Expect::ErrOrNoLarger
            } else {
                truncate_expect
            },
        ));
    }
    let mut magic = bytes.to_vec();
    magic.iter_mut().take(4).for_each(|b| *b ^= 0xff);
    let expect = if case.signature {
        Expect::Err
    } else {
        Expect::ErrOrAny
    };
    out.push(("first 4 bytes flipped".into(), magic, expect));
    let positions =
        (4..header.min(16)).chain((0..24).map(|k| 16 + k * header.saturating_sub(16) / 24));
    for p in positions.filter(|&p| p < header) {
        let mut flipped = bytes.to_vec();
        flipped[p] ^= 0xff;
        out.push((format!("byte {p} flipped"), flipped, Expect::ErrOrAny));
    }
    if let Some(lying) = lie(&case.lie, bytes) {
        out.push((
            "header claims 40000 × 40000 points".into(),
            lying,
            Expect::Err,
        ));
    }
    out
}

fn lie(lie: &Lie, bytes: &[u8]) -> Option<Vec<u8>> {
    let mut b = bytes.to_vec();
    match lie {
        Lie::NoSizeField => return None,
        Lie::U16Be(offsets) => offsets
            .iter()
            .for_each(|&o| b[o..o + 2].copy_from_slice(&(HUGE as u16).to_be_bytes())),
        Lie::U16Le(offsets) => offsets
            .iter()
            .for_each(|&o| b[o..o + 2].copy_from_slice(&(HUGE as u16).to_le_bytes())),
        Lie::U32Le(offsets) => offsets
            .iter()
            .for_each(|&o| b[o..o + 4].copy_from_slice(&HUGE.to_le_bytes())),
        Lie::PaddedDecimal(offsets) => {
            let digits = HUGE.to_string();
            for &o in *offsets {
                assert!(
                    b[o..o + digits.len()]
                        .iter()
                        .all(|c| c.is_ascii_digit() || *c == 0)
                );
                b[o..o + digits.len()].copy_from_slice(digits.as_bytes());
            }
        }
        Lie::Text(pairs) => b = replace_all(&b, pairs),
        Lie::X3pXml(pairs) => {
            b = rezip(bytes, |name, content| {
                if name == "main.xml" {
                    replace_all(&content, pairs)
                } else {
                    content
                }
            })
        }
    }
    Some(b)
}

fn replace_all(bytes: &[u8], pairs: &[(&str, &str)]) -> Vec<u8> {
    let mut text = String::from_utf8_lossy(bytes).into_owned();
    for (from, to) in pairs {
        assert!(text.contains(from), "the fixture lacks '{from}'");
        text = text.replacen(from, to, 1);
    }
    text.into_bytes()
}

#[derive(Clone, Copy, PartialEq)]
enum Expect {
    /// A clean error that names the file.
    Err,
    /// An error that names the file, or any valid map.
    ErrOrAny,
    /// An error that names the file, or a map with no more points than the intact file.
    ErrOrNoLarger,
}

fn check(case: &Case) {
    let path = fixture(case.name);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let intact_points = io::read_bytes(&path, &bytes).ok().map(|m| m.nx() * m.ny());
    let limit = 16 * bytes.len() + (1 << 20);
    let mut failures = Vec::new();
    for (mutation, damaged, expect) in damaged_copies(case, &bytes) {
        LARGEST.with(|l| l.set(0));
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            io::read_bytes(Path::new(case.name), &damaged)
        }));
        let largest = LARGEST.with(Cell::get);
        let problem = match outcome {
            Err(panic) => {
                let message = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                Some(format!("panicked: {message}"))
            }
            Ok(Err(e)) if !e.to_string().contains(case.name) => {
                Some(format!("error does not name the file: {e}"))
            }
            Ok(Err(_)) => None,
            Ok(Ok(map)) => match expect {
                Expect::Err => Some(format!("read as a {} × {} map", map.nx(), map.ny())),
                Expect::ErrOrAny => None,
                Expect::ErrOrNoLarger => (intact_points.is_some_and(|n| map.nx() * map.ny() > n))
                    .then(|| format!("read as a larger {} × {} map", map.nx(), map.ny())),
            },
        };
        if let Some(problem) = problem {
            failures.push(format!("{}, {mutation}: {problem}", case.name));
        }
        if largest > limit {
            failures.push(format!(
                "{}, {mutation}: allocated {largest} bytes at once",
                case.name
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} damaged copies mishandled:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

macro_rules! cases {
    ($($test:ident: $case:expr;)*) => {
        $(#[test] fn $test() { check(&$case); })*
    };
}

/// A binary fixture that starts with a signature.
const fn binary(name: &'static str, header: usize, lie: Lie) -> Case {
    Case {
        name,
        header,
        text: false,
        signature: true,
        data_end: None,
        lie,
    }
}

/// A text fixture that starts with a signature.
const fn text(name: &'static str, header: usize, lie: Lie) -> Case {
    Case {
        name,
        header,
        text: true,
        signature: true,
        data_end: None,
        lie,
    }
}

/// The `<SizeX>` and `<SizeY>` of an X3P's main.xml set to 40000.
macro_rules! x3p_sizes {
    ($nx:literal, $ny:literal) => {
        Lie::X3pXml(&[
            (concat!("<SizeX>", $nx, "</SizeX>"), "<SizeX>40000</SizeX>"),
            (concat!("<SizeY>", $ny, "</SizeY>"), "<SizeY>40000</SizeY>"),
        ])
    };
}

cases! {
    // X3P: the header is the first zip local file header (30 bytes and the entry's name).
    x3p_mountainsmap: binary("x3p-2.x3p", 46, x3p_sizes!(650, 650));
    x3p_alicona: binary("SkiInfiniteFocus.x3p", 46, x3p_sizes!(1197, 940));
    x3p_opengps_xml: binary("ISO5436-sample1.x3p", 38, x3p_sizes!(4, 4));
    x3p_opengps_binary: binary("ISO5436-sample1_bin.x3p", 38, x3p_sizes!(4, 4));
    x3p_opengps_int16: binary("ISO5436-sample4_bin.x3p", 38, x3p_sizes!(4, 4));
    sdf_ascii: text("sdf-1.sdf", 223, Lie::Text(&[
        ("NumPoints = 7", "NumPoints = 40000"),
        ("NumProfiles = 4", "NumProfiles = 40000"),
    ]));
    // The title loses as many bytes as the sizes gain, so that the NUL padding stays right.
    gsf: binary("gsf-1.gsf", 128, Lie::Text(&[
        ("XRes = 16\n", "XRes = 40000\n"),
        ("YRes = 12\n", "YRes = 40000\n"),
        ("Title = gonio GSF fixture", "Title = gonio GSF f"),
    ]));
    gwyddion_matrix: text("matrix-3.txt", 75, Lie::NoSizeField);
    gwyddion_export: text("gwyddion-export-english.txt", 83, Lie::NoSizeField);
    // MetroPro: 834-byte header (header_size at offset 6); ac_width, ac_height at 52, 54 and
    // cn_width, cn_height at 68, 70, big-endian u16.
    zygo: binary("metropro-1.dat", 834, Lie::U16Be(&[52, 54, 68, 70]));
    // Wyko OPD: the directory and small blocks end where the "Raw" block starts at 24020 with
    // its array header (640, 480, 4 bytes per value) as little-endian u16.
    wyko: binary("opd-1.opd", 24026, Lie::U16Le(&[24020, 24022]));
    // Sensofar PLU: a 500-byte header that starts with a date (no signature), then rows (576)
    // and columns (768) as little-endian u32 at 500 and 504, and 576 × 768 f32 heights. An RGB
    // image and vendor blocks of no stated size follow, so the cuts are made in the heights.
    plu: Case {
        signature: false,
        data_end: Some(508 + 4 * 768 * 576),
        ..binary("plu-1.plu", 508, Lie::U32Le(&[500, 504]))
    };
    // Digital Surf: 512-byte header, points per line (563) and lines (484) as little-endian
    // u32 at 108 and 112.
    sur: binary("sur-2.sur", 512, Lie::U32Le(&[108, 112]));
    // Alicona: 52-byte tag records; the values of "Cols" (200) and "Rows" (296) start at 141
    // and 713. The depth image starts at 1261 (DepthImageOffset).
    al3d: binary("al3d-1.al3d", 1261, Lie::PaddedDecimal(&[141, 713]));
    // FRT: blocks 0x0065, 0x0077, 0x0066 (columns and rows as little-endian u32 at 38 and 42),
    // 0x0067, 0x006c, then the counts of block 0x000b from 124.
    frt: binary("frt-1.frt", 124, Lie::U32Le(&[38, 42]));
    // MountainsMap document: a compound file (512-byte header); the x and y point counts (960,
    // 600) of the measured surface are u32 entries of the ScopedContents stream, which lie at
    // 160440 and 160647 of the file.
    mnt: binary("mnt-1.mnt", 512, Lie::U32Le(&[160_440, 160_647]));
    // NanoFocus NMS: 3468-byte header with columns and rows (512) as little-endian u32 at 1368
    // and 1372. Its version string sits at 32, so flipping the first bytes hits the data type.
    nms: binary("nms-1.nms", 3468, Lie::U32Le(&[1368, 1372]));
    // TrueMap TMD: 32-byte magic, 24-byte comment, columns and rows (300) as little-endian u32
    // at 56 and 60, the heights from 80.
    tmd: binary("tmd-1.tmd", 80, Lie::U32Le(&[56, 60]));
    // The x y z list states no point count; its "header" is the first line.
    xyz: text("xyz-1.txt", 6, Lie::NoSizeField);
    matrix_header: text("matrix-4.txt", HEADER_MATRIX_HEADER, Lie::Text(&[
        ("h=305 w=75", "h=40000 w=40000"),
    ]));
    // Nanoscope: a text header up to the first data block (Data offset 40960); the first image
    // section's grid is the first `Samps/line` directly followed by `Number of lines`.
    nanoscope_4_channels: binary("di-1.di", 40960, Lie::Text(&[(
        "\\Samps/line: 512\r\n\\Number of lines: 512",
        "\\Samps/line: 40000\r\n\\Number of lines: 40000",
    )]));
    nanoscope_zsensor: binary("di-3.di", 40960, Lie::Text(&[(
        "\\Samps/line: 256\r\n\\Number of lines: 256",
        "\\Samps/line: 40000\r\n\\Number of lines: 40000",
    )]));
    // Nanosurf: an INI header ended by `#!` at 30746; the first data set's grid.
    nid: binary("nid-1.nid", 30748, Lie::Text(&[(
        "Points=256\r\nLines=256\r\n",
        "Points=40000\r\nLines=40000\r\n",
    )]));
    // PicoView: a text header ended by its `data` line (5073 bytes), then four int32 buffers.
    picoview: binary("mi-1.mi", 5073, Lie::Text(&[
        ("xPixels       256", "xPixels       40000"),
        ("yPixels       256", "yPixels       40000"),
    ]));
    // WSxM: a text header of the size its third line states (2245 and 4607 bytes), then the
    // image (int16 and f64).
    wsxm_int16: binary("top-1.top", 2245, Lie::Text(&[
        ("Number of columns: 256", "Number of columns: 40000"),
        ("Number of rows: 256", "Number of rows: 40000"),
    ]));
    wsxm_double: binary("stp-1.stp", 4607, Lie::Text(&[
        ("Number of columns: 256", "Number of columns: 40000"),
        ("Number of rows: 256", "Number of rows: 40000"),
    ]));
    // Igor binary wave: a 64-byte binary header and a 320-byte wave header, whose nDim[0] and
    // nDim[1] (256, 256) are little-endian i32 at 64 + 68 and 64 + 72. The sections the header
    // sizes (wave record, note, labels of the layers) end at 2112969; the 131578 bytes Asylum
    // appends after them have no stated size, so the cuts are made before that point.
    ibw: Case {
        data_end: Some(2_112_969),
        ..binary("spot_1-1000nm.ibw", 384, Lie::U32Le(&[132, 136]))
    };
    // OPDx: a tree of items; the profile's values start at 48561 (its Array item at 48556 and
    // 5 leading bytes). NumPoints (3001) is a little-endian u64 at 48397; its low half is
    // patched.
    opdx_profile: binary("opdx-3.opdx", 48561, Lie::U32Le(&[48397]));
}

/// Length of matrix-4.txt's four header lines (`h=305 w=75` to the conversion factor).
const HEADER_MATRIX_HEADER: usize = 96;

/// Every file in tests/data has a case above.
#[test]
fn every_fixture_is_covered() {
    let covered = [
        "x3p-2.x3p",
        "SkiInfiniteFocus.x3p",
        "ISO5436-sample1.x3p",
        "ISO5436-sample1_bin.x3p",
        "ISO5436-sample4_bin.x3p",
        "sdf-1.sdf",
        "gsf-1.gsf",
        "matrix-3.txt",
        "gwyddion-export-english.txt",
        "metropro-1.dat",
        "opd-1.opd",
        "plu-1.plu",
        "sur-2.sur",
        "al3d-1.al3d",
        "frt-1.frt",
        "mnt-1.mnt",
        "nms-1.nms",
        "tmd-1.tmd",
        "xyz-1.txt",
        "matrix-4.txt",
        "di-1.di",
        "di-3.di",
        "nid-1.nid",
        "mi-1.mi",
        "top-1.top",
        "stp-1.stp",
        "spot_1-1000nm.ibw",
        "opdx-3.opdx",
    ];
    for entry in std::fs::read_dir(fixture("")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name != "README.md" {
            assert!(
                covered.contains(&name.as_str()),
                "{name} has no case in corrupt.rs"
            );
        }
    }
}
