//! The CIE standard observers (colour-matching functions) and standard illuminants, embedded in
//! the binary from the tables in `crates/color/data/` (provenance in its README) and parsed once.
//!
//! Sources: CIE 15:2004 *Colorimetry*, 3rd ed., tables T.1 (illuminant A and D65 relative spectral
//! power), T.4 (1931 2° observer) and T.5 (1964 10° observer); the files are the 1 nm versions
//! distributed by the Colour & Vision Research Laboratory (cvrl.org).

use crate::spectrum::{Spectrum, check_increasing, parse_rows};
use std::fmt;
use std::sync::LazyLock;

/// A CIE standard colorimetric observer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Observer {
    /// CIE 1931 standard colorimetric observer (2° field).
    Cie1931TwoDegree,
    /// CIE 1964 supplementary standard colorimetric observer (10° field).
    Cie1964TenDegree,
}

/// A CIE standard illuminant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Illuminant {
    /// CIE standard illuminant D65 (average daylight, about 6504 K); the white of sRGB.
    D65,
    /// CIE standard illuminant A (tungsten filament, Planckian at about 2856 K).
    A,
}

/// The three colour-matching functions x̄, ȳ, z̄ of an observer on the grid of its table.
#[derive(Debug)]
pub struct ColorMatchingFunctions {
    /// x̄(λ).
    pub xbar: Spectrum,
    /// ȳ(λ), the photopic luminous efficiency function V(λ) for the 2° observer.
    pub ybar: Spectrum,
    /// z̄(λ).
    pub zbar: Spectrum,
}

impl ColorMatchingFunctions {
    /// The table's wavelengths (nm): 360 to 830 nm at 1 nm.
    pub fn wavelengths_nm(&self) -> &[f64] {
        self.xbar.wavelengths_nm()
    }

    /// (x̄, ȳ, z̄) at `wavelength_nm`, linear between the 1 nm table entries; outside 360–830 nm
    /// the end values, which are below 1e-3 of the peak.
    pub fn at(&self, wavelength_nm: f64) -> [f64; 3] {
        [
            self.xbar.value_at(wavelength_nm),
            self.ybar.value_at(wavelength_nm),
            self.zbar.value_at(wavelength_nm),
        ]
    }
}

static CIE1931_2: LazyLock<ColorMatchingFunctions> = LazyLock::new(|| {
    parse_cmfs(
        include_str!("../data/ciexyz_1931_2.dat"),
        "ciexyz_1931_2.dat",
    )
});
static CIE1964_10: LazyLock<ColorMatchingFunctions> = LazyLock::new(|| {
    parse_cmfs(
        include_str!("../data/ciexyz_1964_10.dat"),
        "ciexyz_1964_10.dat",
    )
});
static D65: LazyLock<Spectrum> =
    LazyLock::new(|| parse_spd(include_str!("../data/CIE_D65.csv"), "CIE_D65.csv"));
static A: LazyLock<Spectrum> =
    LazyLock::new(|| parse_spd(include_str!("../data/CIE_A.csv"), "CIE_A.csv"));

impl Observer {
    /// Both observers.
    pub const ALL: [Observer; 2] = [Observer::Cie1931TwoDegree, Observer::Cie1964TenDegree];

    /// The observer of a field size in degrees (2 or 10).
    pub fn from_field_deg(field_deg: u32) -> Option<Observer> {
        match field_deg {
            2 => Some(Observer::Cie1931TwoDegree),
            10 => Some(Observer::Cie1964TenDegree),
            _ => None,
        }
    }

    /// The field size in degrees: 2 or 10.
    pub fn field_deg(self) -> u32 {
        match self {
            Observer::Cie1931TwoDegree => 2,
            Observer::Cie1964TenDegree => 10,
        }
    }

    /// The colour-matching functions (parsed from the embedded table on first use).
    pub fn cmfs(self) -> &'static ColorMatchingFunctions {
        match self {
            Observer::Cie1931TwoDegree => &CIE1931_2,
            Observer::Cie1964TenDegree => &CIE1964_10,
        }
    }
}

impl fmt::Display for Observer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Observer::Cie1931TwoDegree => f.write_str("CIE 1931 2°"),
            Observer::Cie1964TenDegree => f.write_str("CIE 1964 10°"),
        }
    }
}

