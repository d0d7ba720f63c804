//! The CIEDE2000 colour difference ΔE00 between two CIELAB colours.
//!
//! Source: CIE 142-2001 *Improvement to industrial colour-difference evaluation*, implemented as
//! in G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula: implementation
//! notes, supplementary test data, and mathematical observations", Color Research & Application
//! 30(1), 21–30 (2005), eqs. (1)–(22), including their notes on the hue of achromatic colours
//! (h' = 0 when a' = b' = 0) and on the mean hue when |h'₁ − h'₂| > 180°.

use crate::xyz::Lab;

/// ΔE00 between `lab1` and `lab2` with the parametric factors k_L = k_C = k_H = 1.
pub fn ciede2000(lab1: Lab, lab2: Lab) -> f64 {
    ciede2000_weighted(lab1, lab2, [1.0, 1.0, 1.0])
}

/// ΔE00 with parametric factors [k_L, k_C, k_H] (Sharma et al. 2005, eq. 22).
pub fn ciede2000_weighted(lab1: Lab, lab2: Lab, [k_l, k_c, k_h]: [f64; 3]) -> f64 {
    const POW25_7: f64 = 6_103_515_625.0; // 25^7
    // Eqs. 2–5: a' rescaled by G, which depends on the mean chroma.
    let c_mean = (lab1.chroma() + lab2.chroma()) / 2.0;
    let c7 = c_mean.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + POW25_7)).sqrt());
    let prime = |lab: Lab| {
        let a = (1.0 + g) * lab.a;
        let c = a.hypot(lab.b);
        let h = if a == 0.0 && lab.b == 0.0 {
            0.0
        } else {
            lab.b.atan2(a).to_degrees().rem_euclid(360.0)
        };
        (c, h)
    };
    let (c1, h1) = prime(lab1);
    let (c2, h2) = prime(lab2);

    // Eqs. 8–10: differences.
    let dl = lab2.l - lab1.l;
    let dc = c2 - c1;
    let dh_angle = if c1 * c2 == 0.0 {
        0.0
    } else if (h2 - h1).abs() <= 180.0 {
        h2 - h1
    } else if h2 - h1 > 180.0 {
        h2 - h1 - 360.0
    } else {
        h2 - h1 + 360.0
    };
    let dh = 2.0 * (c1 * c2).sqrt() * (dh_angle.to_radians() / 2.0).sin();

    // Eqs. 12–14: means.
    let l_mean = (lab1.l + lab2.l) / 2.0;
    let c_mean_prime = (c1 + c2) / 2.0;
    let h_mean = if c1 * c2 == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        (h1 + h2) / 2.0
    } else if h1 + h2 < 360.0 {
        (h1 + h2 + 360.0) / 2.0
    } else {
        (h1 + h2 - 360.0) / 2.0
    };

    // Eqs. 15–21: weighting functions and the rotation term.
    let t = 1.0 - 0.17 * (h_mean - 30.0).to_radians().cos()
        + 0.24 * (2.0 * h_mean).to_radians().cos()
        + 0.32 * (3.0 * h_mean + 6.0).to_radians().cos()
        - 0.20 * (4.0 * h_mean - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((h_mean - 275.0) / 25.0).powi(2)).exp();
    let c7 = c_mean_prime.powi(7);
    let r_c = 2.0 * (c7 / (c7 + POW25_7)).sqrt();
    let l50 = (l_mean - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * c_mean_prime;
    let s_h = 1.0 + 0.015 * c_mean_prime * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;

    // Eq. 22.
    let (tl, tc, th) = (dl / (k_l * s_l), dc / (k_c * s_c), dh / (k_h * s_h));
    (tl * tl + tc * tc + th * th + r_t * tc * th).sqrt()
}
