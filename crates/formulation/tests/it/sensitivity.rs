//! The estimators against analytic indices: Ishigami's function for Sobol's, linear models for
//! Morris's; the designs' layout; refused inputs.

use gonio_formulation::sensitivity::{self, Input, Problem, Z95, morris, sobol};
use ndarray::Array2;
use std::f64::consts::PI;

/// Ishigami & Homma's function (1990) with a = 7, b = 0.1 over [−π, π]³.
pub fn ishigami(x: &[f64]) -> f64 {
    let (a, b) = (7.0, 0.1);
    x[0].sin() + a * x[1].sin().powi(2) + b * x[2].powi(4) * x[0].sin()
}

pub fn ishigami_problem() -> Problem {
    Problem::new(
        ["x1", "x2", "x3"]
            .iter()
            .map(|n| Input::new(*n, -PI, PI))
            .collect(),
    )
    .unwrap()
}

/// Ishigami's first-order and total indices, analytic (Sobol & Levitan, Comput. Phys. Commun.
/// 117, 52, 1999; Saltelli et al. 2010 §4): V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2,
/// V1 = ½ (1 + bπ⁴/5)², V2 = a²/8, V3 = 0, V13 = 8 b² π⁸ / 225.
fn ishigami_indices() -> ([f64; 3], [f64; 3]) {
    let (a, b) = (7.0f64, 0.1f64);
    let pi4 = PI.powi(4);
    let v = a * a / 8.0 + b * pi4 / 5.0 + b * b * pi4 * pi4 / 18.0 + 0.5;
    let v1 = 0.5 * (1.0 + b * pi4 / 5.0).powi(2);
    let v2 = a * a / 8.0;
    let v13 = 8.0 * b * b * pi4 * pi4 / 225.0;
    ([v1 / v, v2 / v, 0.0], [(v1 + v13) / v, v2 / v, v13 / v])
}

fn evaluate_ishigami(points: &Array2<f64>) -> Array2<f64> {
    sensitivity::evaluate(points, 1, |x| Ok(vec![ishigami(x)])).unwrap()
}

/// The published figures follow from the formulas above (S1 = 0.3139, 0.4424, 0;
/// ST = 0.5576, 0.4424, 0.2437).
#[test]
fn ishigami_analytic_indices_are_the_published_ones() {
    let (s1, st) = ishigami_indices();
    for (got, want) in s1
        .iter()
        .chain(&st)
        .zip([0.3139, 0.4424, 0.0, 0.5576, 0.4424, 0.2437])
    {
        assert!((got - want).abs() < 5e-5, "{got} vs {want}");
    }
}

/// Sobol indices of Ishigami's function at N = 4 096 base points (20 480 evaluations): each
/// estimate within three of its bootstrap standard errors (the 95% half-width / 1.96) of the
/// analytic value; a bootstrap error describes independent rows and so over-states the error
/// of a scrambled Sobol design, and three of them are passed by chance with probability 0.27%
/// per index. So that the bound means something, the intervals must also be narrow: every
/// half-width under 0.06 (with N independent rows the first-order estimator's standard error is
/// about √(Var[f(B)(f(AB)−f(A))]/N)/V, 0.02–0.03 here).
#[test]
fn sobol_recovers_ishigamis_indices() {
    let problem = ishigami_problem();
    let points = sobol::sample(&problem, 4096, 7).unwrap();
    assert_eq!(points.dim(), (4096 * 5, 3));
    let indices = &sobol::analyze(&problem, &evaluate_ishigami(&points), 11).unwrap()[0];
    let (s1, st) = ishigami_indices();
    for i in 0..3 {
        for (name, got, conf, want) in [
            ("S1", indices.s1[i], indices.s1_conf[i], s1[i]),
            ("ST", indices.st[i], indices.st_conf[i], st[i]),
        ] {
            let se = conf / Z95;
            assert!(conf < 0.06, "{name}{}: interval ±{conf}", i + 1);
            assert!(
                (got - want).abs() < 3.0 * se,
                "{name}{}: {got} ± {conf} vs {want}",
                i + 1
            );
        }
    }
}

/// Saltelli's layout: per base point the rows A, AB_1 … AB_d, B, where AB_i is A with column
/// i from B; every coordinate within the bounds; the same seed gives the same design.
#[test]
fn sobol_design_is_saltellis() {
    let problem = Problem::new(vec![
        Input::new("a", 0.0, 1.0),
        Input::new("b", 10.0, 20.0),
        Input::new("c", -1.0, 0.0),
    ])
    .unwrap();
    let x = sobol::sample(&problem, 64, 3).unwrap();
    for n in 0..64 {
        let (a, b) = (x.row(n * 5), x.row(n * 5 + 4));
        for i in 0..3 {
            let ab = x.row(n * 5 + 1 + i);
            for j in 0..3 {
                assert_eq!(ab[j], if i == j { b[j] } else { a[j] });
                assert_ne!(a[j], b[j]);
            }
        }
    }
    for (j, input) in problem.inputs().iter().enumerate() {
        assert!(x.column(j).iter().all(|&v| v >= input.lo && v < input.hi));
    }
    assert_eq!(x, sobol::sample(&problem, 64, 3).unwrap());
    assert_ne!(x, sobol::sample(&problem, 64, 4).unwrap());
}