impl Illuminant {
    /// Both illuminants.
    pub const ALL: [Illuminant; 2] = [Illuminant::D65, Illuminant::A];

    /// The illuminant named `name` (`D65` or `A`, case-insensitive).
    pub fn from_name(name: &str) -> Option<Illuminant> {
        match name.to_ascii_uppercase().as_str() {
            "D65" => Some(Illuminant::D65),
            "A" => Some(Illuminant::A),
            _ => None,
        }
    }

    /// The CIE name: `D65` or `A`.
    pub fn name(self) -> &'static str {
        match self {
            Illuminant::D65 => "D65",
            Illuminant::A => "A",
        }
    }

    /// Relative spectral power distribution, 360–830 nm at 1 nm (100 at 560 nm for D65 and near
    /// 560 nm for A, as CIE tabulates them).
    pub fn spd(self) -> &'static Spectrum {
        match self {
            Illuminant::D65 => &D65,
            Illuminant::A => &A,
        }
    }
}

impl fmt::Display for Illuminant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Rows of an embedded table with `columns` numbers each, wavelengths increasing. The tables are
/// compiled in and checked by the tests, so a failure here is a build defect, not bad input.
fn parse_table(text: &str, name: &str, columns: usize) -> Vec<Vec<f64>> {
    let lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let rows = parse_rows(lines, columns)
        .and_then(|rows| check_increasing(&rows).map(|()| rows))
        .unwrap_or_else(|(line, problem)| panic!("embedded {name}, line {line}: {problem}"));
    rows.into_iter().map(|(_, row)| row).collect()
}

fn column_spectrum(rows: &[Vec<f64>], column: usize, name: &str) -> Spectrum {
    let wavelengths = rows.iter().map(|r| r[0]).collect();
    let values = rows.iter().map(|r| r[column]).collect();
    Spectrum::new(wavelengths, values).unwrap_or_else(|e| panic!("embedded {name}: {e}"))
}

fn parse_cmfs(text: &str, name: &str) -> ColorMatchingFunctions {
    let rows = parse_table(text, name, 4);
    ColorMatchingFunctions {
        xbar: column_spectrum(&rows, 1, name),
        ybar: column_spectrum(&rows, 2, name),
        zbar: column_spectrum(&rows, 3, name),
    }
}

fn parse_spd(text: &str, name: &str) -> Spectrum {
    column_spectrum(&parse_table(text, name, 2), 1, name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_tables_cover_360_to_830_nm_at_1_nm() {
        for observer in Observer::ALL {
            let cmfs = observer.cmfs();
            for s in [&cmfs.xbar, &cmfs.ybar, &cmfs.zbar] {
                assert_eq!(s.len(), 471);
                assert_eq!(s.range_nm(), (360.0, 830.0));
                assert_eq!(s.uniform_step_nm(), Some(1.0));
            }
        }
        for illuminant in Illuminant::ALL {
            let spd = illuminant.spd();
            assert_eq!((spd.len(), spd.range_nm()), (471, (360.0, 830.0)));
            assert_eq!(spd.uniform_step_nm(), Some(1.0));
        }
    }

    /// CIE 15:2004 table T.1 and T.4: D65 and A are 100 at 560 nm; the 1931 ȳ (= V(λ)) peaks at
    /// 555 nm with value 1.
    #[test]
    fn published_table_entries() {
        assert_eq!(Illuminant::D65.spd().value_at(560.0), 100.0);
        assert!((Illuminant::A.spd().value_at(560.0) - 100.0).abs() < 1e-3);
        let ybar = &Observer::Cie1931TwoDegree.cmfs().ybar;
        assert_eq!(ybar.value_at(555.0), 1.0);
        let peak = ybar.values().iter().cloned().fold(0.0, f64::max);
        assert_eq!(peak, 1.0);
    }

    #[test]
    fn names_round_trip() {
        for i in Illuminant::ALL {
            assert_eq!(Illuminant::from_name(&i.name().to_lowercase()), Some(i));
        }
        for o in Observer::ALL {
            assert_eq!(Observer::from_field_deg(o.field_deg()), Some(o));
        }
        assert_eq!(Illuminant::from_name("F2"), None);
        assert_eq!(Observer::from_field_deg(4), None);
    }
}
