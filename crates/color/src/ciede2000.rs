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

#[cfg(test)]
mod tests {
    use super::*;

    /// Sharma, Wu & Dalal (2005), Table 1: L1, a1, b1, L2, a2, b2, ΔE00 (four decimals). The
    /// transcription is checked against colour-science by
    /// `crates/color/tests/reference/ciede2000_sharma.py`.
    const SHARMA_2005: [[f64; 7]; 34] = [
        [50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425],
        [50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615],
        [50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412],
        [
            50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000,
        ],
        [
            50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000,
        ],
        [
            50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000,
        ],
        [50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669],
        [50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461],
        [50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065],
        [50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492],
        [50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977],
        [50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030],
        [50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000],
        [
            60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644,
        ],
        [
            63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630,
        ],
        [61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731],
        [35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645],
        [
            22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373,
        ],
        [36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146],
        [90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441],
        [90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381],
        [6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377],
        [2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082],
    ];

    /// Every pair within the table's rounding (half a unit in the fourth decimal), both ways round
    /// (ΔE00 is symmetric).
    #[test]
    fn reproduces_the_sharma_table() {
        for (i, p) in SHARMA_2005.iter().enumerate() {
            let lab1 = Lab {
                l: p[0],
                a: p[1],
                b: p[2],
            };
            let lab2 = Lab {
                l: p[3],
                a: p[4],
                b: p[5],
            };
            let de = ciede2000(lab1, lab2);
            assert!(
                (de - p[6]).abs() <= 5e-5,
                "pair {}: {de} vs {}",
                i + 1,
                p[6]
            );
            assert!(
                (ciede2000(lab2, lab1) - de).abs() < 1e-12,
                "pair {} not symmetric",
                i + 1
            );
        }
    }

    #[test]
    fn identical_colours_differ_by_zero_and_lightness_is_scaled() {
        let lab = Lab {
            l: 40.0,
            a: 10.0,
            b: -20.0,
        };
        assert_eq!(ciede2000(lab, lab), 0.0);
        // Two greys differing only in lightness around L = 50: S_L = 1, so ΔE00 = ΔL.
        let g1 = Lab {
            l: 49.5,
            a: 0.0,
            b: 0.0,
        };
        let g2 = Lab {
            l: 50.5,
            a: 0.0,
            b: 0.0,
        };
        assert!((ciede2000(g1, g2) - 1.0).abs() < 1e-12);
        assert!((ciede2000_weighted(g1, g2, [2.0, 1.0, 1.0]) - 0.5).abs() < 1e-12);
    }
}
