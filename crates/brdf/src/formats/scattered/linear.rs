//! Small dense linear systems of the local regressions.

/// Solve the symmetric N×N system `a x = rhs` for `m` right-hand sides stored row-wise in `rhs`
/// (`rhs[r * m + k]`), in place, by Gaussian elimination with partial pivoting.
pub(in crate::formats) fn solve<const N: usize>(
    mut a: [[f64; N]; N],
    rhs: &mut [f64],
    m: usize,
) -> Option<()> {
    for col in 0..N {
        let piv = (col..N).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-12 {
            return None;
        }
        if piv != col {
            a.swap(piv, col);
            for k in 0..m {
                rhs.swap(piv * m + k, col * m + k);
            }
        }
        for r in col + 1..N {
            let f = a[r][col] / a[col][col];
            if f == 0.0 {
                continue;
            }
            let pivot_row = a[col];
            for (x, p) in a[r][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            for k in 0..m {
                rhs[r * m + k] -= f * rhs[col * m + k];
            }
        }
    }
    for col in (0..N).rev() {
        for k in 0..m {
            let mut v = rhs[col * m + k];
            for c in col + 1..N {
                v -= a[col][c] * rhs[c * m + k];
            }
            rhs[col * m + k] = v / a[col][col];
        }
    }
    Some(())
}
