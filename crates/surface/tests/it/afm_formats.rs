//! The AFM and profile readers (Bruker Nanoscope, Nanosurf NID, Asylum/Igor IBW, PicoView MI,
//! WSxM, Bruker Vision64 OPDx) on real files (tests/data, provenance in its README): grid,
//! lateral size, the channels listed and the one read by default, channel selection by name and
//! index, and Sq after removing the least-squares plane against SurfaceTopography.
//!
//! Reference values: SurfaceTopography 1.27.1, `read_topography(path)` (its default channel),
//! `t.rms_height_from_area()` (rms about the mean, no levelling) and
//! `t.detrend('height').rms_height_from_area()` (levelled Sq), and `open_topography(path)
//! .channels` for the channel lists; run on these very files.

use crate::fixture_tools::{fixture, rel, rms_about_mean, sq_plane};
use gonio_surface::io::{self, ReadOptions};
use gonio_surface::{ChannelSelector, HeightMap};

/// What SurfaceTopography reports for a fixture, and the channels gonio lists in it.
struct Expected {
    name: &'static str,
    format: &'static str,
    grid: (usize, usize),
    /// Lateral size, m.
    size: (f64, f64),
    /// Channel names as gonio lists them, and which are height channels.
    channels: &'static [(&'static str, bool)],
    /// Index of the channel read by default.
    default: usize,
    /// SurfaceTopography's rms height about the mean, m.
    rms: f64,
    /// SurfaceTopography's Sq after removing the least-squares plane, m.
    sq: f64,
}

