//! Sparkle and graininess read from luminance images, as gonio defines them
//! (`docs/instruments.md`, "Texture"). The commercial multi-angle texture cameras do not
//! publish their algorithms; the CIE JTC 12 work (A. Ferrero et al., "Preliminary measurement
//! scales for sparkle and graininess", Opt. Express 29(5), 7589, 2021; A. Ferrero et al.,
//! "Definition of a measurement scale of graininess from reflectance and visual
//! measurements", Opt. Express 26(23), 30116, 2018) describes sparkle by the density and the
//! contrast of spots brighter than their surround under directional light, and graininess by
//! the luminance contrast of the pattern under diffuse light. gonio follows those
//! descriptions with its own thresholds:
//!
//! - a pixel belongs to a spot where its contrast `C = (Y − Y_b) / Y_b` to the surround is
//!   at least [`SPOT_CONTRAST`]; spots are the 8-connected groups of such pixels;
//! - the surround `Y_b` is the mean luminance of the pixels outside spots (found by
//!   iterating from the mean of all: a field's sparkles can outshine the rest of it many
//!   times over), kept at least `floor` (a small share of a white diffuser's luminance under
//!   the same light, so that a black field does not make every glint a spot of infinite
//!   contrast);
//! - **sparkle density**: spots per mm²; **sparkle area**: the share of the field in spots,
//!   %; **sparkle intensity**: the spots' mean peak contrast; **sparkle grade**: by how much
//!   the spots raise the field's mean luminance over its surround, `100 Σ_spots (Y − Y_b) /
//!   (N Y_b)` % over the N pixels (area and intensity in one number: it grows with both);
//! - **graininess**: the coefficient of variation of the luminance under diffuse light, %,
//!   with the Monte Carlo noise of the picture taken out: two pictures of the same flakes with
//!   independent samples, `A` and `B`, have noise variance `var(A − B) / 2` each, and the
//!   texture's variance is `var((A + B)/2) − var(A − B)/4`.

/// The contrast from which a pixel is part of a sparkle spot: ten times as bright as its
/// surround. Far above the pictures' Monte Carlo noise (a coating without flakes reads no
/// spot, tested) and above the base seen between dark flakes (`1/(1 − c)` times the mean for
/// a coverage c, under 10 up to c = 0.9), and far below the contrast of a flake that fills
/// a pixel with the lamp's mirror image (`R π / (ρ Ω cos θ)`: about 3000 for aluminium over
/// a base of ρ 0.25 under the 2° lamp at 15°).
pub const SPOT_CONTRAST: f64 = 9.0;

/// Relative luminance of linear sRGB (ITU-R BT.709 weights, the Y of CIE 1931 XYZ).
pub fn luminance(rgb: [f32; 3]) -> f64 {
    0.2126 * f64::from(rgb[0]) + 0.7152 * f64::from(rgb[1]) + 0.0722 * f64::from(rgb[2])
}

/// Sparkle read from one image under directional light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sparkle {
    /// The surround's luminance `Y_b` (the mean outside spots, at least the floor).
    pub surround: f64,
    /// The number of spots.
    pub spots: usize,
    /// Spots per mm² of the field.
    pub density_per_mm2: f64,
    /// The share of the field in spots, %.
    pub area_percent: f64,
    /// The spots' mean peak contrast `(Y − Y_b) / Y_b` (0 without spots).
    pub intensity: f64,
    /// By how much the spots raise the field's mean luminance over its surround, %.
    pub grade: f64,
}

