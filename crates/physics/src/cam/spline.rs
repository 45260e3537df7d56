//! Periodic cubic interpolating spline (period 2π): the smooth interpolant of measured lift
//! tables. C² everywhere (continuous curvature of the follower motion, hence of the cam radius of
//! curvature); the third derivative (jerk) is piecewise constant.

use super::jet::Jet;
use crate::SolveError;
use std::f64::consts::TAU;

#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicSpline {
    /// Knots in `[x0, x0 + 2π)`, strictly increasing.
    x: Vec<f64>,
    y: Vec<f64>,
    /// Second derivatives at the knots.
    m: Vec<f64>,
}

impl PeriodicSpline {
    /// Interpolate `(x_i, y_i)` (radians, any origin, strictly increasing, spanning less than 2π;
    /// the point at `x_0 + 2π` is implied equal to `y_0`). At least 4 knots.
    pub fn new(x: &[f64], y: &[f64]) -> Result<Self, SolveError> {
        let n = x.len();
        if n < 4 || y.len() != n {
            return Err(SolveError::invalid("", "a periodic spline needs at least 4 points and equal-length arrays"));
        }
        for i in 1..n {
            if !(x[i] > x[i - 1]) {
                return Err(SolveError::invalid("", format!("angles must increase strictly (index {i})")));
            }
        }
        if !(x[n - 1] - x[0] < TAU) {
            return Err(SolveError::invalid("", "angles must span less than one revolution"));
        }
        let h: Vec<f64> = (0..n).map(|i| if i + 1 < n { x[i + 1] - x[i] } else { x[0] + TAU - x[n - 1] }).collect();
        // Cyclic tridiagonal system: h[i-1] m[i-1] + 2(h[i-1]+h[i]) m[i] + h[i] m[i+1] = rhs[i].
        let mut a = vec![0.0; n]; // sub-diagonal (coefficient of m[i-1])
        let mut b = vec![0.0; n];
        let mut c = vec![0.0; n]; // super-diagonal (coefficient of m[i+1])
        let mut r = vec![0.0; n];
        for i in 0..n {
            let im = (i + n - 1) % n;
            let ip = (i + 1) % n;
            a[i] = h[im];
            b[i] = 2.0 * (h[im] + h[i]);
            c[i] = h[i];
            r[i] = 6.0 * ((y[ip] - y[i]) / h[i] - (y[i] - y[im]) / h[im]);
        }
        let m = solve_cyclic(&a, &b, &c, &r);
        Ok(PeriodicSpline { x: x.to_vec(), y: y.to_vec(), m })
    }

    /// Value and first three derivatives at `t` (radians, any real).
    pub fn eval(&self, t: f64) -> Jet {
        let n = self.x.len();
        let x0 = self.x[0];
        let t = x0 + (t - x0).rem_euclid(TAU);
        // Interval i: x[i] <= t < x[i+1] (the last wraps to x0 + 2π).
        let i = match self.x.binary_search_by(|v| v.partial_cmp(&t).unwrap_or(std::cmp::Ordering::Less)) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        }
        .min(n - 1);
        let ip = (i + 1) % n;
        let xi = self.x[i];
        let xr = if i + 1 < n { self.x[i + 1] } else { x0 + TAU };
        let h = xr - xi;
        let (a, b) = (xr - t, t - xi);
        let (mi, mr) = (self.m[i], self.m[ip]);
        let (yi, yr) = (self.y[i], self.y[ip]);
        let v = mi * a * a * a / (6.0 * h) + mr * b * b * b / (6.0 * h) + (yi / h - mi * h / 6.0) * a
            + (yr / h - mr * h / 6.0) * b;
        let d1 = -mi * a * a / (2.0 * h) + mr * b * b / (2.0 * h) - (yi / h - mi * h / 6.0)
            + (yr / h - mr * h / 6.0);
        let d2 = mi * a / h + mr * b / h;
        let d3 = (mr - mi) / h;
        Jet::new(v, d1, d2, d3)
    }
}