fn read(name: &str) -> HeightMap {
    io::read(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn read_channel(name: &str, channel: &str) -> gonio_surface::Result<HeightMap> {
    let options = ReadOptions {
        channel: Some(channel.parse().unwrap()),
    };
    io::read_with(&fixture(name), &options)
}

/// Grid, size, channels, valid fraction and Sq of the default read, within 0.5 % of
/// SurfaceTopography's Sq.
fn check(e: &Expected) {
    let map = read(e.name);
    assert_eq!(map.meta.format.as_deref(), Some(e.format));
    assert_eq!((map.nx(), map.ny()), e.grid, "{}: grid", e.name);
    let size = (map.dx() * map.nx() as f64, map.dy() * map.ny() as f64);
    assert!(
        rel(size.0, e.size.0) < 1e-9,
        "{}: x size {} m",
        e.name,
        size.0
    );
    assert!(
        rel(size.1, e.size.1) < 1e-9,
        "{}: y size {} m",
        e.name,
        size.1
    );
    let channels: Vec<(&str, bool)> = map
        .meta
        .channels
        .iter()
        .map(|c| (c.name.as_str(), c.is_height))
        .collect();
    assert_eq!(channels, e.channels, "{}: channels", e.name);
    for (k, c) in map.meta.channels.iter().enumerate() {
        assert_eq!(c.index, k);
    }
    assert_eq!(map.meta.channel, e.default, "{}: default channel", e.name);
    assert_eq!(map.valid_fraction(), 1.0, "{}: valid fraction", e.name);
    let rms = rms_about_mean(&map);
    assert!(
        rel(rms, e.rms) < 5e-3,
        "{}: rms {rms:e} m, SurfaceTopography {:e} m",
        e.name,
        e.rms
    );
    let sq = sq_plane(&map);
    assert!(
        rel(sq, e.sq) < 5e-3,
        "{}: Sq {sq:e} m, SurfaceTopography {:e} m",
        e.name,
        e.sq
    );
}

/// Reading `channel` gives that channel (by index `index`) with Sq `sq` (SurfaceTopography).
fn check_other_channel(name: &str, channel: &str, index: usize, sq: f64) {
    let map = read_channel(name, channel).unwrap_or_else(|e| panic!("{name} {channel}: {e}"));
    assert_eq!(map.meta.channel, index, "{name}: channel {channel}");
    let got = sq_plane(&map);
    assert!(
        rel(got, sq) < 5e-3,
        "{name} {channel}: Sq {got:e} m, expected {sq:e} m"
    );
}

/// An unknown channel is an error that names the file and lists the channels.
fn check_unknown_channel(name: &str) {
    let map = read(name);
    for wanted in ["no-such-channel", "99"] {
        let e = read_channel(name, wanted).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
        for c in &map.meta.channels {
            assert!(e.contains(&c.to_string()), "{e} lacks {c}");
        }
    }
}

const NM: f64 = 1e-9;
const UM: f64 = 1e-6;

#[test]
fn nanoscope_di1_reads_the_first_height_channel() {
    check(&Expected {
        name: "di-1.di",
        format: "Nanoscope",
        grid: (512, 512),
        size: (500.0 * NM, 500.0 * NM),
        channels: &[
            ("Height", true),
            ("Height", true),
            ("Phase", false),
            ("AmplitudeError", false),
        ],
        default: 0,
        rms: 9.94599 * NM,
        sq: 9.84366 * NM,
    });
    // The retrace height, by index (SurfaceTopography, channel_index=1: Sq 9.96656 nm).
    check_other_channel("di-1.di", "1", 1, 9.96656 * NM);
    check_unknown_channel("di-1.di");
    // Phase is in degrees (soft scale "Sens. Phase"), not a height.
    let e = read_channel("di-1.di", "phase").unwrap_err().to_string();
    assert!(
        e.contains("does not hold heights") && e.contains("2 'Phase' (º)"),
        "{e}"
    );
}

#[test]
fn nanoscope_di3_reads_the_height_sensor() {
    check(&Expected {
        name: "di-3.di",
        format: "Nanoscope",
        grid: (256, 256),
        size: (10.0 * UM, 10.0 * UM),
        channels: &[
            ("ZSensor", true),
            ("AmplitudeError", false),
            ("Phase", false),
            ("Height", true),
        ],
        default: 0,
        rms: 226.425 * NM,
        sq: 35.2229 * NM,
    });
    // The piezo height by name, any case (SurfaceTopography, channel_index=3: Sq 45.4622 nm).
    check_other_channel("di-3.di", "HEIGHT", 3, 45.4622 * NM);
    check_unknown_channel("di-3.di");
}

#[test]
fn nanoscope_scale_follows_the_header() {
    // di-1.di, first channel: `@2:Z scale: V [Sens. Zsens] (0.005035400 V/LSB) 2.910461 V` and
    // `@Sens. Zsens: V 20.82646 nm/V`, so a count is 2.910461 / 65536 × 20.82646 nm. The first
    // stored value is 3074 (bytes 40960..40962, little-endian); SurfaceTopography shows the
    // lines bottom-up, so its first row (6.0599801 nm at x = 0) is our last one.
    let map = read("di-1.di");
    let count = 2.910461 / 65536.0 * 20.82646 * NM;
    assert!(rel(map.get(0, 0).unwrap(), 3074.0 * count) < 1e-12);
    assert!(rel(map.get(0, 511).unwrap(), 6.0599801 * NM) < 1e-7);
}

#[test]
fn nid_reads_the_forward_z_axis() {
    // SurfaceTopography lists only the four channels in a length unit (its indices 0..3 are
    // our 1, 3, 5, 7); gonio lists the deflection (N) and friction (V) channels too, since
    // they have data blocks of their own between the heights (the file holds 8 blocks of
    // 256 × 256 × 4 bytes after the header's `#!`).
    check(&Expected {
        name: "nid-1.nid",
        format: "Nanosurf NID",
        grid: (256, 256),
        size: (20.0 * UM, 20.0 * UM),
        channels: &[
            ("Scan forward (Deflection)", false),
            ("Scan forward (Z-Axis)", true),
            ("Scan forward (Friction force)", false),
            ("Scan forward (Z-AxisSensor)", true),
            ("Scan backward (Deflection)", false),
            ("Scan backward (Z-Axis)", true),
            ("Scan backward (Friction force)", false),
            ("Scan backward (Z-AxisSensor)", true),
        ],
        default: 1,
        rms: 2.3959e-7,
        sq: 7.11192e-9,
    });
    // SurfaceTopography's channels 1, 2 and 3: Sq 11.4186, 11.8523 and 11.5652 nm.
    check_other_channel("nid-1.nid", "scan forward (z-axissensor)", 3, 11.4186 * NM);
    check_other_channel("nid-1.nid", "5", 5, 11.8523 * NM);
    check_other_channel("nid-1.nid", "Scan backward (Z-AxisSensor)", 7, 11.5652 * NM);
    check_unknown_channel("nid-1.nid");
}

#[test]
fn single_channel_formats_report_one_height_channel() {
    let map = read("sur-2.sur");
    assert_eq!(map.meta.channels.len(), 1);
    assert!(map.meta.channels[0].is_height);
    assert_eq!(map.meta.channel, 0);
    assert!(read_channel("sur-2.sur", "0").is_ok());
    let e = read_channel("sur-2.sur", "Phase").unwrap_err().to_string();
    assert!(e.contains("sur-2.sur") && e.contains("0 'Height'"), "{e}");
    assert_eq!(
        ChannelSelector::Name("Phase".into()),
        "Phase".parse().unwrap()
    );
}

#[test]
fn picoview_reads_the_topography() {
    check(&Expected {
        name: "mi-1.mi",
        format: "PicoView",
        grid: (256, 256),
        size: (20.0 * UM, 20.0 * UM),
        channels: &[
            ("Topography", true),
            ("Deflection", false),
            ("Friction", false),
            ("Friction", false),
        ],
        default: 0,
        rms: 0.0332154 * UM,
        sq: 0.00343396 * UM,
    });
    check_unknown_channel("mi-1.mi");
    // Deflection is in V: listed, but not a height.
    let e = read_channel("mi-1.mi", "deflection")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("1 'Deflection' (V)") && e.contains("does not hold heights"),
        "{e}"
    );
}

#[test]
fn wsxm_integer_and_float_images() {
    // The same scan saved as int16 (.top, normalised to the Z amplitude 18.8851 nm) and as
    // f64 (.stp, in nm). SurfaceTopography names the one channel "Default"; gonio takes the
    // header's "Acquisition channel".
    for (name, rms, sq) in [
        ("top-1.top", 3.1531 * NM, 1.61398 * NM),
        ("stp-1.stp", 1.65416 * NM, 1.63534 * NM),
    ] {
        check(&Expected {
            name,
            format: "WSxM",
            grid: (256, 256),
            size: (600.0 * NM, 600.0 * NM),
            channels: &[("Topography", true)],
            default: 0,
            rms,
            sq,
        });
        check_unknown_channel(name);
    }
    // top-1.top: the stored counts span [Minimum, Maximum] = [5927, 6900] of [Miscellaneous],
    // so the normalisation from the data equals SurfaceTopography's from the header.
    let top = read("top-1.top");
    let span = top
        .heights()
        .iter()
        .fold(f64::NEG_INFINITY, |a, &h| a.max(h))
        - top.heights().iter().fold(f64::INFINITY, |a, &h| a.min(h));
    assert!(rel(span, 18.8851 * NM) < 1e-12, "span {span:e} m");
}

#[test]
fn igor_wave_reads_the_height_trace() {
    // The wave's one data unit is `m`, so all eight layers count as height channels, as in
    // SurfaceTopography (which reports the phase layers in m as well).
    check(&Expected {
        name: "spot_1-1000nm.ibw",
        format: "Igor binary wave",
        grid: (256, 256),
        // sfA = 7.843137254901961e-08 m per pixel: 256 of them.
        size: (2.007843137254902e-5, 2.007843137254902e-5),
        channels: &[
            ("HeightTrace", true),
            ("HeightRetrace", true),
            ("AmplitudeTrace", true),
            ("AmplitudeRetrace", true),
            ("PhaseTrace", true),
            ("PhaseRetrace", true),
            ("NapPotentialTrace", true),
            ("NapPotentialRetrace", true),
        ],
        default: 0,
        rms: 8.94548e-8,
        sq: 9.55224e-9,
    });
    // SurfaceTopography, channel_index=1 and 2: Sq 9.80597 nm and 0.694361 nm.
    check_other_channel("spot_1-1000nm.ibw", "heightretrace", 1, 9.80597 * NM);
    check_other_channel("spot_1-1000nm.ibw", "2", 2, 0.694361 * NM);
    check_unknown_channel("spot_1-1000nm.ibw");
}

#[test]
fn opdx_profile() {
    // SurfaceTopography: a line scan of 3001 points, 49.983344425752584 µm long (the Extent,
    // 49.966688862798314 µm from the first to the last point, times 3001/3000), rms
    // 5.30751 nm, and 2.82572 nm after removing the least-squares line.
    let map = read("opdx-3.opdx");
    assert!(map.is_profile());
    assert_eq!(map.meta.format.as_deref(), Some("Bruker OPDx"));
    assert_eq!((map.nx(), map.ny()), (3001, 1));
    assert!(rel(map.dx() * 3001.0, 49.983344425752584 * UM) < 1e-12);
    assert_eq!(map.valid_fraction(), 1.0);
    let channels: Vec<(&str, bool)> = map
        .meta
        .channels
        .iter()
        .map(|c| (c.name.as_str(), c.is_height))
        .collect();
    assert_eq!(channels, [("Height", true)]);
    assert!(rel(rms_about_mean(&map), 5.30751 * NM) < 5e-3);
    let s = gonio_surface::profile_stats::profile_statistics(&map).unwrap();
    assert!(rel(s.rq, 2.82572 * NM) < 5e-3, "Rq {:e} m", s.rq);
    check_unknown_channel("opdx-3.opdx");
}

/// How SurfaceTopography's `heights()[x, y]` maps onto gonio's point `(ix, iy)` of an
/// `nx × ny` map.
#[derive(Clone, Copy)]
enum Orientation {
    /// Lines in reverse order: SurfaceTopography (like Gwyddion) shows the file's first line at
    /// the bottom of the image (Nanoscope, Nanosurf, Igor waves, PicoView).
    LinesReversed,
    /// Turned by 180°: SurfaceTopography turns WSxM images to match Gwyddion.
    Turned,
}

/// Heights at three points equal SurfaceTopography's (`heights()[x, y]` in metres, from
/// `read_topography(path)`), once its orientation is accounted for: the readers agree on every
/// value and differ only in which corner comes first. gonio keeps the file's line order.
#[test]
fn heights_match_surface_topography_point_by_point() {
    use Orientation::*;
    let cases: [(&str, Orientation, [f64; 3]); 7] = [
        (
            "di-1.di",
            LinesReversed,
            [
                6.059980111183002e-09,
                1.1811041822314855e-09,
                9.33784481112692e-09,
            ],
        ),
        (
            "di-3.di",
            LinesReversed,
            [
                5.6401630244078e-07,
                5.142240066919355e-07,
                -1.1470010985001677e-07,
            ],
        ),
        (
            "nid-1.nid",
            LinesReversed,
            [
                -9.253918035998941e-07,
                -9.850195037126541e-07,
                -1.649836201876402e-06,
            ],
        ),
        (
            "spot_1-1000nm.ibw",
            LinesReversed,
            [
                -3.9969469867173757e-07,
                -4.203554340165283e-07,
                -6.291397767199669e-07,
            ],
        ),
        (
            "mi-1.mi",
            LinesReversed,
            [
                -4.986900329589845e-07,
                -4.888579559326172e-07,
                -5.91961898803711e-07,
            ],
        ),
        (
            "top-1.top",
            Turned,
            [
                1.1550383360739981e-07,
                1.1544560616649539e-07,
                1.2233585334018502e-07,
            ],
        ),
        (
            "stp-1.stp",
            Turned,
            [
                7.677747254128065e-11,
                -5.3942068085049756e-11,
                3.5704202406718084e-09,
            ],
        ),
    ];
    for (name, orientation, expected) in cases {
        let map = read(name);
        let (nx, ny) = (map.nx(), map.ny());
        for ((x, y), want) in [(0, 0), (17, 5), (200, 100)].into_iter().zip(expected) {
            let (ix, iy) = match orientation {
                LinesReversed => (x, ny - 1 - y),
                Turned => (nx - 1 - x, ny - 1 - y),
            };
            let got = map.get(ix, iy).unwrap();
            // WSxM int16: SurfaceTopography normalises with the header's rounded span, gonio
            // with the data's; here they are equal, so the values agree to rounding.
            assert!(
                rel(got, want) < 1e-9,
                "{name} ({x}, {y}): {got:e} m, expected {want:e} m"
            );
        }
    }
}

/// The fixture `name` with each `(from, to)` of `edits` replaced once, `to` as long as `from`
/// so that every offset in the file stays valid.
fn edited(name: &str, edits: &[(&[u8], &[u8])]) -> Vec<u8> {
    let mut bytes = std::fs::read(fixture(name)).unwrap();
    for (from, to) in edits {
        assert_eq!(from.len(), to.len(), "an edit keeps the file's length");
        let at = bytes.windows(from.len()).position(|w| w == *from).unwrap();
        bytes[at..at + to.len()].copy_from_slice(to);
    }
    bytes
}

#[test]
fn nanoscope_32_bit_storage_is_refused() {
    // di-3.di made to look like a version 9.2 file whose first block holds 4 bytes per point
    // while Bytes/pixel says 2.
    let patched = edited(
        "di-3.di",
        &[
            (b"\\Version: 0x09010201", b"\\Version: 0x09200000"),
            (b"\\Data length: 131072", b"\\Data length: 262144"),
        ],
    );
    let e = io::read_bytes(std::path::Path::new("di-3.di"), &patched)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("di-3.di") && e.contains("4 bytes per point"),
        "{e}"
    );
}