/// For a linear model every elementary effect of x_j is c_j (hi_j − lo_j) exactly: μ* = |c_j|
/// times the range, μ its signed value, σ = 0 (to rounding: the effects are differences of sums
/// of a few terms of order 10, divided by Δ). A second output, x₁ x₂, has effects that depend
/// on the other input (σ > 0) and none from x₃ or x₄.
#[test]
fn morris_effects_of_a_linear_model_are_its_coefficients_times_the_range() {
    let inputs = vec![
        Input::new("x1", 0.0, 1.0),
        Input::new("x2", 2.0, 5.0),
        Input::new("x3", -10.0, 10.0),
        Input::new("x4", 0.5, 0.75),
    ];
    let c = [2.0, -3.0, 0.25, 0.0];
    let problem = Problem::new(inputs.clone()).unwrap();
    for levels in [4, 6] {
        let x = morris::sample(&problem, 40, levels, 5).unwrap();
        assert_eq!(x.dim(), (40 * 5, 4));
        let y = sensitivity::evaluate(&x, 2, |x| {
            Ok(vec![
                x.iter().zip(&c).map(|(x, c)| x * c).sum(),
                x[0] * x[1],
            ])
        })
        .unwrap();
        let e = morris::analyze(&problem, &x, &y, levels, 1).unwrap();
        for (j, input) in inputs.iter().enumerate() {
            let want = c[j] * (input.hi - input.lo);
            assert!((e[0].mu[j] - want).abs() < 1e-12, "{levels}: {:?}", e[0].mu);
            assert!((e[0].mu_star[j] - want.abs()).abs() < 1e-12);
            assert!(e[0].sigma[j] < 1e-12 && e[0].mu_star_conf[j] < 1e-12);
        }
        assert!(
            e[1].sigma[0] > 0.1 && e[1].sigma[1] > 0.1,
            "{:?}",
            e[1].sigma
        );
        assert_eq!(e[1].mu_star[2], 0.0);
        assert_eq!(e[1].mu_star[3], 0.0);
    }
}

/// Morris's trajectories: d + 1 points, consecutive points differing in one input by Δ of its
/// range, every input moving once, every coordinate on the p-level grid.
#[test]
fn morris_trajectories_move_one_input_at_a_time_on_the_grid() {
    let problem = Problem::new(vec![
        Input::new("a", 0.0, 3.0),
        Input::new("b", 0.0, 3.0),
        Input::new("c", 0.0, 3.0),
    ])
    .unwrap();
    let x = morris::sample(&problem, 50, 4, 9).unwrap();
    let step = 3.0 * morris::delta(4);
    assert!((step - 2.0).abs() < 1e-15);
    for t in 0..50 {
        let mut moved = [0; 3];
        for k in 0..3 {
            let (p, q) = (x.row(t * 4 + k), x.row(t * 4 + k + 1));
            let changed: Vec<usize> = (0..3).filter(|&j| p[j] != q[j]).collect();
            assert_eq!(changed.len(), 1);
            assert!(((q[changed[0]] - p[changed[0]]).abs() - step).abs() < 1e-12);
            moved[changed[0]] += 1;
        }
        assert_eq!(moved, [1, 1, 1]);
    }
    assert!(x.iter().all(|v| [0.0, 1.0, 2.0, 3.0].contains(v)), "{x}");
    // A design that is not made of trajectories is refused.
    let mut bad = x.clone();
    bad[[1, 0]] += 0.5;
    bad[[1, 1]] += 0.5;
    let y = Array2::zeros((200, 1));
    assert!(morris::analyze(&problem, &bad, &y, 4, 0).is_err());
}

#[test]
fn bad_inputs_are_refused() {
    assert!(Problem::new(vec![]).is_err());
    assert!(Problem::new(vec![Input::new("a", 1.0, 1.0)]).is_err());
    assert!(Problem::new(vec![Input::new("a", 0.0, f64::NAN)]).is_err());
    assert!(Problem::new(vec![Input::new("a", 0.0, 1.0), Input::new("a", 0.0, 2.0)]).is_err());
    let p = ishigami_problem();
    assert!(sobol::sample(&p, 1, 0).is_err());
    assert!(sobol::analyze(&p, &Array2::zeros((7, 1)), 0).is_err());
    assert!(morris::sample(&p, 10, 5, 0).is_err());
    let x = sobol::sample(&p, 4, 0).unwrap();
    let err = sensitivity::evaluate(&x, 1, |x| Ok(vec![(x[0] - 10.0).ln()])).unwrap_err();
    assert!(err.to_string().contains("point 1"), "{err}");
    assert!(sensitivity::evaluate(&x, 2, |_| Ok(vec![1.0])).is_err());
}

/// An output that does not vary gets indices 0 and variance 0 rather than 0/0.
#[test]
fn a_constant_output_has_zero_indices() {
    let p = ishigami_problem();
    let x = sobol::sample(&p, 16, 0).unwrap();
    let y = sensitivity::evaluate(&x, 1, |_| Ok(vec![3.0])).unwrap();
    let s = &sobol::analyze(&p, &y, 0).unwrap()[0];
    assert_eq!(s.variance, 0.0);
    assert!(s.s1.iter().chain(&s.st).all(|&v| v == 0.0));
}