/// Solve a cyclic tridiagonal system (Sherman–Morrison on the Thomas algorithm).
fn solve_cyclic(a: &[f64], b: &[f64], c: &[f64], r: &[f64]) -> Vec<f64> {
    let n = b.len();
    let alpha = c[n - 1]; // bottom-left corner (coefficient of x0 in the last row)
    let beta = a[0]; // top-right corner (coefficient of x[n-1] in the first row)
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] = b[0] - gamma;
    bb[n - 1] = b[n - 1] - alpha * beta / gamma;
    let x = thomas(a, &bb, c, r);
    let mut u = vec![0.0; n];
    u[0] = gamma;
    u[n - 1] = alpha;
    let z = thomas(a, &bb, c, &u);
    let fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
    x.iter().zip(&z).map(|(xi, zi)| xi - fact * zi).collect()
}

fn thomas(a: &[f64], b: &[f64], c: &[f64], r: &[f64]) -> Vec<f64> {
    let n = b.len();
    let mut cp = vec![0.0; n];
    let mut dp = vec![0.0; n];
    cp[0] = c[0] / b[0];
    dp[0] = r[0] / b[0];
    for i in 1..n {
        let den = b[i] - a[i] * cp[i - 1];
        cp[i] = c[i] / den;
        dp[i] = (r[i] - a[i] * dp[i - 1]) / den;
    }
    let mut x = vec![0.0; n];
    x[n - 1] = dp[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = dp[i] - cp[i] * x[i + 1];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_knots_and_a_smooth_periodic_function() {
        let n = 72;
        let x: Vec<f64> = (0..n).map(|i| TAU * i as f64 / n as f64 + 0.1).collect();
        let f = |t: f64| 0.003 * (t.sin() + 0.3 * (2.0 * t).cos());
        let y: Vec<f64> = x.iter().map(|&t| f(t)).collect();
        let s = PeriodicSpline::new(&x, &y).unwrap();
        for (xi, yi) in x.iter().zip(&y) {
            assert!((s.eval(*xi).v - yi).abs() < 1e-15);
        }
        // Cubic spline errors (Hall & Meyer): |e| ≤ 5/384 h⁴ max|f''''|, |e'| ≤ h³/24 max|f''''|,
        // |e''| ≤ 3/8 h² max|f''''| with h = 0.0873, max|f''''| ≤ 0.003·(1 + 0.3·16) = 0.0174.
        let (h, f4) = (TAU / n as f64, 0.003 * (1.0 + 0.3 * 16.0));
        let (e0, e1, e2) = (5.0 / 384.0 * h.powi(4) * f4, h.powi(3) / 24.0 * f4, 3.0 / 8.0 * h * h * f4);
        for k in 0..500 {
            let t = -3.0 + 0.0371 * k as f64;
            let j = s.eval(t);
            assert!((j.v - f(t)).abs() < e0, "value at {t}: {} vs {}", j.v, f(t));
            let d1 = 0.003 * (t.cos() - 0.6 * (2.0 * t).sin());
            assert!((j.d1 - d1).abs() < e1, "slope at {t}");
            let d2 = 0.003 * (-t.sin() - 1.2 * (2.0 * t).cos());
            assert!((j.d2 - d2).abs() < e2, "curvature at {t}");
        }
        // C² continuity across a knot.
        let k = x[10];
        let (l, r) = (s.eval(k - 1e-10), s.eval(k + 1e-10));
        assert!((l.d2 - r.d2).abs() < 1e-8);
    }

    #[test]
    fn rejects_bad_tables() {
        assert!(PeriodicSpline::new(&[0.0, 1.0, 1.0, 2.0], &[0.0; 4]).is_err());
        assert!(PeriodicSpline::new(&[0.0, 1.0, 2.0], &[0.0; 3]).is_err());
        assert!(PeriodicSpline::new(&[0.0, 1.0, 2.0, 7.0], &[0.0; 4]).is_err());
    }
}