/// Sparkle of a `width × height` luminance image `y` (row-major) whose pixels are `pixel_mm`
/// square on the specimen, the surround kept at least `floor`.
pub fn sparkle(y: &[f64], width: usize, pixel_mm: f64, floor: f64) -> Sparkle {
    let height = y.len() / width;
    let mut surround = (y.iter().sum::<f64>() / y.len() as f64).max(floor);
    for _ in 0..50 {
        let limit = (1.0 + SPOT_CONTRAST) * surround;
        let (sum, n) = y
            .iter()
            .filter(|&&v| v < limit)
            .fold((0.0, 0usize), |(s, n), &v| (s + v, n + 1));
        let next = if n > 0 {
            (sum / n as f64).max(floor)
        } else {
            floor
        };
        if next == surround {
            break;
        }
        surround = next;
    }
    let contrast = |v: f64| (v - surround) / surround;
    let bright: Vec<bool> = y.iter().map(|&v| contrast(v) >= SPOT_CONTRAST).collect();
    // 8-connected groups by a flood fill.
    let mut seen = vec![false; y.len()];
    let (mut spots, mut peaks, mut excess, mut in_spots) = (0usize, 0.0, 0.0, 0usize);
    let mut stack = Vec::new();
    for start in 0..y.len() {
        if !bright[start] || seen[start] {
            continue;
        }
        spots += 1;
        let mut peak = 0.0f64;
        seen[start] = true;
        stack.push(start);
        while let Some(k) = stack.pop() {
            peak = peak.max(contrast(y[k]));
            excess += y[k] - surround;
            in_spots += 1;
            let (x, r) = ((k % width) as isize, (k / width) as isize);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (nx, ny) = (x + dx, r + dy);
                    if nx < 0 || ny < 0 || nx >= width as isize || ny >= height as isize {
                        continue;
                    }
                    let n = ny as usize * width + nx as usize;
                    if bright[n] && !seen[n] {
                        seen[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
        peaks += peak;
    }
    let n = y.len() as f64;
    let area_mm2 = n * pixel_mm * pixel_mm;
    Sparkle {
        surround,
        spots,
        density_per_mm2: spots as f64 / area_mm2,
        area_percent: 100.0 * in_spots as f64 / n,
        intensity: if spots > 0 { peaks / spots as f64 } else { 0.0 },
        grade: 100.0 * excess / (n * surround),
    }
}

/// Graininess, %, from two luminance images `a` and `b` of the same field under diffuse
/// light rendered with independent samples: the coefficient of variation of the pattern with
/// the pictures' noise taken out (see the module's documentation).
pub fn graininess(a: &[f64], b: &[f64]) -> f64 {
    let (m, texture, _) = pattern_and_noise(a, b);
    if m > 0.0 {
        100.0 * texture.sqrt() / m
    } else {
        0.0
    }
}

/// The standard uncertainty of [`graininess`], %, from the pictures' noise: with the
/// pattern t, each picture's noise e of variance `V_e = var(A − B)/2` per pixel and N
/// pixels, the estimate of the pattern's variance `V_t` errs by `2 cov(t, ē) + cov(e_A,
/// e_B)` (the two noises' mean ē, of variance `V_e/2`), of variance `(2 V_t V_e + V_e²)/N`,
/// and the graininess `100 √V_t / m` by `100 σ(V_t) / (2 √V_t m)` (first order; its square
/// root's bound `100 √σ(V_t) / m` where the pattern vanishes).
pub fn graininess_uncertainty(a: &[f64], b: &[f64]) -> f64 {
    let (m, texture, noise) = pattern_and_noise(a, b);
    if m <= 0.0 {
        return 0.0;
    }
    let sigma = ((2.0 * texture * noise + noise * noise) / a.len() as f64).sqrt();
    let first_order = 100.0 * sigma / (2.0 * texture.sqrt() * m);
    first_order.min(100.0 * sigma.sqrt() / m)
}

/// The mean of two pictures `a` and `b` of one field, the variance of its pattern with the
/// noise taken out and each picture's noise variance (see the module's documentation).
fn pattern_and_noise(a: &[f64], b: &[f64]) -> (f64, f64, f64) {
    let n = a.len() as f64;
    let mean = |v: &mut dyn Iterator<Item = f64>| v.sum::<f64>() / n;
    let m = mean(&mut a.iter().zip(b).map(|(x, y)| 0.5 * (x + y)));
    let d = mean(&mut a.iter().zip(b).map(|(x, y)| x - y));
    let var_mean = mean(&mut a.iter().zip(b).map(|(x, y)| (0.5 * (x + y) - m).powi(2)));
    let var_diff = mean(&mut a.iter().zip(b).map(|(x, y)| (x - y - d).powi(2)));
    (m, (var_mean - var_diff / 4.0).max(0.0), var_diff / 2.0)
}
