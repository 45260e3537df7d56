//! A tabulated asperity pressure–gap relation `p̄_a(h)` (seed 001 eq. 12, its Fig. 7a "h–p̄_a
//! curve"): from a deterministic dry rough-contact calculation of the measured surfaces, or from
//! a user's table. It replaces Greenwood–Tripp in the load-sharing models
//! ([`super::Roughness::load_sharing_pressure`]).
//!
//! Interpolation: monotone cubic Hermite (Steffen 1990 slopes: no overshoot, C¹) of `ln p̄_a`
//! against `h`, so the relation stays positive and non-increasing between the points; beyond the
//! ends `ln p̄_a` continues linearly with the end slope (an exponential tail, the form such
//! curves take at large gaps; towards zero gap the growth continues until the plastic cap).

/// The curve: films ascending (m), mean asperity pressures (Pa, positive, non-increasing).
#[derive(Debug, Clone, PartialEq)]
pub struct PressureGapCurve {
    film: Vec<f64>,
    ln_pressure: Vec<f64>,
    slope: Vec<f64>,
}

impl PressureGapCurve {
    /// The curve through `(film[i], pressure[i])`. Errors name the rule broken: at least two
    /// points, films finite, positive and strictly ascending, pressures finite, positive and
    /// non-increasing.
    pub fn new(film: &[f64], pressure: &[f64]) -> Result<Self, String> {
        if film.len() < 2 || film.len() != pressure.len() {
            return Err("needs at least two points and as many pressures as films".into());
        }
        if !film.iter().all(|h| h.is_finite() && *h > 0.0) || film.windows(2).any(|w| w[1] <= w[0]) {
            return Err("films must be finite, positive and strictly ascending".into());
        }
        if !pressure.iter().all(|p| p.is_finite() && *p > 0.0) || pressure.windows(2).any(|w| w[1] > w[0]) {
            return Err("pressures must be finite, positive and non-increasing with the film".into());
        }
        let ln_pressure: Vec<f64> = pressure.iter().map(|p| p.ln()).collect();
        let slope = monotone_slopes(film, &ln_pressure);
        Ok(PressureGapCurve { film: film.to_vec(), ln_pressure, slope })
    }

    /// `(p̄_a, dp̄_a/dh)` at film `h` (Pa, Pa/m).
    pub fn pressure(&self, h: f64) -> (f64, f64) {
        let (x, y, m) = (&self.film, &self.ln_pressure, &self.slope);
        let n = x.len();
        let (ln, d) = if h <= x[0] {
            (y[0] + m[0] * (h - x[0]), m[0])
        } else if h >= x[n - 1] {
            (y[n - 1] + m[n - 1] * (h - x[n - 1]), m[n - 1])
        } else {
            let i = x.partition_point(|&v| v <= h).clamp(1, n - 1) - 1;
            let dx = x[i + 1] - x[i];
            let t = (h - x[i]) / dx;
            let (t2, t3) = (t * t, t * t * t);
            let ln = (2.0 * t3 - 3.0 * t2 + 1.0) * y[i] + (t3 - 2.0 * t2 + t) * dx * m[i] + (-2.0 * t3 + 3.0 * t2) * y[i + 1] + (t3 - t2) * dx * m[i + 1];
            let d = ((6.0 * t2 - 6.0 * t) * y[i] + (3.0 * t2 - 4.0 * t + 1.0) * dx * m[i] + (-6.0 * t2 + 6.0 * t) * y[i + 1] + (3.0 * t2 - 2.0 * t) * dx * m[i + 1]) / dx;
            (ln, d)
        };
        // Cap the exponent: a steep tail far beyond the data stays finite.
        let p = ln.min(700.0).exp();
        (p, p * d)
    }

    /// The data points `(film, pressure)`.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.film.iter().zip(&self.ln_pressure).map(|(h, l)| (*h, l.exp()))
    }
}

/// Steffen's (1990) slopes of data `(x, y)`: monotone where the data are, no overshoot; one-sided
/// at the ends (the secant, limited like the interior).
pub fn monotone_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let secant: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / (x[i + 1] - x[i])).collect();
    let mut m = vec![0.0; n];
    m[0] = secant[0];
    m[n - 1] = secant[n - 2];
    for i in 1..n - 1 {
        let (s0, s1) = (secant[i - 1], secant[i]);
        let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let p = (s0 * h1 + s1 * h0) / (h0 + h1);
        m[i] = if s0 * s1 <= 0.0 { 0.0 } else { (s0.signum() + s1.signum()) * s0.abs().min(s1.abs()).min(0.5 * p.abs()) };
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_monotonically_with_a_consistent_slope() {
        let h = [0.05e-6, 0.1e-6, 0.2e-6, 0.4e-6, 0.8e-6];
        let p = [400e6, 150e6, 30e6, 2e6, 1e4];
        let c = PressureGapCurve::new(&h, &p).unwrap();
        for (i, (hh, pp)) in c.points().enumerate() {
            assert!((hh - h[i]).abs() < 1e-20 && (pp / p[i] - 1.0).abs() < 1e-12);
            assert!((c.pressure(h[i]).0 / p[i] - 1.0).abs() < 1e-12);
        }
        let mut last = f64::INFINITY;
        for k in 0..=200 {
            let x = 0.01e-6 + k as f64 * 0.005e-6;
            let (v, d) = c.pressure(x);
            assert!(v <= last * (1.0 + 1e-12) && d <= 0.0 && v > 0.0, "{x}: {v} {d}");
            let fd = (c.pressure(x + 1e-13).0 - c.pressure(x - 1e-13).0) / 2e-13;
            assert!((d - fd).abs() <= 1e-5 * fd.abs() + 1e-3, "{x}: {d} vs {fd}");
            last = v;
        }
        assert!(PressureGapCurve::new(&[1e-7], &[1e6]).is_err());
        assert!(PressureGapCurve::new(&[1e-7, 2e-7], &[1e6, 2e6]).is_err());
        assert!(PressureGapCurve::new(&[2e-7, 1e-7], &[2e6, 1e6]).is_err());
    }
}
