//! Third-order jets: a value with its first three derivatives with respect to one variable (the
//! cam angle). Arithmetic on jets applies the Leibniz and Faà di Bruno rules, so any composition
//! of the operations below yields exact derivatives — the lift laws, the multi-arc geometry and
//! the kinematics use them instead of finite differences.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// `f, f', f'', f'''` of a function of the cam angle (radians).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    pub v: f64,
    pub d1: f64,
    pub d2: f64,
    pub d3: f64,
}

impl Jet {
    pub const fn new(v: f64, d1: f64, d2: f64, d3: f64) -> Self {
        Jet { v, d1, d2, d3 }
    }
    /// A constant.
    pub const fn constant(v: f64) -> Self {
        Jet { v, d1: 0.0, d2: 0.0, d3: 0.0 }
    }
    /// The independent variable at `x`.
    pub const fn variable(x: f64) -> Self {
        Jet { v: x, d1: 1.0, d2: 0.0, d3: 0.0 }
    }
    /// `g(self)` given `g` and its first three derivatives at `self.v` (Faà di Bruno).
    pub fn compose(self, g0: f64, g1: f64, g2: f64, g3: f64) -> Self {
        let (a1, a2, a3) = (self.d1, self.d2, self.d3);
        Jet {
            v: g0,
            d1: g1 * a1,
            d2: g2 * a1 * a1 + g1 * a2,
            d3: g3 * a1 * a1 * a1 + 3.0 * g2 * a1 * a2 + g1 * a3,
        }
    }
    pub fn sin(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.compose(s, c, -s, -c)
    }
    pub fn cos(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.compose(c, -s, -c, s)
    }
    /// Square root; the caller guarantees `self.v > 0`.
    pub fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        let g1 = 0.5 / r;
        let g2 = -0.5 * g1 / self.v;
        let g3 = -1.5 * g2 / self.v;
        self.compose(r, g1, g2, g3)
    }
    /// `1/self`; the caller guarantees `self.v != 0`.
    pub fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.compose(r, -r * r, 2.0 * r * r * r, -6.0 * r * r * r * r)
    }
    pub fn scale(self, k: f64) -> Self {
        Jet { v: k * self.v, d1: k * self.d1, d2: k * self.d2, d3: k * self.d3 }
    }
    pub fn is_finite(&self) -> bool {
        self.v.is_finite() && self.d1.is_finite() && self.d2.is_finite() && self.d3.is_finite()
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, o: Jet) -> Jet {
        Jet { v: self.v + o.v, d1: self.d1 + o.d1, d2: self.d2 + o.d2, d3: self.d3 + o.d3 }
    }
}
impl Sub for Jet {
    type Output = Jet;
    fn sub(self, o: Jet) -> Jet {
        Jet { v: self.v - o.v, d1: self.d1 - o.d1, d2: self.d2 - o.d2, d3: self.d3 - o.d3 }
    }
}
impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        self.scale(-1.0)
    }
}
impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        Jet {
            v: self.v * o.v,
            d1: self.d1 * o.v + self.v * o.d1,
            d2: self.d2 * o.v + 2.0 * self.d1 * o.d1 + self.v * o.d2,
            d3: self.d3 * o.v + 3.0 * self.d2 * o.d1 + 3.0 * self.d1 * o.d2 + self.v * o.d3,
        }
    }
}
impl Div for Jet {
    type Output = Jet;
    fn div(self, o: Jet) -> Jet {
        self * o.recip()
    }
}
impl Add<f64> for Jet {
    type Output = Jet;
    fn add(self, k: f64) -> Jet {
        Jet { v: self.v + k, ..self }
    }
}
impl Sub<f64> for Jet {
    type Output = Jet;
    fn sub(self, k: f64) -> Jet {
        Jet { v: self.v - k, ..self }
    }
}
impl Mul<f64> for Jet {
    type Output = Jet;
    fn mul(self, k: f64) -> Jet {
        self.scale(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_matches_hand_derivatives() {
        // f(x) = sqrt(1 + x²) · sin(x) / (2 + cos x) at x = 0.7, against central differences of
        // the analytic first derivative and a direct evaluation.
        let f = |x: Jet| (x * x + 1.0).sqrt() * x.sin() / (x.cos() + 2.0);
        let x0 = 0.7;
        let j = f(Jet::variable(x0));
        let fv = |x: f64| (1.0 + x * x).sqrt() * x.sin() / (2.0 + x.cos());
        assert!((j.v - fv(x0)).abs() < 1e-15);
        let h = 1e-3;
        // 4th-order central differences.
        let d1 = (-fv(x0 + 2.0 * h) + 8.0 * fv(x0 + h) - 8.0 * fv(x0 - h) + fv(x0 - 2.0 * h)) / (12.0 * h);
        let d2 = (-fv(x0 + 2.0 * h) + 16.0 * fv(x0 + h) - 30.0 * fv(x0) + 16.0 * fv(x0 - h)
            - fv(x0 - 2.0 * h))
            / (12.0 * h * h);
        let d3 = (fv(x0 + 2.0 * h) - 2.0 * fv(x0 + h) + 2.0 * fv(x0 - h) - fv(x0 - 2.0 * h))
            / (2.0 * h * h * h);
        assert!((j.d1 - d1).abs() < 1e-10, "{} {}", j.d1, d1);
        assert!((j.d2 - d2).abs() < 1e-7, "{} {}", j.d2, d2);
        assert!((j.d3 - d3).abs() < 1e-5, "{} {}", j.d3, d3);
    }
}
