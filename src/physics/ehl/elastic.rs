//! Elastic deflection of the half-space under a line load distribution, in the Hertzian
//! dimensionless variables of [`super`]: `V(X) = (1/π) ∫ ln|X − X'| P(X') dX'`, so that the film is
//! `H = H0 + X²/2 − V` (seed 000 eq. 3 reduced to a line contact; Johnson eq. 2.25b).
//!
//! The pressure is taken piecewise constant on cells of width `Δ` centred on the nodes of a uniform
//! grid; the integral over one cell is exact, so the influence coefficients depend on `|i − j|`
//! only (a symmetric Toeplitz matrix). The Newton solver needs the whole matrix in its Jacobian
//! anyway (the film at every node depends on the pressure at every node), so the deflection is a
//! dense product: `O(n²)` against the `O(n³)` factorisation that dominates each Newton step.

/// Influence coefficients `D_k = ∫_{kΔ−Δ/2}^{kΔ+Δ/2} ln|s| ds`, `k = 0..n`.
pub fn influence_coefficients(n: usize, dx: f64) -> Vec<f64> {
    // ∫ ln|s| ds = s (ln|s| − 1); zero at s = 0.
    let f = |s: f64| if s == 0.0 { 0.0 } else { s * (s.abs().ln() - 1.0) };
    (0..n)
        .map(|k| {
            let s = k as f64 * dx;
            f(s + 0.5 * dx) - f(s - 0.5 * dx)
        })
        .collect()
}

/// `V_i = (1/π) Σ_j D_|i−j| P_j` for every node, written into `out`.
pub fn deflection(kernel: &[f64], p: &[f64], out: &mut [f64]) {
    let n = p.len();
    // Only nodes with non-zero pressure contribute: skip the cavitated tail and the far inlet.
    let first = p.iter().position(|&v| v != 0.0);
    let Some(first) = first else {
        out.iter_mut().for_each(|v| *v = 0.0);
        return;
    };
    let last = p.iter().rposition(|&v| v != 0.0).unwrap_or(first);
    for (i, o) in out.iter_mut().enumerate().take(n) {
        let mut s = 0.0;
        for (j, &pj) in p.iter().enumerate().take(last + 1).skip(first) {
            s += kernel[i.abs_diff(j)] * pj;
        }
        *o = s * std::f64::consts::FRAC_1_PI;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hertzian pressure `sqrt(1 − X²)` deflects the surface into `X²/2 + const` inside the
    /// contact (that is what makes the dry film flat): the deflection's curvature there is 1.
    #[test]
    fn hertz_pressure_flattens_the_film() {
        let n = 2001;
        let (x0, x1) = (-2.0, 2.0);
        let dx = (x1 - x0) / (n - 1) as f64;
        let x: Vec<f64> = (0..n).map(|i| x0 + i as f64 * dx).collect();
        let p: Vec<f64> = x.iter().map(|&x| (1.0 - x * x).max(0.0).sqrt()).collect();
        let k = influence_coefficients(n, dx);
        let mut v = vec![0.0; n];
        deflection(&k, &p, &mut v);
        let centre = n / 2;
        let gap: Vec<f64> = (0..n).map(|i| x[i] * x[i] / 2.0 - v[i] + v[centre]).collect();
        for i in 0..n {
            if x[i].abs() < 0.9 {
                assert!(gap[i].abs() < 2e-4, "gap {} at X = {}", gap[i], x[i]);
            }
        }
        // Outside the contact the gap opens.
        assert!(gap[n - 1] > 0.1);
    }
}