#[test]
fn opdx_uneven_positions_are_refused() {
    // The PositionArray of opdx-3.opdx (f64 values from byte 24308 + 5) is evenly spaced at
    // 0.016655562954266 µm; moving point 10 by a tenth of a step makes it uneven.
    let mut bytes = std::fs::read(fixture("opdx-3.opdx")).unwrap();
    let at = 24308 + 5 + 8 * 10;
    let x = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
    assert!(rel(x, 10.0 * 0.016655562954266) < 1e-9);
    bytes[at..at + 8].copy_from_slice(&(x + 0.0016655).to_le_bytes());
    let e = io::read_bytes(std::path::Path::new("opdx-3.opdx"), &bytes)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("opdx-3.opdx") && e.contains("not evenly spaced"),
        "{e}"
    );
}

/// di-3.di with its AmplitudeError channel given a soft scale in nm/V over its Z scale in mV
/// (`@2:Z scale: V [Sens. Amplitude Error] (0.04577637 mV/LSB) 2999.954 mV`), the layout of a
/// Bruker file a user met: `\@Sens. Amplitude Error: V 1.000000 ` edited to `V 62.0 nm/V`.
fn di3_amplitude_error_per_volt() -> Vec<u8> {
    edited(
        "di-3.di",
        &[(
            b"\\@Sens. Amplitude Error: V 1.000000 ",
            b"\\@Sens. Amplitude Error: V 62.0 nm/V",
        )],
    )
}

