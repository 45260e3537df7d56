//! Elastic deflection of the half-space over the 2-D grid by DC-FFT (Liu, Wang & Liu, Wear 243
//! (2000)): the pressure is piecewise constant on the `dx × dy` cells, the influence coefficient
//! of a cell is Love's closed form (Johnson, *Contact Mechanics* eq. 3.25 integrated over a
//! rectangle), and the discrete (aperiodic) convolution is done as a periodic one on a grid
//! padded to at least `2n − 1` points per side with the coefficients wrapped around. The
//! periodic product itself is `physics::rough`'s FFT convolution (rustfft, real-input packing).
//!
//! Dimensionless, in the Hertzian units of [`super`]: `W_ij = c Σ_kl D(X_i − X_k, Y_j − Y_l) P_kl`
//! with `D(x, y) = ∫∫_cell dx'dy' / sqrt((x − x')² + (y − y')²)` and `c = 2 p_ref R_x/(π E' a)`
//! (seed 000 eq. 3's `2/(πE') ∫∫ p/r`, in units of `a²/R_x`).

use crate::rough::fft::{ConvWorkspace, Convolution};

/// `∫∫` of `1/r` over the rectangle `[x − hx, x + hx] × [y − hy, y + hy]` around the origin,
/// written with `F(s, t) = s asinh(t/|s|) + t asinh(s/|t|)` (the mixed antiderivative up to
/// terms in one variable, which cancel in the four-corner sum; each term 0 where its
/// multiplier is 0).
pub fn rectangle_influence(x: f64, y: f64, hx: f64, hy: f64) -> f64 {
    let f = |s: f64, t: f64| {
        let a = if s != 0.0 { s * (t / s.abs()).asinh() } else { 0.0 };
        let b = if t != 0.0 { t * (s / t.abs()).asinh() } else { 0.0 };
        a + b
    };
    f(x + hx, y + hy) - f(x + hx, y - hy) - f(x - hx, y + hy) + f(x - hx, y - hy)
}

/// A padded side: the smallest even `2^a 3^b ≥ 2n − 1` (fast FFT sizes).
fn padded(n: usize) -> usize {
    let need = 2 * n - 1;
    let mut best = usize::MAX;
    let mut p2 = 2;
    while p2 < 4 * need {
        let mut v = p2;
        while v < 4 * need {
            if v >= need && v < best {
                best = v;
            }
            v *= 3;
        }
        p2 *= 2;
    }
    best
}

/// The deflection operator of an `nx × ny` node grid with spacings `dx`, `dy`.
pub struct Deflection {
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    conv: Convolution,
    /// Influence coefficients `c D(di dx, dj dy)` for `di < nx`, `dj < ny` (row-major `[dj·nx + di]`).
    coeff: Vec<f64>,
    buf_in: Vec<f64>,
    buf_out: Vec<f64>,
    ws: ConvWorkspace,
}

impl Deflection {
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64, c: f64) -> Self {
        let (px, py) = (padded(nx), padded(ny));
        let mut coeff = vec![0.0; nx * ny];
        for dj in 0..ny {
            for di in 0..nx {
                coeff[dj * nx + di] = c * rectangle_influence(di as f64 * dx, dj as f64 * dy, 0.5 * dx, 0.5 * dy);
            }
        }
        // Wrap-around kernel: index k and p − k hold the coefficient of offset k (k < n); the
        // rest (never reached by a product of two n-point grids) is zero.
        let mut kernel = vec![0.0; px * py];
        for dj in 0..ny {
            for di in 0..nx {
                let v = coeff[dj * nx + di];
                for jj in [dj, (py - dj) % py] {
                    for ii in [di, (px - di) % px] {
                        kernel[jj * px + ii] = v;
                    }
                }
            }
        }
        let conv = Convolution::from_kernel(px, py, &kernel);
        let ws = conv.workspace();
        Deflection { nx, ny, px, py, conv, coeff, buf_in: vec![0.0; px * py], buf_out: vec![0.0; px * py], ws }
    }

    /// Influence coefficient between nodes `|di|`, `|dj|` apart.
    #[inline]
    pub fn coefficient(&self, di: usize, dj: usize) -> f64 {
        self.coeff[dj * self.nx + di]
    }

    /// `out = c D * p` on the node grid (row-major `[j·nx + i]`).
    pub fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let (nx, ny, px) = (self.nx, self.ny, self.px);
        self.buf_in.iter_mut().for_each(|v| *v = 0.0);
        for j in 0..ny {
            self.buf_in[j * px..j * px + nx].copy_from_slice(&p[j * nx..(j + 1) * nx]);
        }
        // Only the grid's own rows in and out (the padding rows of `p` are zero).
        self.conv.apply_rows(&self.buf_in, &mut self.buf_out, &mut self.ws, ny, ny);
        for j in 0..ny {
            out[j * nx..(j + 1) * nx].copy_from_slice(&self.buf_out[j * px..j * px + nx]);
        }
        let _ = self.py;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FFT product equals the direct double sum of the coefficients.
    #[test]
    fn dc_fft_equals_the_direct_sum() {
        let (nx, ny, dx, dy) = (13, 9, 0.3, 0.5);
        let mut d = Deflection::new(nx, ny, dx, dy, 0.7);
        let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 37) % 11) as f64 - 3.0).collect();
        let mut out = vec![0.0; nx * ny];
        d.apply(&p, &mut out);
        for j in 0..ny {
            for i in 0..nx {
                let mut s = 0.0;
                for l in 0..ny {
                    for k in 0..nx {
                        s += d.coefficient(i.abs_diff(k), j.abs_diff(l)) * p[l * nx + k];
                    }
                }
                assert!((s - out[j * nx + i]).abs() < 1e-10 * s.abs().max(1.0), "{i},{j}: {s} vs {}", out[j * nx + i]);
            }
        }
    }

    /// Hertz: the pressure `sqrt(1 − r²)` on a unit circle deflects the surface by
    /// `(π²/4)(2 − r²)/... `: with `c = 2/π²` (the circular Hertz scaling) the deflection is
    /// `1 − r²/2` inside the contact (so that the gap `H0 + r²/2 + W` is flat), Johnson eq. 3.41.
    #[test]
    fn hertz_pressure_flattens_the_gap() {
        let n = 129;
        let h = 4.0 / (n - 1) as f64;
        let c = 2.0 / (std::f64::consts::PI * std::f64::consts::PI);
        let mut d = Deflection::new(n, n, h, h, c);
        let xy = |k: usize| -2.0 + k as f64 * h;
        let p: Vec<f64> = (0..n * n).map(|k| (1.0 - xy(k % n).powi(2) - xy(k / n).powi(2)).max(0.0).sqrt()).collect();
        let mut w = vec![0.0; n * n];
        d.apply(&p, &mut w);
        for k in 0..n * n {
            let r2 = xy(k % n).powi(2) + xy(k / n).powi(2);
            if r2 < 0.8 {
                assert!((w[k] - (1.0 - 0.5 * r2)).abs() < 3e-3, "r² {r2}: {}", w[k]);
            }
        }
    }
}
