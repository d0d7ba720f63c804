//! gonio's Sobol and Morris analyses against SALib's (PyPI `SALib`, 1.6.0 when written): gonio
//! writes its own design and outputs to a file, SALib's `sobol.analyze` (calc_second_order =
//! False) and `morris.analyze` read the same numbers, and the point estimates must agree to
//! 1e-12 (the same formulas on the same numbers; only the order of summation differs, numpy's
//! pairwise sums against gonio's sequential ones, a few 1e-16 relative per sum of a few thousand
//! terms). The intervals come from different resamples and are not compared.

use crate::oracle;
use crate::sensitivity::{ishigami, ishigami_problem};
use gonio_formulation::sensitivity::{self, Problem, morris, sobol};
use ndarray::Array2;

const SCRIPT: &str = r#"
import json, sys, warnings
import numpy as np
from SALib.analyze import morris, sobol
warnings.simplefilter("ignore")
case = json.load(open(sys.argv[1]))
problem = {"num_vars": len(case["names"]), "names": case["names"], "bounds": case["bounds"]}
X = np.array(case["points"], dtype=float)
Y = np.array(case["outputs"], dtype=float)
out = []
for k in range(Y.shape[1]):
    if case["method"] == "sobol":
        s = sobol.analyze(problem, Y[:, k].copy(), calc_second_order=False, seed=1)
        out.append({"s1": list(s["S1"]), "st": list(s["ST"])})
    else:
        s = morris.analyze(problem, X, Y[:, k].copy(), num_levels=case["levels"], seed=1)
        out.append({"mu": list(s["mu"]), "mu_star": list(s["mu_star"]), "sigma": list(s["sigma"])})
print(json.dumps(out))
"#;

/// The design, the outputs and the problem as the script reads them.
pub fn case(
    problem: &Problem,
    method: &str,
    levels: usize,
    points: &Array2<f64>,
    outputs: &Array2<f64>,
) -> serde_json::Value {
    let rows =
        |m: &Array2<f64>| -> Vec<Vec<f64>> { m.rows().into_iter().map(|r| r.to_vec()).collect() };
    serde_json::json!({
        "names": problem.inputs().iter().map(|i| i.name.clone()).collect::<Vec<_>>(),
        "bounds": problem.inputs().iter().map(|i| [i.lo, i.hi]).collect::<Vec<_>>(),
        "method": method,
        "levels": levels,
        "points": rows(points),
        "outputs": rows(outputs),
    })
}

/// SALib's figures of `case`, one map of name → values per output; `None` when SALib is missing.
pub fn salib(case: &serde_json::Value) -> Option<Vec<std::collections::HashMap<String, Vec<f64>>>> {
    oracle::run(SCRIPT, "SALib", "SALib", case)
}

/// `got` equals SALib's `want` to 1e-12 relative to the larger of the value and `scale`.
pub fn assert_same(what: &str, got: &[f64], want: &[f64], scale: f64) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= 1e-12 * w.abs().max(scale),
            "{what}: gonio {got:?} SALib {want:?} (difference {:e})",
            g - w
        );
    }
}

/// Ishigami's function and a second output (x₁ + x₂², another scale and mean): Sobol at N = 512,
/// Morris with 64 trajectories on 4 and 6 levels.
#[test]
fn indices_equal_salibs_on_the_same_outputs() {
    let problem = ishigami_problem();
    let model = |x: &[f64]| Ok(vec![ishigami(x), 100.0 + x[0] + x[1] * x[1]]);
    let points = sobol::sample(&problem, 512, 2).unwrap();
    let outputs = sensitivity::evaluate(&points, 2, model).unwrap();
    let ours = sobol::analyze(&problem, &outputs, 0).unwrap();
    let Some(theirs) = salib(&case(&problem, "sobol", 0, &points, &outputs)) else {
        return;
    };
    for (o, t) in ours.iter().zip(&theirs) {
        assert_same("S1", &o.s1, &t["s1"], 1.0);
        assert_same("ST", &o.st, &t["st"], 1.0);
    }
    for levels in [4, 6] {
        let points = morris::sample(&problem, 64, levels, 3).unwrap();
        let outputs = sensitivity::evaluate(&points, 2, model).unwrap();
        let ours = morris::analyze(&problem, &points, &outputs, levels, 0).unwrap();
        let theirs = salib(&case(&problem, "morris", levels, &points, &outputs)).unwrap();
        for (o, t) in ours.iter().zip(&theirs) {
            let scale = o.mu_star.iter().cloned().fold(0.0, f64::max);
            assert_same("mu", &o.mu, &t["mu"], scale);
            assert_same("mu_star", &o.mu_star, &t["mu_star"], scale);
            assert_same("sigma", &o.sigma, &t["sigma"], scale);
        }
    }
}
