//! How a match reads a formulation against its target: the coating at the constituents'
//! values, its reading with the common random numbers of seed 0, the objective (mean ΔE00 plus
//! weighted gloss differences, or rms ΔR), the residual vector and the Gauss–Newton
//! uncertainty at the optimum ([`crate::matching`] describes each and cites its source).

use crate::appearance::gloss_at;
use crate::coating_sensitivity::Varied;
use crate::error::{FormulationError, Result};
use crate::match_objective::{Objective, reflectance_differences, rms};
use crate::matching::{Comparison, Settings};
use crate::target::GlossTarget;
use gonio_coating::system::Coating;
use gonio_instrument::coating_study::{self, Reading};
use gonio_instrument::gloss::GlossReport;
use gonio_instrument::multiangle::{Geometry, MultiangleReading};
use gonio_instrument::multiangle_target::Target;
use rayon::prelude::*;

/// The matcher's reading of formulations against the target.
pub(crate) struct Reader<'a> {
    start: &'a Coating,
    pub(crate) varied: &'a [Varied],
    target: &'a Target,
    gloss: &'a [GlossTarget],
    settings: &'a Settings,
    pub(crate) geometries: Vec<Geometry>,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(
        start: &'a Coating,
        varied: &'a [Varied],
        target: &'a Target,
        gloss: &'a [GlossTarget],
        settings: &'a Settings,
    ) -> Self {
        Reader {
            start,
            varied,
            target,
            gloss,
            settings,
            geometries: target.geometries(),
        }
    }

    pub(crate) fn coating(&self, x: &[f64]) -> Result<Coating> {
        let mut c = self.start.clone();
        for (v, &value) in self.varied.iter().zip(x) {
            c = v.constituent.apply(&c, value)?;
        }
        Ok(c)
    }

    /// Read the formulation `x` (seed 0): the multi-angle colour, and the gloss meter when
    /// `with_gloss` (its reading is most of the cost: only when the objective needs it).
    pub(crate) fn read(
        &self,
        x: &[f64],
        with_gloss: bool,
    ) -> Result<(Option<GlossReport>, MultiangleReading)> {
        let s = self.settings;
        let coating = self.coating(x)?;
        if with_gloss {
            let Reading { gloss, multiangle } = coating_study::read_coating(
                &coating,
                &self.geometries,
                &s.wavelengths_nm,
                s.walks,
                s.gloss_walks,
                0,
            )?;
            return Ok((Some(gloss), multiangle));
        }
        coating.check(&s.wavelengths_nm)?;
        let evaluator = coating.evaluator(&s.wavelengths_nm)?;
        let multiangle = coating_study::multiangle_reading(
            &evaluator,
            &s.wavelengths_nm,
            &self.geometries,
            s.walks,
            0,
        )?;
        Ok((None, multiangle))
    }

    /// The weighted gloss differences of `gloss` from the targets, in target order.
    pub(crate) fn gloss_differences(&self, gloss: &GlossReport) -> Result<Vec<f64>> {
        self.gloss
            .iter()
            .map(|t| Ok(self.settings.gloss_weight * (gloss_at(gloss, t.angle)? - t.gu)))
            .collect()
    }

    /// The objective of a reading: mean ΔE00 + Σ weight |ΔGU| (the gloss when read), or the rms
    /// ΔR.
    pub(crate) fn score(
        &self,
        multiangle: &MultiangleReading,
        gloss: Option<&GlossReport>,
    ) -> Result<f64> {
        let mut f = match self.settings.objective {
            Objective::De00 => {
                let de = self.target.de00(multiangle)?;
                de.iter().sum::<f64>() / de.len() as f64
            }
            Objective::Spectral => rms(&reflectance_differences(self.target, multiangle)?),
        };
        if let Some(g) = gloss {
            f += self
                .gloss_differences(g)?
                .iter()
                .map(|d| d.abs())
                .sum::<f64>();
        }
        Ok(f)
    }

    /// The objective at `x`.
    pub(crate) fn objective(&self, x: &[f64]) -> Result<f64> {
        let (gloss, multiangle) = self.read(x, !self.gloss.is_empty())?;
        let f = self.score(&multiangle, gloss.as_ref())?;
        if !f.is_finite() {
            return Err(FormulationError::Invalid(format!(
                "the objective at {} is not a number",
                self.describe(x)
            )));
        }
        Ok(f)
    }

    /// The residual vector at `x`: ΔL*, Δa*, Δb* per geometry (ΔR per geometry and band for the
    /// spectral objective), then the weighted ΔGU.
    pub(crate) fn residuals(&self, x: &[f64]) -> Result<Vec<f64>> {
        let (gloss, multiangle) = self.read(x, !self.gloss.is_empty())?;
        let mut r = Vec::new();
        match self.settings.objective {
            Objective::De00 => {
                for &(g, lab) in &self.target.colours {
                    let m = multiangle
                        .at(g)
                        .ok_or_else(|| FormulationError::Invalid(format!("{g} was not read")))?;
                    r.extend([m.lab.l - lab.l, m.lab.a - lab.a, m.lab.b - lab.b]);
                }
            }
            Objective::Spectral => r = reflectance_differences(self.target, &multiangle)?,
        }
        if let Some(g) = gloss {
            r.extend(self.gloss_differences(&g)?);
        }
        Ok(r)
    }

    /// The formulation `x` read in full against the target.
    pub(crate) fn compare(&self, x: &[f64]) -> Result<Comparison> {
        let (gloss, multiangle) = self.read(x, true)?;
        let gloss = gloss.expect("read with the gloss meter");
        let objective = self.score(&multiangle, (!self.gloss.is_empty()).then_some(&gloss))?;
        let rms_reflectance = match self.target.spectra {
            Some(_) => Some(rms(&reflectance_differences(self.target, &multiangle)?)),
            None => None,
        };
        Ok(Comparison {
            values: x.to_vec(),
            de00: self.target.de00(&multiangle)?,
            gloss,
            multiangle,
            rms_reflectance,
            objective,
        })
    }

    pub(crate) fn describe(&self, x: &[f64]) -> String {
        self.varied
            .iter()
            .zip(x)
            .map(|(v, x)| format!("{} {x:.4}", v.name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// One standard deviation of each constituent at `x` (Gauss–Newton, module docs) and the
    /// residuals' standard deviation; the number of readings made.
    pub(crate) fn uncertainty(&self, x: &[f64]) -> Result<(Option<Vec<f64>>, f64, usize)> {
        let p = x.len();
        let r0 = self.residuals(x)?;
        let m = r0.len();
        let s2 = if m > p {
            r0.iter().map(|r| r * r).sum::<f64>() / (m - p) as f64
        } else {
            f64::NAN
        };
        // Central differences, one-sided at a bound: columns of J.
        let columns = (0..p)
            .into_par_iter()
            .map(|i| {
                let v = &self.varied[i];
                let h = 0.01 * (v.hi - v.lo);
                let up = (x[i] + h).min(v.hi);
                let down = (x[i] - h).max(v.lo);
                let at = |value: f64| -> Result<Vec<f64>> {
                    let mut y = x.to_vec();
                    y[i] = value;
                    self.residuals(&y)
                };
                let (ru, rd) = (at(up)?, at(down)?);
                Ok(ru
                    .iter()
                    .zip(&rd)
                    .map(|(a, b)| (a - b) / (up - down))
                    .collect::<Vec<f64>>())
            })
            .collect::<Result<Vec<_>>>()?;
        let readings = 1 + 2 * p;
        let j = nalgebra::DMatrix::from_fn(m, p, |row, col| columns[col][row]);
        let sigma = (m > p)
            .then(|| (j.transpose() * &j).try_inverse())
            .flatten()
            .map(|inv| {
                (0..p)
                    .map(|i| (s2 * inv[(i, i)]).sqrt())
                    .collect::<Vec<_>>()
            })
            .filter(|s| s.iter().all(|v| v.is_finite()));
        Ok((sigma, s2.sqrt(), readings))
    }
}
