//! The Beckmann microfacet normal distribution and Smith masking, shared by the analytic models,
//! the ray-method references and the samplers.
//!
//! Conventions of `shared/docs/physics.md`: `m` is the total rms slope (per-axis rms slope
//! `m/√2`); `D(th) = exp(-tan²th/m²) / (π m² cos⁴th)`. Smith masking for Beckmann from
//! E. Heitz, "Understanding the masking-shadowing function in microfacet-based BRDFs",
//! JCGT 3(2), 2014, eq. 72 and §5: `a = 1/(m tan t)`,
//! `Λ = (erf(a) - 1)/2 + exp(-a²)/(2 a √π)`.

use std::f64::consts::PI;

/// Beckmann distribution of normals `D(h)` in 1/sr (projected-area normalised:
/// `∫ D(h) cos th dh = 1`) for a normal at `cos_th` from the macroscopic normal.
pub fn beckmann_d(cos_th: f64, m: f64) -> f64 {
    if cos_th <= 0.0 {
        return 0.0;
    }
    let c2 = cos_th * cos_th;
    let tan2 = (1.0 - c2) / c2;
    (-tan2 / (m * m)).exp() / (PI * m * m * c2 * c2)
}

/// Smith's `Λ` for the Beckmann distribution, for a direction at `cos_t` from the normal.
pub fn beckmann_lambda(cos_t: f64, m: f64) -> f64 {
    if cos_t >= 1.0 {
        return 0.0;
    }
    if cos_t <= 0.0 {
        return f64::INFINITY;
    }
    let tan_t = (1.0 - cos_t * cos_t).sqrt() / cos_t;
    let a = 1.0 / (m * tan_t);
    if a > 30.0 {
        return 0.0;
    }
    (libm::erf(a) - 1.0) / 2.0 + (-a * a).exp() / (2.0 * a * PI.sqrt())
}

/// Smith masking `G1 = 1/(1 + Λ)` of one direction.
pub fn smith_g1(cos_t: f64, m: f64) -> f64 {
    1.0 / (1.0 + beckmann_lambda(cos_t, m))
}

/// Height-correlated masking-shadowing `G2 = 1/(1 + Λ(wi) + Λ(wo))` (Heitz 2014, eq. 99).
pub fn smith_g2(cos_i: f64, cos_o: f64, m: f64) -> f64 {
    1.0 / (1.0 + beckmann_lambda(cos_i, m) + beckmann_lambda(cos_o, m))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Numerical quadrature of `∫ D cos th dω` over the hemisphere, which must be 1.
    #[test]
    fn beckmann_is_normalised() {
        for m in [0.05, 0.2, 0.5] {
            let n = 20000;
            let dth = (PI / 2.0) / n as f64;
            let sum: f64 = (0..n)
                .map(|i| {
                    let th = (i as f64 + 0.5) * dth;
                    beckmann_d(th.cos(), m) * th.cos() * th.sin() * 2.0 * PI * dth
                })
                .sum();
            assert!((sum - 1.0).abs() < 1e-6, "m = {m}: {sum}");
        }
    }

    /// The masking identity `∫ G1(wo) <wo·h> D(h) dh = cos to` (Heitz 2014, eq. 2) checked by
    /// quadrature at several outgoing angles.
    #[test]
    fn smith_satisfies_projected_area_identity() {
        let m = 0.4;
        for to_deg in [0.0f64, 30.0, 60.0, 80.0] {
            let to = to_deg.to_radians();
            let wo = [to.sin(), 0.0, to.cos()];
            let (nth, nph) = (800, 800);
            let mut sum = 0.0;
            for i in 0..nth {
                let th = (i as f64 + 0.5) * (PI / 2.0) / nth as f64;
                for j in 0..nph {
                    let ph = (j as f64 + 0.5) * 2.0 * PI / nph as f64;
                    let h = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
                    let dot = (wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]).max(0.0);
                    sum += dot * beckmann_d(th.cos(), m) * th.sin() * (PI / 2.0 / nth as f64) * (2.0 * PI / nph as f64);
                }
            }
            let lhs = smith_g1(to.cos(), m) * sum;
            assert!((lhs - to.cos()).abs() < 2e-3, "to = {to_deg}: {lhs} vs {}", to.cos());
        }
    }
}
