//! Sampled spectra: (wavelength in nm, value) pairs with linear interpolation, resampling, and the
//! `wavelength_nm,value` CSV format.
//!
//! Between samples a spectrum is linear; outside its range it holds its end values, the
//! extrapolation CIE 15:2004 (section 7.2.2.1) recommends for reflectance data that do not cover
//! the range of the colour-matching functions. A spectrum whose wavelengths are evenly spaced is
//! recognised when it is built and evaluated in O(1) per wavelength; others use a binary search.

use crate::error::{ColorError, Result};
use std::path::Path;

/// A spectrum sampled at strictly increasing wavelengths (nm).
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
    grid: Grid,
}

/// How the wavelengths are spaced: a uniform grid allows O(1) lookup.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Grid {
    Uniform { start_nm: f64, step_nm: f64 },
    Irregular,
}

impl Spectrum {
    /// A spectrum from samples. Wavelengths must be finite and strictly increasing, values finite,
    /// both of the same length, at least two samples.
    pub fn new(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        if wavelengths_nm.len() != values.len() {
            return Err(ColorError::InvalidSpectrum(format!(
                "{} wavelengths but {} values",
                wavelengths_nm.len(),
                values.len()
            )));
        }
        if wavelengths_nm.len() < 2 {
            return Err(ColorError::InvalidSpectrum(format!(
                "{} sample(s); a spectrum needs at least two",
                wavelengths_nm.len()
            )));
        }
        if let Some(i) = wavelengths_nm.iter().position(|w| !w.is_finite()) {
            return Err(ColorError::InvalidSpectrum(format!(
                "wavelength {} of sample {} is not a finite number",
                wavelengths_nm[i],
                i + 1
            )));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(ColorError::InvalidSpectrum(format!(
                "value {} at {} nm is not a finite number",
                values[i], wavelengths_nm[i]
            )));
        }
        if let Some(i) = wavelengths_nm.windows(2).position(|w| w[1] <= w[0]) {
            return Err(ColorError::InvalidSpectrum(format!(
                "wavelengths must increase, but {} nm follows {} nm",
                wavelengths_nm[i + 1],
                wavelengths_nm[i]
            )));
        }
        let grid = detect_grid(&wavelengths_nm);
        Ok(Self {
            wavelengths_nm,
            values,
            grid,
        })
    }

    /// A spectrum on the uniform grid `start_nm + i · step_nm`, i = 0..values.len().
    pub fn uniform(start_nm: f64, step_nm: f64, values: Vec<f64>) -> Result<Self> {
        let wavelengths = (0..values.len())
            .map(|i| start_nm + i as f64 * step_nm)
            .collect();
        Self::new(wavelengths, values)
    }

    /// A spectrum with the same value at every wavelength of `wavelengths_nm`.
    pub fn constant(wavelengths_nm: Vec<f64>, value: f64) -> Result<Self> {
        let values = vec![value; wavelengths_nm.len()];
        Self::new(wavelengths_nm, values)
    }

    /// The sample wavelengths (nm).
    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The sample values.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Always false: a spectrum has at least two samples.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// First and last sample wavelength (nm).
    pub fn range_nm(&self) -> (f64, f64) {
        (self.wavelengths_nm[0], self.wavelengths_nm[self.len() - 1])
    }

    /// The grid spacing (nm) when the samples are evenly spaced.
    pub fn uniform_step_nm(&self) -> Option<f64> {
        match self.grid {
            Grid::Uniform { step_nm, .. } => Some(step_nm),
            Grid::Irregular => None,
        }
    }

    /// The value at `wavelength_nm`: linear between samples, the end value outside the range.
    pub fn value_at(&self, wavelength_nm: f64) -> f64 {
        let (i, t) = self.segment(wavelength_nm);
        let v = &self.values;
        v[i] + t * (v[i + 1] - v[i])
    }

    /// The segment `i` (between samples i and i + 1) holding `wavelength_nm` and the fraction `t`
    /// in [0, 1] along it; outside the range the nearest end (t = 0 or 1).
    pub(crate) fn segment(&self, wavelength_nm: f64) -> (usize, f64) {
        let w = &self.wavelengths_nm;
        let last = w.len() - 1;
        if wavelength_nm <= w[0] {
            return (0, 0.0);
        }
        if wavelength_nm >= w[last] {
            return (last - 1, 1.0);
        }
        let i = match self.grid {
            Grid::Uniform { start_nm, step_nm } => {
                (((wavelength_nm - start_nm) / step_nm) as usize).min(last - 1)
            }
            Grid::Irregular => w.partition_point(|&x| x <= wavelength_nm) - 1,
        };
        let t = ((wavelength_nm - w[i]) / (w[i + 1] - w[i])).clamp(0.0, 1.0);
        (i, t)
    }

