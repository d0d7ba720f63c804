//! The bilinear 2D distribution (Mitsuba's `Marginal2D`): sampling and its inverse, a density
//! that integrates to one, an interpolant through its nodes.

use gonio_brdf::sampling::bilinear::*;

fn warp() -> Marginal2D {
    // Two parameter slices of a 5 × 4 grid with a bump.
    let mut data = vec![];
    for s in 0..2 {
        for y in 0..4 {
            for x in 0..5 {
                data.push(
                    0.2 + (x * (y + 1)) as f32 * (1.0 + s as f32) + if x == 2 { 3.0 } else { 0.0 },
                );
            }
        }
    }
    Marginal2D::new(&data, 5, 4, vec![vec![0.0, 1.0]], true).unwrap()
}

#[test]
fn sample_and_invert_are_inverse_and_the_density_integrates_to_one() {
    let w = warp();
    for p in [0.0, 0.3, 1.0] {
        for i in 0..50 {
            let u = [
                ((i as f64 + 0.5) * 0.618034) % 1.0,
                (i as f64 * 0.414214 + 0.05) % 1.0,
            ];
            let (pos, pdf) = w.sample(u, &[p]);
            let (back, pdf2) = w.invert(pos, &[p]);
            assert!(
                (back[0] - u[0]).abs() < 1e-9 && (back[1] - u[1]).abs() < 1e-9,
                "{u:?} -> {back:?}"
            );
            assert!(
                (pdf - pdf2).abs() < 1e-9 * pdf && (w.eval(pos, &[p]) - pdf).abs() < 1e-9 * pdf
            );
        }
        let m = 200;
        let integral: f64 = (0..m * m)
            .map(|k| {
                w.eval(
                    [
                        ((k % m) as f64 + 0.5) / m as f64,
                        ((k / m) as f64 + 0.5) / m as f64,
                    ],
                    &[p],
                )
            })
            .sum::<f64>()
            / (m * m) as f64;
        assert!((integral - 1.0).abs() < 1e-4, "{integral}");
    }
}

#[test]
fn plain_interpolant_hits_nodes() {
    let data: Vec<f32> = (0..12).map(|i| i as f32).collect();
    let m = Marginal2D::new(&data, 4, 3, vec![], false).unwrap();
    assert_eq!(m.eval([1.0 / 3.0, 0.5], &[]), 5.0);
    assert!((m.eval([0.5, 0.25], &[]) - (1.5 + 4.0 * 0.5)).abs() < 1e-12);
}

/// Evaluating at every node of the last parameter at once gives each node's `eval` to the
/// bit, between and at the leading parameter's nodes (a tensor file's values: two angles and
/// the wavelengths, here one angle and four uneven wavelengths on a 3 × 4 grid).
#[test]
fn every_node_of_the_last_parameter_at_once() {
    let lambdas = vec![400.0, 430.0, 550.0, 700.0];
    let data: Vec<f32> = (0..2 * 4 * 12)
        .map(|i| ((i * 37) % 11) as f32 * 0.3 + 0.1)
        .collect();
    let m = Marginal2D::new(&data, 3, 4, vec![vec![0.0, 1.0], lambdas.clone()], false).unwrap();
    for p in [0.0, 0.37, 1.0] {
        for pos in [[0.0, 0.0], [0.3, 0.8], [1.0, 0.45]] {
            let mut all = [0.0; 4];
            m.eval_at_last_nodes(pos, &[p], &mut all);
            for (l, got) in lambdas.iter().zip(all) {
                assert_eq!(
                    got.to_bits(),
                    m.eval(pos, &[p, *l]).to_bits(),
                    "{p} {pos:?} {l}"
                );
            }
        }
    }
}

/// More than three parameters are refused with an error (the interpolation weights are held in
/// place for at most eight corners), not a panic.
#[test]
fn more_than_three_parameters_are_refused() {
    let data = vec![1.0f32; 16 * 4];
    let params = vec![vec![0.0]; 4];
    let err = Marginal2D::new(&data, 2, 2, params, true).unwrap_err();
    assert!(err.contains("at most 3"), "{err}");
    let ok = Marginal2D::new(&data[..4 * 8], 2, 2, vec![vec![0.0, 1.0]; 3], true);
    assert!(ok.is_ok());
}