#[test]
fn nanoscope_z_scale_in_mv_under_a_soft_scale_per_volt_is_converted() {
    let bytes = di3_amplitude_error_per_volt();
    let path = std::path::Path::new("di-3-amplitude.di");
    // The default channel reads as in the unedited file.
    let map = io::read_bytes(path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.meta.channel, 0);
    assert!(rel(sq_plane(&map), 35.2229 * NM) < 0.005);
    let amplitude = &map.meta.channels[1];
    assert_eq!(amplitude.name, "AmplitudeError");
    assert_eq!(amplitude.unit.as_deref(), Some("nm"));
    assert!(amplitude.is_height && amplitude.problem.is_none());
    // The channel itself: a count is 2999.954 mV / 65536 × 10⁻³ V/mV × 62 nm/V. Reference:
    // SurfaceTopography 1.27.1 on this edited file, `open_topography(path).topography(
    // channel_index=1).to_unit('m')`: heights()[x, y] at three points (lines reversed, as for
    // every Nanoscope file) and the levelled Sq.
    let options = io::ReadOptions {
        channel: Some("AmplitudeError".parse().unwrap()),
    };
    let map = io::read_bytes_with(path, &bytes, &options).unwrap_or_else(|e| panic!("{e}"));
    let ny = map.ny();
    for ((x, y), want) in [(0, 0), (17, 5), (200, 100)].into_iter().zip([
        -1.5041883612060548e-10,
        -1.6177120111083984e-10,
        1.4190456237792971e-11,
    ]) {
        let got = map.get(x, ny - 1 - y).unwrap();
        assert!(
            rel(got, want) < 1e-9,
            "({x}, {y}): {got:e} m against {want:e} m"
        );
    }
    let sq = sq_plane(&map);
    assert!(rel(sq, 1.983169978817549e-10) < 1e-6, "Sq {sq:e} m");
}