    /// This spectrum evaluated (see [`Spectrum::value_at`]) at other wavelengths.
    pub fn resample(&self, wavelengths_nm: &[f64]) -> Result<Spectrum> {
        let values = wavelengths_nm.iter().map(|&w| self.value_at(w)).collect();
        Spectrum::new(wavelengths_nm.to_vec(), values)
    }

    /// This spectrum evaluated on the uniform grid `start_nm + i · step_nm`, i = 0..count.
    pub fn resample_uniform(&self, start_nm: f64, step_nm: f64, count: usize) -> Result<Spectrum> {
        let values = (0..count)
            .map(|i| self.value_at(start_nm + i as f64 * step_nm))
            .collect();
        Spectrum::uniform(start_nm, step_nm, values)
    }

    /// Read a `wavelength_nm,value` CSV file: a header line whose first column is `wavelength_nm`,
    /// then one sample per line, wavelengths increasing. Blank lines are skipped.
    pub fn read_csv(path: &Path) -> Result<Spectrum> {
        let text = std::fs::read_to_string(path).map_err(|cause| ColorError::Io {
            file: path.to_path_buf(),
            cause,
        })?;
        Self::parse_csv(&text, path)
    }

    /// Parse the text of a `wavelength_nm,value` CSV file; `path` names it in errors.
    pub fn parse_csv(text: &str, path: &Path) -> Result<Spectrum> {
        let parse_error = |line: usize, problem: String| ColorError::Parse {
            file: path.to_path_buf(),
            line,
            problem,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((header_index, header)) = lines.next() else {
            return Err(parse_error(
                1,
                "the file is empty; expected a header `wavelength_nm,value` and one sample per line"
                    .into(),
            ));
        };
        let columns: Vec<&str> = header.split(',').map(str::trim).collect();
        if columns.len() != 2 || columns[0] != "wavelength_nm" {
            return Err(parse_error(
                header_index + 1,
                format!(
                    "expected the header `wavelength_nm,value` (two columns, wavelengths in nm), \
                     found `{}`",
                    header.trim()
                ),
            ));
        }
        let rows = parse_rows(lines, 2).map_err(|(line, problem)| parse_error(line, problem))?;
        check_increasing(&rows).map_err(|(line, problem)| parse_error(line, problem))?;
        if rows.len() < 2 {
            return Err(parse_error(
                header_index + 1,
                format!(
                    "{} sample(s) after the header; a spectrum needs at least two",
                    rows.len()
                ),
            ));
        }
        let (wavelengths, values) = rows.into_iter().map(|(_, r)| (r[0], r[1])).unzip();
        Spectrum::new(wavelengths, values)
    }
}

/// Uniform if every wavelength lies within 1e-9 of a step of the grid through the first two.
fn detect_grid(wavelengths_nm: &[f64]) -> Grid {
    let start_nm = wavelengths_nm[0];
    let step_nm =
        (wavelengths_nm[wavelengths_nm.len() - 1] - start_nm) / (wavelengths_nm.len() - 1) as f64;
    let uniform = wavelengths_nm
        .iter()
        .enumerate()
        .all(|(i, &w)| (w - (start_nm + i as f64 * step_nm)).abs() <= 1e-9 * step_nm);
    if uniform {
        Grid::Uniform { start_nm, step_nm }
    } else {
        Grid::Irregular
    }
}

/// Parsed rows with their 1-based line numbers.
pub(crate) type Rows = Vec<(usize, Vec<f64>)>;

/// A parse failure: (1-based line, problem).
pub(crate) type LineError = (usize, String);

/// Comma-separated rows of exactly `columns` finite numbers, with their 1-based line numbers.
pub(crate) fn parse_rows<'a>(
    lines: impl Iterator<Item = (usize, &'a str)>,
    columns: usize,
) -> std::result::Result<Rows, LineError> {
    let mut rows = Vec::new();
    for (index, line) in lines {
        let line_no = index + 1;
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != columns {
            return Err((
                line_no,
                format!(
                    "expected {columns} comma-separated numbers, found {} fields",
                    fields.len()
                ),
            ));
        }
        let mut row = Vec::with_capacity(columns);
        for (c, field) in fields.iter().enumerate() {
            match field.parse::<f64>() {
                Ok(v) if v.is_finite() => row.push(v),
                _ => {
                    return Err((
                        line_no,
                        format!("column {}: `{field}` is not a number", c + 1),
                    ));
                }
            }
        }
        rows.push((line_no, row));
    }
    Ok(rows)
}

/// The first column must increase strictly from row to row.
pub(crate) fn check_increasing(rows: &[(usize, Vec<f64>)]) -> std::result::Result<(), LineError> {
    for pair in rows.windows(2) {
        let (prev, (line, next)) = (&pair[0].1, (&pair[1].0, &pair[1].1));
        if next[0] <= prev[0] {
            return Err((
                *line,
                format!(
                    "wavelength {} nm does not exceed the previous one ({} nm); sort the samples \
                     by increasing wavelength",
                    next[0], prev[0]
                ),
            ));
        }
    }
    Ok(())
}
