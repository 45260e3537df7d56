//! Monotone piecewise-cubic Hermite interpolation (Fritsch & Carlson, SIAM J. Numer. Anal. 17,
//! 1980, with the Fritsch–Butland weighted harmonic-mean slopes): the interpolant is monotone
//! wherever the data are, and C¹. Outside the data it continues linearly with the end slope.

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Pchip {
    x: Vec<f64>,
    y: Vec<f64>,
    d: Vec<f64>,
}

impl Pchip {
    /// `x` strictly increasing, at least two points.
    pub(crate) fn new(x: Vec<f64>, y: Vec<f64>) -> Self {
        let n = x.len();
        debug_assert!(n >= 2 && y.len() == n);
        let h: Vec<f64> = (0..n - 1).map(|k| x[k + 1] - x[k]).collect();
        let del: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        let mut d = vec![0.0; n];
        if n == 2 {
            d[0] = del[0];
            d[1] = del[0];
        } else {
            for k in 1..n - 1 {
                if del[k - 1] * del[k] > 0.0 {
                    let (w1, w2) = (2.0 * h[k] + h[k - 1], h[k] + 2.0 * h[k - 1]);
                    d[k] = (w1 + w2) / (w1 / del[k - 1] + w2 / del[k]);
                }
            }
            d[0] = end_slope(h[0], h[1], del[0], del[1]);
            d[n - 1] = end_slope(h[n - 2], h[n - 3], del[n - 2], del[n - 3]);
        }
        Pchip { x, y, d }
    }

    /// Value and derivative at `t`.
    pub(crate) fn eval(&self, t: f64) -> (f64, f64) {
        let n = self.x.len();
        if t <= self.x[0] {
            return (self.y[0] + self.d[0] * (t - self.x[0]), self.d[0]);
        }
        if t >= self.x[n - 1] {
            return (self.y[n - 1] + self.d[n - 1] * (t - self.x[n - 1]), self.d[n - 1]);
        }
        let k = self.x.partition_point(|&v| v <= t).saturating_sub(1).min(n - 2);
        let h = self.x[k + 1] - self.x[k];
        let s = (t - self.x[k]) / h;
        let (y0, y1, d0, d1) = (self.y[k], self.y[k + 1], self.d[k] * h, self.d[k + 1] * h);
        let (s2, s3) = (s * s, s * s * s);
        let v = (2.0 * s3 - 3.0 * s2 + 1.0) * y0 + (s3 - 2.0 * s2 + s) * d0 + (-2.0 * s3 + 3.0 * s2) * y1 + (s3 - s2) * d1;
        let dv = ((6.0 * s2 - 6.0 * s) * y0 + (3.0 * s2 - 4.0 * s + 1.0) * d0 + (-6.0 * s2 + 6.0 * s) * y1 + (3.0 * s2 - 2.0 * s) * d1) / h;
        (v, dv)
    }
}

/// Shape-preserving three-point end slope.
fn end_slope(h0: f64, h1: f64, del0: f64, del1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * del0 - h0 * del1) / (h0 + h1);
    if d.signum() != del0.signum() || del0 == 0.0 {
        0.0
    } else if del0.signum() != del1.signum() && d.abs() > 3.0 * del0.abs() {
        3.0 * del0
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rough_pchip_is_monotone_and_exact_on_lines() {
        let p = Pchip::new(vec![0.0, 1.0, 2.0, 4.0], vec![1.0, 3.0, 5.0, 9.0]);
        for t in [-1.0, 0.5, 1.7, 3.3, 5.0] {
            let (v, d) = p.eval(t);
            assert!((v - (1.0 + 2.0 * t)).abs() < 1e-12 && (d - 2.0).abs() < 1e-12);
        }
        let q = Pchip::new(vec![0.0, 1.0, 2.0, 3.0], vec![0.0, 0.9, 1.0, 1.0]);
        let mut last = -1.0;
        for k in 0..=300 {
            let (v, d) = q.eval(k as f64 * 0.01);
            assert!(v >= last - 1e-15 && d >= -1e-15);
            last = v;
        }
    }
}