#[test]
fn a_nanoscope_channel_whose_scale_cannot_be_read_is_that_channels_problem() {
    // di-3.di with its Phase channel's soft scale made per kHz, while its Z scale is in º.
    let bytes = edited(
        "di-3.di",
        &[(
            b"\\@Sens. Phase: V 1.000000 ",
            b"\\@Sens. Phase: V 1 nm/kHz ",
        )],
    );
    let path = std::path::Path::new("di-3-phase.di");
    let map = io::read_bytes(path, &bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.meta.channel, 0);
    assert!(rel(sq_plane(&map), 35.2229 * NM) < 0.005);
    let phase = &map.meta.channels[2];
    let problem = phase
        .problem
        .as_deref()
        .expect("the Phase channel has a problem");
    assert!(
        problem.contains("per kHz") && problem.contains("º"),
        "{problem}"
    );
    assert!(!phase.is_height);
    // The other channels are unaffected; asking for this one, by name or index, says why not.
    assert!(
        map.meta
            .channels
            .iter()
            .filter(|c| c.problem.is_some())
            .count()
            == 1
    );
    for selector in ["Phase", "2"] {
        let options = io::ReadOptions {
            channel: Some(selector.parse().unwrap()),
        };
        let e = io::read_bytes_with(path, &bytes, &options)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("di-3-phase.di") && e.contains("cannot be read") && e.contains("per kHz"),
            "{e}"
        );
    }
}
