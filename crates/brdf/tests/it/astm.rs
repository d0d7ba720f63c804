//! The ASTM E1392 reader refuses malformed files and names the line.

use gonio_brdf::formats::astm::*;
use std::path::Path;

#[test]
fn malformed_files_are_rejected_with_the_line() {
    let p = Path::new("x.astm");
    let head = "SAMPLE_NAME test\nNUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s,400nm,500nm\n";
    assert!(parse(&format!("{head}0.1,0,0.2,3.1,0.5,0.6\n"), p).is_ok());
    let e = parse(&format!("{head}0.1,0,0.2,3.1,0.5\n"), p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("x.astm") && e.contains("line 4"), "{e}");
    let e = parse(&format!("{head}10,0,20,180,0.5,0.6\n"), p)
        .unwrap_err()
        .to_string();
    assert!(e.contains("radians"), "{e}");
    let e = parse(head, p).unwrap_err().to_string();
    assert!(e.contains("NUM_POINTS"), "{e}");
    let e = parse("0.1,0,0.2,3.1,0.5\n", p).unwrap_err().to_string();
    assert!(e.contains("VARS"), "{e}");
}
